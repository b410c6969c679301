// SPDX-License-Identifier: GPL-3.0-or-later
// Plain text tables outside the stream: CSV tables, 2D profiles, section planes.
#include "section/io/csv.h"

#include "io/stream_text.h"
#include "io/text.h"
#include "section/error.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

namespace section {

namespace {

using detail::parse_double;
using detail::stream_fail;
using detail::trim;

// Splits on commas or runs of blanks (detail::split_fields).
std::vector<std::string_view> fields_of(std::string_view line) {
  std::vector<std::string_view> out;
  detail::split_fields(line, [&](std::string_view f) {
    out.push_back(f);
    return true;
  });
  return out;
}

template <class F>
void for_each_line(std::string_view text, F&& f) {
  std::size_t pos = 0, line_no = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    ++line_no;
    std::string_view line = trim(text.substr(pos, end - pos));
    pos = end + 1;
    if (line.empty() || line[0] == '#') continue;
    f(line, line_no);
  }
}

}  // namespace

Table parse_csv(std::string_view text, const std::string& source) {
  Table t;
  t.name = source;
  if (const char* why = detail::text_encoding_problem(text)) throw Error("pipe: " + source + ": " + why);
  detail::skip_bom(text);
  bool header = false;
  for_each_line(text, [&](std::string_view line, std::size_t line_no) {
    const auto fields = fields_of(line);
    if (!header) {
      for (const auto& f : fields) {
        if (trim(f).empty()) stream_fail(source, line_no, "empty column name in the header");
        if (t.find_column(std::string(trim(f))) >= 0)
          stream_fail(source, line_no, "column '" + std::string(trim(f)) + "' appears twice in the header");
        t.columns.emplace_back(trim(f));
      }
      header = true;
      return;
    }
    if (fields.size() != t.columns.size())
      stream_fail(
          source, line_no,
          std::to_string(fields.size()) + " values for " + std::to_string(t.columns.size()) + " columns");
    for (std::size_t c = 0; c < fields.size(); ++c) {
      double v = 0;
      if (!parse_double(trim(fields[c]), v))
        stream_fail(source, line_no,
                    "column '" + t.columns[c] + "': expected a number, found '" +
                        std::string(fields[c].substr(0, 40)) + "'");
      if (!std::isfinite(v)) stream_fail(source, line_no, "column '" + t.columns[c] + "': non-finite value");
      t.values.push_back(v);
    }
  });
  if (!header) throw Error("pipe: " + source + ": empty table (no header row)");
  return t;
}

