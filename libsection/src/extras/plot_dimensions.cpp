// SPDX-License-Identifier: GPL-3.0-or-later
// Dimension lines of a section's drawing (chord, maximum thickness, edge radii) and the
// thickness values at the stations; see plot_parts.h.
#include "plot_parts.h"

namespace section::detail::plot {

namespace {

V2 perp(const V2& d) {
  return {-d.y(), d.x()};
}

// The camber line's point and unit tangent at arc length `s` (by index fraction `f` when
// the camber table has no arc lengths).
std::pair<V2, V2> camber_at(const SectionData& d, double s, double f) {
  const auto& c = d.camber;
  std::size_t i = 0;
  double t = 0;
  const bool by_s = d.camber_s.size() == c.size() && std::isfinite(d.camber_s.front()) &&
                    std::isfinite(d.camber_s.back()) && std::isfinite(s);
  if (by_s) {
    while (i + 2 < c.size() && d.camber_s[i + 1] < s) ++i;
    const double ds = d.camber_s[i + 1] - d.camber_s[i];
    t = ds > 0 ? std::clamp((s - d.camber_s[i]) / ds, 0.0, 1.0) : 0.0;
  } else {
    const double x = std::clamp(f, 0.0, 1.0) * static_cast<double>(c.size() - 1);
    i = std::min(static_cast<std::size_t>(x), c.size() - 2);
    t = x - static_cast<double>(i);
  }
  return {c[i] + t * (c[i + 1] - c[i]), (c[i + 1] - c[i]).normalized()};
}

// The station nearest `p`, or null.
const Station* nearest_station(const SectionData& d, const V2& p) {
  const Station* best = nullptr;
  for (const auto& st : d.stations)
    if (!best || (st.center - p).norm() < (best->center - p).norm()) best = &st;
  return best;
}

std::string line(const std::string& cls, const V2& a, const V2& b) {
  return "<line class=\"" + cls + "\" x1=\"" + px(a.x()) + "\" y1=\"" + px(a.y()) + "\" x2=\"" + px(b.x()) +
         "\" y2=\"" + px(b.y()) + "\"/>";
}

// A filled arrow head with its tip at `tip`, pointing along the unit px vector `dir`.
std::string arrow(const V2& tip, const V2& dir) {
  const V2 back = tip - 9 * dir, side = 3 * perp(dir);
  const V2 l = back + side, r = back - side;
  return "<path class=\"dim-arrow\" d=\"M" + px(tip.x()) + " " + px(tip.y()) + " L" + px(l.x()) + " " +
         px(l.y()) + " L" + px(r.x()) + " " + px(r.y()) + " Z\"/>";
}

// Text at px `at`, rotated to run along px direction `dir` and kept upright; `anchor`
// start, middle or end (flipped with the text when it is turned round).
std::string label(const std::string& cls, const std::string& text, const V2& at, V2 dir, std::string anchor,
                  double lift) {
  if (dir.x() < -1e-9 || (std::abs(dir.x()) <= 1e-9 && dir.y() > 0)) {
    dir = -dir;
    anchor = anchor == "start" ? "end" : anchor == "end" ? "start" : anchor;
  }
  const double angle = std::atan2(dir.y(), dir.x()) * 180 / M_PI;
  const V2 p = at + lift * perp(dir);
  return "<text class=\"" + cls + "\" x=\"" + px(p.x()) + "\" y=\"" + px(p.y()) + "\" text-anchor=\"" +
         anchor + "\" transform=\"rotate(" + fixed(angle, 2) + " " + px(p.x()) + " " + px(p.y()) + ")\">" +
         escape(text) + "</text>";
}

}  // namespace

std::vector<Dimension> main_dimensions(const SectionData& d, const std::vector<V2>& profile) {
  std::vector<Dimension> out;
  const V2 le(param(d, "le_u"), param(d, "le_v")), te(param(d, "te_u"), param(d, "te_v"));
  const double chord = param(d, "chord");
  if (finite(le) && finite(te) && std::isfinite(chord) && (te - le).norm() > 0) {
    // Offset to the side of the chord line the profile leaves least, beyond the profile.
    const V2 n = perp(te - le).normalized();
    double lo = 0, hi = 0;
    for (const auto& p : profile)
      if (finite(p)) {
        lo = std::min(lo, (p - le).dot(n));
        hi = std::max(hi, (p - le).dot(n));
      }
    const double side = hi <= -lo ? 1 : -1, beyond = side > 0 ? hi : -lo;
    Dimension dim{
        "chord", le, te, side * (beyond + 0.06 * chord) * n, chord, "chord " + length_text(chord, d.units)};
    dim.flagged = !failed_checks(d, "chord").empty();
    out.push_back(dim);
  }
  const double t = param(d, "max_thickness"), pos = param(d, "max_thickness_pos");
  if (d.camber.size() >= 2 && std::isfinite(t) && t > 0 && std::isfinite(pos)) {
    const auto [c, tangent] = camber_at(d, pos * param(d, "camber_length"), pos);
    V2 n = perp(tangent);
    // From the pressure side to the suction side: the label goes beyond it, in the row of
    // the stations' labels.
    if (const Station* st = nearest_station(d, c); st && finite(st->suction) && (st->suction - c).dot(n) > 0)
      n = -n;
    if (finite(c) && finite(n)) {
      out.push_back({"max-thickness",
                     c + 0.5 * t * n,
                     c - 0.5 * t * n,
                     {0, 0},
                     t,
                     "max thickness " + length_text(t, d.units)});
      out.back().flagged = !failed_checks(d, "max_thickness").empty();
    }
  }
  return out;
}

std::vector<Dimension> edge_dimensions(const SectionData& d, const EdgeInset& e) {
  if (!e.circle || (e.circle_center - e.center).norm() + e.radius > e.half) return {};
  // The radius drawn at 60 degrees from the edge direction, clear of the camber line.
  V2 dir = e.point && (e.edge_point - e.circle_center).norm() > 0
               ? (e.edge_point - e.circle_center).normalized()
               : V2(1, 0);
  dir = 0.5 * dir + std::sqrt(0.75) * perp(dir);
  Dimension dim{e.key + "-radius",
                e.circle_center,
                e.circle_center + e.radius * dir,
                {0, 0},
                e.radius,
                "R " + length_text(e.radius, d.units)};
  dim.arrow_a = false;
  dim.level = true;
  dim.flagged = !failed_checks(d, e.key + "_radius").empty();
  return {dim};
}

std::vector<V2> draw_dimensions(std::string& s, const std::vector<Dimension>& dims, const View& v,
                                const Box& frame) {
  auto pixel = [&](const V2& p) { return V2(v.x(p.x()), v.y(p.y())); };
  std::vector<V2> anchors;
  for (const auto& dim : dims) {
    const V2 a = pixel(dim.a), b = pixel(dim.b), pa = pixel(dim.a + dim.offset),
             pb = pixel(dim.b + dim.offset);
    if ((pb - pa).norm() < 1e-9) continue;
    const V2 dir = (pb - pa).normalized();
    const std::string cls = dim.flagged ? "dim-label flagged" : "dim-label";  // a flagged value red
    s += "<g class=\"dimension dim-" + dim.key + "\" data-value=\"" + trimmed(dim.value, 9) + "\">";
    if (dim.offset.norm() > 0) {  // extension lines, a little beyond the dimension line
      const V2 out = (pa - a).norm() > 0 ? (pa - a).normalized() : V2(0, 0);
      s += line("dim-ext", a, pa + 5 * out) + line("dim-ext", b, pb + 5 * out);
    }
    s += line("dim-line", pa, pb);
    if (dim.arrow_a) s += arrow(pa, -dir);
    s += arrow(pb, dir);
    const V2 mid = 0.5 * (pa + pb);
    const std::string value = fixed(dim.value, 4);  // the short label: the number alone
    if (dim.offset.norm() > 0) {                    // along the line, on its outer side
      const V2 outward = pa - a;
      const double lift = perp(dir.x() < 0 ? V2(-dir) : dir).dot(outward) > 0 ? 13 : -5;
      s += label(cls, dim.label, mid, dir, "middle", lift);
      anchors.push_back(mid);
    } else if (!dim.level && (pb - pa).norm() >= text_width(value, 12) + 24) {
      // Along the line between its arrows, the whole label when it fits, else the number.
      const bool whole = (pb - pa).norm() >= text_width(dim.label, 12) + 24;
      s += label(cls, whole ? dim.label : value, mid, dir, "middle", -4);
      anchors.push_back(mid);
    } else {
      // Along the line beyond b, else beyond a, where the label fits the frame; else level
      // beside b, kept within the frame.
      const double w = text_width(dim.label, 12) + 6;
      auto fits = [&](const V2& end, const V2& out) {
        const V2 tip = end + w * out, side = 7 * perp(out);
        return !dim.level && frame.contains(tip + side) && frame.contains(tip - side) &&
               frame.contains(end + side) && frame.contains(end - side);
      };
      if (fits(pb, dir) || fits(pa, -dir)) {
        const bool at_b = fits(pb, dir);
        const V2 end = at_b ? pb : pa, out = at_b ? dir : V2(-dir);
        s += label(cls, dim.label, end + 6 * out, out, "start", 4);
        anchors.push_back(end + 5 * out);
      } else {
        double x = dir.x() >= 0 ? pb.x() + 6 : pb.x() - w;
        x = std::clamp(x, frame.u0 + 4, std::max(frame.u0 + 4, frame.u1 - w));
        const double y = std::clamp(pb.y() + 4, frame.v0 + 14, frame.v1 - 4);
        s += "<text class=\"" + cls + "\" x=\"" + px(x) + "\" y=\"" + px(y) + "\">" + escape(dim.label) +
             "</text>";
        anchors.emplace_back(x, y);
      }
    }
    s += "</g>";
  }
  return anchors;
}

void draw_station_labels(std::string& s, const SectionData& d, const View& v, std::vector<V2> taken) {
  std::vector<V2>& placed = taken;
  s += "<g class=\"station-labels\">";
  for (const auto& st : d.stations) {
    const bool outside = finite(st.suction) && (st.suction - st.center).norm() > 0;
    const V2 c(v.x(st.center.x()), v.y(st.center.y()));
    V2 dir(0, -1), at = c + V2(0, -4);
    if (outside) {
      const V2 q(v.x(st.suction.x()), v.y(st.suction.y()));
      dir = (q - c).normalized();
      at = q + 5 * dir;
    }
    bool crowded = false;
    for (const auto& p : placed) crowded |= (p - at).norm() < 12;
    if (crowded) continue;
    placed.push_back(at);
    s += "<g class=\"station-label\" data-value=\"" + trimmed(st.thickness, 9) + "\">" +
         label(st.flagged ? "station-value flagged" : "station-value", fixed(st.thickness, 3), at, dir,
               outside ? "start" : "middle", 3.5) +
         "</g>";
  }
  s += "</g>";
}

}  // namespace section::detail::plot
