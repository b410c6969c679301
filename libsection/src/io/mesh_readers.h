// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The mesh readers (STL, OBJ, OFF, PLY) and what they share; io/formats.h lists them.
#include "section/mesh.h"

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace section::detail {

/// The lines of a text, split into whitespace-separated tokens; blank lines are skipped and,
/// with `comments`, everything from '#' to the end of a line.
class Lines {
public:
  Lines(std::string_view text, bool comments) : rest_(text), comments_(comments) {}
  /// Moves to the next line holding a token; false at the end of the text.
  bool next();
  const std::vector<std::string_view>& tokens() const { return tok_; }
  std::size_t line_no() const { return line_no_; }

private:
  std::string_view rest_;
  bool comments_;
  std::size_t line_no_ = 0;
  std::vector<std::string_view> tok_;
};

/// Adds a polygon as a fan of triangles; a triangle repeating a vertex has no area and is left out.
void add_polygon(const std::vector<int>& idx, Mesh& mesh);

/// Each reads the mesh of the whole text of `path`; errors start "read_mesh: PATH: ".
Mesh read_stl(const std::string& path, const std::string& text);
Mesh read_obj(const std::string& path, const std::string& text);
Mesh read_off(const std::string& path, const std::string& text);
Mesh read_ply_mesh(const std::string& path, const std::string& text);

}  // namespace section::detail
