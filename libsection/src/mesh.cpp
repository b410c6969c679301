#include "section/mesh.h"

#include "section/error.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

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

// OpenMesh reserves the element counts an OFF or PLY header declares before it reads the
// body, so a header claiming billions of elements would end in an allocation failure; refuse
// counts the file cannot hold (an ascii vertex takes at least 6 bytes, "0 0 0\n"; a face or
// a binary vertex at least 1).
void check_declared_counts(const std::string& path, const std::string& ext) {
  if (ext != "off" && ext != "ply") return;
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return;
  std::string head(1 << 16, '\0');
  head.resize(std::fread(&head[0], 1, head.size(), f));
  long long size = -1;
  if (std::fseek(f, 0, SEEK_END) == 0) size = std::ftell(f);
  std::fclose(f);
  if (size < 0) return;
  const auto refuse = [&](unsigned long long n, const char* what) {
    throw Error("read_mesh: " + path + ": the header declares " + std::to_string(n) + " " + what +
                " but the file has only " + std::to_string(size) + " bytes (corrupt or truncated file?)");
  };
  const auto number = [](const std::string& t, unsigned long long& n) {
    const auto r = std::from_chars(t.data(), t.data() + t.size(), n);
    return r.ec == std::errc() && r.ptr == t.data() + t.size();
  };
  std::vector<std::string> tok;  // header tokens, '#' comments dropped
  for (std::size_t i = 0; i < head.size() && tok.size() < 4096;) {
    const char c = head[i];
    if (c == '#') {
      while (i < head.size() && head[i] != '\n') ++i;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
    } else {
      const std::size_t s = i;
      while (i < head.size() && !std::isspace(static_cast<unsigned char>(head[i]))) ++i;
      tok.push_back(head.substr(s, i - s));
      if (ext == "ply" && tok.back() == "end_header") break;
      if (ext == "off" && tok.size() == 6) break;
    }
  }
  const unsigned long long bytes = static_cast<unsigned long long>(size);
  if (ext == "off") {
    // OpenMesh reads a garbled header into uninitialised counts (found by fuzz_obj_off: a
    // hang), so the header must parse here: [ST][C][N][4][n]OFF [BINARY] [dim] V F [E].
    const auto malformed = [&] {
      throw Error("read_mesh: " + path + ": malformed OFF header (expected 'OFF' and the vertex and face counts)");
    };
    std::size_t k = 1;
    const std::string& magic = tok.empty() ? std::string() : tok[0];
    if (magic.size() < 3 || magic.compare(magic.size() - 3, 3, "OFF") != 0 || magic.size() > 8) malformed();
    if (k < tok.size() && tok[k] == "BINARY") ++k;
    if (magic.find("nOFF") != std::string::npos) ++k;  // nOFF: a dimension first
    unsigned long long nv = 0, nf = 0;
    if (k + 1 >= tok.size() || !number(tok[k], nv) || !number(tok[k + 1], nf)) malformed();
    if (nv > bytes / 6) refuse(nv, "vertices");
    if (nf > bytes) refuse(nf, "faces");
    return;
  }
  for (std::size_t i = 0; i + 2 < tok.size(); ++i) {
    unsigned long long n = 0;
    if (tok[i] == "element" && number(tok[i + 2], n) && n > bytes)
      refuse(n, (tok[i + 1] + " elements").c_str());
  }
}

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
  check_declared_counts(path, ext);
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
    if (std::max({std::abs(p[0]), std::abs(p[1]), std::abs(p[2])}) > 1e15)  // squares would overflow
      throw Error("read_mesh: " + path + ": vertex " + std::to_string(vh.idx()) + " has a coordinate beyond +-1e15 (corrupt file?)");
    mesh.vertices.emplace_back(p[0], p[1], p[2]);
  }
  for (const auto fh : om.faces()) {
    std::vector<int> idx;
    for (const auto vh : om.fv_range(fh)) idx.push_back(vh.idx());
    for (std::size_t k = 1; k + 1 < idx.size(); ++k) mesh.triangles.push_back({idx[0], idx[k], idx[k + 1]});
  }
  if (mesh.triangles.empty())
    throw Error("read_mesh: " + path + ": the mesh has no faces (" +
                (mesh.vertices.empty() ? std::string("nor vertices; ") : std::string()) +
                "malformed or truncated file, or faces with bad vertex indices?)");
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
