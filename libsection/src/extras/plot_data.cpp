// SPDX-License-Identifier: GPL-3.0-or-later
// What the stream holds of a section, in the plot's terms, and the text helpers of the
// drawing: see plot_parts.h.
#include "plot_parts.h"

#include "io/text.h"
#include "section/checks.h"
#include "section/error.h"
#include "section/fit_spline.h"
#include "section/io/stream.h"
#include "section/pipe/fit_spline_stream.h"
#include "section/pipe/schema.h"

#include <charconv>

namespace section::detail::plot {

std::string fixed(double value, int decimals) {
  char buf[400];  // room for the largest double in fixed notation (309 digits) and its decimals
  const auto r = std::to_chars(buf, buf + sizeof buf, value, std::chars_format::fixed, decimals);
  if (r.ec != std::errc()) return "?";  // never the buffer's bytes
  std::string s(buf, r.ptr);
  if (s == "-0" || (s.rfind("-0.", 0) == 0 && s.find_first_not_of("0.", 1) == std::string::npos))
    s.erase(0, 1);  // no "-0.00"
  return s;
}

std::string trimmed(double value, int decimals) {
  std::string s = fixed(value, decimals);
  if (s.find('.') != std::string::npos) {
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
  }
  return s;
}

std::string escape(const std::string& text) {
  std::string out;
  for (char c : detail::well_formed_utf8(text)) {  // XML is UTF-8 without control characters
    if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n') {
      out += "\xEF\xBF\xBD";
      continue;
    }
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

double text_width(const std::string& text, double font) {
  std::size_t glyphs = 0;
  for (unsigned char c : text) glyphs += (c & 0xC0) != 0x80;  // UTF-8 lead bytes
  return 0.62 * font * static_cast<double>(glyphs);
}

std::vector<std::string> wrap(const std::string& text, double width, double font) {
  const auto most = static_cast<std::size_t>(std::max(8.0, width / (0.62 * font)));
  std::vector<std::string> lines;
  std::string line;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find(' ', start);
    if (end == std::string::npos) end = text.size();
    std::string word = text.substr(start, end - start);
    start = end + 1;
    while (text_width(word, font) > width + 1e-9 && word.size() > most) {  // a word longer than a line
      if (!line.empty()) lines.push_back(std::move(line));
      line.clear();
      lines.push_back(word.substr(0, most));
      word.erase(0, most);
    }
    const std::string joined = line.empty() ? word : line + " " + word;
    if (!line.empty() && text_width(joined, font) > width) {
      lines.push_back(std::move(line));
      line = word;
    } else {
      line = joined;
    }
  }
  if (!line.empty()) lines.push_back(std::move(line));
  return lines;
}

std::string length_text(double length, const std::string& units) {
  return fixed(length, 4) + " " + units;
}

// Rows of table `name` for `section`, the wanted columns in order (NaN where the column
// is absent), sorted by (loop or side, index) when those columns exist.
std::vector<std::vector<double>> rows_of(const Stream& stream, const std::string& name, int section,
                                         const std::vector<std::string>& columns) {
  std::vector<std::vector<double>> out;
  const Table* t = stream.find(name);
  if (!t) return out;
  const long cs = t->find_column("section");
  if (cs < 0) return out;
  long group = t->find_column("loop");
  if (group < 0) group = t->find_column("side");
  const long index = t->find_column("index");
  std::vector<long> cols;
  for (const auto& c : columns) cols.push_back(t->find_column(c));
  std::vector<std::pair<std::pair<double, double>, std::size_t>> order;
  for (std::size_t r = 0; r < t->rows(); ++r)
    if (t->at(r, cs) == section)
      order.push_back({{group >= 0 ? t->at(r, group) : 0.0, index >= 0 ? t->at(r, index) : double(r)}, r});
  std::stable_sort(order.begin(), order.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [key, r] : order) {
    std::vector<double> row;
    for (long c : cols) row.push_back(c >= 0 ? t->at(r, c) : nan);
    out.push_back(std::move(row));
  }
  return out;
}

namespace {

std::map<int, std::vector<V2>> loops_of(const Stream& stream, const std::string& name, int section) {
  std::map<int, std::vector<V2>> out;
  for (const auto& row : rows_of(stream, name, section, {"loop", "u", "v"})) {
    const V2 p(row[1], row[2]);
    if (finite(p)) out[std::isfinite(row[0]) ? static_cast<int>(row[0]) : 0].push_back(p);
  }
  return out;
}

std::map<std::string, double> row_map(const Stream& stream, const std::string& name, int section, int loop) {
  std::map<std::string, double> out;
  const Table* t = stream.find(name);
  if (!t) return out;
  const long cs = t->find_column("section"), cl = t->find_column("loop");
  if (cs < 0) return out;
  for (std::size_t r = 0; r < t->rows(); ++r) {
    if (t->at(r, cs) != section || (cl >= 0 && t->at(r, cl) != loop)) continue;
    for (std::size_t c = 0; c < t->columns.size(); ++c) out[t->columns[c]] = t->at(r, c);
    break;
  }
  return out;
}

}  // namespace

Curves read_curves(const Stream& stream) {
  Curves c;
  if (!stream.find("splines") || !stream.find("spline_knots") || !stream.find("spline_ctrl")) return c;
  try {
    c.splines = splines(stream);
  } catch (const Error& e) {
    c.error = e.what();
  }
  return c;
}

SectionData collect(const Stream& stream, int section, const Curves& curves) {
  SectionData d;
  d.id = section;
  d.units = stream.units;
  if (stream.find("frames")) {
    try {
      const auto f = frames(stream);
      if (const auto it = f.find(section); it != f.end()) {
        d.has_frame = true;
        d.frame = it->second;
      }
    } catch (const Error& e) {
      // A malformed frames table only costs the title its plane, said with the section's issues.
      d.issues.push_back(std::string("plot: the frames table is unreadable, the plane not shown: ") +
                         e.what());
    }
    for (const auto& row : rows_of(stream, "frames", section, {"radius"}))
      if (std::isfinite(row[0])) d.radius = row[0];
  }
  d.points = loops_of(stream, "points", section);
  for (const auto& row : rows_of(stream, "points", section, {"u", "v", "offset"}))
    if (std::isfinite(row[2]) && row[2] != 0 && finite(V2(row[0], row[1])))
      d.carried.emplace_back(row[0], row[1]);
  for (const auto& [key, b] : curves.splines)
    if (key.first == section && b.control.size() >= static_cast<std::size_t>(b.degree + 1))
      d.splines[key.second] = b;
  if (!d.splines.empty()) {
    d.curve_source = "spline";
  } else if (auto s = loops_of(stream, "samples", section); !s.empty()) {
    d.polyline = std::move(s);
    d.curve_source = "samples";
  } else if (auto m = loops_of(stream, "smoothed", section); !m.empty()) {
    d.polyline = std::move(m);
    d.curve_source = "smoothed";
  }
  if (!curves.error.empty()) d.issues.push_back("plot: spline tables unreadable: " + curves.error);
  for (const auto& row : rows_of(stream, "skeleton", section, {"loop", "u", "v"}))
    if ((!std::isfinite(row[0]) || row[0] == 0) && finite(V2(row[1], row[2])))
      d.skeleton.emplace_back(row[1], row[2]);
  for (const auto& row : rows_of(stream, "camber", section, {"u", "v", "s"}))
    if (finite(V2(row[0], row[1]))) {
      d.camber.emplace_back(row[0], row[1]);
      d.camber_s.push_back(row[2]);
    }
  // flags: NaN, none flagged, in a stream written before the thickness rows had them.
  for (const auto& row : rows_of(stream, "thickness", section,
                                 {"fraction", "u", "v", "thickness", "suction_u", "suction_v", "flags"})) {
    Station s;
    s.fraction = row[0];
    s.center = {row[1], row[2]};
    s.thickness = row[3];
    s.suction = {row[4], row[5]};
    s.flagged = flags_mask(row[6]) != 0;
    if (finite(s.center) && std::isfinite(s.thickness) && s.thickness > 0) d.stations.push_back(s);
  }
  d.params = row_map(stream, "params", section, 0);
  d.fit = row_map(stream, "splines", section, 0);
  collect_compare(stream, section, d);
  for (const auto& issue : stream.issues)
    if (issue.section == section)
      d.issues.push_back(issue.stage + (issue.loop >= 0 ? " (loop " + std::to_string(issue.loop) + ")" : "") +
                         ": " + issue.message);
  return d;
}

std::string failed_checks(const SectionData& d, const std::string& name) {
  return check_names_text(checks_flagging(flags_mask(param(d, "flags")), name.c_str()));
}

double param(const SectionData& d, const std::string& name) {
  const auto it = d.params.find(name);
  return it == d.params.end() ? nan : it->second;
}

std::vector<Row> parameter_rows(const SectionData& d) {
  std::vector<Row> rows;
  const std::string& u = d.units;
  auto length = [&](const char* label, const std::string& key) {
    const double x = param(d, key);
    if (std::isfinite(x)) rows.push_back({label, fixed(x, 4) + " " + u, failed_checks(d, key)});
  };
  auto angle = [&](const char* label, const std::string& key) {
    const double x = param(d, key);
    if (std::isfinite(x)) rows.push_back({label, fixed(x, 3) + "\xC2\xB0", failed_checks(d, key)});
  };
  length("chord", "chord");
  length("camber length", "camber_length");
  length("max thickness", "max_thickness");
  if (const double x = param(d, "max_thickness_pos"); std::isfinite(x))
    rows.push_back(
        {"max thickness at", fixed(100 * x, 2) + " % of camber", failed_checks(d, "max_thickness_pos")});
  const char* shapes[] = {"round", "blunt", "sharp"};
  for (const std::string e : {"le", "te"}) {
    const double r = param(d, e + "_radius"), shape = param(d, e + "_shape");
    if (!std::isfinite(r)) continue;
    std::string value = fixed(r, 4) + " " + u;
    if (shape == 0 || shape == 1 || shape == 2) value += " (" + std::string(shapes[int(shape)]) + ")";
    rows.push_back({e == "le" ? "LE radius" : "TE radius", value, failed_checks(d, e + "_radius")});
  }
  angle("stagger", "stagger");
  angle("inlet angle", "inlet_angle");
  angle("outlet angle", "outlet_angle");
  angle("camber angle", "camber_angle");
  if (const double a = param(d, "area"); std::isfinite(a))
    rows.push_back({"area", fixed(a, 3) + " " + u + "\xC2\xB2", failed_checks(d, "area")});
  length("caliper chord", "caliper_chord");
  if (!d.fit.empty()) {
    const auto get = [&](const char* k) {
      const auto it = d.fit.find(k);
      return it == d.fit.end() ? nan : it->second;
    };
    const double rms = get("rms"), mx = get("max");
    if (std::isfinite(rms) && std::isfinite(mx)) {
      const bool um = u == "mm";
      rows.push_back({"fit rms / max", fixed(um ? rms * 1000 : rms, um ? 2 : 6) + " / " +
                                           fixed(um ? mx * 1000 : mx, um ? 2 : 6) +
                                           (um ? " \xC2\xB5m" : " " + u)});
    }
    if (const double cp = get("control_points"); std::isfinite(cp))
      rows.push_back({"control points", trimmed(cp, 0)});
  }
  std::size_t n = 0;
  for (const auto& [loop, pts] : d.points) n += pts.size();
  if (n)
    rows.push_back(
        {"measured points",
         std::to_string(n) +
             (d.points.size() > 1 ? " in " + std::to_string(d.points.size()) + " loops" : "") +
             (d.carried.empty() ? "" : ", " + std::to_string(d.carried.size()) + " carried onto the plane")});
  if (!d.curve_source.empty()) rows.push_back({"curve from", d.curve_source});
  return rows;
}

std::string frame_text(const SectionData& d) {
  if (!d.has_frame) return "";
  auto v3 = [](const Eigen::Vector3d& p) {
    return "(" + trimmed(p.x(), 4) + ", " + trimmed(p.y(), 4) + ", " + trimmed(p.z(), 4) + ")";
  };
  return "plane through " + v3(d.frame.origin) + ", normal " + v3(d.frame.n) + "; u = " + v3(d.frame.u) +
         ", v up";
}

std::string plane_name(const SectionData& d) {
  if (std::isfinite(d.radius)) return "r = " + trimmed(d.radius, 4) + " " + d.units;
  if (!d.has_frame) return "";
  const Eigen::Vector3d& n = d.frame.n;
  for (int axis = 0; axis < 3; ++axis)
    if (std::abs(n[axis]) > 1 - 1e-9)
      return std::string(1, "xyz"[axis]) + " = " + trimmed(d.frame.origin[axis], 4) + " " + d.units;
  return "h = " + trimmed(d.frame.origin.dot(n), 4) + " " + d.units + " along (" + trimmed(n.x(), 4) + ", " +
         trimmed(n.y(), 4) + ", " + trimmed(n.z(), 4) + ")";
}

}  // namespace section::detail::plot
