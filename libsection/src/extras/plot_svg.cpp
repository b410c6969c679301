// SPDX-License-Identifier: GPL-3.0-or-later
// The SVG drawing of one section: the main view, the legend, the edge insets and the
// parameter table, laid out top to bottom; see plot_parts.h.
#include "plot_parts.h"

namespace section::detail::plot {

namespace {

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
    ".scale-bar-back{fill:#fff;fill-opacity:.8}.scale-bar-line{stroke:#000;stroke-width:2.5}.scale-bar-tick{"
    "stroke:#000;stroke-width:1.5}"
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
          s +=
              "<circle cx=\"" + px(v.x(p.x())) + "\" cy=\"" + px(v.y(p.y())) + "\" r=\"" + px(2 * r) + "\"/>";
      s += "</g>";
    }
  }
  if (whole) draw_compare(s, d, v);
  for (int loop : curve_loops(d)) {
    const std::string data = path_data(curve_of(d, loop, o, density), closed_loop(d, loop), v, near, whole);
    if (!data.empty())
      s += "<path class=\"curve\" data-loop=\"" + std::to_string(loop) + "\" data-source=\"" +
           d.curve_source + "\" d=\"" + data + "\"/>";
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

void title(Page& p) {
  const SectionData& d = p.d;
  p.body += "<text class=\"title\" x=\"" + px(p.margin) + "\" y=\"" + px(p.y) + "\">Section " +
            std::to_string(d.id) + "</text>";
  const std::string sub = frame_text(d);
  p.body += "<text class=\"subtitle\" x=\"" + px(p.margin + 110) + "\" y=\"" + px(p.y) + "\">" +
            escape(sub.empty() ? "units " + d.units : sub + "; units " + d.units) + "</text>";
  p.y += 12;
  // compare's verdict and what its whiskers show (plot_compare.cpp).
  const char* colour = d.verdict == 1 ? "#c00" : d.verdict == 2 ? "#b07800" : "#080";
  for (const auto& [text, style] :
       {std::pair{verdict_line(d), std::string("font-weight:bold;fill:") + colour},
        std::pair{whisker_legend(d), std::string("font-size:11px;fill:#555")}}) {
    if (text.empty()) continue;
    p.body += "<text class=\"verdict\" x=\"" + px(p.margin) + "\" y=\"" + px(p.y + 8) + "\" style=\"" +
              style + "\">" + escape(text) + "</text>";
    p.y += 18;
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
View main_view(Page& p, const Box& all, const std::vector<EdgeInset>& edges) {
  const SectionData& d = p.d;
  const PlotOptions& o = p.o;
  const double margin = p.margin, y = p.y;
  const bool drawable = !all.empty();
  View main;
  const double view_w = p.W - 2 * margin;
  double view_h = 60;
  if (drawable) {
    const double extent = std::max({all.u1 - all.u0, all.v1 - all.v0, 1e-9});
    const Box padded = all.grown(0.04 * extent);
    const double du = padded.u1 - padded.u0, dv = padded.v1 - padded.v0;
    view_h = std::min(o.max_main_height, view_w * dv / du);
    view_h = std::max(view_h, 60.0);
    main = View::fit(padded, margin, y, view_w, view_h);
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
    draw_geometry(body, d, main, everything(), true, o, edges, 1);
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
  p.body += "<g class=\"legend\">";
  double x = p.margin;
  for (const auto& [cls, label] : items) {
    const double ly = p.y + 10;
    if (cls == "points" || cls == "carried")
      p.body +=
          "<g class=\"" + cls + "\"><circle cx=\"" + px(x + 10) + "\" cy=\"" + px(ly) + "\" r=\"3\"/></g>";
    else
      p.body += "<line class=\"" + cls + "\" x1=\"" + px(x) + "\" y1=\"" + px(ly) + "\" x2=\"" + px(x + 22) +
                "\" y2=\"" + px(ly) + "\"/>";
    p.body += "<text x=\"" + px(x + 28) + "\" y=\"" + px(ly + 4) + "\">" + escape(label) + "</text>";
    x += 36 + 7.2 * static_cast<double>(label.size());
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
  draw_geometry(body, p.d, v, window, false, p.o, marks, std::max(1.0, 0.5 * magnification));
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

// The parameter table and the section's issues at `at`; returns the bottom of the drawing.
double param_table(Page& p, const TablePlace& at) {
  const SectionData& d = p.d;
  if (!p.o.table && d.issues.empty()) return at.row_bottom;
  double ty = at.y + 13;
  const double table_x = at.x, value_x = std::min(p.W - p.margin, table_x + 360);
  std::string& body = p.body;
  body += "<g id=\"" + p.id + "-params\" class=\"param-table\">";
  if (p.o.table) {
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
      body += "<text class=\"empty\" x=\"" + px(table_x) + "\" y=\"" + px(ty) +
              "\">no parameters in the stream</text>";
      ty += 18;
    }
  }
  for (const auto& issue : d.issues) {
    body +=
        "<text class=\"issue\" x=\"" + px(table_x) + "\" y=\"" + px(ty) + "\">" + escape(issue) + "</text>";
    ty += 18;
  }
  body += "</g>";
  return std::max(at.row_bottom, ty - 13);
}

}  // namespace

std::string svg_of(const SectionData& d, const PlotOptions& o) {
  Page p(d, o);
  const Box all = drawn_bounds(d, o);
  const auto edges = all.empty() ? std::vector<EdgeInset>{} : edge_insets(d, all, o);
  title(p);
  const View main = main_view(p, all, edges);
  legend(p, edges);
  const TablePlace at = insets(p, main, edges);
  const double H = std::ceil(param_table(p, at) + p.margin);
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
