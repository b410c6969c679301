#include "section/io/mesh_io.h"

#include "section/error.h"

#include "detail/text.h"
#include "detail/ply.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

// The readers are our own, not OpenMesh's: on hostile input those hang (an OFF body, a PLY
// header without end_header) or abort on an assert (an OBJ face without a usable index), all
// found by the fuzz targets (docs/ROBUSTNESS.md); its STL reader takes 'vertex 1 zero 0' for
// a vertex; and none of them reports a line number. OpenMesh still writes every format.

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

// A token for an error message: at most 40 characters, control and non-ASCII bytes as \xHH,
// so that the message stays one readable line whatever the file holds.
std::string printable(std::string_view t) {
  std::string q;
  for (std::size_t i = 0; i < t.size() && i < 40; ++i) {
    const unsigned char c = static_cast<unsigned char>(t[i]);
    if (c >= 0x20 && c < 0x7f) {
      q += static_cast<char>(c);
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", c);
      q += hex;
    }
  }
  return t.size() > 40 ? q + "..." : q;
}

std::string quoted(std::string_view t) { return "'" + printable(t) + "'"; }

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw Error("read_mesh: " + path + ": read error");
  return text;
}

bool parse_integer(std::string_view t, long long& n) {
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  const auto r = std::from_chars(t.data(), t.data() + t.size(), n);
  return r.ec == std::errc() && r.ptr == t.data() + t.size() && !t.empty();
}

// The lines of a text, split into whitespace-separated tokens; blank lines are skipped and,
// with `comments`, everything from '#' to the end of a line.
class Lines {
public:
  Lines(std::string_view text, bool comments) : rest_(text), comments_(comments) {}

  /// Moves to the next line holding a token; false at the end of the text.
  bool next() {
    while (!rest_.empty()) {
      const auto nl = rest_.find('\n');
      std::string_view line = rest_.substr(0, nl);
      rest_.remove_prefix(nl == std::string_view::npos ? rest_.size() : nl + 1);
      ++line_no_;
      if (comments_) line = line.substr(0, line.find('#'));
      tok_.clear();
      for (std::size_t i = 0; i < line.size();) {
        if (detail::is_space(line[i])) {
          ++i;
          continue;
        }
        const std::size_t s = i;
        while (i < line.size() && !detail::is_space(line[i])) ++i;
        tok_.push_back(line.substr(s, i - s));
      }
      if (!tok_.empty()) return true;
    }
    tok_.clear();
    return false;
  }

  const std::vector<std::string_view>& tokens() const { return tok_; }
  std::size_t line_no() const { return line_no_; }

private:
  std::string_view rest_;
  bool comments_;
  std::size_t line_no_ = 0;
  std::vector<std::string_view> tok_;
};

// Adds a polygon as a fan of triangles; a triangle repeating a vertex has no area and is left out.
void add_polygon(const std::vector<int>& idx, Mesh& mesh) {
  for (std::size_t k = 1; k + 1 < idx.size(); ++k)
    if (idx[0] != idx[k] && idx[k] != idx[k + 1] && idx[0] != idx[k + 1])
      mesh.triangles.push_back({idx[0], idx[k], idx[k + 1]});
}

// ---------------------------------------------------------------- OFF

