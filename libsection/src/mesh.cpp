#include "section/mesh.h"

#include "section/error.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>

namespace section {

namespace {

struct Traits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
};
using OMesh = OpenMesh::PolyMesh_ArrayKernelT<Traits>;

std::string extension(const std::string& path) {
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos) return "";
  std::string e = path.substr(dot + 1);
  for (auto& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

// OpenMesh reports through its own global logs; silence them for the duration of a call so
// that our single error message is what the user sees.
class QuietOpenMesh {
public:
  QuietOpenMesh() {
    omerr().disable();
    omlog().disable();
    omout().disable();
  }
  ~QuietOpenMesh() {
    omerr().enable();
    omlog().enable();
    omout().enable();
  }
};

}  // namespace

bool is_mesh_file(const std::string& path) {
  const std::string ext = extension(path);
  if (ext == "stl" || ext == "obj" || ext == "off") return true;
  if (ext != "ply") return false;
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return false;
  char line[512];
  bool faces = false;
  int lines = 0;
  while (std::fgets(line, sizeof line, f) && lines++ < 200) {
    if (std::strncmp(line, "end_header", 10) == 0) break;
    unsigned long long n = 0;
    if (std::sscanf(line, "element face %llu", &n) == 1 && n > 0) faces = true;
  }
  std::fclose(f);
  return faces;
}

Mesh read_mesh(const std::string& path) {
  if (path == "-") throw Error("read_mesh: meshes are read from files, not standard input");
  {
    std::ifstream probe(path, std::ios::binary);
    if (!probe) throw Error("read_mesh: " + path + ": cannot open: " + std::strerror(errno));
    if (probe.peek() == std::ifstream::traits_type::eof()) throw Error("read_mesh: " + path + ": empty file");
  }
  const std::string ext = extension(path);
  if (ext != "stl" && ext != "obj" && ext != "off" && ext != "ply")
    throw Error("read_mesh: " + path + ": unknown mesh extension (use .stl .obj .off .ply)");
  OMesh om;
  bool ok;
  {
    QuietOpenMesh quiet;
    OpenMesh::IO::Options opt;
    try {
      ok = OpenMesh::IO::read_mesh(om, path, opt);
    } catch (const std::exception& e) {
      throw Error("read_mesh: " + path + ": " + e.what());
    }
  }
  if (!ok) throw Error("read_mesh: " + path + ": not a readable " + ext + " mesh (malformed or truncated)");
  Mesh mesh;
  mesh.vertices.reserve(om.n_vertices());
  for (const auto vh : om.vertices()) {
    const auto& p = om.point(vh);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      throw Error("read_mesh: " + path + ": vertex " + std::to_string(vh.idx()) + " has a non-finite coordinate");
    mesh.vertices.emplace_back(p[0], p[1], p[2]);
  }
  for (const auto fh : om.faces()) {
    std::vector<int> idx;
    for (const auto vh : om.fv_range(fh)) idx.push_back(vh.idx());
    for (std::size_t k = 1; k + 1 < idx.size(); ++k) mesh.triangles.push_back({idx[0], idx[k], idx[k + 1]});
  }
  if (mesh.triangles.empty()) throw Error("read_mesh: " + path + ": the mesh has no faces");
  return mesh;
}

void write_mesh(const std::string& path, const Mesh& mesh) {
  OMesh om;
  std::vector<OMesh::VertexHandle> vh;
  vh.reserve(mesh.vertices.size());
  for (const auto& p : mesh.vertices) vh.push_back(om.add_vertex(OMesh::Point(p.x(), p.y(), p.z())));
  QuietOpenMesh quiet;
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k)
      if (t[k] < 0 || t[k] >= static_cast<int>(vh.size())) throw Error("write_mesh: triangle index out of range");
    om.add_face(vh[t[0]], vh[t[1]], vh[t[2]]);
  }
  OpenMesh::IO::Options opt;
  const std::string ext = extension(path);
  if (ext == "stl" || ext == "ply") opt += OpenMesh::IO::Options::Binary;
  if (!OpenMesh::IO::write_mesh(om, path, opt))
    throw Error("write_mesh: " + path + ": cannot write (unknown extension or unwritable path)");
}

}  // namespace section
