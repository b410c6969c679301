// SPDX-License-Identifier: GPL-3.0-or-later
// The XYZ and CSV cloud readers: one point a line, parsed in pieces by all cores.
#include "io/cloud_readers.h"

#include "detail/parallel.h"
#include "io/text.h"
#include "section/error.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <string_view>

namespace section::detail {

namespace {

struct TextState {
  bool csv_header_seen = false;
  int cx = 0, cy = 1, cz = 2;  // columns of x, y, z
  int needed = 3;              // columns a row must have at least
  bool require_header = false;
  bool pts = false;  // a line holding one integer is a PTS count line
  bool dat = false;  // a first line of two whole numbers is T-Blade3's `POINTS SECTIONS`
  unsigned long long dat_points = 0, dat_sections = 0;  // that line's counts (0: none)
  bool semicolon = false;  // ';' separates the cells and ',' is a decimal comma (first data line holds a ';')
  bool decimal_comma = false;  // blanks separate the cells and ',' is a decimal comma (decimal_commas)
};

// A first data row of blank-separated cells whose first three each hold one comma between
// digits, and no '.' anywhere ("18,450 -3,589 25,111", a European export): its commas are
// decimal commas. Read as separators, that row was the six numbers 18 450 -3 589 25 111,
// and a scan the garbage x = 18, y = 450, z = -3, which slice cut into a "section".
bool decimal_commas(std::string_view line) {
  if (line.find_first_of(".;") != std::string_view::npos) return false;
  const auto digit = [](char c) { return c >= '0' && c <= '9'; };
  int cells = 0;
  for (std::size_t i = 0; i < line.size() && cells < 3;) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    if (i == line.size()) break;
    std::size_t end = i;
    while (end < line.size() && line[end] != ' ' && line[end] != '\t') ++end;
    const std::string_view cell = line.substr(i, end - i);
    const std::size_t c = cell.find(',');
    if (c == std::string_view::npos || c == 0 || c + 1 == cell.size() || !digit(cell[c - 1]) ||
        !digit(cell[c + 1]) || cell.find(',', c + 1) != std::string_view::npos)
      return false;
    ++cells;
    i = end;
  }
  return cells == 3;
}

// Splits a line into at most `max_fields` fields (split_fields; at each ';' when
// `semicolon`, at blanks only when `decimal_comma`); returns the count.
int split_row(std::string_view line, std::string_view* fields, int max_fields, bool semicolon,
              bool decimal_comma = false) {
  int n = 0;
  if (decimal_comma) {
    for (std::size_t i = 0; i < line.size() && n < max_fields;) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
      const std::size_t start = i;
      while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
      if (i > start) fields[n++] = line.substr(start, i - start);
    }
    return n;
  }
  if (semicolon) {
    for (std::size_t at = 0; n < max_fields;) {
      const std::size_t end = std::min(line.find(';', at), line.size());
      fields[n++] = trim(line.substr(at, end - at));
      if (end == line.size()) break;
      at = end + 1;
    }
    return n;
  }
  split_fields(line, [&](std::string_view f) {
    fields[n++] = f;
    return n < max_fields;
  });
  return n;
}

std::string unquote(std::string_view s) {
  s = trim(s);
  if (s.size() >= 2 && (s.front() == '"' || s.front() == '\'') && s.back() == s.front())
    s = s.substr(1, s.size() - 2);
  return lower(std::string(s));
}

// Parses a cell; with `semicolon`, a ',' in it is the decimal point ("1,5" is 1.5).
bool parse_cell(std::string_view cell, double& v, bool semicolon) {
  if (!semicolon || cell.find(',') == std::string_view::npos || cell.size() > 64)
    return parse_double(cell, v);
  char buf[64];
  std::copy(cell.begin(), cell.end(), buf);
  std::replace(buf, buf + cell.size(), ',', '.');
  return parse_double({buf, cell.size()}, v);
}

bool try_header(std::string_view line, TextState& st) {
  std::string_view f[64];
  const int n = split_row(line, f, 64, st.semicolon);
  int cx = -1, cy = -1, cz = -1;
  for (int i = 0; i < n; ++i) {
    const std::string name = unquote(f[i]);
    if (name == "x" || name == "//x") cx = i;
    if (name == "y") cy = i;
    if (name == "z") cz = i;
  }
  if (cx < 0 || cy < 0 || cz < 0) return false;
  st.cx = cx;
  st.cy = cy;
  st.cz = cz;
  st.needed = std::max({cx, cy, cz}) + 1;
  st.csv_header_seen = true;
  return true;
}

