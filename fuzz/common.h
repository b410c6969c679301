#pragma once
// Shared by the mesh fuzz targets: read_mesh reads files only (OpenMesh picks the reader by
// extension), so each input goes through a per-process temporary file.
#include "section/error.h"
#include "section/mesh.h"
#include "section/io/mesh_io.h"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <unistd.h>

inline int fuzz_read_mesh(const std::uint8_t* data, std::size_t size, const char* ext) {
  const std::string path = "/tmp/section-fuzz-" + std::to_string(::getpid()) + "." + ext;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) std::abort();
  if (size) std::fwrite(data, 1, size, f);
  std::fclose(f);
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
