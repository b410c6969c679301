// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/ply.h"

#include "io/text.h"
#include "section/error.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string_view>

namespace section::detail {

namespace {

// Size in bytes and kind of a PLY scalar type name (the classic and the sized spellings);
// false for an unknown name.
bool ply_type(std::string_view t, int& size, char& kind) {
  static const struct {
    const char* name;
    int size;
    char kind;
  } types[] = {{"char", 1, 'i'},  {"int8", 1, 'i'},    {"uchar", 1, 'u'},  {"uint8", 1, 'u'},
               {"short", 2, 'i'}, {"int16", 2, 'i'},   {"ushort", 2, 'u'}, {"uint16", 2, 'u'},
               {"int", 4, 'i'},   {"int32", 4, 'i'},   {"uint", 4, 'u'},   {"uint32", 4, 'u'},
               {"float", 4, 'f'}, {"float32", 4, 'f'}, {"double", 8, 'f'}, {"float64", 8, 'f'}};
  for (const auto& e : types)
    if (t == e.name) {
      size = e.size;
      kind = e.kind;
      return true;
    }
  return false;
}

bool host_little_endian() {
  const std::uint16_t one = 1;
  unsigned char c;
  std::memcpy(&c, &one, 1);
  return c == 1;
}

// The next header line from `pos` on, fetching more of `src` as needed (its '\n' left out);
// false when the bytes end first. `file` starts the message of a header over 1 MiB.
bool header_line(ByteSource& src, std::size_t& pos, std::string_view& line, const std::string& file) {
  std::string_view buf = src.bytes();
  std::size_t nl = buf.find('\n', pos);
  while (nl == std::string_view::npos) {
    if (buf.size() > (1 << 20)) throw Error(file + "PLY header longer than 1 MiB");
    if (src.fetch(1 << 16) == 0) return false;
    buf = src.bytes();
    nl = buf.find('\n', pos);
  }
  line = buf.substr(pos, nl - pos);
  pos = nl + 1;
  return true;
}

// Decodes the lines of one header, naming their place as the reader's messages do.
class HeaderDecoder {
public:
  HeaderDecoder(const std::string& name, const PlyMessages& m) : name_(name), m_(m) {}

  Error at(std::size_t line, const std::string& what) const {
    const std::string n = std::to_string(line);
    return Error(m_.line_words ? m_.component + name_ + ": line " + n + ": " + what
                               : m_.component + name_ + ":" + n + ": " + what);
  }
  Error file(const std::string& what) const { return Error(m_.component + name_ + ": " + what); }

  // One line past the first; false at end_header.
  bool line(const std::vector<std::string_view>& w, std::size_t line_no, PlyHeader& h,
            bool& format_seen) const {
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") return true;
    if (w[0] == "end_header") return false;
    if (w[0] == "format") {
      if (w.size() < 2) throw at(line_no, "bad format line");
      if (w[1] == "ascii")
        h.format = PlyFormat::ascii;
      else if (w[1] == "binary_little_endian")
        h.format = PlyFormat::binary_le;
      else if (w[1] == "binary_big_endian")
        h.format = PlyFormat::binary_be;
      else
        throw at(line_no, "unknown PLY format " + quoted(w[1]));
      format_seen = true;
    } else if (w[0] == "element") {
      if (w.size() < 3) throw at(line_no, "bad element line");
      PlyElement e;
      e.name = std::string(w[1]);
      if (!parse_integer(w[2], e.count)) throw at(line_no, "bad element count " + quoted(w[2]));
      h.elements.push_back(e);
    } else if (w[0] == "property") {
      if (h.elements.empty()) throw at(line_no, "property before any element");
      h.elements.back().props.push_back(property(w, line_no));
    } else if (std::any_of(w[0].begin(), w[0].end(), [](char c) { return c < 0x20 || c > 0x7e; })) {
      // (not the bytes themselves: they are no use to read, and they garble a terminal)
      throw at(line_no, "binary data where a PLY header line should be (a header without end_header?)");
    } else {
      throw at(line_no, "unexpected PLY header line starting " + quoted(w[0]));
    }
    return true;
  }

private:
  // `property TYPE NAME` or `property list COUNT_TYPE TYPE NAME`.
  PlyProperty property(const std::vector<std::string_view>& w, std::size_t line_no) const {
    PlyProperty p;
    const bool list = w.size() >= 2 && w[1] == "list";
    if (w.size() < (list ? 5u : 3u)) throw at(line_no, "bad property line");
    if (list && !ply_type(w[2], p.count_size, p.count_kind))
      throw at(line_no, "unknown property type " + quoted(w[2]));
    if (list) p.count_type = std::string(w[2]);
    const std::string_view type = w[list ? 3 : 1];
    if (!ply_type(type, p.size, p.kind)) throw at(line_no, "unknown property type " + quoted(type));
    p.name = std::string(w[list ? 4 : 2]);
    p.line = line_no;
    return p;
  }

  const std::string& name_;
  const PlyMessages& m_;
};

}  // namespace

bool PlyHeader::swap() const {
  return (format == PlyFormat::binary_le) != host_little_endian();
}

PlyHeader read_ply_header(ByteSource& src, const PlyMessages& messages) {
  const HeaderDecoder decode(src.name(), messages);
  const std::string file = messages.component + src.name() + ": ";
  PlyHeader h;
  std::size_t pos = 0;
  bool format_seen = false;
  std::string_view line;
  std::vector<std::string_view> words;
  while (true) {
    if (!header_line(src, pos, line, file)) throw decode.file("truncated PLY header (no end_header)");
    split_words(line, words);
    ++h.lines;
    if (h.lines > 1) {
      if (!decode.line(words, h.lines, h, format_seen)) break;
    } else if (words.size() != 1 || words[0] != "ply") {
      // (the mesh readers' message has no line number)
      const std::string what = "not a PLY file (no 'ply' magic)";
      throw messages.line_words ? decode.file(what) : decode.at(1, what);
    }
  }
  if (!format_seen) throw decode.file("PLY header without a format line");
  h.bytes = pos;
  return h;
}

bool ply_declares_faces(ByteSource& src) {
  bool faces = false;
  try {
    std::size_t pos = 0;
    std::string_view line;
    std::vector<std::string_view> w;
    for (int n = 0; n < 200 && header_line(src, pos, line, ""); ++n) {
      split_words(line, w);
      if (!w.empty() && w[0] == "end_header") break;
      unsigned long long count = 0;
      if (w.size() >= 3 && w[0] == "element" && w[1] == "face" && parse_integer(w[2], count) && count > 0)
        faces = true;
    }
  } catch (const Error&) {
  }
  return faces;
}

double ply_scalar(const unsigned char* p, int size, char kind, bool swap) {
  unsigned char b[8];
  std::memcpy(b, p, static_cast<std::size_t>(size));
  if (swap) std::reverse(b, b + size);
  const auto as = [&](auto v) {
    std::memcpy(&v, b, sizeof v);
    return static_cast<double>(v);
  };
  if (kind == 'f') return size == 4 ? as(float()) : as(double());
  if (kind == 'i') return size == 1 ? as(std::int8_t()) : size == 2 ? as(std::int16_t()) : as(std::int32_t());
  return size == 1 ? as(std::uint8_t()) : size == 2 ? as(std::uint16_t()) : as(std::uint32_t());
}

}  // namespace section::detail
