// SPDX-License-Identifier: GPL-3.0-or-later
// The PLY mesh reader (ascii, binary little or big endian): the x, y, z of the 'vertex'
// element and the 'vertex_indices' (or 'vertex_index') list of the 'face' element; other
// elements and properties are read past.
#include "io/mesh_readers.h"

#include "io/byte_source.h"
#include "io/ply.h"
#include "io/text.h"
#include "section/error.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace section::detail {

namespace {

// A list's count must be an integer. Counts are checked against the file size before
// anything is reserved or looped over: an element takes at least a byte per scalar in
// binary, two ("0 ") in ascii, and one at all.
void check_header(const PlyHeader& h, std::size_t size, const std::string& where) {
  for (const PlyElement& e : h.elements)
    for (const PlyProperty& p : e.props)
      if (p.list() && p.count_kind == 'f')
        throw Error(where + "line " + std::to_string(p.line) + ": unknown property type in " +
                    quoted(p.count_type));
  for (const PlyElement& e : h.elements) {
    unsigned long long least = 0;
    for (const PlyProperty& p : e.props)
      least += h.format == PlyFormat::ascii ? 2 : p.list() ? p.count_size : p.size;
    if (e.count > size / std::max(least, 1ULL))
      throw Error(where + "the header declares " + std::to_string(e.count) + " " + printable(e.name) +
                  " elements but the file has only " + std::to_string(size) +
                  " bytes (corrupt or truncated file?)");
  }
}

std::string number(double d) {
  char b[32];
  std::snprintf(b, sizeof b, "%.17g", d);
  return std::string(b);
}

// Reads the elements after the header: ascii one line per element, binary scalar by scalar.
class PlyBody {
public:
  PlyBody(const std::string& text, const PlyHeader& h, const std::string& where)
      : text_(text),
        where_(where),
        ascii_(std::string_view(text).substr(h.bytes), false),
        binary_(h.format != PlyFormat::ascii),
        swap_(h.swap()),
        header_lines_(h.lines),
        at_(h.bytes) {}

  void element(const PlyElement& e, Mesh& mesh);
  /// Throws when data follow the elements the header declares (a count written too small).
  void end() {
    if (binary_ ? at_ < text_.size() : ascii_.next())
      throw Error(
          (binary_ ? where_ : where_ + "line " + std::to_string(header_lines_ + ascii_.line_no()) + ": ") +
          "more data than the PLY header declares (" +
          (binary_ ? std::to_string(text_.size() - at_) + " bytes" : std::string("a line")) +
          " after its last element): a wrong element count?");
  }
  long long vertices() const { return nv_; }
  void faces(Mesh& mesh) const;

private:
  // "FILE: line N: face 3" in ascii, "FILE: face 3" in binary.
  std::string line_at() const {
    return binary_ ? where_ + what_
                   : where_ + "line " + std::to_string(header_lines_ + ascii_.line_no()) + ": " + what_;
  }
  // One value of `size` bytes and `kind` (ascii: a token).
  double value(int size, char kind);
  // The items of a list property; kept as face indices when `keep`.
  void list(const PlyProperty& p, bool keep);

