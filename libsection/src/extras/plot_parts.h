// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The parts of the plot module (plot.h), internal to section_extras: what the stream holds
// of a section (plot_data.cpp), its geometry and edge insets (plot_geometry.cpp), the SVG
// drawing of one section (plot_svg.cpp); plot.cpp holds the public functions and the page.
#include "section/bspline.h"
#include "section/extras/plot.h"
#include "section/frame.h"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace section::detail::plot {

using V2 = Eigen::Vector2d;
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

// ---------------------------------------------------------------- text (plot_data.cpp)

/// Fixed-point text without locale (SVG wants '.' whatever the C locale says); no "-0.00".
std::string fixed(double value, int decimals);
/// Fixed-point text with trailing zeros dropped: 12.500 -> 12.5, 3.000 -> 3.
std::string trimmed(double value, int decimals);
inline std::string px(double v) {
  return fixed(v, 2);
}
/// Text for XML: & < > " escaped.
std::string escape(const std::string& text);
/// An upper estimate of the width in px of `text` at font size `font` (DejaVu Sans or Arial:
/// no glyph of the plot's text is wider on average than 0.62 em); the browser check
/// (tests/tools/test_plot_layout.sh) measures the real boxes.
double text_width(const std::string& text, double font);
/// `text` broken at spaces into lines of at most `width` px at font size `font` (a word
/// longer than a line is cut).
std::vector<std::string> wrap(const std::string& text, double width, double font);
/// A length with its unit for a label: 4 decimals in the stream's unit ("62.7511 mm").
std::string length_text(double length, const std::string& units);

inline bool finite(const V2& p) {
  return std::isfinite(p.x()) && std::isfinite(p.y());
}

// ---------------------------------------------------------------- what the stream holds (plot_data.cpp)

struct Station {
  double fraction = 0, thickness = 0;
  V2 center{0, 0};
  V2 suction{nan, nan};  // where the inscribed circle touches the suction side, when known
  bool flagged = false;  // its row's flags hold a failed check (a thickness it cannot stand behind)
};

// compare's deviation of one measured point (plot_compare.cpp).
struct Whisker {
  V2 foot{0, 0}, normal{0, 0};
  double deviation = 0;
  int zone = 0;
  bool outlier = false;
};

// compare's profile tolerance and verdict of one zone.
struct ZoneBand {
  int bounds = 0;  // 1 low, 2 high, 3 both
  double low = 0, high = 0;
  int verdict = -1;
};

// Everything drawable of one section.
struct SectionData {
  int id = 0;
  std::string units = "mm";
  bool has_frame = false;
  Frame frame;
  double radius = nan;  // the section surface's radius (frames' "radius" column), when given
  std::map<int, std::vector<V2>> points;    // measured, by loop, in loop order
  std::vector<V2> carried;                  // those the gap fill carried onto the plane (offset != 0)
  std::map<int, BSpline> splines;           // fitted curves by loop (spline tables)
  std::map<int, std::vector<V2>> polyline;  // fitted curve by loop when there is no spline
  std::string curve_source;                 // "spline", "samples", "smoothed" or ""
  std::vector<V2> skeleton;
  std::vector<V2> camber;
  std::vector<double> camber_s;  // arc length of each camber point from the LE (NaN when absent)
  std::vector<Station> stations;
  std::map<std::string, double> params;  // the section's params row
  std::map<std::string, double> fit;     // loop 0's splines row
  std::vector<std::string> issues;       // "stage: message" lines
  // compare's tables (plot_compare.cpp): whiskers, zone bands, the section's verdict
  // (-2 not compared) with its counts and the values failed, not measured or uncertain.
  std::vector<Whisker> whiskers;
  std::map<int, ZoneBand> bands;
  int verdict = -2, passed = 0, failed = 0, not_measured = 0, uncertain = 0;
  std::vector<std::string> failed_items, unmeasured_items, uncertain_items;
};

// The spline tables read once per stream; an unreadable set becomes a note, not an error.
struct Curves {
  std::map<std::pair<int, int>, BSpline> splines;
  std::string error;
};
Curves read_curves(const Stream& stream);

/// Everything drawable of section `section`.
SectionData collect(const Stream& stream, int section, const Curves& curves);

/// Rows of table `name` for `section`, the wanted columns in order (NaN where a column is
/// absent), sorted by (loop or side, index) when those columns exist.
std::vector<std::vector<double>> rows_of(const Stream& stream, const std::string& name, int section,
                                         const std::vector<std::string>& columns);

/// The section's params value `name`, NaN when absent.
double param(const SectionData& d, const std::string& name);
/// The checks of the params row's flags that flag its column `name`, ", "-separated ("" when
/// none): a value drawn or printed is never shown bare when one failed.
std::string failed_checks(const SectionData& d, const std::string& name);

/// "plane through (x, y, z), normal (...); u = (...), v up", or "" without a frame.
std::string frame_text(const SectionData& d);
/// The section's name by its plane: "r = 120 mm" on a surface of revolution, "z = 12.5 mm"
/// for a plane normal to an axis, "h = 3 mm along (0.6, 0, 0.8)" otherwise (h = origin . n);
/// "" without a frame.
std::string plane_name(const SectionData& d);

struct Row {
  std::string name, value;
  std::string failed = {};  ///< the checks that flag the value, ", "-separated ("" when none)
};
/// The rows of the parameter table: what the params and splines rows hold, with units, and
/// the failed checks that flag each value (the params row's flags).
std::vector<Row> parameter_rows(const SectionData& d);

// ---------------------------------------------------------------- geometry (plot_geometry.cpp)

