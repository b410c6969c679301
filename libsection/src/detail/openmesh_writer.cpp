// SPDX-License-Identifier: GPL-3.0-or-later
#include "detail/openmesh_writer.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include <vector>

namespace section::detail {

namespace {

struct Traits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
};
using OMesh = OpenMesh::PolyMesh_ArrayKernelT<Traits>;

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

bool openmesh_write(const std::string& path, const Mesh& mesh, bool binary) {
  OMesh om;
  std::vector<OMesh::VertexHandle> vh;
  vh.reserve(mesh.vertices.size());
  for (const auto& p : mesh.vertices) vh.push_back(om.add_vertex(OMesh::Point(p.x(), p.y(), p.z())));
  QuietOpenMesh quiet;
  for (const auto& t : mesh.triangles) om.add_face(vh[t[0]], vh[t[1]], vh[t[2]]);
  OpenMesh::IO::Options opt;
  if (binary) opt += OpenMesh::IO::Options::Binary;
  return OpenMesh::IO::write_mesh(om, path, opt);
}

}  // namespace section::detail