// T-Blade3's count line: two whole numbers, the points of a section and the sections
// (`241 21`), each under 2^31 so that their product cannot overflow.
bool dat_count_line(std::string_view line, TextState& st) {
  std::string_view f[3];
  const int n = split_row(line, f, 3, false);
  unsigned long long points = 0, sections = 0;
  const unsigned long long most = 1ull << 31;
  if (n != 2 || !parse_integer(trim(f[0]), points) || !parse_integer(trim(f[1]), sections) || points == 0 ||
      sections == 0 || points >= most || sections >= most)
    return false;
  st.dat_points = points;
  st.dat_sections = sections;
  return true;
}

template <class Out>
void parse_text_line(std::string_view line, std::size_t line_no, TextState& st, const std::string& name,
                     Out& out, bool& first_data) {
  line = trim(line);
  if (line.empty() || line[0] == '#' || (line.size() > 1 && line[0] == '/' && line[1] == '/')) return;
  unsigned long long count = 0;
  if (st.pts && line.find_first_of(" \t,;") == std::string_view::npos && parse_integer(line, count)) {
    out.declare(count);
    return;
  }
  if (first_data && st.dat && st.dat_sections == 0 && dat_count_line(line, st)) {
    out.declare(st.dat_points * st.dat_sections);
    return;
  }
  if (first_data) {
    first_data = false;
    st.semicolon = line.find(';') != std::string_view::npos;
    st.decimal_comma = decimal_commas(line);
    double tmp;
    std::string_view f[64];
    const bool comma = st.semicolon || st.decimal_comma;
    const int n = split_row(line, f, 64, st.semicolon, st.decimal_comma);
    if (n == 0 || !parse_cell(trim(f[0]), tmp, comma) || (st.require_header && !st.csv_header_seen)) {
      if (try_header(line, st)) {
        first_data = true;  // the row after the header says how its numbers are written
        return;
      }
      if (st.require_header)
        fail_line(name, line_no, "a CSV cloud needs a header row naming the x, y and z columns");
      if (n > 0 && !parse_cell(trim(f[0]), tmp, comma))
        fail_line(name, line_no,
                  "expected a number in column 1, found '" + std::string(trim(f[0]).substr(0, 40)) +
                      "' (a header row must name x, y and z columns)");
    }
  }
  std::string_view f[64];
  const int n = split_row(line, f, std::min(64, st.needed), st.semicolon, st.decimal_comma);
  if (n < st.needed)
    fail_line(name, line_no,
              "expected at least " + std::to_string(st.needed) + " columns, found " + std::to_string(n));
  double v[3];
  const int cols[3] = {st.cx, st.cy, st.cz};
  for (int k = 0; k < 3; ++k) {
    const std::string_view cell = trim(f[cols[k]]);
    if (!parse_cell(cell, v[k], st.semicolon || st.decimal_comma))
      fail_line(name, line_no,
                "expected a number in column " + std::to_string(cols[k] + 1) + ", found '" +
                    std::string(cell.substr(0, 40)) + "'");
    if (!std::isfinite(v[k]))
      fail_line(name, line_no,
                "non-finite coordinate '" + std::string(cell) + "' in column " + std::to_string(cols[k] + 1));
  }
  out.add(v[0], v[1], v[2]);
}

// The common row "x y z [more columns]" (blank or comma separated) parsed without
// splitting it into fields. True only when parse_text_line would read the same three
// values; anything unusual (comment, header, bad cell, non-finite value, a '\r' inside the
// row) returns false and the line goes to parse_text_line, which also words the error.
inline bool parse_xyz_fast(const char* p, const char* e, double* v) {
  for (int k = 0; k < 3; ++k) {
    while (p < e && (*p == ' ' || *p == '\t')) ++p;
    if (k > 0 && p < e && *p == ',') {
      ++p;
      while (p < e && (*p == ' ' || *p == '\t')) ++p;
    }
    if (p < e && *p == '+') ++p;
    const auto r = std::from_chars(p, e, v[k]);
    if (r.ec != std::errc() || !std::isfinite(v[k])) return false;
    p = r.ptr;
    // The cell must end here: at a separator, or (the last one) at the end of the line.
    if (p == e) return k == 2;
    if (*p == ' ' || *p == '\t' || *p == ',') continue;
    return k == 2 && *p == '\r' && p + 1 == e;
  }
  return true;
}

