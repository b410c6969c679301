// SPDX-License-Identifier: GPL-3.0-or-later
// The STL mesh reader: ascii and binary.
#include "io/mesh_readers.h"

#include "io/text.h"
#include "section/error.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <unordered_map>

namespace section::detail {

namespace {

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
  if (const char* problem = text_encoding_problem(text)) throw Error(where + problem);
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
    if (!parse_double(t, d)) fail("expected a number, found " + quoted(t));
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

}  // namespace

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
  skip_bom(body);
  const auto first = body.find_first_not_of(" \t\r\n");
  if (first != std::string_view::npos && body.size() - first >= 5) {
    std::string head(body.substr(first, 5));
    for (auto& c : head) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    // A binary file whose header starts with "solid" has NUL bytes: it is reported as binary.
    if (head == "solid" && (text.size() < 84 || !text_encoding_problem(body)))
      return read_stl_ascii(where, body);
  }
  if (text.size() < 84)
    throw Error(where + "neither an ascii STL (no 'solid') nor a binary one (" + std::to_string(text.size()) +
                " bytes, shorter than the 84-byte header)");
  if (text.size() != need)  // shorter: cut; longer: a count written too small, not read in part
    throw Error(where + "the binary STL header declares " + std::to_string(count) + " triangles (" +
                std::to_string(need) + " bytes) but the file has " + (text.size() < need ? "only " : "") +
                std::to_string(text.size()) + " bytes (" +
                (text.size() < need ? std::string("corrupt or truncated file?)")
                                    : "room for " + std::to_string((text.size() - 84) / 50) +
                                          " triangles: a wrong triangle count?)"));
  return read_stl_binary(where, text, count);
}

}  // namespace section::detail
