// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Shared by the fuzz targets: each runs one reader on the input and checks what it promises.
#include "section/cloud.h"
#include "section/error.h"
#include "section/mesh.h"
#include "section/io/cloud_io.h"
#include "section/io/mesh_io.h"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <unistd.h>

// parse_cloud in `format`, in 7-point chunks (they exercise the chunk boundaries): the input
// either parses into finite points or throws section::Error; anything else is a finding.
inline int fuzz_parse_cloud(const std::uint8_t* data, std::size_t size, section::CloudFormat format,
                            const char* name) {
  section::CloudReadOptions options;
  options.format = format;
  options.chunk_points = 7;
  try {
    const section::Cloud cloud =
        section::parse_cloud({reinterpret_cast<const char*>(data), size}, name, options);
    for (const auto& p : cloud.points)
      if (!p.allFinite()) std::abort();  // the reader promises finite coordinates
  } catch (const section::Error&) {
  }
  return 0;
}

// The input in a per-process temporary file with extension `ext`, for the readers of files.
inline std::string fuzz_file(const std::uint8_t* data, std::size_t size, const char* ext) {
  const std::string path = "/tmp/section-fuzz-" + std::to_string(::getpid()) + "." + ext;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) std::abort();
  if (size) std::fwrite(data, 1, size, f);
  std::fclose(f);
  return path;
}

// read_mesh reads files only (the reader is picked by extension), so each input goes
// through a per-process temporary file.
inline int fuzz_read_mesh(const std::uint8_t* data, std::size_t size, const char* ext) {
  const std::string path = fuzz_file(data, size, ext);
  try {
    const section::Mesh mesh = section::read_mesh(path);
    for (const auto& t : mesh.triangles)
      for (int k : t)
        if (k < 0 || k >= static_cast<int>(mesh.vertices.size())) std::abort();  // bad index passed on
  } catch (const section::Error&) {
  }
  std::remove(path.c_str());
  return 0;
}
