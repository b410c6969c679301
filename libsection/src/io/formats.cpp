// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/formats.h"

#include "io/cloud_readers.h"
#include "io/mesh_readers.h"
#include "io/ply.h"
#include "io/text.h"
#include "section/error.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace section::detail {

const std::vector<InputFormat>& input_formats() {
  using C = CloudFormat;
  // Meshes first, then clouds: the order in which messages name the extensions. A PLY file
  // with faces is a mesh, else a cloud.
  // Each: extensions, further extensions, cloud format, cloud reader, text, magic, mesh reader, holds_mesh.
  static const std::vector<InputFormat> formats = {
      {{"stl"}, {}, C::automatic, nullptr, false, nullptr, read_stl, nullptr},
      {{"obj"}, {}, C::automatic, nullptr, false, nullptr, read_obj, nullptr},
      {{"off"}, {}, C::automatic, nullptr, false, nullptr, read_off, nullptr},
      {{"xyz", "asc", "txt"}, {"xyzn"}, C::xyz, read_xyz_cloud, true, nullptr, nullptr, nullptr},
      {{"pts"}, {}, C::pts, read_pts_cloud, true, nullptr, nullptr, nullptr},
      {{"csv"}, {}, C::csv, read_csv_cloud, true, nullptr, nullptr, nullptr},
      {{"ply"}, {}, C::ply, read_ply_cloud, false, "ply", read_ply_mesh, ply_declares_faces},
      {{"pcd"}, {}, C::pcd, read_pcd_cloud, false, "# .PCD|VERSION 0.7|VERSION .7", nullptr, nullptr},
      {{"las", "laz"}, {}, C::las, read_las_cloud, false, "LASF", nullptr, nullptr},
      {{"e57"}, {}, C::e57, read_e57_cloud, false, "ASTM-E57", nullptr, nullptr},
      {{"dat"}, {}, C::dat, read_dat_cloud, true, nullptr, nullptr, nullptr},
  };
  return formats;
}

std::string extension(const std::string& path) {
  const auto dot = path.find_last_of('.');
  const auto slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  return lower(path.substr(dot + 1));
}

const InputFormat* format_of_extension(const std::string& path) {
  const std::string ext = extension(path);
  const auto has = [&](const std::vector<std::string_view>& list) {
    return std::find(list.begin(), list.end(), ext) != list.end();
  };
  if (ext.empty()) return nullptr;
  for (const InputFormat& f : input_formats())
    if (has(f.extensions) || has(f.also)) return &f;
  return nullptr;
}

const InputFormat* mesh_format_of_content(std::string_view head, long long size) {
  const auto named = [](std::string_view ext) {
    for (const InputFormat& f : input_formats())
      if (!f.extensions.empty() && f.extensions[0] == ext) return &f;
    return static_cast<const InputFormat*>(nullptr);
  };
  if (head.compare(0, 3, "ply") == 0) return named("ply");
  if (size >= 84 && head.size() >= 84) {
    std::uint32_t count = 0;
    std::memcpy(&count, head.data() + 80, 4);  // little endian, as the host
    if (static_cast<unsigned long long>(size) == 84 + 50ULL * count) return named("stl");
  }
  skip_bom(head);
  std::vector<std::string_view> words;
  std::size_t at = 0;
  while (at < head.size()) {  // the first line holding a word that is not a comment
    const std::size_t nl = std::min(head.find('\n', at), head.size());
    split_words(head.substr(at, nl - at), words);
    at = nl + 1;
    if (!words.empty() && words[0][0] != '#') break;
    words.clear();
  }
  if (words.empty()) return nullptr;
  const std::string first = lower(std::string(words[0]));
  if (first == "solid" && head.find("facet") != std::string_view::npos) return named("stl");
  if (first.size() >= 3 && first.size() <= 8 && words[0].substr(words[0].size() - 3) == "OFF" &&
      words[0].find_first_not_of("STCN4nOF") == std::string_view::npos)
    return named("off");
  for (const char* s : {"v", "vn", "vt", "f", "o", "g", "s", "mtllib", "usemtl"})
    if (words[0] == s) return named("obj");
  return nullptr;
}

const InputFormat& cloud_format(const std::string& path, std::string_view head, CloudFormat forced) {
  const auto& all = input_formats();
  const auto named = [&](CloudFormat c) -> const InputFormat& {
    for (const InputFormat& f : all)
      if (f.cloud == c) return f;
    throw Error("read_cloud: no reader for this cloud format");
  };
  if (forced != CloudFormat::automatic) return named(forced);
  if (path != "-") {
    if (const InputFormat* f = format_of_extension(path)) {
      if (!f->read_cloud) throw Error("read_cloud: " + path + ": is a mesh, not a point cloud");
      return *f;
    }
  }
  const auto starts = [&](std::string_view magic) {  // one of magic's '|'-separated prefixes
    for (std::size_t at = 0; at <= magic.size();) {
      const std::size_t bar = std::min(magic.find('|', at), magic.size());
      if (head.substr(0, bar - at) == magic.substr(at, bar - at)) return true;
      at = bar + 1;
    }
    return false;
  };
  for (const InputFormat& f : all)
    if (f.read_cloud && f.magic && starts(f.magic)) return f;
  if (path != "-" && !extension(path).empty())
    throw Error("read_cloud: " + path + ": unknown point cloud extension '." + extension(path) + "' (use " +
                named_extensions(false) + ")");
  return named(CloudFormat::xyz);
}

std::string named_extensions(bool meshes) {
  std::string out;
  for (const InputFormat& f : input_formats())
    if (meshes ? f.read_mesh != nullptr : f.read_cloud != nullptr)
      for (const std::string_view e : f.extensions) out += (out.empty() ? "." : " .") + std::string(e);
  return out;
}

}  // namespace section::detail