// Parses the complete lines buf[begin, end) (end just after a '\n') past the first data
// line; `line_no` counts the lines. Throws at the first bad line.
template <class Out>
void parse_text_lines(std::string_view buf, std::size_t begin, std::size_t end, std::size_t& line_no,
                      TextState& st, const std::string& name, Out& out) {
  const bool plain = st.cx == 0 && st.cy == 1 && st.cz == 2 && !st.semicolon && !st.decimal_comma;
  const char* p = buf.data() + begin;
  const char* const stop = buf.data() + end;
  bool first_data = false;
  while (p < stop) {
    const char* nl = static_cast<const char*>(std::memchr(p, '\n', std::size_t(stop - p)));
    ++line_no;
    if (std::size_t(nl - p) > max_line)
      fail_line(name, line_no, "line longer than " + std::to_string(max_line) + " characters");
    double v[3];
    if (plain && parse_xyz_fast(p, nl, v))
      out.add(v[0], v[1], v[2]);
    else
      parse_text_line(std::string_view(p, std::size_t(nl - p)), line_no, st, name, out, first_data);
    p = nl + 1;
  }
}

// Points of one piece of a text block, parsed by one worker.
struct PieceOut {
  std::vector<Eigen::Vector3d> points;
  std::size_t lines = 0;  // lines of the piece (all of them unless it failed)
  bool failed = false;    // a line is malformed: the piece is parsed again, in order, for the message
  unsigned long long declared = 0;  // points the PTS count lines of the piece declare
  void add(double x, double y, double z) { points.emplace_back(x, y, z); }
  void declare(unsigned long long n) { declared += n; }
};

// The points of a text cloud in chunks, and the points its PTS count lines declare.
struct TextOut {
  Chunker chunks;
  unsigned long long declared = 0;
  bool counted = false;  // a count line was seen
  void add(double x, double y, double z) { chunks.add(x, y, z); }
  void declare(unsigned long long n) {
    declared += n;
    counted = true;
  }
};

// Parses the complete lines buf[begin, end) (end just after a '\n'; the first data line
// already seen, so the state is read-only) split at line boundaries across threads.
// Points reach `out` in file order and the error thrown is that of the first bad line, as
// if parsed line by line: `line_no` is the number of lines before `begin`.
// `parts` is kept from block to block so that its buffers are reused, not faulted in anew.
void parse_text_block(std::string_view buf, std::size_t begin, std::size_t end, std::size_t& line_no,
                      const TextState& st, const std::string& name, const CloudReadOptions& opt, TextOut& out,
                      std::vector<PieceOut>& parts) {
  const std::size_t bytes = end - begin;
  std::size_t pieces = worker_count(opt.threads);
  pieces = std::max<std::size_t>(1, std::min(pieces * 4, bytes / (1 << 18)));  // >= 256 KiB each
  std::vector<std::size_t> cut{begin};
  for (std::size_t k = 1; k < pieces; ++k) {
    std::size_t at = begin + bytes * k / pieces;
    if (at <= cut.back()) continue;
    const std::size_t nl = buf.find('\n', at - 1);
    if (nl == std::string_view::npos || nl + 1 >= end) break;
    if (nl + 1 > cut.back()) cut.push_back(nl + 1);
  }
  cut.push_back(end);
  const std::size_t n = cut.size() - 1;
  // Each piece counts its own lines; line numbers are only needed for a message, so a
  // failed piece is parsed again once the lines before it are known.
  if (parts.size() < n) parts.resize(n);
  detail::parallel_for(n, opt.threads, [&](std::size_t k) {
    PieceOut& part = parts[k];
    part.points.clear();
    part.lines = 0;
    part.failed = false;
    part.declared = 0;
    part.points.reserve((cut[k + 1] - cut[k]) / 24);
    TextState local = st;
    try {
      parse_text_lines(buf, cut[k], cut[k + 1], part.lines, local, name, part);
    } catch (...) {
      part.failed = true;
    }
  });
  for (std::size_t k = 0; k < n; ++k) {
    if (parts[k].failed) {
      PieceOut again;
      TextState local = st;
      parse_text_lines(buf, cut[k], cut[k + 1], line_no, local, name, again);  // throws
    }
    if (out.chunks.total() + parts[k].points.size() > opt.max_points)
      throw Error("read_cloud: " + name + ": more than " + std::to_string(opt.max_points) + " points");
    out.chunks.add_many(parts[k].points.data(), parts[k].points.size());
    if (parts[k].declared) out.declare(parts[k].declared);
    line_no += parts[k].lines;
  }
}

