// SPDX-License-Identifier: GPL-3.0-or-later
// The OFF and OBJ mesh readers (ascii), and the line splitter every mesh reader uses.
#include "io/mesh_readers.h"

#include "io/text.h"
#include "section/error.h"

#include <cmath>
#include <limits>

// The readers are our own, not OpenMesh's: on hostile input those hang (an OFF body, a PLY
// header without end_header) or abort on an assert (an OBJ face without a usable index), all
// found by the fuzz targets (docs/ROBUSTNESS.md); its STL reader takes 'vertex 1 zero 0' for
// a vertex; and none of them reports a line number.

namespace section::detail {

bool Lines::next() {
  while (!rest_.empty()) {
    const auto nl = rest_.find('\n');
    std::string_view line = rest_.substr(0, nl);
    rest_.remove_prefix(nl == std::string_view::npos ? rest_.size() : nl + 1);
    ++line_no_;
    if (comments_) line = line.substr(0, line.find('#'));
    split_words(line, tok_);
    if (!tok_.empty()) return true;
  }
  tok_.clear();
  return false;
}

void add_polygon(const std::vector<int>& idx, Mesh& mesh) {
  for (std::size_t k = 1; k + 1 < idx.size(); ++k)
    if (idx[0] != idx[k] && idx[k] != idx[k + 1] && idx[0] != idx[k + 1])
      mesh.triangles.push_back({idx[0], idx[k], idx[k + 1]});
}

namespace {

// What an OFF header declares.
struct OffHeader {
  long long vertices = 0, faces = 0;
  bool homogeneous = false;  // 4OFF: x y z w
};

// The keyword ([ST][C][N][4][n]OFF), then [dim] and the counts, on one line or several.
OffHeader read_off_header(Lines& lines, const std::string& where, std::size_t size) {
  const auto malformed = [&] {
    throw Error(where + "malformed OFF header (expected 'OFF' and the vertex and face counts)");
  };
  if (!lines.next()) malformed();
  const std::string_view magic = lines.tokens()[0];
  if (magic.size() < 3 || magic.substr(magic.size() - 3) != "OFF") malformed();
  OffHeader h;
  bool has_dim = false;
  std::string_view p = magic.substr(0, magic.size() - 3);  // [ST][C][N][4][n], in this order
  for (const std::string_view part : {"ST", "C", "N", "4", "n"})
    if (p.substr(0, part.size()) == part) {
      p.remove_prefix(part.size());
      h.homogeneous |= part == "4";
      has_dim |= part == "n";
    }
  if (!p.empty()) malformed();
  std::vector<std::string_view> head(lines.tokens().begin() + 1, lines.tokens().end());
  if (!head.empty() && head[0] == "BINARY")
    throw Error(where + "binary OFF is not supported (save the mesh as ascii OFF, PLY or STL)");
  const std::size_t need = has_dim ? 3 : 2;
  while (head.size() < need) {
    if (!lines.next()) malformed();
    head.insert(head.end(), lines.tokens().begin(), lines.tokens().end());
  }
  long long dim = 3;
  if (has_dim && (!parse_integer(head[0], dim) || dim != 3))
    throw Error(where + "nOFF of dimension " + quoted(head[0]) + " (only 3 is supported)");
  if (!parse_integer(head[need - 2], h.vertices) || !parse_integer(head[need - 1], h.faces) ||
      h.vertices < 0 || h.faces < 0)
    malformed();
  // Counts are checked against the file size before anything is reserved: a vertex line takes
  // at least 6 bytes ("0 0 0\n"), a face line at least 2.
  const auto refuse = [&](long long n, const char* what) {
    throw Error(where + "the header declares " + std::to_string(n) + " " + what + " but the file has only " +
                std::to_string(size) + " bytes (corrupt or truncated file?)");
  };
  if (static_cast<unsigned long long>(h.vertices) > size / 6 || h.vertices > std::numeric_limits<int>::max())
    refuse(h.vertices, "vertices");
  if (static_cast<unsigned long long>(h.faces) > size / 2) refuse(h.faces, "faces");
  return h;
}

// The faces of an OFF body: n i1 .. in, then an optional colour (ignored).
void read_off_faces(Lines& lines, const OffHeader& h, const std::string& where, Mesh& mesh) {
  const auto fail = [&](const std::string& what) {
    throw Error(where + "line " + std::to_string(lines.line_no()) + ": " + what);
  };
  std::vector<int> idx;
  const long long nv = h.vertices, nf = h.faces;
  for (long long f = 0; f < nf; ++f) {
    const std::string face = "face " + std::to_string(f);
    if (!lines.next())
      fail("the file ends after " + std::to_string(f) + " of " + std::to_string(nf) + " faces");
    const auto& tok = lines.tokens();
    long long n = 0;
    if (!parse_integer(tok[0], n)) fail(face + ": expected a vertex count, found " + quoted(tok[0]));
    if (n < 0) fail(face + " has a negative vertex count " + std::to_string(n));
    if (static_cast<unsigned long long>(n) > tok.size() - 1)
      fail(face + " announces " + std::to_string(n) + " vertices but the line has " +
           std::to_string(tok.size() - 1) + " more values");
    idx.clear();
    for (long long k = 1; k <= n; ++k) {
      long long v = 0;
      if (!parse_integer(tok[k], v)) fail(face + ": expected a vertex index, found " + quoted(tok[k]));
      if (v < 0 || v >= nv)
        fail(face + " has the vertex index " + std::to_string(v) + " (the mesh has " + std::to_string(nv) +
             " vertices, numbered from 0)");
      idx.push_back(static_cast<int>(v));
    }
    add_polygon(idx, mesh);
  }
}

}  // namespace

// Ascii OFF: the header, V vertex lines (x y z [w], then normals, colours, texture
// coordinates: ignored), F face lines; '#' starts a comment. Every vertex and face must be
// there and parse.
Mesh read_off(const std::string& path, const std::string& text) {
  const std::string where = "read_mesh: " + path + ": ";
  std::string_view body(text);
  skip_bom(body);
  // UTF-16 shows in the first line; NUL bytes further on are reported as bad tokens.
  if (const char* problem = text_encoding_problem(body.substr(0, body.find('\n'))))
    throw Error(where + problem);
  Lines lines(body, true);
  const auto fail = [&](const std::string& what) {
    throw Error(where + "line " + std::to_string(lines.line_no()) + ": " + what);
  };
  const OffHeader h = read_off_header(lines, where, text.size());
  Mesh mesh;
  mesh.vertices.reserve(static_cast<std::size_t>(h.vertices));
  const std::size_t ncoord = h.homogeneous ? 4 : 3;
  for (long long i = 0; i < h.vertices; ++i) {
    const std::string vertex = "vertex " + std::to_string(i);
    if (!lines.next())
      fail("the file ends after " + std::to_string(i) + " of " + std::to_string(h.vertices) + " vertices");
    const auto& tok = lines.tokens();
    if (tok.size() < ncoord)
      fail(vertex + ": expected " + std::to_string(ncoord) + " coordinates, found " +
           std::to_string(tok.size()));
    double c[4] = {0, 0, 0, 1};
    for (std::size_t k = 0; k < ncoord; ++k)
      if (!parse_double(tok[k], c[k])) fail(vertex + ": expected a number, found " + quoted(tok[k]));
    for (std::size_t k = 0; k < ncoord; ++k)
      if (!std::isfinite(c[k])) fail(vertex + " has a non-finite coordinate");
    if (c[3] == 0) fail(vertex + " has the homogeneous coordinate 0");
    mesh.vertices.emplace_back(c[0] / c[3], c[1] / c[3], c[2] / c[3]);
  }
  read_off_faces(lines, h, where, mesh);
  return mesh;
}

// OBJ: 'v x y z [w or colour]' and 'f i[/t][/n] ...' lines (indices from 1, negative ones count
// back from the last vertex); every other statement (vt, vn, g, o, s, usemtl, l, ...) is skipped.
Mesh read_obj(const std::string& path, const std::string& text) {
  const std::string where = "read_mesh: " + path + ": ";
  std::string_view body(text);
  skip_bom(body);
  if (const char* problem = text_encoding_problem(body)) throw Error(where + problem);
  Lines lines(body, true);
  const auto fail = [&](const std::string& what) {
    throw Error(where + "line " + std::to_string(lines.line_no()) + ": " + what);
  };
  Mesh mesh;
  std::vector<int> idx;
  while (lines.next()) {
    const auto& tok = lines.tokens();
    if (tok[0] == "v") {
      if (tok.size() < 4)
        fail("a vertex needs x, y and z, found " + std::to_string(tok.size() - 1) + " values");
      double c[3];
      for (int k = 0; k < 3; ++k) {
        if (!parse_double(tok[k + 1], c[k])) fail("expected a number, found " + quoted(tok[k + 1]));
        if (!std::isfinite(c[k])) fail("non-finite coordinate " + quoted(tok[k + 1]));
      }
      if (mesh.vertices.size() >= static_cast<std::size_t>(std::numeric_limits<int>::max()))
        fail("more vertices than a mesh can index");
      mesh.vertices.emplace_back(c[0], c[1], c[2]);
    } else if (tok[0] == "f") {
      if (tok.size() < 4) fail("a face needs at least 3 vertices, found " + std::to_string(tok.size() - 1));
      const long long nv = static_cast<long long>(mesh.vertices.size());
      idx.clear();
      for (std::size_t k = 1; k < tok.size(); ++k) {
        long long v = 0;
        const std::string_view t = tok[k].substr(0, tok[k].find('/'));  // v/vt/vn: the vertex
        if (!parse_integer(t, v)) fail("expected a vertex index, found " + quoted(tok[k]));
        const long long i = v > 0 ? v - 1 : nv + v;
        if (v == 0 || i < 0 || i >= nv)
          fail("the face refers to vertex " + std::to_string(v) + " but " + std::to_string(nv) +
               " vertices are defined before it (OBJ counts from 1)");
        idx.push_back(static_cast<int>(i));
      }
      add_polygon(idx, mesh);
    }
  }
  return mesh;
}

}  // namespace section::detail
