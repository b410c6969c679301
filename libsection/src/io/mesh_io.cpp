#include "section/io/mesh_io.h"

#include "detail/openmesh_writer.h"
#include "io/byte_source.h"
#include "io/formats.h"
#include "io/text.h"
#include "section/error.h"

#include <string>

namespace section {

bool is_mesh_file(const std::string& path) {
  const detail::InputFormat* format = detail::format_of_extension(path);
  if (!format || !format->read_mesh) return false;
  if (!format->holds_mesh) return true;
  try {
    detail::ByteSource src(path, "");
    return format->holds_mesh(src);
  } catch (const Error&) {
    return false;
  }
}

Mesh read_mesh(const std::string& path) {
  if (path == "-") throw Error("read_mesh: meshes are read from files, not standard input");
  detail::ByteSource src(path, "read_mesh: ");
  // (a directory reads as empty, as it always did)
  const std::string text = src.is_directory() ? std::string() : src.read_all();
  if (text.empty()) throw Error("read_mesh: " + path + ": empty file");
  const detail::InputFormat* format = detail::format_of_extension(path);
  if (!format || !format->read_mesh)
    throw Error("read_mesh: " + path + ": unknown mesh extension (use " + detail::named_extensions(true) +
                ")");
  Mesh mesh = format->read_mesh(path, text);
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Eigen::Vector3d& p = mesh.vertices[i];
    if (!p.allFinite())
      throw Error("read_mesh: " + path + ": vertex " + std::to_string(i) + " has a non-finite coordinate");
    if (p.cwiseAbs().maxCoeff() > detail::max_coordinate)  // squares would overflow
      throw Error("read_mesh: " + path + ": vertex " + std::to_string(i) +
                  " has a coordinate beyond +-1e15 (corrupt file?)");
  }
  if (mesh.triangles.empty())
    throw Error("read_mesh: " + path + ": the mesh has no faces (" +
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
  if (!detail::openmesh_write(path, mesh, ext == "stl" || ext == "ply"))
    throw Error("write_mesh: " + path + ": cannot write (unknown extension or unwritable path)");
}

}  // namespace section
