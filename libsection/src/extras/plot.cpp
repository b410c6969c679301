// SVG and HTML drawings of the sections of a pipe stream (plot.h).
#include "section/extras/plot.h"

#include "section/bspline.h"
#include "section/error.h"
#include "section/fit_spline.h"
#include "section/frame.h"
#include "section/io/stream.h"
#include "section/pipe/schema.h"
#include "section/pipe/fit_spline_stream.h"

#include <Eigen/Dense>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace section {

namespace {

using V2 = Eigen::Vector2d;
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

// ---------------------------------------------------------------- text helpers

// Fixed-point text without locale (SVG wants '.' whatever the C locale says).
std::string fixed(double value, int decimals) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, value, std::chars_format::fixed, decimals);
  std::string s(buf, r.ptr);
  if (s == "-0" || (s.rfind("-0.", 0) == 0 && s.find_first_not_of("0.", 1) == std::string::npos))
    s.erase(0, 1);  // no "-0.00"
  return s;
}

// Fixed-point text with trailing zeros dropped: 12.500 -> 12.5, 3.000 -> 3.
std::string trimmed(double value, int decimals) {
  std::string s = fixed(value, decimals);
  if (s.find('.') != std::string::npos) {
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
  }
  return s;
}

std::string px(double v) { return fixed(v, 2); }

std::string escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

bool finite(const V2& p) { return std::isfinite(p.x()) && std::isfinite(p.y()); }

// ---------------------------------------------------------------- what the stream holds

struct Station {
  double fraction = 0, thickness = 0;
  V2 center{0, 0};
};

// Everything drawable of one section.
struct SectionData {
  int id = 0;
  std::string units = "mm";
  bool has_frame = false;
  Frame frame;
  std::map<int, std::vector<V2>> points;   // measured, by loop, in loop order
  std::vector<V2> carried;                 // those the gap fill carried onto the plane (offset != 0)
  std::map<int, BSpline> splines;          // fitted curves by loop (spline tables)
  std::map<int, std::vector<V2>> polyline; // fitted curve by loop when there is no spline
  std::string curve_source;                // "spline", "samples", "smoothed" or ""
  std::vector<V2> skeleton;
  std::vector<V2> camber;
  std::vector<Station> stations;
  std::map<std::string, double> params;    // the section's params row
  std::map<std::string, double> fit;       // loop 0's splines row
  std::vector<std::string> issues;         // "stage: message" lines
};

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

// The spline tables read once per stream; an unreadable set becomes a note, not an error.
struct Curves {
  std::map<std::pair<int, int>, BSpline> splines;
  std::string error;
};

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
    } catch (const Error&) {
      // A malformed frames table only costs the title its plane.
    }
  }
  d.points = loops_of(stream, "points", section);
  for (const auto& row : rows_of(stream, "points", section, {"u", "v", "offset"}))
    if (std::isfinite(row[2]) && row[2] != 0 && finite(V2(row[0], row[1]))) d.carried.emplace_back(row[0], row[1]);
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
    if ((!std::isfinite(row[0]) || row[0] == 0) && finite(V2(row[1], row[2]))) d.skeleton.emplace_back(row[1], row[2]);
  for (const auto& row : rows_of(stream, "camber", section, {"u", "v"}))
    if (finite(V2(row[0], row[1]))) d.camber.emplace_back(row[0], row[1]);
  for (const auto& row : rows_of(stream, "thickness", section, {"fraction", "u", "v", "thickness"})) {
    Station s;
    s.fraction = row[0];
    s.center = {row[1], row[2]};
    s.thickness = row[3];
    if (finite(s.center) && std::isfinite(s.thickness) && s.thickness > 0) d.stations.push_back(s);
  }
  d.params = row_map(stream, "params", section, 0);
  d.fit = row_map(stream, "splines", section, 0);
  for (const auto& issue : stream.issues)
    if (issue.section == section)
      d.issues.push_back(issue.stage + (issue.loop >= 0 ? " (loop " + std::to_string(issue.loop) + ")" : "") +
                         ": " + issue.message);
  return d;
}

double param(const SectionData& d, const std::string& name) {
  const auto it = d.params.find(name);
  return it == d.params.end() ? nan : it->second;
}

// ---------------------------------------------------------------- geometry

