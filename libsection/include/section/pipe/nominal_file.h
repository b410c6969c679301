// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file pipe/nominal_file.h
/// A blade's nominal read from its file, as `compare --nominal` reads it (docs/COMPARE.md):
/// a mesh by its extension, else a stream by its first line, else a CSV table of section
/// points; a mesh or points converted to mm.
#include "section/io/stream.h"
#include "section/mesh.h"
#include "section/pipe/compare_stream.h"
#include "section/units.h"

#include <string>

namespace section {

/// A nominal as read: one of its mesh, stream or points, the others empty.
struct NominalFile {
  Mesh mesh;
  Stream stream;  ///< converted to mm (convert_to_mm)
  Table points;   ///< columns section, u, v or x, y, z
  std::string name;
  enum class Kind { mesh, stream, points } kind = Kind::mesh;
  /// How the unit of a mesh or points was taken (its `warning` says what to check); a
  /// stream's is its own `# units` line.
  InputUnits units;
  /// The nominal as nominal_stream takes it (pointing into this object).
  NominalSource source() const;
};

/// Reads the nominal at `path`: a mesh when the name ends in .stl, .obj, .off or .ply (any
/// case), a stream when the text starts with `# libsection-stream`, else a CSV table of
/// points. `units` is the unit of a mesh or points ("" = from its extent, as nominal_to_mm
/// takes it). Throws section::Error naming `path`: unreadable or malformed, or `units`
/// given for a stream (a stream says its own unit).
NominalFile read_nominal(const std::string& path, const std::string& units = "");

}  // namespace section