// Ascii OFF: [ST][C][N][4][n]OFF, [dim], V F [E], V vertex lines (x y z [w], then normals,
// colours, texture coordinates: ignored), F face lines (n i1 .. in, then an optional colour:
// ignored); '#' starts a comment. Every vertex and face must be there and parse.
Mesh read_off(const std::string& path, const std::string& text) {
  const std::string where = "read_mesh: " + path + ": ";
  std::string_view body(text);
  detail::skip_bom(body);
  // UTF-16 shows in the first line; NUL bytes further on are reported as bad tokens.
  if (const char* problem = detail::text_encoding_problem(body.substr(0, body.find('\n'))))
    throw Error(where + problem);
  Lines lines(body, true);
  const auto fail = [&](const std::string& what) {
    throw Error(where + "line " + std::to_string(lines.line_no()) + ": " + what);
  };
  const auto malformed = [&] {
    throw Error(where + "malformed OFF header (expected 'OFF' and the vertex and face counts)");
  };

  // Header: the keyword, then the counts, on one line or several.
  if (!lines.next()) malformed();
  const std::string_view magic = lines.tokens()[0];
  if (magic.size() < 3 || magic.substr(magic.size() - 3) != "OFF") malformed();
  bool homogeneous = false, has_dim = false;
  {
    std::string_view p = magic.substr(0, magic.size() - 3);  // [ST][C][N][4][n], in this order
    for (const std::string_view part : {"ST", "C", "N", "4", "n"})
      if (p.substr(0, part.size()) == part) {
        p.remove_prefix(part.size());
        homogeneous |= part == "4";
        has_dim |= part == "n";
      }
    if (!p.empty()) malformed();
  }
  std::vector<std::string_view> head(lines.tokens().begin() + 1, lines.tokens().end());
  if (!head.empty() && head[0] == "BINARY")
    throw Error(where + "binary OFF is not supported (save the mesh as ascii OFF, PLY or STL)");
  const std::size_t need = has_dim ? 3 : 2;
  while (head.size() < need) {
    if (!lines.next()) malformed();
    head.insert(head.end(), lines.tokens().begin(), lines.tokens().end());
  }
  long long dim = 3, nv = 0, nf = 0;
  if (has_dim && (!parse_integer(head[0], dim) || dim != 3))
    throw Error(where + "nOFF of dimension " + quoted(head[0]) + " (only 3 is supported)");
  if (!parse_integer(head[need - 2], nv) || !parse_integer(head[need - 1], nf) || nv < 0 || nf < 0) malformed();
  // Counts are checked against the file size before anything is reserved: a vertex line takes
  // at least 6 bytes ("0 0 0\n"), a face line at least 2.
  const auto refuse = [&](long long n, const char* what) {
    throw Error(where + "the header declares " + std::to_string(n) + " " + what + " but the file has only " +
                std::to_string(text.size()) + " bytes (corrupt or truncated file?)");
  };
  if (static_cast<unsigned long long>(nv) > text.size() / 6 || nv > std::numeric_limits<int>::max())
    refuse(nv, "vertices");
  if (static_cast<unsigned long long>(nf) > text.size() / 2) refuse(nf, "faces");

  Mesh mesh;
  mesh.vertices.reserve(static_cast<std::size_t>(nv));
  const std::size_t ncoord = homogeneous ? 4 : 3;
  for (long long i = 0; i < nv; ++i) {
    const std::string vertex = "vertex " + std::to_string(i);
    if (!lines.next()) fail("the file ends after " + std::to_string(i) + " of " + std::to_string(nv) + " vertices");
    const auto& tok = lines.tokens();
    if (tok.size() < ncoord)
      fail(vertex + ": expected " + std::to_string(ncoord) + " coordinates, found " + std::to_string(tok.size()));
    double c[4] = {0, 0, 0, 1};
    for (std::size_t k = 0; k < ncoord; ++k)
      if (!detail::parse_double(tok[k], c[k])) fail(vertex + ": expected a number, found " + quoted(tok[k]));
    for (std::size_t k = 0; k < ncoord; ++k)
      if (!std::isfinite(c[k])) fail(vertex + " has a non-finite coordinate");
    if (c[3] == 0) fail(vertex + " has the homogeneous coordinate 0");
    mesh.vertices.emplace_back(c[0] / c[3], c[1] / c[3], c[2] / c[3]);
  }
  std::vector<int> idx;
  for (long long f = 0; f < nf; ++f) {
    const std::string face = "face " + std::to_string(f);
    if (!lines.next()) fail("the file ends after " + std::to_string(f) + " of " + std::to_string(nf) + " faces");
    const auto& tok = lines.tokens();
    long long n = 0;
    if (!parse_integer(tok[0], n)) fail(face + ": expected a vertex count, found " + quoted(tok[0]));
    if (n < 0) fail(face + " has a negative vertex count " + std::to_string(n));
    if (static_cast<unsigned long long>(n) > tok.size() - 1)
      fail(face + " announces " + std::to_string(n) + " vertices but the line has " + std::to_string(tok.size() - 1) +
           " more values");
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
  return mesh;
}

// ---------------------------------------------------------------- OBJ

// OBJ: 'v x y z [w or colour]' and 'f i[/t][/n] ...' lines (indices from 1, negative ones count
// back from the last vertex); every other statement (vt, vn, g, o, s, usemtl, l, ...) is skipped.
Mesh read_obj(const std::string& path, const std::string& text) {
  const std::string where = "read_mesh: " + path + ": ";
  std::string_view body(text);
  detail::skip_bom(body);
  if (const char* problem = detail::text_encoding_problem(body)) throw Error(where + problem);
  Lines lines(body, true);
  const auto fail = [&](const std::string& what) {
    throw Error(where + "line " + std::to_string(lines.line_no()) + ": " + what);
  };
  Mesh mesh;
  std::vector<int> idx;
  while (lines.next()) {
    const auto& tok = lines.tokens();
    if (tok[0] == "v") {
      if (tok.size() < 4) fail("a vertex needs x, y and z, found " + std::to_string(tok.size() - 1) + " values");
      double c[3];
      for (int k = 0; k < 3; ++k) {
        if (!detail::parse_double(tok[k + 1], c[k])) fail("expected a number, found " + quoted(tok[k + 1]));
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

// ---------------------------------------------------------------- PLY

struct PlyProperty {
  std::string name;
  int size = 0;        // bytes of a scalar (of the items, for a list)
  char kind = 'f';     // 'f' float, 'i' signed, 'u' unsigned
  int count_size = 0;  // bytes of a list's count; 0 for a scalar
  char count_kind = 'u';
};

struct PlyElement {
  std::string name;
  unsigned long long count = 0;
  std::vector<PlyProperty> props;
};

using detail::ply_type;

// A binary scalar of `size` bytes and `kind` at `p`, byte-swapped when `swap`.
double binary_scalar(const char* p, int size, char kind, bool swap) {
  unsigned char b[8];
  std::memcpy(b, p, static_cast<std::size_t>(size));
  if (swap) std::reverse(b, b + size);
  if (kind == 'f') {
    if (size == 4) {
      float f;
      std::memcpy(&f, b, 4);
      return f;
    }
    double d;
    std::memcpy(&d, b, 8);
    return d;
  }
  std::uint64_t u = 0;
  for (int k = size - 1; k >= 0; --k) u = (u << 8) | b[k];  // little-endian after the swap
  if (kind == 'i' && size < 8 && (u >> (8 * size - 1)) & 1) return static_cast<double>(u) - std::ldexp(1.0, 8 * size);
  return static_cast<double>(u);
}

// PLY (ascii, binary little or big endian): the x, y, z of the 'vertex' element and the
// 'vertex_indices' (or 'vertex_index') list of the 'face' element; other elements and
// properties are read past.
Mesh read_ply(const std::string& path, const std::string& text) {
  const std::string where = "read_mesh: " + path + ": ";
  // Header, line by line up to end_header.
  std::size_t pos = 0, line_no = 0;
  int format = -1;  // 0 ascii, 1 little endian, 2 big endian
  std::vector<PlyElement> elements;
  bool ended = false;
  while (!ended) {
    const auto nl = text.find('\n', pos);
    if (nl == std::string::npos) throw Error(where + "truncated PLY header (no end_header)");
    ++line_no;
    Lines words(std::string_view(text).substr(pos, nl - pos), false);
    pos = nl + 1;
    const std::string at = where + "line " + std::to_string(line_no) + ": ";
    if (!words.next()) continue;
    const auto& tok = words.tokens();
    if (line_no == 1) {
      if (tok[0] != "ply" || tok.size() != 1) throw Error(where + "not a PLY file (no 'ply' magic)");
    } else if (tok[0] == "end_header") {
      ended = true;
    } else if (tok[0] == "comment" || tok[0] == "obj_info") {
    } else if (tok[0] == "format" && tok.size() >= 2) {
      const std::string_view f = tok[1];
      format = f == "ascii" ? 0 : f == "binary_little_endian" ? 1 : f == "binary_big_endian" ? 2 : -2;
      if (format == -2) throw Error(at + "unknown PLY format " + quoted(f));
    } else if (tok[0] == "element" && tok.size() == 3) {
      PlyElement e;
      e.name = std::string(tok[1]);
      long long n = 0;
      if (!parse_integer(tok[2], n) || n < 0) throw Error(at + "bad element count " + quoted(tok[2]));
      e.count = static_cast<unsigned long long>(n);
      elements.push_back(e);
    } else if (tok[0] == "property" && !elements.empty() && (tok.size() == 3 || (tok.size() == 5 && tok[1] == "list"))) {
      PlyProperty p;
      p.name = std::string(tok.back());
      const bool ok = tok.size() == 3 ? ply_type(tok[1], p.size, p.kind)
                                      : ply_type(tok[2], p.count_size, p.count_kind) && p.count_kind != 'f' &&
                                            ply_type(tok[3], p.size, p.kind);
      if (!ok) throw Error(at + "unknown property type in " + quoted(words.tokens().size() == 3 ? tok[1] : tok[2]));
      elements.back().props.push_back(p);
    } else {
      throw Error(at + "unexpected PLY header line starting " + quoted(tok[0]));
    }
  }
  if (format < 0) throw Error(where + "PLY header without a format line");
  // Counts are checked against the file size before anything is reserved or looped over: an
  // element takes at least a byte per scalar in binary, two ("0 ") in ascii, and one at all.
  for (const PlyElement& e : elements) {
    unsigned long long least = 0;
    for (const PlyProperty& p : e.props) least += format == 0 ? 2 : p.count_size ? p.count_size : p.size;
    if (e.count > text.size() / std::max(least, 1ULL))
      throw Error(where + "the header declares " + std::to_string(e.count) + " " + printable(e.name) +
                  " elements but the file has only " + std::to_string(text.size()) + " bytes (corrupt or truncated file?)");
  }

  Mesh mesh;
  long long nv = -1;
  std::vector<int> idx;
  std::vector<long long> faces_raw;  // face indices as read, checked against nv at the end
  std::vector<std::size_t> face_start;
  // Ascii: one line per element, `tok_at` its next token; binary: `at` the next byte.
  Lines ascii(std::string_view(text).substr(pos), false);
  std::size_t tok_at = 0, at = pos;
  const bool swap = format == 2;  // the host is little endian (x86, arm64)
  std::string what;                // the element being read, for messages
  // "FILE: line N: face 3" in ascii, "FILE: face 3" in binary.
  const auto line_at = [&] {
    return format == 0 ? where + "line " + std::to_string(line_no + ascii.line_no()) + ": " + what : where + what;
  };
  const auto number = [](double d) {
    char b[32];
    std::snprintf(b, sizeof b, "%.17g", d);
    return std::string(b);
  };
  // Reads one value of `size` bytes and `kind` (ascii: a token).
  const auto value = [&](int size, char kind) -> double {
    if (format == 0) {
      if (tok_at >= ascii.tokens().size()) throw Error(line_at() + ": fewer values than the header declares");
      const std::string_view t = ascii.tokens()[tok_at++];
      double d = 0;
      if (!detail::parse_double(t, d)) throw Error(line_at() + ": expected a number, found " + quoted(t));
      if (kind != 'f' && d != std::floor(d)) throw Error(line_at() + ": expected an integer, found " + quoted(t));
      return d;
    }
    if (text.size() - at < static_cast<std::size_t>(size)) throw Error(where + "the file ends inside " + what);
    const double d = binary_scalar(text.data() + at, size, kind, swap);
    at += static_cast<std::size_t>(size);
    return d;
  };
  for (const PlyElement& e : elements) {
    const bool is_vertex = e.name == "vertex", is_face = e.name == "face";
    int ix = -1, iy = -1, iz = -1, ii = -1;
    for (std::size_t k = 0; k < e.props.size(); ++k) {
      const PlyProperty& p = e.props[k];
      if (p.count_size == 0 && p.name == "x") ix = static_cast<int>(k);
      if (p.count_size == 0 && p.name == "y") iy = static_cast<int>(k);
      if (p.count_size == 0 && p.name == "z") iz = static_cast<int>(k);
      if (p.count_size != 0 && (p.name == "vertex_indices" || p.name == "vertex_index")) ii = static_cast<int>(k);
    }
    if (is_vertex) {
      if (ix < 0 || iy < 0 || iz < 0) throw Error(where + "the PLY vertex element lacks x, y or z");
      nv = static_cast<long long>(e.count);
      if (nv > std::numeric_limits<int>::max()) throw Error(where + "more vertices than a mesh can index");
      mesh.vertices.reserve(e.count);
    }
    if (is_face && ii < 0) throw Error(where + "the PLY face element lacks vertex_indices");
    for (unsigned long long n = 0; n < e.count; ++n) {
      what = printable(e.name) + " " + std::to_string(n);
      if (format == 0) {
        if (!ascii.next())
          throw Error(where + "the file ends after " + std::to_string(n) + " of " + std::to_string(e.count) + " " +
                      printable(e.name) + " elements");
        tok_at = 0;
      }
      double c[3] = {0, 0, 0};
      for (std::size_t k = 0; k < e.props.size(); ++k) {
        const PlyProperty& p = e.props[k];
        if (p.count_size == 0) {
          const double d = value(p.size, p.kind);
          if (static_cast<int>(k) == ix) c[0] = d;
          if (static_cast<int>(k) == iy) c[1] = d;
          if (static_cast<int>(k) == iz) c[2] = d;
          continue;
        }
        const double count = value(p.count_size, p.count_kind);
        if (count < 0) throw Error(line_at() + " has a list of negative length " + number(count));
        // Each item takes at least a byte, so a longer list cannot be in the file.
        if (count > static_cast<double>(text.size())) throw Error(where + "the file ends inside " + what);
        const bool keep = is_face && static_cast<int>(k) == ii;
        if (keep) face_start.push_back(faces_raw.size());
        for (long long j = 0; j < static_cast<long long>(count); ++j) {
          const double d = value(p.size, p.kind);
          if (keep) {
            if (d != std::floor(d) || std::abs(d) > 9e18)
              throw Error(line_at() + " has the vertex index " + number(d));
            faces_raw.push_back(static_cast<long long>(d));
          }
        }
      }
      if (format == 0 && tok_at < ascii.tokens().size())
        throw Error(line_at() + ": more values than the header declares");
      if (is_vertex) mesh.vertices.emplace_back(c[0], c[1], c[2]);
    }
  }
  if (nv < 0) throw Error(where + "PLY file without a vertex element");
  face_start.push_back(faces_raw.size());
  for (std::size_t f = 0; f + 1 < face_start.size(); ++f) {
    idx.clear();
    for (std::size_t j = face_start[f]; j < face_start[f + 1]; ++j) {
      const long long v = faces_raw[j];
      if (v < 0 || v >= nv)
        throw Error(where + "face " + std::to_string(f) + " has the vertex index " + std::to_string(v) +
                    " (the mesh has " + std::to_string(nv) + " vertices, numbered from 0)");
      idx.push_back(static_cast<int>(v));
    }
    add_polygon(idx, mesh);
  }
  return mesh;
}

// ---------------------------------------------------------------- STL

// STL stores every triangle's corners; corners at the same coordinates become one vertex, as
// the slicer needs shared vertices to chain the cut segments into loops (-0 is merged with 0).
class VertexMerger {
public:
  explicit VertexMerger(Mesh& mesh) : mesh_(mesh) {}
  int add(double x, double y, double z) {
    const std::array<double, 3> key = {x + 0.0, y + 0.0, z + 0.0};
    const auto [it, added] = index_.emplace(key, static_cast<int>(mesh_.vertices.size()));
    if (added) mesh_.vertices.emplace_back(key[0], key[1], key[2]);
    return it->second;
  }

private:
  struct Hash {
    std::size_t operator()(const std::array<double, 3>& p) const {
      std::size_t h = 0;
      for (double d : p) {
        std::uint64_t u;
        std::memcpy(&u, &d, 8);
        h = (h ^ u) * 0x100000001b3ULL;
      }
      return h ^ (h >> 29);
    }
  };
  Mesh& mesh_;
  std::unordered_map<std::array<double, 3>, int, Hash> index_;
};

// Binary STL: an 80-byte header, a little-endian uint32 triangle count, then per triangle
// 12 float32 (normal, three corners) and a uint16.
Mesh read_stl_binary(const std::string& where, const std::string& text, unsigned long long count) {
  Mesh mesh;
  VertexMerger merge(mesh);
  std::vector<int> idx(3);
  for (unsigned long long t = 0; t < count; ++t) {
    const char* rec = text.data() + 84 + 50 * t;
    for (int k = 0; k < 3; ++k) {
      float c[3];
      std::memcpy(c, rec + 12 + 12 * k, 12);
      if (!std::isfinite(c[0]) || !std::isfinite(c[1]) || !std::isfinite(c[2]))
        throw Error(where + "triangle " + std::to_string(t) + " has a non-finite coordinate");
      idx[k] = merge.add(c[0], c[1], c[2]);
    }
    add_polygon(idx, mesh);
  }
  return mesh;
}

// Ascii STL: solid NAME, then facets (facet normal N N N, outer loop, vertex X Y Z three
// times, endloop, endfacet), endsolid [NAME]; several solids may follow each other.
// Keywords are matched without regard to case.
Mesh read_stl_ascii(const std::string& where, std::string_view text) {
  if (const char* problem = detail::text_encoding_problem(text)) throw Error(where + problem);
  Lines lines(text, false);
  std::size_t at = 0;  // the next token of the current line
  bool more = lines.next();
  const auto fail = [&](const std::string& what) {
    throw Error(where + "line " + std::to_string(lines.line_no()) + ": " + what);
  };
  const auto next = [&](std::string_view& t) {
    while (more && at >= lines.tokens().size()) {
      more = lines.next();
      at = 0;
    }
    if (!more) return false;
    t = lines.tokens()[at++];
    return true;
  };
  const auto is = [](std::string_view t, std::string_view keyword) {
    return t.size() == keyword.size() && std::equal(t.begin(), t.end(), keyword.begin(), [](char a, char b) {
             return std::tolower(static_cast<unsigned char>(a)) == b;
           });
  };
  const auto expect = [&](std::string_view keyword) {
    std::string_view t;
    if (!next(t)) fail("the file ends where '" + std::string(keyword) + "' should follow (truncated file?)");
    if (!is(t, keyword)) fail("expected '" + std::string(keyword) + "', found " + quoted(t));
  };
  const auto number = [&]() {
    std::string_view t;
    double d = 0;
    if (!next(t)) fail("the file ends inside a facet (truncated file?)");
    if (!detail::parse_double(t, d)) fail("expected a number, found " + quoted(t));
    if (!std::isfinite(d)) fail("non-finite coordinate " + quoted(t));
    return d;
  };
  Mesh mesh;
  VertexMerger merge(mesh);
  std::vector<int> idx;
  std::string_view t;
  while (next(t)) {
    if (!is(t, "solid")) fail("expected 'solid', found " + quoted(t));
    at = lines.tokens().size();  // the rest of the line is the solid's name
    while (true) {
      if (!next(t)) fail("the file ends before 'endsolid' (truncated file?)");
      if (is(t, "endsolid")) {
        at = lines.tokens().size();
        break;
      }
      if (!is(t, "facet")) fail("expected 'facet' or 'endsolid', found " + quoted(t));
      expect("normal");
      for (int k = 0; k < 3; ++k) number();
      expect("outer");
      expect("loop");
      idx.clear();
      while (next(t) && is(t, "vertex")) {
        const double x = number(), y = number(), z = number();
        idx.push_back(merge.add(x, y, z));
      }
      if (!more) fail("the file ends inside a facet (truncated file?)");
      if (!is(t, "endloop")) fail("expected 'vertex' or 'endloop', found " + quoted(t));
      if (idx.size() < 3) fail("a facet with " + std::to_string(idx.size()) + " vertices (3 are needed)");
      expect("endfacet");
      add_polygon(idx, mesh);
    }
  }
  return mesh;
}

Mesh read_stl(const std::string& path, const std::string& text) {
  const std::string where = "read_mesh: " + path + ": ";
  unsigned long long count = 0;
  if (text.size() >= 84) {
    std::uint32_t c;
    std::memcpy(&c, text.data() + 80, 4);  // little endian, as the host
    count = c;
  }
  const unsigned long long need = 84 + 50 * count;
  // Binary files may start with "solid" too: a size that matches the count decides.
  if (text.size() >= 84 && text.size() == need) return read_stl_binary(where, text, count);
  std::string_view body(text);
  detail::skip_bom(body);
  const auto first = body.find_first_not_of(" \t\r\n");
  if (first != std::string_view::npos && body.size() - first >= 5) {
    std::string head(body.substr(first, 5));
    for (auto& c : head) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    // A binary file whose header starts with "solid" has NUL bytes: it is reported as binary.
    if (head == "solid" && (text.size() < 84 || !detail::text_encoding_problem(body))) return read_stl_ascii(where, body);
  }
  if (text.size() < 84)
    throw Error(where + "neither an ascii STL (no 'solid') nor a binary one (" + std::to_string(text.size()) +
                " bytes, shorter than the 84-byte header)");
  if (text.size() < need)
    throw Error(where + "the binary STL header declares " + std::to_string(count) + " triangles (" +
                std::to_string(need) + " bytes) but the file has only " + std::to_string(text.size()) +
                " bytes (corrupt or truncated file?)");
  return read_stl_binary(where, text, count);  // bytes after the last triangle are ignored
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
  Mesh mesh;
  if (ext == "off") {
    mesh = read_off(path, read_file(path));
  } else if (ext == "obj") {
    mesh = read_obj(path, read_file(path));
  } else if (ext == "ply") {
    mesh = read_ply(path, read_file(path));
  } else if (ext == "stl") {
    mesh = read_stl(path, read_file(path));
  } else {
    throw Error("read_mesh: " + path + ": unknown mesh extension (use .stl .obj .off .ply)");
  }
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
