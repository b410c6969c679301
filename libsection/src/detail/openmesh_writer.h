// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// OpenMesh behind one function: the mesh writer (STL, OBJ, OFF, PLY by extension).
#include "section/mesh.h"

#include <string>

namespace section::detail {

/// Writes `mesh` (its triangle indices in range) to `path` in the format of its extension,
/// binary when `binary` and the format has a binary form; false when OpenMesh cannot (an
/// unknown extension, an unwritable path). OpenMesh's own logs stay quiet.
bool openmesh_write(const std::string& path, const Mesh& mesh, bool binary);

}  // namespace section::detail