struct Box {
  double u0 = std::numeric_limits<double>::infinity(), v0 = u0, u1 = -u0, v1 = -u0;
  void add(const V2& p) {
    if (!finite(p)) return;
    u0 = std::min(u0, p.x()); v0 = std::min(v0, p.y());
    u1 = std::max(u1, p.x()); v1 = std::max(v1, p.y());
  }
  void add(const V2& c, double r) { add(c - V2(r, r)); add(c + V2(r, r)); }
  bool empty() const { return !(u1 >= u0 && v1 >= v0); }
  bool touches(const Box& b) const { return !(b.u0 > u1 || b.u1 < u0 || b.v0 > v1 || b.v1 < v0); }
  bool contains(const V2& p) const { return p.x() >= u0 && p.x() <= u1 && p.y() >= v0 && p.y() <= v1; }
  Box grown(double d) const { return {u0 - d, v0 - d, u1 + d, v1 + d}; }
};

Box everything() {
  const double big = std::numeric_limits<double>::max();
  return {-big, -big, big, big};
}

// World (u, v) to px: x = scale u + tx, y = -scale v + ty (v up, equal axes).
struct View {
  double scale = 1, tx = 0, ty = 0;
  double x(double u) const { return scale * u + tx; }
  double y(double v) const { return -scale * v + ty; }
  // Maps `box` centred into the px rectangle (left, top, w, h) at the largest scale.
  static View fit(const Box& box, double left, double top, double w, double h) {
    View v;
    const double du = std::max(box.u1 - box.u0, 1e-12), dv = std::max(box.v1 - box.v0, 1e-12);
    v.scale = std::min(w / du, h / dv);
    v.tx = left + 0.5 * (w - du * v.scale) - v.scale * box.u0;
    v.ty = top + 0.5 * (h - dv * v.scale) + v.scale * box.v1;
    return v;
  }
};

// The curve of one loop as a polyline; spline curves are sampled `factor` times denser
// than options.spline_samples (insets magnify).
std::vector<V2> curve_of(const SectionData& d, int loop, const PlotOptions& o, double factor) {
  if (const auto it = d.splines.find(loop); it != d.splines.end()) {
    const int n = static_cast<int>(std::clamp(o.spline_samples * factor, 16.0, 400000.0));
    return sample(it->second, n);
  }
  if (const auto it = d.polyline.find(loop); it != d.polyline.end()) return it->second;
  return {};
}

std::vector<int> curve_loops(const SectionData& d) {
  std::vector<int> out;
  for (const auto& [loop, b] : d.splines) out.push_back(loop);
  for (const auto& [loop, p] : d.polyline) out.push_back(loop);
  return out;
}

bool closed_loop(const SectionData& d, int loop) {
  const auto it = d.splines.find(loop);
  return it == d.splines.end() || it->second.closed;
}

// Path data of a polyline: the runs of segments touching `window` (all of it when the
// window holds everything), each run a subpath.
std::string path_data(const std::vector<V2>& pts, bool closed, const View& v, const Box& window, bool whole) {
  std::string d;
  const std::size_t n = pts.size();
  if (n < 2) return d;
  if (whole) {
    bool pen = false;
    for (const auto& p : pts) {
      if (!finite(p)) { pen = false; continue; }
      d += (pen ? " L" : (d.empty() ? "M" : " M")) + px(v.x(p.x())) + " " + px(v.y(p.y()));
      pen = true;
    }
    if (closed) d += " Z";
    return d;
  }
  const std::size_t segments = closed ? n : n - 1;
  bool open_run = false;
  for (std::size_t i = 0; i < segments; ++i) {
    const V2& a = pts[i];
    const V2& b = pts[(i + 1) % n];
    Box seg;
    seg.add(a);
    seg.add(b);
    if (!finite(a) || !finite(b) || !seg.touches(window)) {
      open_run = false;
      continue;
    }
    if (!open_run) d += (d.empty() ? "M" : " M") + px(v.x(a.x())) + " " + px(v.y(a.y()));
    d += " L" + px(v.x(b.x())) + " " + px(v.y(b.y()));
    open_run = true;
  }
  return d;
}

// The inset of one edge: its window and what marks it.
struct EdgeInset {
  std::string key;      // "le" or "te"
  std::string label;    // "LE", "TE", or "end 1"/"end 2" without params
  V2 center{0, 0};      // window centre
  double half = 0;      // window half-width
  bool circle = false;  // a fitted edge circle exists
  V2 circle_center{0, 0};
  double radius = 0;
  bool point = false;   // an edge point exists
  V2 edge_point{0, 0};
};