std::vector<Eigen::Vector2d> parse_profile(std::string_view text, const std::string& source) {
  std::vector<Eigen::Vector2d> points;
  std::set<std::pair<double, double>> seen;
  if (const char* why = detail::text_encoding_problem(text)) throw Error("pipe: " + source + ": " + why);
  detail::skip_bom(text);
  bool data = false;
  std::size_t cx = 0, cy = 1;  // x and y: the first two columns, unless a header names them
  // A header of 3 or more names, none of them x and y: which two are the profile is unknown.
  std::size_t unnamed_line = 0, unnamed_fields = 0;
  std::string unnamed;
  for_each_line(text, [&](std::string_view line, std::size_t line_no) {
    const auto fields = fields_of(line);
    double x = 0, y = 0;
    const bool numeric = fields.size() > std::max(cx, cy) && parse_double(trim(fields[cx]), x) &&
                         parse_double(trim(fields[cy]), y);
    if (!numeric) {
      if (!data) {  // a title line, or a header naming the columns x and y
        std::size_t hx = fields.size(), hy = fields.size();
        bool names = fields.size() >= 3;
        for (std::size_t c = 0; c < fields.size(); ++c) {
          const std::string name = detail::lower(std::string(trim(fields[c])));
          if (name == "x" || name == "\"x\"") hx = c;
          if (name == "y" || name == "\"y\"") hy = c;
          double v = 0;
          names = names && !parse_double(trim(fields[c]), v);
        }
        if (hx < fields.size() && hy < fields.size()) {
          cx = hx, cy = hy, unnamed_fields = 0;
        } else if (names) {
          unnamed_line = line_no, unnamed_fields = fields.size(), unnamed.clear();
          for (std::size_t c = 0; c < fields.size() && c < 6; ++c)
            unnamed += (c ? ", " : "") + std::string(trim(fields[c]).substr(0, 20));
          if (fields.size() > 6) unnamed += ", ...";
        }
        return;
      }
      stream_fail(source, line_no,
                  fields.size() <= std::max(cx, cy)
                      ? "expected x and y, found " + std::to_string(fields.size()) + " value(s)"
                      : "expected two numbers x, y, found '" + std::string(line.substr(0, 40)) + "'");
    }
    if (!data && unnamed_fields == fields.size())
      stream_fail(source, unnamed_line,
                  "the header names the columns " + unnamed +
                      " but none x and y: name the profile's two columns x and y (or give x y alone)");
    data = true;
    if (!std::isfinite(x) || !std::isfinite(y)) stream_fail(source, line_no, "non-finite coordinate");
    if (std::abs(x) > detail::max_coordinate || std::abs(y) > detail::max_coordinate)
      stream_fail(source, line_no, "coordinate beyond +-1e15 (corrupt file?)");
    // An exact copy of a point read before counts once (a closing point repeated, every line
    // written twice): kept, it doubled the point counts the fit's spans are sized by (a TE
    // radius 25 % off). A profile passes no point twice.
    if (seen.insert({x + 0.0, y + 0.0}).second) points.emplace_back(x, y);
  });
  if (points.empty()) throw Error("pipe: " + source + ": no profile points (expected lines of x y)");
  return points;
}

std::vector<Plane> parse_planes(std::string_view csv, const std::string& source) {
  const Table t = parse_csv(csv, source);
  const char* names[6] = {"origin_x", "origin_y", "origin_z", "normal_x", "normal_y", "normal_z"};
  std::size_t c[6];
  for (int k = 0; k < 6; ++k) {
    const long col = t.find_column(names[k]);
    if (col < 0) throw Error("slice: " + source + ": the planes file needs the column '" + names[k] + "'");
    c[k] = static_cast<std::size_t>(col);
  }
  std::vector<Plane> planes;
  for (std::size_t r = 0; r < t.rows(); ++r) {
    Plane p{{t.at(r, c[0]), t.at(r, c[1]), t.at(r, c[2])}, {t.at(r, c[3]), t.at(r, c[4]), t.at(r, c[5])}};
    const std::string plane =
        "slice: " + source + ": plane " + std::to_string(r) + " (data row " + std::to_string(r + 1) + ")";
    if (p.normal.isZero(0)) throw Error(plane + " has a zero normal");
    p.normal = usable_normal(p.normal);
    if (p.origin.cwiseAbs().maxCoeff() > detail::max_coordinate)
      throw Error(plane + " has an origin coordinate beyond +-1e15 (corrupt file?)");
    planes.push_back(p);
  }
  if (planes.empty()) throw Error("slice: " + source + ": no planes");
  return planes;
}

std::string format_csv(const Table& table) {
  // A partial row (a table built in memory) was left out without a word.
  if (const std::string why = detail::partial_rows(table); !why.empty())
    throw Error("csv: refusing to write table '" + table.name + "': " + why);
  std::string out;
  for (std::size_t c = 0; c < table.columns.size(); ++c) out += (c ? "," : "") + table.columns[c];
  out += '\n';
  for (std::size_t r = 0; r < table.rows(); ++r) {
    for (std::size_t c = 0; c < table.columns.size(); ++c) {
      if (c) out += ',';
      out += format_number(table.at(r, c));
    }
    out += '\n';
  }
  return out;
}

}  // namespace section
