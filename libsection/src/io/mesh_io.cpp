// SPDX-License-Identifier: GPL-3.0-or-later
#include "section/io/mesh_io.h"

#include "detail/openmesh_writer.h"
#include "io/byte_source.h"
#include "io/formats.h"
#include "io/text.h"
#include "section/error.h"

#include <string>

namespace section {

namespace {

// The check the text mesh readers make of their first bytes, made on a pipe's before it is
// copied (ByteSource's spool): the same message, before the rest of an endless input.
void check_head(const std::string& path, std::string_view head) {
  const std::string ext = path == "-" ? "" : detail::extension(path);
  // With no extension, a mesh or a cloud is told by content later; only NUL bytes (an
  // endless /dev/zero) are no input at all, refused as the cloud reader words it.
  if (ext.empty() && !head.empty() && head.find_first_not_of('\0') == std::string_view::npos)
    throw Error("read_cloud: " + std::string(path == "-" ? "<stdin>" : path) +
                ": binary data in a text file");
  if (ext != "obj" && ext != "off") return;
  detail::skip_bom(head);
  if (ext == "off") head = head.substr(0, head.find('\n'));  // (read_off checks its first line)
  if (const char* why = detail::text_encoding_problem(head)) throw Error("read_mesh: " + path + ": " + why);
}

// The mesh format of `src` (the input `path`): by its extension, or by its content when it has
// none (standard input, a process substitution); nullptr for a cloud. A PLY file is a mesh
// when its header declares faces.
const detail::InputFormat* mesh_format(const std::string& path, detail::ByteSource& src) {
  const bool by_extension = path != "-" && !detail::extension(path).empty();
  const detail::InputFormat* format = detail::format_of_extension(path);
  if (!by_extension) {
    src.fetch(1 << 16);
    format = detail::mesh_format_of_content(src.bytes(), src.size());
  }
  if (!format || !format->read_mesh) return nullptr;
  return !format->holds_mesh || format->holds_mesh(src) ? format : nullptr;
}

}  // namespace

bool is_mesh_file(const std::string& path) {
  const detail::InputFormat* known = detail::format_of_extension(path);
  if (known && !known->read_mesh) return false;  // a cloud by its extension: not opened
  try {
    detail::ByteSource src(path, "", [&](std::string_view head) { check_head(path, head); });
    return mesh_format(path, src) != nullptr;
  } catch (const Error&) {
    return false;
  }
}

Mesh read_mesh(const std::string& path) {
  const std::string name = path == "-" ? "<stdin>" : path;
  const detail::InputFormat* known = detail::format_of_extension(path);
  if (path != "-" && !detail::extension(path).empty() && (!known || !known->read_mesh))
    throw Error("read_mesh: " + path + ": unknown mesh extension (use " + detail::named_extensions(true) +
                ")");
  // (a pipe is copied to a temporary file once: is_mesh_file may have read it)
  detail::ByteSource src(path, "read_mesh: ", [&](std::string_view head) { check_head(path, head); });
  const detail::InputFormat* format = mesh_format(path, src);
  if (!format && known) format = known;  // (a PLY without faces: its reader says so)
  if (!format)
    throw Error("read_mesh: " + name + ": not a mesh (" + detail::named_extensions(true) +
                " by content: an input with no extension is told by its first bytes)");
  const std::string text = src.read_all();
  if (text.empty()) throw Error("read_mesh: " + name + ": empty file");
  Mesh mesh = format->read_mesh(name, text);
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Eigen::Vector3d& p = mesh.vertices[i];
    if (!p.allFinite())
      throw Error("read_mesh: " + name + ": vertex " + std::to_string(i) + " has a non-finite coordinate");
    if (p.cwiseAbs().maxCoeff() > detail::max_coordinate)  // squares would overflow
      throw Error("read_mesh: " + name + ": vertex " + std::to_string(i) +
                  " has a coordinate beyond +-1e15 (corrupt file?)");
  }
  if (mesh.triangles.empty())
    throw Error("read_mesh: " + name + ": the mesh has no faces (" +
                (mesh.vertices.empty() ? std::string("nor vertices; ") : std::string()) +
                "malformed or truncated file?)");
  return mesh;
}

void write_mesh(const std::string& path, const Mesh& mesh) {
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k)
      if (t[k] < 0 || t[k] >= static_cast<int>(mesh.vertices.size()))
        throw Error("write_mesh: triangle index out of range");
  const std::string ext = detail::extension(path);
  // OpenMesh writes the file by its name: a temporary one with the same extension, renamed
  // when whole (ByteSink), or the path itself when it is not a regular file.
  detail::ByteSink out(path, "write_mesh: ", ext.empty() ? "" : "." + ext);
  const std::string& target = out.temporary().empty() ? path : out.temporary();
  if (!detail::openmesh_write(target, mesh, ext == "stl" || ext == "ply"))
    throw Error("write_mesh: " + path + ": cannot write (unknown extension or unwritable path)");
  out.close();
}

}  // namespace section
