// SPDX-License-Identifier: GPL-3.0-or-later
// The PCD cloud reader: PCL's Point Cloud Data format, version 0.7 (ascii and binary; a
// binary_compressed file is refused). Read from the format's documentation
// (pointclouds.org, "The PCD (Point Cloud Data) file format"): a text header of
// `KEY values` lines, FIELDS / SIZE / TYPE / COUNT describing a point's record, WIDTH x
// HEIGHT (= POINTS) points, then DATA ascii (one point a line) or binary (packed
// little-endian records). A NaN coordinate marks a point with no measurement (an
// organised cloud's hole): such points are dropped.
#include "io/cloud_readers.h"

#include "io/ply.h"
#include "io/text.h"
#include "section/error.h"

#include <cmath>
#include <cstring>

namespace section::detail {

namespace {

struct PcdHeader {
  std::vector<std::string> fields;
  std::vector<int> size, count;
  std::vector<char> kind;  // 'f', 'i' or 'u' (ply_scalar's kinds)
  unsigned long long points = 0;
  bool binary = false;
  std::size_t lines = 0;              // header lines, the DATA line included
  int column[3] = {-1, -1, -1};       // value index of x, y, z in an ascii line
  std::size_t offset[3] = {0, 0, 0};  // byte offset of x, y, z in a binary record
  std::size_t field[3] = {0, 0, 0};   // field index of x, y, z
  std::size_t record = 0;             // bytes per binary record
  std::size_t values = 0;             // values per ascii line
};

[[noreturn]] void fail(const std::string& name, const std::string& what) {
  throw Error("read_cloud: " + name + ": " + what);
}

// The numbers of a header line's values, each checked.
std::vector<int> header_numbers(const std::vector<std::string_view>& w, const std::string& name,
                                std::size_t line) {
  std::vector<int> out;
  for (std::size_t i = 1; i < w.size(); ++i) {
    int v = 0;
    if (!parse_integer(w[i], v) || v <= 0)
      fail_line(name, line,
                "PCD " + std::string(w[0]) + " value " + quoted(w[i]) + " is not a positive integer");
    out.push_back(v);
  }
  return out;
}

// Where x, y and z lie in a point, checked: sizes and types a PCD file may hold.
void locate_xyz(PcdHeader& h, const std::string& name) {
  const std::size_t n = h.fields.size();
  if (n == 0 || h.size.size() != n || h.kind.size() != n || h.count.size() != n)
    fail(name, "PCD header's FIELDS, SIZE, TYPE and COUNT do not name the same number of fields");
  for (std::size_t i = 0; i < n; ++i) {
    const int s = h.size[i];
    const bool ok = h.kind[i] == 'f' ? (s == 4 || s == 8) : (s == 1 || s == 2 || s == 4);
    for (int c = 0; c < 3; ++c)
      if (h.fields[i].size() == 1 && h.fields[i][0] == char('x' + c)) {
        if (!ok)
          fail(name, "PCD field '" + h.fields[i] + "' of SIZE " + std::to_string(s) + " TYPE " +
                         std::string(1, char(std::toupper(h.kind[i]))) + " cannot be read");
        h.column[c] = static_cast<int>(h.values);
        h.field[c] = i;
        h.offset[c] = h.record;
      }
    h.record += static_cast<std::size_t>(s) * static_cast<std::size_t>(h.count[i]);
    h.values += static_cast<std::size_t>(h.count[i]);
  }
  if (h.column[0] < 0 || h.column[1] < 0 || h.column[2] < 0) fail(name, "PCD FIELDS lack x, y or z");
}

// Reads one header line's key and values into `h`; true at the DATA line.
bool header_line(PcdHeader& h, const std::vector<std::string_view>& w, const std::string& name,
                 unsigned long long& width, unsigned long long& height) {
  const std::string key = lower(std::string(w[0]));
  const std::size_t line = h.lines;
  if (key == "fields") {
    for (std::size_t i = 1; i < w.size(); ++i) h.fields.emplace_back(lower(std::string(w[i])));
  } else if (key == "size") {
    h.size = header_numbers(w, name, line);
  } else if (key == "count") {
    h.count = header_numbers(w, name, line);
  } else if (key == "type") {
    for (std::size_t i = 1; i < w.size(); ++i) {
      if (w[i].size() != 1 || std::string_view("FIUfiu").find(w[i][0]) == std::string_view::npos)
        fail_line(name, line, "PCD TYPE " + quoted(w[i]) + " is not F, I or U");
      h.kind.push_back(char(std::tolower(w[i][0])));
    }
  } else if (key == "width" || key == "height" || key == "points") {
    unsigned long long v = 0;
    if (w.size() != 2 || !parse_integer(w[1], v)) fail_line(name, line, "PCD " + key + " needs one integer");
    (key == "width" ? width : key == "height" ? height : h.points) = v;
  } else if (key == "data") {
    const std::string kind = w.size() == 2 ? lower(std::string(w[1])) : "";
    if (kind == "binary_compressed")
      fail(name,
           "PCD DATA binary_compressed is not supported: save it as binary or ascii "
           "(pcl_convert_pcd_ascii_binary)");
    if (kind != "ascii" && kind != "binary")
      fail_line(name, line, "PCD DATA must be ascii or binary, found " + quoted(w.size() > 1 ? w[1] : ""));
    h.binary = kind == "binary";
    return true;
  } else if (key != "version" && key != "viewpoint") {
    fail_line(name, line, "unknown PCD header line " + quoted(w[0]));
  }
  return false;
}

// The header, up to and including the DATA line (consumed from `src`).
PcdHeader read_header(ByteSource& src, const CloudReadOptions& opt) {
  const std::string& name = src.name();
  PcdHeader h;
  unsigned long long width = 0, height = 1;
  std::string_view line;
  std::vector<std::string_view> w;
  bool data = false;
  while (!data) {
    if (!src.next_line(line, max_line)) fail(name, "PCD header ends before its DATA line (truncated file?)");
    ++h.lines;
    split_words(line, w);
    if (w.empty() || w[0][0] == '#') continue;
    data = header_line(h, w, name, width, height);
  }
  if (h.count.empty()) h.count.assign(h.fields.size(), 1);
  locate_xyz(h, name);
  if (h.points == 0) h.points = width * height;
  if (h.points != width * height)
    fail(name, "PCD POINTS " + std::to_string(h.points) +
                   " is not WIDTH x HEIGHT = " + std::to_string(width * height));
  if (h.points == 0) fail(name, "no points (PCD header declares 0 points)");
  if (h.points > opt.max_points)
    fail(name, "PCD header declares " + std::to_string(h.points) + " points, more than the limit of " +
                   std::to_string(opt.max_points));
  return h;
}

// Adds a point unless it has a NaN coordinate (no measurement); throws on an infinite one.
void add_point(Chunker& out, const double v[3], unsigned long long k, const std::string& name) {
  if (std::isnan(v[0]) || std::isnan(v[1]) || std::isnan(v[2])) return;
  if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
    fail(name, "point " + std::to_string(k + 1) + " has an infinite coordinate");
  out.add(v[0], v[1], v[2]);
}

void read_ascii(ByteSource& src, const PcdHeader& h, Chunker& out) {
  const std::string& name = src.name();
  std::size_t line_no = h.lines;
  unsigned long long done = 0;
  std::string_view line;
  std::vector<std::string_view> w;
  while (src.next_line(line, max_line)) {
    ++line_no;
    if (line.size() >= max_line && line.back() != '\n')
      fail_line(name, line_no, "line longer than " + std::to_string(max_line) + " characters");
    split_words(line, w);
    if (w.empty()) continue;
    if (done == h.points)
      fail_line(name, line_no, "more points than the PCD header declares (" + std::to_string(h.points) + ")");
    if (w.size() != h.values)
      fail_line(name, line_no,
                "expected " + std::to_string(h.values) + " values, found " + std::to_string(w.size()));
    double v[3];
    for (int c = 0; c < 3; ++c)
      if (!parse_double(w[static_cast<std::size_t>(h.column[c])], v[c]))
        fail_line(name, line_no,
                  "expected a number, found " + quoted(w[static_cast<std::size_t>(h.column[c])]));
    add_point(out, v, done++, name);
  }
  if (done < h.points)
    fail(name, "PCD file ends after " + std::to_string(done) + " of " + std::to_string(h.points) +
                   " points (truncated file?)");
}

void read_binary(ByteSource& src, const PcdHeader& h, Chunker& out) {
  const std::string& name = src.name();
  const unsigned long long bytes = h.points * h.record;
  if (src.size() >= 0) {
    const unsigned long long body = static_cast<unsigned long long>(src.size()) - src.offset();
    if (body < bytes)
      fail(name, "PCD header declares " + std::to_string(h.points) + " points but the file holds only " +
                     std::to_string(body / h.record) + " (truncated file?)");
    if (body > bytes)
      fail(name, "the file holds " + std::to_string(body - bytes) +
                     " bytes more than its PCD header declares (" + std::to_string(h.points) +
                     " points): a wrong point count?");
  }
  unsigned long long done = 0;
  while (done < h.points) {
    std::size_t n = static_cast<std::size_t>(
        std::min<unsigned long long>(src.bytes().size() / h.record, h.points - done));
    if (n == 0) {
      if (src.fetch(std::max<std::size_t>(h.record, block_size)) == 0)
        fail(name, "PCD file ends after " + std::to_string(done) + " of " + std::to_string(h.points) +
                       " points (truncated file?)");
      continue;
    }
    const auto* r = reinterpret_cast<const unsigned char*>(src.bytes().data());
    for (std::size_t k = 0; k < n; ++k, r += h.record) {
      double v[3];
      for (int c = 0; c < 3; ++c)
        v[c] = ply_scalar(r + h.offset[c], h.size[h.field[c]], h.kind[h.field[c]], false);
      add_point(out, v, done + k, name);
    }
    done += n;
    src.consume(n * h.record);
  }
}

}  // namespace

std::size_t read_pcd_cloud(ByteSource& src, const CloudReadOptions& opt, const PointChunkFn& fn,
                           const PointChunkFn&) {
  const PcdHeader h = read_header(src, opt);
  Chunker out(fn, opt.chunk_points);
  if (h.binary)
    read_binary(src, h, out);
  else
    read_ascii(src, h, out);
  out.flush();
  if (out.total() == 0) fail(src.name(), "no points (every PCD point has a NaN coordinate)");
  return out.total();
}

}  // namespace section::detail
