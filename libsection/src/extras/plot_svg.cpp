// SPDX-License-Identifier: GPL-3.0-or-later
// The SVG drawing of one section: the main view, the legend, the edge insets and the
// parameter table, laid out top to bottom; see plot_parts.h.
#include "plot_parts.h"

#include <set>

namespace section::detail::plot {

namespace {

const char* const style =
    "text{font-family:'DejaVu Sans',Arial,sans-serif;font-size:13px;fill:#222}"
    ".title{font-size:17px;font-weight:bold}.subtitle{fill:#555}"
    ".view-frame{fill:#fff;stroke:#aaa;stroke-width:1}"
    ".carried circle{fill:none;stroke:#ff7f0e;stroke-width:1}"
    ".curve{fill:none;stroke:#111;stroke-width:1.3}"
    ".camber{fill:none;stroke:#d62728;stroke-width:1.5}"
    ".skeleton{fill:none;stroke:#d62728;stroke-width:1.2;stroke-dasharray:5 3}"
    ".station{fill:none;stroke:#2ca02c;stroke-width:.9}"
    ".station-center{fill:#2ca02c}"
    ".station.flagged{stroke:#c00;stroke-dasharray:3 2}.station-center.flagged{fill:#c00}"
    ".chord{stroke:#444;stroke-width:1.1;stroke-dasharray:7 4}"
    ".le-circle{fill:none;stroke:#ff7f0e;stroke-width:1.8}"
    ".te-circle{fill:none;stroke:#9467bd;stroke-width:1.8}"
    ".le-point{fill:#ff7f0e;stroke:#000;stroke-width:.6}.te-point{fill:#9467bd;stroke:#000;stroke-width:.6}"
    ".inset-frame{fill:none;stroke:#777;stroke-width:1;stroke-dasharray:3 2}"
    ".inset-label{font-weight:bold}"
    ".scale-bar-back{fill:#fff;fill-opacity:.8}.scale-bar-line{stroke:#000;stroke-width:2.5}.scale-bar-tick{"
    "stroke:#000;stroke-width:1.5}"
    ".param-name{fill:#444}.param-value{font-weight:bold;text-anchor:end}.param-value.flagged{fill:#c00}"
    ".param-fails{fill:#c00;font-size:11px;text-anchor:end}"
    ".param-head{font-weight:bold;font-size:14px}"
    ".issue{fill:#c00}.empty{fill:#888;font-style:italic}"
    ".legend line{stroke-width:2.5}"
    ".points{fill:none;stroke:#1f77b4;stroke-opacity:.6;stroke-linecap:round}"
    ".dim-line,.dim-ext{stroke:#0b5394;stroke-width:1}.dim-ext{stroke-width:.7}.dim-arrow{fill:#0b5394}"
    ".dim-label{font-size:12px;fill:#0b5394}.station-value{font-size:10px;fill:#1a7a1a}"
    ".station-value.flagged,.dim-label.flagged{fill:#c00}";

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
void scale_bar(std::string& s, const std::string& id, const View& v, double left, double bottom, double width,
               const std::string& units) {
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

// The measured points as one path of dots (round caps on zero-length segments: a tenth of
// the text of circles), thinned to one per dot-sized cell of the view's screen: every
// point lies within a dot's width of a drawn one; the insets, magnified, show the edges'
// points one by one.
void draw_points(std::string& s, const SectionData& d, const View& v, const Box& near, bool whole,
                 const PlotOptions& o) {
  const double r = whole ? o.point_radius : 1.5 * o.point_radius;
  const double cell = std::max(1.0, r);
  std::set<std::pair<long, long>> taken;
  std::string data;
  long X = 0, Y = 0;  // the last dot, in tenths of a px: each dot moves from it (m dx dy)
  for (const auto& [loop, pts] : d.points)
    for (const auto& p : pts) {
      if (!near.contains(p)) continue;
      const double x = v.x(p.x()), y = v.y(p.y());
      if (!taken.insert({std::lround(x / cell), std::lround(y / cell)}).second) continue;
      const long x10 = std::lround(10 * x), y10 = std::lround(10 * y);
      data += (data.empty() ? "M" + trimmed(0.1 * x10, 1) + " " + trimmed(0.1 * y10, 1)
                            : "m" + trimmed(0.1 * (x10 - X), 1) + " " + trimmed(0.1 * (y10 - Y), 1)) +
              "h0";
      X = x10;
      Y = y10;
    }
  if (!data.empty()) s += "<path class=\"points\" stroke-width=\"" + px(2 * r) + "\" d=\"" + data + "\"/>";
  // Carried points ringed on top of their dots: the slab had no point there.
  if (!d.carried.empty()) {
    s += "<g class=\"carried\">";
    for (const auto& p : d.carried)
      if (near.contains(p))
        s += "<circle cx=\"" + px(v.x(p.x())) + "\" cy=\"" + px(v.y(p.y())) + "\" r=\"" + px(2 * r) + "\"/>";
    s += "</g>";
  }
}

// The section's geometry in view `v`, restricted to `window` unless `whole`; `dims` the
// dimension lines drawn on top.
void draw_geometry(std::string& s, const SectionData& d, const View& v, const Box& window, bool whole,
                   const PlotOptions& o, const std::vector<EdgeInset>& edges, double density,
                   const std::vector<Dimension>& dims) {
  const Box near = whole ? everything() : window.grown(0.05 * (window.u1 - window.u0));
  if (o.stations && !d.stations.empty()) {
    s += "<g class=\"stations\">";
    for (const auto& st : d.stations) {
      Box b;
      b.add(st.center, 0.5 * st.thickness);
      if (!b.touches(near)) continue;
      // A thickness its row flags (a hole at its circle's contact, ...) drawn apart.
      const std::string flagged = st.flagged ? " flagged" : "";
      circle(s, "station" + flagged, v, st.center, 0.5 * st.thickness * v.scale);
      circle(s, "station-center" + flagged, v, st.center, 1.8);
    }
    s += "</g>";
  }
  if (o.points && !d.points.empty()) draw_points(s, d, v, near, whole, o);
  if (whole) draw_compare(s, d, v);
  for (int loop : curve_loops(d)) {
    const auto pts = thinned(curve_of(d, loop, o, density), v, 0.2);
    const std::string data = path_data(pts, closed_loop(d, loop), v, near, whole);
    if (!data.empty())
      s += "<path class=\"curve\" data-loop=\"" + std::to_string(loop) + "\" data-source=\"" +
           d.curve_source + "\" d=\"" + data + "\"/>";
  }
  // The camber table is a sampled curve: refined to 2 px steps, it stays smooth magnified.
  const auto& mean = d.camber.size() >= 2 ? d.camber : d.skeleton;
  if (mean.size() >= 2) {
    const std::string data = path_data(thinned(refined(mean, 2 / v.scale), v, 0.2), false, v, near, whole);
    if (!data.empty())
      s += std::string("<path class=\"") + (d.camber.size() >= 2 ? "camber" : "skeleton") + "\" d=\"" + data +
           "\"/>";
  }
  const V2 le(param(d, "le_u"), param(d, "le_v")), te(param(d, "te_u"), param(d, "te_v"));
  if (finite(le) && finite(te))
    s += "<line class=\"chord\" x1=\"" + px(v.x(le.x())) + "\" y1=\"" + px(v.y(le.y())) + "\" x2=\"" +
         px(v.x(te.x())) + "\" y2=\"" + px(v.y(te.y())) + "\"/>";
  for (const auto& e : edges) {
    if (e.circle) circle(s, e.key + "-circle", v, e.circle_center, e.radius * v.scale);
    if (e.point) circle(s, e.key + "-point", v, e.edge_point, 3.5);
  }
  const Box frame{v.x(window.u0), v.y(window.v1), v.x(window.u1), v.y(window.v0)};
  const auto anchors = draw_dimensions(s, dims, v, frame);
  if (whole && o.stations && !d.stations.empty()) draw_station_labels(s, d, v, anchors);
}

// One section's drawing as it is laid out: the SVG body so far and where the next part goes.
struct Page {
  const SectionData& d;
  const PlotOptions& o;
  std::string id;      // "s<section>", the prefix of the element ids
  double margin = 16;  // px
  double W = 0;        // px, the drawing's width
  double y = 0;        // px, the top of the next part
  std::string body;

  Page(const SectionData& data, const PlotOptions& options)
      : d(data), o(options), id("s" + std::to_string(data.id)), W(options.width), y(margin + 18) {}
};

// The world box seen through the px box `b` of view `v`.
Box frame_world(const View& v, const Box& b) {
  return {(b.u0 - v.tx) / v.scale, (v.ty - b.v1) / v.scale, (b.u1 - v.tx) / v.scale, (v.ty - b.v0) / v.scale};
}

// The px kept around the main view's profile for the labels outside it (station values).
double labels_pad(const SectionData& d, const PlotOptions& o) {
  return o.stations && !d.stations.empty() ? 44 : 0;
}

// Bounds of everything drawn in the main view.
Box drawn_bounds(const SectionData& d, const PlotOptions& o) {
  Box all;
  for (const auto& [loop, pts] : d.points)
    for (const auto& p : pts) all.add(p);
  for (int loop : curve_loops(d))
    for (const auto& p : curve_of(d, loop, o, 1)) all.add(p);
  for (const auto& p : d.camber) all.add(p);
  for (const auto& p : d.skeleton) all.add(p);
  return all;
}

// Lines of text at the left margin, each `step` px below the last, wrapped to the width.
void lines(Page& p, const std::string& cls, const std::string& text, double font, double step,
           const std::string& style = "") {
  for (const auto& l : wrap(text, p.W - 2 * p.margin, font)) {
    p.body += "<text class=\"" + cls + "\" x=\"" + px(p.margin) + "\" y=\"" + px(p.y) + "\"" +
              (style.empty() ? "" : " style=\"" + style + "\"") + ">" + escape(l) + "</text>";
    p.y += step;
  }
}

// The section's name by its plane (plane_name), its id, and the frame.
void title(Page& p) {
  const SectionData& d = p.d;
  const std::string plane = plane_name(d);
  lines(p, "title", (plane.empty() ? "" : plane + "  \xC2\xB7  ") + "section " + std::to_string(d.id), 17,
        18);
  const std::string sub = frame_text(d);
  lines(p, "subtitle", sub.empty() ? "units " + d.units : sub + "; units " + d.units, 13, 16);
  p.y -= 4;
  // compare's verdict and what its whiskers show (plot_compare.cpp).
  const char* colour = d.verdict == 1 ? "#c00" : d.verdict == 2 || d.verdict == 3 ? "#b07800" : "#080";
  for (const auto& [text, style] :
       {std::pair{verdict_line(d), std::string("font-weight:bold;fill:") + colour},
        std::pair{whisker_legend(d), std::string("font-size:11px;fill:#555")}}) {
    if (text.empty()) continue;
    p.y += 8;
    lines(p, "verdict", text, 13, 18, style);
    p.y -= 8;
  }
}

// The insets' frames and labels on the main view.
void inset_frames(Page& p, const View& main, const std::vector<EdgeInset>& edges) {
  for (const auto& e : edges) {
    const double x0 = main.x(e.center.x() - e.half), y0 = main.y(e.center.y() + e.half);
    const double side = 2 * e.half * main.scale;
    p.body += "<rect class=\"inset-frame\" x=\"" + px(x0) + "\" y=\"" + px(y0) + "\" width=\"" + px(side) +
              "\" height=\"" + px(side) + "\"/>";
    p.body += "<text class=\"inset-label\" x=\"" + px(x0) + "\" y=\"" + px(y0 - 4) + "\">" + escape(e.label) +
              "</text>";
  }
}

// The main view: everything in `all` to scale, within the width and max_main_height.
View main_view(Page& p, const Box& all, const std::vector<EdgeInset>& edges,
               const std::vector<Dimension>& dims) {
  const SectionData& d = p.d;
  const PlotOptions& o = p.o;
  const double margin = p.margin, y = p.y;
  const bool drawable = !all.empty();
  View main;
  const double view_w = p.W - 2 * margin;
  double view_h = 60;
  if (drawable) {
    const double pad = labels_pad(d, o);  // px kept for the labels outside the profile
    const double extent = std::max({all.u1 - all.u0, all.v1 - all.v0, 1e-9});
    const Box padded = all.grown(0.04 * extent);
    const double du = padded.u1 - padded.u0, dv = padded.v1 - padded.v0;
    view_h = std::min(o.max_main_height, (view_w - 2 * pad) * dv / du + 2 * pad);
    view_h = std::max(view_h, 60.0);
    main = View::fit(padded, margin + pad, y + pad, view_w - 2 * pad, view_h - 2 * pad);
  }
  std::string& body = p.body;
  body += "<g id=\"" + p.id + "-main\" class=\"view main\" data-scale=\"" + trimmed(main.scale, 6) +
          "\" data-tx=\"" + trimmed(main.tx, 4) + "\" data-ty=\"" + trimmed(main.ty, 4) + "\">";
  const std::string frame_rect = "x=\"" + px(margin) + "\" y=\"" + px(y) + "\" width=\"" + px(view_w) +
                                 "\" height=\"" + px(view_h) + "\"";
  body += "<clipPath id=\"" + p.id + "-main-clip\"><rect " + frame_rect + "/></clipPath>";
  body += "<rect class=\"view-frame\" " + frame_rect + "/>";
  if (drawable) {
    body += "<g clip-path=\"url(#" + p.id + "-main-clip)\">";
    const Box frame{margin, y, margin + view_w, y + view_h};
    draw_geometry(body, d, main, frame_world(main, frame), true, o, edges, 1, dims);
    if (o.inset_size > 0) inset_frames(p, main, edges);
    body += "</g>";
    scale_bar(body, p.id + "-main-scale", main, margin, y + view_h, view_w, d.units);
  } else {
    body += "<text class=\"empty\" x=\"" + px(margin + 12) + "\" y=\"" + px(y + 36) +
            "\">nothing to draw: the stream holds no geometry for this section</text>";
  }
  body += "</g>";
  p.y += view_h + 8;
  return main;
}

// The legend: one sample mark and label for each kind of element drawn.
void legend(Page& p, const std::vector<EdgeInset>& edges) {
  const SectionData& d = p.d;
  const PlotOptions& o = p.o;
  std::vector<std::pair<std::string, std::string>> items;  // class, label
  if (o.points && !d.points.empty()) items.push_back({"points", "measured points"});
  if (o.points && !d.carried.empty())
    items.push_back({"carried", "points carried onto the plane (gap fill)"});
  if (d.curve_source == "smoothed")
    items.push_back({"curve", "smoothed points"});
  else if (!d.curve_source.empty())
    items.push_back({"curve", "fitted curve (" + d.curve_source + ")"});
  if (d.camber.size() >= 2)
    items.push_back({"camber", "mean-camber line"});
  else if (d.skeleton.size() >= 2)
    items.push_back({"skeleton", "skeleton"});
  if (o.stations && !d.stations.empty()) items.push_back({"station", "inscribed circles"});
  if (std::isfinite(param(d, "chord"))) items.push_back({"chord", "chord line"});
  for (const auto& e : edges)
    if (e.circle) items.push_back({e.key + "-circle", e.label + " circle"});
  if (o.dimensions && std::isfinite(param(d, "chord")))
    items.push_back({"dim-line", "dimensions (" + d.units + ")"});
  if (o.stations && !d.stations.empty()) items.push_back({"station-value", "thickness at the stations"});
  p.body += "<g class=\"legend\">";
  double x = p.margin;
  for (const auto& [cls, label] : items) {
    const double item = 44 + text_width(label, 13);
    if (x > p.margin && x + item > p.W - p.margin) {  // next row
      x = p.margin;
      p.y += 20;
    }
    const double ly = p.y + 10;
    if (cls == "points")
      p.body += "<path class=\"points\" stroke-width=\"6\" d=\"M" + px(x + 10) + " " + px(ly) + "h0\"/>";
    else if (cls == "carried")
      p.body +=
          "<g class=\"" + cls + "\"><circle cx=\"" + px(x + 10) + "\" cy=\"" + px(ly) + "\" r=\"3\"/></g>";
    else if (cls == "station-value")
      p.body += "<text class=\"station-value\" x=\"" + px(x) + "\" y=\"" + px(ly + 4) + "\">1.234</text>";
    else
      p.body += "<line class=\"" + cls + "\" x1=\"" + px(x) + "\" y1=\"" + px(ly) + "\" x2=\"" + px(x + 22) +
                "\" y2=\"" + px(ly) + "\"/>";
    const double gap = cls == "station-value" ? 36 : 28;
    p.body += "<text x=\"" + px(x + gap) + "\" y=\"" + px(ly + 4) + "\">" + escape(label) + "</text>";
    x += item;
  }
  p.body += "</g>";
  p.y += 26;
}

// The inset of edge `e`, a square of side inset_size at (x, lower + 18) under its label.
void inset(Page& p, const View& main, const EdgeInset& e, double x, double lower) {
  const double side = p.o.inset_size;
  const std::string gid = p.id + "-" + e.key;
  const double top = lower + 18;
  Box window{e.center.x() - e.half, e.center.y() - e.half, e.center.x() + e.half, e.center.y() + e.half};
  const View v = View::fit(window, x, top, side, side);
  const double magnification = v.scale / main.scale;
  std::string& body = p.body;
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
  draw_geometry(body, p.d, v, window, false, p.o, marks, std::max(1.0, 0.5 * magnification),
                p.o.dimensions ? edge_dimensions(p.d, e) : std::vector<Dimension>{});
  body += "</g>";
  scale_bar(body, gid + "-scale", v, x, top + side, side, p.d.units);
  body += "</g>";
}

// Where the parameter table goes, and the bottom of the row above it.
struct TablePlace {
  double x = 0, y = 0, row_bottom = 0;
};

// The lower row: the edge insets, then the parameter table beside them (or below when narrow).
TablePlace insets(Page& p, const View& main, const std::vector<EdgeInset>& edges) {
  const double lower = p.y;
  TablePlace at{p.margin, p.y, p.y};
  if (p.o.inset_size > 0 && !edges.empty()) {
    const double gap = 16, side = p.o.inset_size;
    double x = p.margin;
    for (const auto& e : edges) {
      inset(p, main, e, x, lower);
      x += side + gap;
    }
    at.row_bottom = lower + 18 + side;
    at.x = x + 8;
    if (p.W - p.margin - at.x < 280) {  // no room beside the insets
      at.x = p.margin;
      at.y = at.row_bottom + 16;
    }
  }
  return at;
}

// The parameter table at `at`; returns the bottom of the row. A value too long to stand
// beside its name goes on the line below it.
double param_table(Page& p, const TablePlace& at) {
  const SectionData& d = p.d;
  if (!p.o.table) return at.row_bottom;
  double ty = at.y + 13;
  const double table_x = at.x, value_x = std::min(p.W - p.margin, table_x + 360);
  std::string& body = p.body;
  body += "<g id=\"" + p.id + "-params\" class=\"param-table\">";
  body += "<text class=\"param-head\" x=\"" + px(table_x) + "\" y=\"" + px(ty) + "\">Parameters</text>";
  ty += 20;
  const auto rows = parameter_rows(d);
  for (const auto& r : rows) {
    body += "<text class=\"param-name\" x=\"" + px(table_x) + "\" y=\"" + px(ty) + "\">" + escape(r.name) +
            "</text>";
    if (text_width(r.name, 13) + text_width(r.value, 13) + 12 > value_x - table_x) ty += 16;
    const bool flagged = !r.failed.empty();
    body += "<text class=\"param-value" + std::string(flagged ? " flagged" : "") + "\" x=\"" + px(value_x) +
            "\" y=\"" + px(ty) + "\">" + escape(r.value) + "</text>";
    ty += 18;
    // A value a check flags is not shown bare: the checks it failed under it.
    if (flagged)
      for (const auto& line : wrap("fails check " + r.failed, value_x - table_x, 11)) {
        body += "<text class=\"param-fails\" x=\"" + px(value_x) + "\" y=\"" + px(ty - 3) + "\">" +
                escape(line) + "</text>";
        ty += 14;
      }
  }
  if (rows.empty()) {
    body += "<text class=\"empty\" x=\"" + px(table_x) + "\" y=\"" + px(ty) +
            "\">no parameters in the stream</text>";
    ty += 18;
  }
  body += "</g>";
  return std::max(at.row_bottom, ty - 13);
}

// The section's issues under everything, across the width, each wrapped to it.
void issues(Page& p) {
  if (p.d.issues.empty()) return;
  p.y += 22;
  p.body += "<g id=\"" + p.id + "-issues\" class=\"issues\">";
  for (const auto& issue : p.d.issues) lines(p, "issue", issue, 13, 17);
  p.body += "</g>";
  p.y -= 17;
}

// The largest inset half-width (world) for a main view of `all`: the inset magnifies at
// least twice.
double largest_half(const Box& all, const SectionData& d, const PlotOptions& o) {
  const double pad = labels_pad(d, o), view_w = o.width - 2 * 16 - 2 * pad;
  const double extent = std::max({all.u1 - all.u0, all.v1 - all.v0, 1e-9});
  const Box padded = all.grown(0.04 * extent);
  const double scale = std::min(view_w / (padded.u1 - padded.u0), std::max(o.max_main_height - 2 * pad, 1.0) /
                                                                      std::max(padded.v1 - padded.v0, 1e-12));
  return o.inset_size > 0 ? o.inset_size / (2 * 2.2 * scale) : std::numeric_limits<double>::infinity();
}

}  // namespace

std::string svg_of(const SectionData& d, const PlotOptions& o) {
  Page p(d, o);
  const Box profile = drawn_bounds(d, o);
  const auto edges =
      profile.empty() ? std::vector<EdgeInset>{} : edge_insets(d, profile, o, largest_half(profile, d, o));
  // The main view holds the dimension lines and the insets' windows too.
  std::vector<V2> outline;
  for (int loop : curve_loops(d))
    for (const auto& q : curve_of(d, loop, o, 1)) outline.push_back(q);
  if (outline.empty())
    for (const auto& [loop, pts] : d.points) outline.insert(outline.end(), pts.begin(), pts.end());
  const auto dims = profile.empty() || !o.dimensions ? std::vector<Dimension>{} : main_dimensions(d, outline);
  Box all = profile;
  for (const auto& dim : dims) {
    all.add(V2(dim.a + dim.offset));
    all.add(V2(dim.b + dim.offset));
  }
  if (o.inset_size > 0)
    for (const auto& e : edges) all.add(e.center, e.half);
  title(p);
  const View main = main_view(p, all, edges, dims);
  legend(p, edges);
  const TablePlace at = insets(p, main, edges);
  p.y = param_table(p, at);
  issues(p);
  const double H = std::ceil(p.y + p.margin);
  const double W = p.W;
  std::string s = "<svg xmlns=\"http://www.w3.org/2000/svg\" id=\"" + p.id +
                  "\" class=\"section-plot\" width=\"" + px(W) + "\" height=\"" + px(H) +
                  "\" viewBox=\"0 0 " + px(W) + " " + px(H) + "\" data-section=\"" + std::to_string(d.id) +
                  "\" data-units=\"" + escape(d.units) + "\">";
  s += "<style>";
  s += style;
  s += "</style><rect x=\"0\" y=\"0\" width=\"" + px(W) + "\" height=\"" + px(H) + "\" fill=\"#fafafa\"/>";
  s += p.body;
  s += "</svg>\n";
  return s;
}

}  // namespace section::detail::plot
