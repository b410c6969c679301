// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file io/mesh_io.h
/// Triangle mesh readers and writers: STL (ascii and binary), OBJ, ascii OFF, PLY (ascii and
/// binary); OpenMesh writes them.
#include "section/mesh.h"

#include <string>

namespace section {

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