// Bounds in (u, v); empty until a finite point is added.
struct Box {
  double u0 = std::numeric_limits<double>::infinity(), v0 = u0, u1 = -u0, v1 = -u0;
  void add(const V2& p) {
    if (!finite(p)) return;
    u0 = std::min(u0, p.x());
    v0 = std::min(v0, p.y());
    u1 = std::max(u1, p.x());
    v1 = std::max(v1, p.y());
  }
  void add(const V2& c, double r) {
    add(c - V2(r, r));
    add(c + V2(r, r));
  }
  bool empty() const { return !(u1 >= u0 && v1 >= v0); }
  bool touches(const Box& b) const { return !(b.u0 > u1 || b.u1 < u0 || b.v0 > v1 || b.v1 < v0); }
  bool contains(const V2& p) const { return p.x() >= u0 && p.x() <= u1 && p.y() >= v0 && p.y() <= v1; }
  Box grown(double d) const { return {u0 - d, v0 - d, u1 + d, v1 + d}; }
};

// A box holding every point.
inline Box everything() {
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
std::vector<V2> curve_of(const SectionData& d, int loop, const PlotOptions& o, double factor);
/// The loops that have a curve: the splines' then the polylines'.
std::vector<int> curve_loops(const SectionData& d);
/// Whether the loop's curve is closed (polylines always are).
bool closed_loop(const SectionData& d, int loop);

// Path data of a polyline: the runs of segments touching `window` (all of it when the
// window holds everything), each run a subpath.
std::string path_data(const std::vector<V2>& pts, bool closed, const View& v, const Box& window, bool whole);

// The inset of one edge: its window and what marks it.
struct EdgeInset {
  std::string key;      // "le" or "te"
  std::string label;    // "LE", "TE", or "end 1"/"end 2" without params
  V2 center{0, 0};      // window centre
  double half = 0;      // window half-width
  bool circle = false;  // a fitted edge circle exists
  V2 circle_center{0, 0};
  double radius = 0;
  bool point = false;  // an edge point exists
  V2 edge_point{0, 0};
};

/// The edges' insets: around the LE and TE circles (or points) of the params row, else
/// around the ends of the camber line or of the profile; `all` bounds the main view. No
/// window is wider than 2 `max_half`: an edge circle too large for it (a wrong fit) is
/// drawn clipped, the window centred on the edge point, so the inset always magnifies.
std::vector<EdgeInset> edge_insets(const SectionData& d, const Box& all, const PlotOptions& o,
                                   double max_half);

/// The polyline through `pts` refined (Catmull-Rom) so that no step exceeds `step`: a
/// sampled curve (the camber table) drawn smooth where an inset magnifies it.
std::vector<V2> refined(const std::vector<V2>& pts, double step);

/// The vertices of a polyline thinned to the screen (Douglas-Peucker): the thinned line
/// stays within `tolerance` px (in view `v`) of every vertex; the ends of each run of
/// finite points are kept.
std::vector<V2> thinned(const std::vector<V2>& pts, const View& v, double tolerance);

// ---------------------------------------------------------------- dimensions (plot_dimensions.cpp)

/// A dimension line between two points (world), drawn at the px offset of its own.
struct Dimension {
  std::string key;       // "chord", "max-thickness", "le-radius", "te-radius"
  V2 a{0, 0}, b{0, 0};   // what is measured: from a to b
  V2 offset{0, 0};       // world offset of the dimension line from a-b (extension lines)
  double value = 0;      // the value printed (stream units)
  std::string label;     // "chord 62.7511 mm"
  bool arrow_a = true;   // an arrow head at a (a radius has one at b only)
  bool level = false;    // the label level beside b (else along the line)
  bool flagged = false;  // a failed check flags the value (drawn red)
};

/// The main view's dimensions: chord (offset beyond the profile, on the side of the chord
/// line the profile leaves least) and maximum thickness (across the largest inscribed
/// circle, normal to the camber line); none without params.
std::vector<Dimension> main_dimensions(const SectionData& d, const std::vector<V2>& profile);
/// The radius dimension of an inset's edge circle (none without a circle or when the
/// circle does not fit the window).
std::vector<Dimension> edge_dimensions(const SectionData& d, const EdgeInset& e);
/// Draws dimensions in view `v` (class "dimension dim-<key>", label class "dim-label"); a
/// level label is kept within the px box `frame`. Returns the px anchors of the labels.
std::vector<V2> draw_dimensions(std::string& s, const std::vector<Dimension>& dims, const View& v,
                                const Box& frame);
/// The thickness value of each station beside it, outside the suction side, in view `v`;
/// a label closer than a line's height to one placed before or to `taken` is left out.
void draw_station_labels(std::string& s, const SectionData& d, const View& v, std::vector<V2> taken);

// ---------------------------------------------------------------- drawing (plot_svg.cpp)

/// The standalone SVG document of one section (plot_svg in plot.h).
std::string svg_of(const SectionData& d, const PlotOptions& o);

// ---------------------------------------------------------------- compare (plot_compare.cpp)

/// compare's tables of the section into `d` (nothing when the stream has none).
void collect_compare(const Stream& stream, int section, SectionData& d);
/// The whiskers (deviations along the nominal's normal, magnified, coloured by the
/// tolerance they use) and the zones' tolerance bands, in view `v`.
void draw_compare(std::string& s, const SectionData& d, const View& v);
/// The section's verdict line ("" when not compared).
std::string verdict_line(const SectionData& d);
/// What the whiskers and bands show ("" without deviations).
std::string whisker_legend(const SectionData& d);
/// The blade's verdict as an HTML paragraph ("" when no section was compared).
std::string blade_verdict_html(const std::vector<SectionData>& data);

}  // namespace section::detail::plot
