#pragma once
/// @file mesh.h
/// Triangle meshes and their readers: STL (ascii and binary), OBJ, ascii OFF, PLY (ascii and
/// binary); OpenMesh writes them.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <string>
#include <vector>

namespace section {

/// An indexed triangle mesh; polygons are split into triangles on reading.
struct Mesh {
  std::vector<Eigen::Vector3d> vertices;       ///< vertex positions
  std::vector<std::array<int, 3>> triangles;   ///< vertex indices, counterclockwise seen from outside
};

/// Reads a mesh (.stl .obj .off .ply); polygons are fanned into triangles, STL corners at
/// the same coordinates become one vertex. Throws section::Error naming the file (and the
/// line, for text) when it cannot be read, is truncated, has no triangles, or holds
/// non-finite coordinates or bad indices.
Mesh read_mesh(const std::string& path);

/// Writes a mesh; the format follows the extension (.stl binary, .obj, .off, .ply).
void write_mesh(const std::string& path, const Mesh& mesh);

/// True when `path` names a mesh rather than a point cloud: .stl, .obj, .off, or a .ply
/// whose header declares faces.
bool is_mesh_file(const std::string& path);

}  // namespace section