  const std::string& text_;
  const std::string& where_;
  Lines ascii_;             // ascii: the element's line
  std::size_t tok_at_ = 0;  // ascii: its next token
  const bool binary_, swap_;
  const std::size_t header_lines_;
  std::size_t at_;                    // binary: the next byte
  std::string what_;                  // the element being read, for messages
  long long nv_ = -1;                 // vertices declared, -1 before the vertex element
  std::vector<long long> faces_raw_;  // face indices as read, checked against nv at the end
  std::vector<std::size_t> face_start_;
};

double PlyBody::value(int size, char kind) {
  if (!binary_) {
    if (tok_at_ >= ascii_.tokens().size()) throw Error(line_at() + ": fewer values than the header declares");
    const std::string_view t = ascii_.tokens()[tok_at_++];
    double d = 0;
    if (!parse_double(t, d)) throw Error(line_at() + ": expected a number, found " + quoted(t));
    if (kind != 'f' && d != std::floor(d))
      throw Error(line_at() + ": expected an integer, found " + quoted(t));
    return d;
  }
  if (text_.size() - at_ < static_cast<std::size_t>(size))
    throw Error(where_ + "the file ends inside " + what_);
  const double d = ply_scalar(reinterpret_cast<const unsigned char*>(text_.data() + at_), size, kind, swap_);
  at_ += static_cast<std::size_t>(size);
  return d;
}

void PlyBody::list(const PlyProperty& p, bool keep) {
  const double count = value(p.count_size, p.count_kind);
  if (count < 0) throw Error(line_at() + " has a list of negative length " + number(count));
  // Each item takes at least a byte, so a longer list cannot be in the file.
  if (count > static_cast<double>(text_.size())) throw Error(where_ + "the file ends inside " + what_);
  if (keep) face_start_.push_back(faces_raw_.size());
  for (long long j = 0; j < static_cast<long long>(count); ++j) {
    const double d = value(p.size, p.kind);
    if (keep) {
      if (d != std::floor(d) || std::abs(d) > 9e18)
        throw Error(line_at() + " has the vertex index " + number(d));
      faces_raw_.push_back(static_cast<long long>(d));
    }
  }
}

void PlyBody::element(const PlyElement& e, Mesh& mesh) {
  const bool is_vertex = e.name == "vertex", is_face = e.name == "face";
  int ix = -1, iy = -1, iz = -1, ii = -1;
  for (std::size_t k = 0; k < e.props.size(); ++k) {
    const PlyProperty& p = e.props[k];
    if (!p.list() && p.name == "x") ix = static_cast<int>(k);
    if (!p.list() && p.name == "y") iy = static_cast<int>(k);
    if (!p.list() && p.name == "z") iz = static_cast<int>(k);
    if (p.list() && (p.name == "vertex_indices" || p.name == "vertex_index")) ii = static_cast<int>(k);
  }
  if (is_vertex) {
    if (ix < 0 || iy < 0 || iz < 0) throw Error(where_ + "the PLY vertex element lacks x, y or z");
    nv_ = static_cast<long long>(e.count);
    if (nv_ > std::numeric_limits<int>::max()) throw Error(where_ + "more vertices than a mesh can index");
    mesh.vertices.reserve(e.count);
  }
  if (is_face && ii < 0) throw Error(where_ + "the PLY face element lacks vertex_indices");
  for (unsigned long long n = 0; n < e.count; ++n) {
    what_ = printable(e.name) + " " + std::to_string(n);
    if (!binary_) {
      if (!ascii_.next())
        throw Error(where_ + "the file ends after " + std::to_string(n) + " of " + std::to_string(e.count) +
                    " " + printable(e.name) + " elements");
      tok_at_ = 0;
    }
    double c[3] = {0, 0, 0};
    for (std::size_t k = 0; k < e.props.size(); ++k) {
      const PlyProperty& p = e.props[k];
      if (p.list()) {
        list(p, is_face && static_cast<int>(k) == ii);
        continue;
      }
      const double d = value(p.size, p.kind);
      if (static_cast<int>(k) == ix) c[0] = d;
      if (static_cast<int>(k) == iy) c[1] = d;
      if (static_cast<int>(k) == iz) c[2] = d;
    }
    if (!binary_ && tok_at_ < ascii_.tokens().size())
      throw Error(line_at() + ": more values than the header declares");
    if (is_vertex) mesh.vertices.emplace_back(c[0], c[1], c[2]);
  }
}

void PlyBody::faces(Mesh& mesh) const {
  std::vector<int> idx;
  for (std::size_t f = 0; f < face_start_.size(); ++f) {
    const std::size_t end = f + 1 < face_start_.size() ? face_start_[f + 1] : faces_raw_.size();
    idx.clear();
    for (std::size_t j = face_start_[f]; j < end; ++j) {
      const long long v = faces_raw_[j];
      if (v < 0 || v >= nv_)
        throw Error(where_ + "face " + std::to_string(f) + " has the vertex index " + std::to_string(v) +
                    " (the mesh has " + std::to_string(nv_) + " vertices, numbered from 0)");
      idx.push_back(static_cast<int>(v));
    }
    add_polygon(idx, mesh);
  }
}

}  // namespace

Mesh read_ply_mesh(const std::string& path, const std::string& text) {
  const std::string where = "read_mesh: " + path + ": ";
  ByteSource src(std::string_view(text), path);
  const PlyHeader h = read_ply_header(src, PlyMessages{"read_mesh: ", true});
  check_header(h, text.size(), where);
  Mesh mesh;
  PlyBody body(text, h, where);
  for (const PlyElement& e : h.elements) body.element(e, mesh);
  if (body.vertices() < 0) throw Error(where + "PLY file without a vertex element");
  body.end();
  body.faces(mesh);
  return mesh;
}

}  // namespace section::detail