enum class TextKind { xyz, csv, pts, dat };

std::size_t read_text(ByteSource& src, TextKind kind, const CloudReadOptions& opt, const PointChunkFn& fn) {
  TextOut out{Chunker(fn, opt.chunk_points)};
  TextState st;
  st.require_header = kind == TextKind::csv;
  st.pts = kind == TextKind::pts;
  st.dat = kind == TextKind::dat;
  bool first_data = true;
  std::size_t line_no = 0;
  std::vector<PieceOut> parts;
  // Parses the complete lines of `b`; returns the bytes used.
  const auto parse = [&](std::string_view b) {
    std::size_t used = 0, nl;
    // Line by line up to the first data line (it decides the header), then in parallel.
    while (first_data && (nl = b.find('\n', used)) != std::string_view::npos) {
      ++line_no;
      if (nl - used > max_line)
        fail_line(src.name(), line_no, "line longer than " + std::to_string(max_line) + " characters");
      parse_text_line(b.substr(used, nl - used), line_no, st, src.name(), out, first_data);
      if (out.chunks.total() > opt.max_points)
        throw Error("read_cloud: " + src.name() + ": more than " + std::to_string(opt.max_points) +
                    " points");
      used = nl + 1;
    }
    if (!first_data) {
      const std::size_t last = b.rfind('\n');
      if (last != std::string_view::npos && last >= used) {
        parse_text_block(b, used, last + 1, line_no, st, src.name(), opt, out, parts);
        used = last + 1;
      }
    }
    return used;
  };
  while (true) {
    src.consume(parse(src.bytes()));
    if (src.bytes().size() > max_line)
      fail_line(src.name(), line_no + 1, "line longer than " + std::to_string(max_line) + " characters");
    if (src.fetch(block_size) == 0) break;
  }
  if (!src.bytes().empty()) {
    // The last line has no '\n': parse a copy that has one.
    std::string last(src.bytes());
    last.push_back('\n');
    parse(last);
  }
  out.chunks.flush();
  const std::size_t total = out.chunks.total();
  if (st.dat_sections > 0 && out.declared != total)
    throw Error("read_cloud: " + src.name() + ": its count line `" + std::to_string(st.dat_points) + " " +
                std::to_string(st.dat_sections) + "` (points a section, sections) declares " +
                std::to_string(out.declared) + " points, the file holds " + std::to_string(total) +
                " (truncated file or wrong count?)");
  if (out.counted && out.declared != total)
    throw Error("read_cloud: " + src.name() + ": its PTS count lines declare " +
                std::to_string(out.declared) + " points, the file holds " + std::to_string(total) +
                " (truncated file or wrong count?)");
  if (total == 0) throw Error("read_cloud: " + src.name() + ": no points");
  return total;
}

}  // namespace

std::size_t read_xyz_cloud(ByteSource& src, const CloudReadOptions& opt, const PointChunkFn& fn,
                           const PointChunkFn&) {
  return read_text(src, TextKind::xyz, opt, fn);
}

std::size_t read_pts_cloud(ByteSource& src, const CloudReadOptions& opt, const PointChunkFn& fn,
                           const PointChunkFn&) {
  return read_text(src, TextKind::pts, opt, fn);
}

std::size_t read_csv_cloud(ByteSource& src, const CloudReadOptions& opt, const PointChunkFn& fn,
                           const PointChunkFn&) {
  return read_text(src, TextKind::csv, opt, fn);
}

std::size_t read_dat_cloud(ByteSource& src, const CloudReadOptions& opt, const PointChunkFn& fn,
                           const PointChunkFn&) {
  return read_text(src, TextKind::dat, opt, fn);
}

}  // namespace section::detail
