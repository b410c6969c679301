// SPDX-License-Identifier: GPL-3.0-or-later
// The whole blade drawn (plot_blade.h): a few panels of values against the span.
#include "section/extras/plot_blade.h"

#include "plot_parts.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace section {

namespace {

using detail::plot::escape;
using detail::plot::px;
using detail::plot::trimmed;

// One series of a panel: values by section (with their flags) or a fitted line.
struct Series {
  std::string name, colour;
  std::vector<double> value, span;
  std::vector<bool> flagged;
  bool line = false;  // a curve, not dots
};

constexpr double panel_w = 230, panel_h = 420, top = 50, left = 60, gap = 70;

// The panel's frame, ticks and series at column `k`; `s0`..`s1` the span range.
std::string panel(int k, const std::string& title, const std::vector<Series>& series, double s0, double s1) {
  double lo = 0, hi = 0;  // 0 always shown: the reference
  for (const auto& s : series)
    for (double v : s.value)
      if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  if (hi - lo < 1e-9) lo -= 1, hi += 1;
  const double pad = 0.08 * (hi - lo);
  lo -= pad, hi += pad;
  const double x0 = left + k * (panel_w + gap);
  const auto X = [&](double v) { return x0 + (v - lo) / (hi - lo) * panel_w; };
  const auto Y = [&](double s) { return top + panel_h - (s - s0) / std::max(s1 - s0, 1e-12) * panel_h; };
  std::string out = "<g class=\"panel\"><rect x=\"" + px(x0) + "\" y=\"" + px(top) + "\" width=\"" +
                    px(panel_w) + "\" height=\"" + px(panel_h) + "\" fill=\"none\" stroke=\"#999\"/>\n";
  out +=
      "<text x=\"" + px(x0) + "\" y=\"" + px(top - 24) + "\" font-size=\"13\">" + escape(title) + "</text>\n";
  out += "<line x1=\"" + px(X(0)) + "\" y1=\"" + px(top) + "\" x2=\"" + px(X(0)) + "\" y2=\"" +
         px(top + panel_h) + "\" stroke=\"#ccc\"/>\n";
  for (double v : {lo + pad, hi - pad})
    out += "<text x=\"" + px(X(v)) + "\" y=\"" + px(top + panel_h + 16) +
           "\" font-size=\"10\" text-anchor=\"middle\">" + trimmed(v, 4) + "</text>\n";
  double legend = top - 8;
  for (const auto& s : series) {
    out += "<text x=\"" + px(x0 + panel_w) + "\" y=\"" + px(legend) +
           "\" font-size=\"10\" text-anchor=\"end\" fill=\"" + s.colour + "\">" + escape(s.name) +
           "</text>\n";
    legend -= 12;
    if (s.line) {
      std::string d;
      for (std::size_t i = 0; i < s.value.size(); ++i)
        d += (i ? " L" : "M") + px(X(s.value[i])) + "," + px(Y(s.span[i]));
      out += "<path class=\"line\" d=\"" + d + "\" fill=\"none\" stroke=\"" + s.colour + "\"/>\n";
      continue;
    }
    for (std::size_t i = 0; i < s.value.size(); ++i)
      out += s.flagged[i] ? "<circle class=\"flagged\" cx=\"" + px(X(s.value[i])) + "\" cy=\"" +
                                px(Y(s.span[i])) + "\" r=\"4.5\" fill=\"none\" stroke=\"#d00\"/>\n"
                          : "<circle cx=\"" + px(X(s.value[i])) + "\" cy=\"" + px(Y(s.span[i])) +
                                "\" r=\"3\" fill=\"" + s.colour + "\"/>\n";
  }
  return out + "</g>\n";
}

// A series of the sections' values `get`, flagged where `check` is set.
template <class Get>
Series dots(const StackingResult& b, const std::string& name, const std::string& colour, Get get,
            StackCheck check, StackCheck also = StackCheck::order) {
  Series s{name, colour, {}, {}, {}, false};
  for (const auto& v : b.sections) {
    s.value.push_back(get(v));
    s.span.push_back(v.span);
    s.flagged.push_back(v.flags & (static_cast<std::uint32_t>(check) | static_cast<std::uint32_t>(also)));
  }
  return s;
}

// The blade seen along the span (axial right, tangential up, equal scales) at column `k`:
// each section's chord line LE to TE and its centroid, the fitted centroid line.
std::string top_view(int k, const StackingResult& b) {
  const auto at = [&](const Eigen::Vector3d& p) {
    return Eigen::Vector2d(p.dot(b.axial), p.dot(b.tangential));
  };
  detail::plot::Box box;
  for (const auto& v : b.sections) box.add(at(v.le)), box.add(at(v.te)), box.add(at(v.centroid));
  const double x0 = left + k * (panel_w + gap);
  const detail::plot::View view = detail::plot::View::fit(box.grown(1e-9), x0, top, panel_h, panel_h);
  std::string out = "<g class=\"top-view\"><rect x=\"" + px(x0) + "\" y=\"" + px(top) + "\" width=\"" +
                    px(panel_h) + "\" height=\"" + px(panel_h) + "\" fill=\"none\" stroke=\"#999\"/>\n";
  out += "<text x=\"" + px(x0) + "\" y=\"" + px(top - 24) +
         "\" font-size=\"13\">seen along the span: chords, centroids (axial right)</text>\n";
  for (const auto& v : b.sections) {
    const Eigen::Vector2d l = at(v.le), t = at(v.te), c = at(v.centroid);
    const bool flagged =
        v.flags & (static_cast<std::uint32_t>(StackCheck::le) | static_cast<std::uint32_t>(StackCheck::te));
    out += "<line x1=\"" + px(view.x(l.x())) + "\" y1=\"" + px(view.y(l.y())) + "\" x2=\"" +
           px(view.x(t.x())) + "\" y2=\"" + px(view.y(t.y())) + "\" stroke=\"" + (flagged ? "#d00" : "#888") +
           "\"/>\n";
    out += "<circle cx=\"" + px(view.x(c.x())) + "\" cy=\"" + px(view.y(c.y())) +
           "\" r=\"2.5\" fill=\"#1f77b4\"/>\n";
  }
  std::string d;
  for (const auto& p : b.samples) {
    const Eigen::Vector2d c = at(p.centroid);
    d += (d.empty() ? "M" : " L") + px(view.x(c.x())) + "," + px(view.y(c.y()));
  }
  return out + "<path class=\"line\" d=\"" + d + "\" fill=\"none\" stroke=\"#1f77b4\"/>\n</g>\n";
}

}  // namespace