// Farthest pair along the principal axis of some points: the two ends of a profile.
std::pair<V2, V2> principal_ends(const std::vector<V2>& pts) {
  V2 mean(0, 0);
  for (const auto& p : pts) mean += p;
  mean /= static_cast<double>(pts.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const auto& p : pts) cov += (p - mean) * (p - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  const V2 axis = eig.eigenvectors().col(1);
  V2 lo = pts.front(), hi = pts.front();
  for (const auto& p : pts) {
    if ((p - mean).dot(axis) < (lo - mean).dot(axis)) lo = p;
    if ((p - mean).dot(axis) > (hi - mean).dot(axis)) hi = p;
  }
  return {lo, hi};
}

std::vector<EdgeInset> edge_insets(const SectionData& d, const Box& all, const PlotOptions& o) {
  const double extent = std::max(all.u1 - all.u0, all.v1 - all.v0);
  const double min_half = std::max(o.inset_min_fraction * extent, 1e-9);
  std::vector<EdgeInset> out;
  if (!d.params.empty()) {
    for (const std::string key : {"le", "te"}) {
      EdgeInset e;
      e.key = key;
      e.label = key == "le" ? "LE" : "TE";
      e.edge_point = {param(d, key + "_u"), param(d, key + "_v")};
      e.point = finite(e.edge_point);
      e.circle_center = {param(d, key + "_center_u"), param(d, key + "_center_v")};
      e.radius = param(d, key + "_radius");
      e.circle = finite(e.circle_center) && std::isfinite(e.radius) && e.radius > 0;
      if (e.circle) {
        e.center = e.circle_center;
        e.half = std::max(o.inset_radii * e.radius, min_half);
      } else if (e.point) {
        e.center = e.edge_point;
        e.half = 2.5 * min_half;
      } else {
        continue;
      }
      out.push_back(e);
    }
    return out;
  }
  // No parameters: the ends of the camber line, else the profile's extremes along its
  // principal axis, each window moved inward so that it shows the edge, not the outside.
  std::pair<V2, V2> ends;
  double half = 2.5 * min_half;
  if (d.camber.size() >= 2) {
    ends = {d.camber.front(), d.camber.back()};
  } else {
    std::vector<V2> pts;
    if (!d.splines.empty() || !d.polyline.empty()) pts = curve_of(d, curve_loops(d).front(), o, 1);
    if (pts.empty() && !d.points.empty()) pts = d.points.begin()->second;
    if (pts.size() < 3) return out;
    ends = principal_ends(pts);
    const V2 axis = (ends.second - ends.first).normalized();
    half = 3 * min_half;
    if (finite(axis)) {
      ends.first += 0.6 * half * axis;
      ends.second -= 0.6 * half * axis;
    }
  }
  for (int k = 0; k < 2; ++k) {
    EdgeInset e;
    e.key = k == 0 ? "le" : "te";
    e.label = k == 0 ? "end 1" : "end 2";
    e.center = k == 0 ? ends.first : ends.second;
    e.half = half;
    out.push_back(e);
  }
  return out;
}

// ---------------------------------------------------------------- drawing

const char* const style =
    "text{font-family:'DejaVu Sans',Arial,sans-serif;font-size:13px;fill:#222}"
    ".title{font-size:17px;font-weight:bold}.subtitle{fill:#555}"
    ".view-frame{fill:#fff;stroke:#aaa;stroke-width:1}"
    ".points circle{fill:#1f77b4;fill-opacity:.6}"
    ".carried circle{fill:none;stroke:#ff7f0e;stroke-width:1}"
    ".curve{fill:none;stroke:#111;stroke-width:1.3}"
    ".camber{fill:none;stroke:#d62728;stroke-width:1.5}"
    ".skeleton{fill:none;stroke:#d62728;stroke-width:1.2;stroke-dasharray:5 3}"
    ".station{fill:none;stroke:#2ca02c;stroke-width:.9}"
    ".station-center{fill:#2ca02c}"
    ".chord{stroke:#444;stroke-width:1.1;stroke-dasharray:7 4}"
    ".le-circle{fill:none;stroke:#ff7f0e;stroke-width:1.8}"
    ".te-circle{fill:none;stroke:#9467bd;stroke-width:1.8}"
    ".le-point{fill:#ff7f0e;stroke:#000;stroke-width:.6}.te-point{fill:#9467bd;stroke:#000;stroke-width:.6}"
    ".inset-frame{fill:none;stroke:#777;stroke-width:1;stroke-dasharray:3 2}"
    ".inset-label{font-weight:bold}"
    ".scale-bar-back{fill:#fff;fill-opacity:.8}.scale-bar-line{stroke:#000;stroke-width:2.5}.scale-bar-tick{stroke:#000;stroke-width:1.5}"
    ".param-name{fill:#444}.param-value{font-weight:bold;text-anchor:end}"
    ".param-head{font-weight:bold;font-size:14px}"
    ".issue{fill:#c00}.empty{fill:#888;font-style:italic}"
    ".legend line{stroke-width:2.5}";

// 1, 2 or 5 times a power of ten, at most `target`.
double nice_length(double target) {
  const double p = std::pow(10.0, std::floor(std::log10(target)));
  for (double m : {5.0, 2.0, 1.0})
    if (m * p <= target) return m * p;
  return p;
}

std::string length_label(double length, const std::string& units) {
  if (units == "mm" && length < 1) return trimmed(length * 1000, 3) + " \xC2\xB5m";
  return trimmed(length, 6) + " " + units;
}

// A scale bar at the bottom left of the px rectangle (left, bottom), about a fifth of
// `width` px long.
void scale_bar(std::string& s, const std::string& id, const View& v, double left, double bottom,
               double width, const std::string& units) {
  const double length = nice_length(0.2 * width / v.scale);
  const double x0 = left + 12, x1 = x0 + length * v.scale, y = bottom - 12;
  s += "<g id=\"" + id + "\" class=\"scale-bar\" data-length=\"" + trimmed(length, 9) + "\">";
  s += "<rect class=\"scale-bar-back\" x=\"" + px(x0 - 6) + "\" y=\"" + px(y - 24) + "\" width=\"" +
       px(x1 - x0 + 12) + "\" height=\"" + px(32) + "\"/>";
  s += "<line class=\"scale-bar-line\" x1=\"" + px(x0) + "\" y1=\"" + px(y) + "\" x2=\"" + px(x1) +
       "\" y2=\"" + px(y) + "\"/>";
  for (double x : {x0, x1})
    s += "<line class=\"scale-bar-tick\" x1=\"" + px(x) + "\" y1=\"" + px(y - 5) + "\" x2=\"" + px(x) +
         "\" y2=\"" + px(y + 5) + "\"/>";
  s += "<text x=\"" + px(0.5 * (x0 + x1)) + "\" y=\"" + px(y - 8) + "\" text-anchor=\"middle\">" +
       escape(length_label(length, units)) + "</text></g>";
}

void circle(std::string& s, const std::string& cls, const View& v, const V2& c, double r_px) {
  s += "<circle class=\"" + cls + "\" cx=\"" + px(v.x(c.x())) + "\" cy=\"" + px(v.y(c.y())) + "\" r=\"" +
       px(r_px) + "\"/>";
}

// The section's geometry in view `v`, restricted to `window` unless `whole`.
void draw_geometry(std::string& s, const SectionData& d, const View& v, const Box& window, bool whole,
                   const PlotOptions& o, const std::vector<EdgeInset>& edges, double density) {
  const Box near = whole ? everything() : window.grown(0.05 * (window.u1 - window.u0));
  if (o.stations && !d.stations.empty()) {
    s += "<g class=\"stations\">";
    for (const auto& st : d.stations) {
      Box b;
      b.add(st.center, 0.5 * st.thickness);
      if (!b.touches(near)) continue;
      circle(s, "station", v, st.center, 0.5 * st.thickness * v.scale);
      circle(s, "station-center", v, st.center, 1.8);
    }
    s += "</g>";
  }
  if (o.points && !d.points.empty()) {
    s += "<g class=\"points\">";
    const double r = whole ? o.point_radius : 1.5 * o.point_radius;
    for (const auto& [loop, pts] : d.points)
      for (const auto& p : pts)
        if (near.contains(p))
          s += "<circle cx=\"" + px(v.x(p.x())) + "\" cy=\"" + px(v.y(p.y())) + "\" r=\"" + px(r) + "\"/>";
    s += "</g>";
    // Carried points ringed on top of their dots: the slab had no point there.
    if (!d.carried.empty()) {
      s += "<g class=\"carried\">";
      for (const auto& p : d.carried)
        if (near.contains(p))
          s += "<circle cx=\"" + px(v.x(p.x())) + "\" cy=\"" + px(v.y(p.y())) + "\" r=\"" + px(2 * r) + "\"/>";
      s += "</g>";
    }
  }
  for (int loop : curve_loops(d)) {
    const std::string data = path_data(curve_of(d, loop, o, density), closed_loop(d, loop), v, near, whole);
    if (!data.empty())
      s += "<path class=\"curve\" data-loop=\"" + std::to_string(loop) + "\" data-source=\"" + d.curve_source +
           "\" d=\"" + data + "\"/>";
  }
  if (d.camber.size() >= 2) {
    const std::string data = path_data(d.camber, false, v, near, whole);
    if (!data.empty()) s += "<path class=\"camber\" d=\"" + data + "\"/>";
  } else if (d.skeleton.size() >= 2) {
    const std::string data = path_data(d.skeleton, false, v, near, whole);
    if (!data.empty()) s += "<path class=\"skeleton\" d=\"" + data + "\"/>";
  }
  const V2 le(param(d, "le_u"), param(d, "le_v")), te(param(d, "te_u"), param(d, "te_v"));
  if (finite(le) && finite(te))
    s += "<line class=\"chord\" x1=\"" + px(v.x(le.x())) + "\" y1=\"" + px(v.y(le.y())) + "\" x2=\"" +
         px(v.x(te.x())) + "\" y2=\"" + px(v.y(te.y())) + "\"/>";
  for (const auto& e : edges) {
    if (e.circle) circle(s, e.key + "-circle", v, e.circle_center, e.radius * v.scale);
    if (e.point) circle(s, e.key + "-point", v, e.edge_point, 3.5);
  }
}

struct Row {
  std::string name, value;
};

std::vector<Row> parameter_rows(const SectionData& d) {
  std::vector<Row> rows;
  const std::string& u = d.units;
  auto length = [&](const char* label, const std::string& key) {
    const double x = param(d, key);
    if (std::isfinite(x)) rows.push_back({label, fixed(x, 4) + " " + u});
  };
  auto angle = [&](const char* label, const std::string& key) {
    const double x = param(d, key);
    if (std::isfinite(x)) rows.push_back({label, fixed(x, 3) + "\xC2\xB0"});
  };
  length("chord", "chord");
  length("camber length", "camber_length");
  length("max thickness", "max_thickness");
  if (const double x = param(d, "max_thickness_pos"); std::isfinite(x))
    rows.push_back({"max thickness at", fixed(100 * x, 2) + " % of camber"});
  const char* shapes[] = {"round", "blunt", "sharp"};
  for (const std::string e : {"le", "te"}) {
    const double r = param(d, e + "_radius"), shape = param(d, e + "_shape");
    if (!std::isfinite(r)) continue;
    std::string value = fixed(r, 4) + " " + u;
    if (shape == 0 || shape == 1 || shape == 2) value += " (" + std::string(shapes[int(shape)]) + ")";
    rows.push_back({e == "le" ? "LE radius" : "TE radius", value});
  }
  angle("stagger", "stagger");
  angle("inlet angle", "inlet_angle");
  angle("outlet angle", "outlet_angle");
  angle("camber angle", "camber_angle");
  if (const double a = param(d, "area"); std::isfinite(a)) rows.push_back({"area", fixed(a, 3) + " " + u + "\xC2\xB2"});
  length("caliper chord", "caliper_chord");
  if (!d.fit.empty()) {
    const auto get = [&](const char* k) { const auto it = d.fit.find(k); return it == d.fit.end() ? nan : it->second; };
    const double rms = get("rms"), mx = get("max");
    if (std::isfinite(rms) && std::isfinite(mx)) {
      const bool um = u == "mm";
      rows.push_back({"fit rms / max", fixed(um ? rms * 1000 : rms, um ? 2 : 6) + " / " +
                                           fixed(um ? mx * 1000 : mx, um ? 2 : 6) + (um ? " \xC2\xB5m" : " " + u)});
    }
    if (const double cp = get("control_points"); std::isfinite(cp))
      rows.push_back({"control points", trimmed(cp, 0)});
  }
  std::size_t n = 0;
  for (const auto& [loop, pts] : d.points) n += pts.size();
  if (n)
    rows.push_back({"measured points", std::to_string(n) +
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

void check(const PlotOptions& o) {
  auto bad = [](const std::string& what) { throw Error("plot: " + what); };
  if (!(o.width >= 300 && o.width <= 20000)) bad("width must lie in [300, 20000] px, got " + trimmed(o.width, 3));
  if (!(o.max_main_height >= 50)) bad("max_main_height must be at least 50 px");
  if (!(o.inset_size == 0 || (o.inset_size >= 80 && o.inset_size <= o.width / 2 - 20)))
    bad("inset_size must be 0 or lie in [80, width/2 - 20] px, got " + trimmed(o.inset_size, 3));
  if (!(o.inset_radii > 1)) bad("inset_radii must exceed 1 so the edge circle fits its inset");
  if (!(o.inset_min_fraction > 0 && o.inset_min_fraction < 0.5)) bad("inset_min_fraction must lie in (0, 0.5)");
  if (!(o.point_radius >= 0 && o.point_radius <= 20)) bad("point_radius must lie in [0, 20] px");
  if (o.spline_samples < 16) bad("spline_samples must be at least 16");
}

bool has_section(const Stream& stream, int section) {
  const auto ids = plot_sections(stream);
  return std::binary_search(ids.begin(), ids.end(), section);
}

std::string svg_of(const SectionData& d, const PlotOptions& o) {
  const std::string id = "s" + std::to_string(d.id);
  const double margin = 16, W = o.width;
  // Bounds of everything drawn in the main view.
  Box all;
  for (const auto& [loop, pts] : d.points)
    for (const auto& p : pts) all.add(p);
  for (int loop : curve_loops(d))
    for (const auto& p : curve_of(d, loop, o, 1)) all.add(p);
  for (const auto& p : d.camber) all.add(p);
  for (const auto& p : d.skeleton) all.add(p);
  const bool drawable = !all.empty();
  const auto edges = drawable ? edge_insets(d, all, o) : std::vector<EdgeInset>{};

  std::string body;
  double y = margin + 18;
  body += "<text class=\"title\" x=\"" + px(margin) + "\" y=\"" + px(y) + "\">Section " + std::to_string(d.id) +
          "</text>";
  const std::string sub = frame_text(d);
  body += "<text class=\"subtitle\" x=\"" + px(margin + 110) + "\" y=\"" + px(y) + "\">" +
          escape(sub.empty() ? "units " + d.units : sub + "; units " + d.units) + "</text>";
  y += 12;

  View main;
  const double view_w = W - 2 * margin;
  double view_h = 60;
  if (drawable) {
    const double extent = std::max({all.u1 - all.u0, all.v1 - all.v0, 1e-9});
    const Box padded = all.grown(0.04 * extent);
    const double du = padded.u1 - padded.u0, dv = padded.v1 - padded.v0;
    view_h = std::min(o.max_main_height, view_w * dv / du);
    view_h = std::max(view_h, 60.0);
    main = View::fit(padded, margin, y, view_w, view_h);
  }
  body += "<g id=\"" + id + "-main\" class=\"view main\" data-scale=\"" + trimmed(main.scale, 6) + "\" data-tx=\"" +
          trimmed(main.tx, 4) + "\" data-ty=\"" + trimmed(main.ty, 4) + "\">";
  const std::string frame_rect = "x=\"" + px(margin) + "\" y=\"" + px(y) + "\" width=\"" + px(view_w) +
                                 "\" height=\"" + px(view_h) + "\"";
  body += "<clipPath id=\"" + id + "-main-clip\"><rect " + frame_rect + "/></clipPath>";
  body += "<rect class=\"view-frame\" " + frame_rect + "/>";
  if (drawable) {
    body += "<g clip-path=\"url(#" + id + "-main-clip)\">";
    draw_geometry(body, d, main, everything(), true, o, edges, 1);
    if (o.inset_size > 0)
      for (const auto& e : edges) {
        const double x0 = main.x(e.center.x() - e.half), y0 = main.y(e.center.y() + e.half);
        const double side = 2 * e.half * main.scale;
        body += "<rect class=\"inset-frame\" x=\"" + px(x0) + "\" y=\"" + px(y0) + "\" width=\"" + px(side) +
                "\" height=\"" + px(side) + "\"/>";
        body += "<text class=\"inset-label\" x=\"" + px(x0) + "\" y=\"" + px(y0 - 4) + "\">" + escape(e.label) +
                "</text>";
      }
    body += "</g>";
    scale_bar(body, id + "-main-scale", main, margin, y + view_h, view_w, d.units);
  } else {
    body += "<text class=\"empty\" x=\"" + px(margin + 12) + "\" y=\"" + px(y + 36) +
            "\">nothing to draw: the stream holds no geometry for this section</text>";
  }
  body += "</g>";
  y += view_h + 8;

  // Legend of what is drawn.
  {
    std::vector<std::pair<std::string, std::string>> items;  // class, label
    if (o.points && !d.points.empty()) items.push_back({"points", "measured points"});
    if (o.points && !d.carried.empty()) items.push_back({"carried", "points carried onto the plane (gap fill)"});
    if (d.curve_source == "smoothed") items.push_back({"curve", "smoothed points"});
    else if (!d.curve_source.empty()) items.push_back({"curve", "fitted curve (" + d.curve_source + ")"});
    if (d.camber.size() >= 2) items.push_back({"camber", "mean-camber line"});
    else if (d.skeleton.size() >= 2) items.push_back({"skeleton", "skeleton"});
    if (o.stations && !d.stations.empty()) items.push_back({"station", "inscribed circles"});
    if (std::isfinite(param(d, "chord"))) items.push_back({"chord", "chord line"});
    for (const auto& e : edges)
      if (e.circle) items.push_back({e.key + "-circle", e.label + " circle"});
    body += "<g class=\"legend\">";
    double x = margin;
    for (const auto& [cls, label] : items) {
      const double ly = y + 10;
      if (cls == "points" || cls == "carried")
        body += "<g class=\"" + cls + "\"><circle cx=\"" + px(x + 10) + "\" cy=\"" + px(ly) + "\" r=\"3\"/></g>";
      else
        body += "<line class=\"" + cls + "\" x1=\"" + px(x) + "\" y1=\"" + px(ly) + "\" x2=\"" + px(x + 22) +
                "\" y2=\"" + px(ly) + "\"/>";
      body += "<text x=\"" + px(x + 28) + "\" y=\"" + px(ly + 4) + "\">" + escape(label) + "</text>";
      x += 36 + 7.2 * static_cast<double>(label.size());
    }
    body += "</g>";
    y += 26;
  }

  // Lower row: the edge insets, then the parameter table beside them (or below when narrow).
  double lower = y, row_bottom = y;
  double table_x = margin, table_y = y;
  if (o.inset_size > 0 && !edges.empty()) {
    const double gap = 16, side = o.inset_size;
    double x = margin;
    for (const auto& e : edges) {
      const std::string gid = id + "-" + e.key;
      const double top = lower + 18;
      Box window{e.center.x() - e.half, e.center.y() - e.half, e.center.x() + e.half, e.center.y() + e.half};
      const View v = View::fit(window, x, top, side, side);
      const double magnification = v.scale / main.scale;
      body += "<g id=\"" + gid + "\" class=\"view inset " + e.key + "\" data-scale=\"" + trimmed(v.scale, 6) +
              "\" data-tx=\"" + trimmed(v.tx, 4) + "\" data-ty=\"" + trimmed(v.ty, 4) + "\">";
      body += "<text class=\"inset-label\" x=\"" + px(x) + "\" y=\"" + px(lower + 13) + "\">" + escape(e.label) +
              " (\xC3\x97" + trimmed(magnification, 1) + ")</text>";
      body += "<clipPath id=\"" + gid + "-clip\"><rect x=\"" + px(x) + "\" y=\"" + px(top) + "\" width=\"" +
              px(side) + "\" height=\"" + px(side) + "\"/></clipPath>";
      body += "<rect class=\"view-frame\" x=\"" + px(x) + "\" y=\"" + px(top) + "\" width=\"" + px(side) +
              "\" height=\"" + px(side) + "\"/>";
      body += "<g clip-path=\"url(#" + gid + "-clip)\">";
      const std::vector<EdgeInset> marks{e};
      draw_geometry(body, d, v, window, false, o, marks, std::max(1.0, 0.5 * magnification));
      body += "</g>";
      scale_bar(body, gid + "-scale", v, x, top + side, side, d.units);
      body += "</g>";
      x += side + gap;
    }
    row_bottom = lower + 18 + side;
    table_x = x + 8;
    if (W - margin - table_x < 280) {  // no room beside the insets
      table_x = margin;
      table_y = row_bottom + 16;
    }
  }
  if (o.table || !d.issues.empty()) {
    double ty = table_y + 13;
    const double value_x = std::min(W - margin, table_x + 360);
    body += "<g id=\"" + id + "-params\" class=\"param-table\">";
    if (o.table) {
      body += "<text class=\"param-head\" x=\"" + px(table_x) + "\" y=\"" + px(ty) + "\">Parameters</text>";
      ty += 20;
      const auto rows = parameter_rows(d);
      for (const auto& r : rows) {
        body += "<text class=\"param-name\" x=\"" + px(table_x) + "\" y=\"" + px(ty) + "\">" + escape(r.name) +
                "</text><text class=\"param-value\" x=\"" + px(value_x) + "\" y=\"" + px(ty) + "\">" +
                escape(r.value) + "</text>";
        ty += 18;
      }
      if (rows.empty()) {
        body += "<text class=\"empty\" x=\"" + px(table_x) + "\" y=\"" + px(ty) + "\">no parameters in the stream</text>";
        ty += 18;
      }
    }
    for (const auto& issue : d.issues) {
      body += "<text class=\"issue\" x=\"" + px(table_x) + "\" y=\"" + px(ty) + "\">" + escape(issue) + "</text>";
      ty += 18;
    }
    body += "</g>";
    row_bottom = std::max(row_bottom, ty - 13);
  }
  const double H = std::ceil(row_bottom + margin);
  std::string s = "<svg xmlns=\"http://www.w3.org/2000/svg\" id=\"" + id + "\" class=\"section-plot\" width=\"" +
                  px(W) + "\" height=\"" + px(H) + "\" viewBox=\"0 0 " + px(W) + " " + px(H) + "\" data-section=\"" +
                  std::to_string(d.id) + "\" data-units=\"" + escape(d.units) + "\">";
  s += "<style>";
  s += style;
  s += "</style><rect x=\"0\" y=\"0\" width=\"" + px(W) + "\" height=\"" + px(H) + "\" fill=\"#fafafa\"/>";
  s += body;
  s += "</svg>\n";
  return s;
}

}  // namespace

std::vector<int> plot_sections(const Stream& stream) {
  std::set<int> ids;
  for (const auto& t : stream.tables) {
    const long c = t.find_column("section");
    if (c < 0) continue;
    for (std::size_t r = 0; r < t.rows(); ++r)
      if (std::isfinite(t.at(r, c))) ids.insert(static_cast<int>(t.at(r, c)));
  }
  for (const auto& i : stream.issues)
    if (i.section >= 0) ids.insert(i.section);
  return {ids.begin(), ids.end()};
}

std::string plot_svg(const Stream& stream, int section, const PlotOptions& options) {
  check(options);
  if (!has_section(stream, section)) {
    std::string ids;
    for (int i : plot_sections(stream)) ids += (ids.empty() ? "" : ", ") + std::to_string(i);
    throw Error("plot: section " + std::to_string(section) + " is not in the stream (" +
                (ids.empty() ? std::string("it holds no section") : "sections: " + ids) + ")");
  }
  return svg_of(collect(stream, section, read_curves(stream)), options);
}

std::string plot_html(const Stream& stream, const PlotOptions& options) {
  check(options);
  const auto ids = plot_sections(stream);
  if (ids.empty()) throw Error("plot: the stream holds no section to draw");
  const Curves curves = read_curves(stream);
  std::string h =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>libsection: " +
      std::to_string(ids.size()) + " section" + (ids.size() == 1 ? "" : "s") +
      "</title>\n<style>\nbody{font-family:'DejaVu Sans',Arial,sans-serif;margin:16px;background:#fff;color:#222}\n"
      "table.summary{border-collapse:collapse;margin:8px 0 16px}\n"
      "table.summary td,table.summary th{border:1px solid #ccc;padding:3px 8px;text-align:right}\n"
      "pre.history{background:#f4f4f4;padding:6px;font-size:12px}\n.issue{color:#c00}\n"
      "section{margin-bottom:24px}\n</style>\n</head>\n<body>\n<h1>Blade sections</h1>\n";
  if (!stream.history.empty()) {
    h += "<pre class=\"history\">";
    for (const auto& line : stream.history) h += escape(line) + "\n";
    h += "</pre>\n";
  }
  const std::string u = escape(stream.units);
  h += "<table class=\"summary\">\n<tr><th>section</th><th>chord (" + u + ")</th><th>max thickness (" + u +
       ")</th><th>LE radius (" + u + ")</th><th>TE radius (" + u +
       ")</th><th>stagger (\xC2\xB0)</th><th>camber angle (\xC2\xB0)</th><th>issues</th></tr>\n";
  std::vector<SectionData> data;
  for (int id : ids) {
    data.push_back(collect(stream, id, curves));
    const auto& d = data.back();
    auto cell = [&](const char* key, int decimals) {
      const double x = param(d, key);
      return "<td>" + (std::isfinite(x) ? fixed(x, decimals) : std::string("&ndash;")) + "</td>";
    };
    h += "<tr><td><a href=\"#section-" + std::to_string(id) + "\">" + std::to_string(id) + "</a></td>" +
         cell("chord", 4) + cell("max_thickness", 4) + cell("le_radius", 4) + cell("te_radius", 4) +
         cell("stagger", 3) + cell("camber_angle", 3) + "<td class=\"issue\">" +
         (d.issues.empty() ? "" : std::to_string(d.issues.size())) + "</td></tr>\n";
  }
  h += "</table>\n";
  for (const auto& d : data) {
    h += "<section id=\"section-" + std::to_string(d.id) + "\">\n";
    try {
      h += svg_of(d, options);
    } catch (const std::exception& e) {
      h += "<p class=\"issue\">section " + std::to_string(d.id) + " could not be drawn: " + escape(e.what()) + "</p>\n";
    }
    h += "</section>\n";
  }
  h += "</body>\n</html>\n";
  return h;
}

}  // namespace section