std::string plot_blade_svg(const StackingResult& b, const std::string& units) {
  if (b.sections.empty()) return "";
  const double s0 = b.sections.front().span, s1 = b.sections.back().span;
  Series lean_line{"lean, fitted line", "#1f77b4", {}, {}, {}, true}, sweep_line = lean_line;
  sweep_line.colour = "#2ca02c", sweep_line.name = "sweep, fitted line";
  for (const auto& p : b.samples) {
    lean_line.value.push_back(p.lean), lean_line.span.push_back(p.span);
    sweep_line.value.push_back(p.sweep), sweep_line.span.push_back(p.span);
  }
  using V = const StackedValues&;
  const double width = left + 4 * panel_w + 4 * gap + panel_h + 30, height = top + panel_h + 60;
  std::string out = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + px(width) + "\" height=\"" +
                    px(height) +
                    "\" font-family=\"sans-serif\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  out += "<text x=\"8\" y=\"" + px(top + panel_h / 2) + "\" font-size=\"12\" transform=\"rotate(-90 8 " +
         px(top + panel_h / 2) + ")\" dominant-baseline=\"hanging\">span " + trimmed(s0, 3) + " to " +
         trimmed(s1, 3) + " " + escape(units) + " (hub at the bottom)</text>\n";
  out += panel(0, "twist (deg)",
               {dots(
                   b, "twist", "#9467bd", [](V v) { return v.twist; }, StackCheck::twist)},
               s0, s1);
  out += panel(1, "lean, bow (" + units + ")",
               {lean_line,
                dots(
                    b, "lean", "#1f77b4", [](V v) { return v.lean; }, StackCheck::position),
                dots(
                    b, "bow", "#ff7f0e", [](V v) { return v.bow; }, StackCheck::bow, StackCheck::position)},
               s0, s1);
  out += panel(2, "sweep (" + units + ")",
               {sweep_line, dots(
                                b, "sweep", "#2ca02c", [](V v) { return v.sweep; }, StackCheck::position)},
               s0, s1);
  out +=
      panel(3, "chord, max thickness (" + units + ")",
            {dots(
                 b, "chord", "#8c564b", [](V v) { return v.chord; }, StackCheck::chord),
             dots(
                 b, "max thickness", "#e377c2", [](V v) { return v.max_thickness; }, StackCheck::thickness)},
            s0, s1);
  return out + top_view(4, b) + "</svg>\n";
}

}  // namespace section
