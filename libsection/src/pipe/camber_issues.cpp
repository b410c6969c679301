// SPDX-License-Identifier: GPL-3.0-or-later
// The issues camber_stream reports on a section.
#include "pipe/camber_issues.h"

#include "section/edge.h"
#include "section/units.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace section::pipe {

namespace {

std::string join(std::string a, const std::string& b) {
  return a.empty() ? b : b.empty() ? a : a + ", " + b;
}

// An edge that is not round: a flat face is reported with its width and a sharp edge as
// a vertex (never a circle); other blunt edges as the edge model says.
std::string shape_note(const Edge& e, const char* which, EdgeModel model) {
  if (e.shape == EdgeShape::round) return std::string();
  if (e.shape == EdgeShape::sharp)
    return std::string(which) + " is " + edge_shape_name(EdgeShape::sharp) +
           (e.vertex ? ": the profile closes at a vertex" : "") + " (radius reported as 0)";
  if (e.face > 0)
    return std::string(which) + " is " + edge_shape_name(EdgeShape::blunt) + ": a flat face " +
           format_length(e.face) + " wide (radius reported as 0)";
  return std::string(which) + " looks " + edge_shape_name(e.shape) +
         (model == EdgeModel::round
              ? std::string(" (fitted as ") + edge_shape_name(EdgeShape::round) + " anyway)"
              : std::string(" (radius reported as 0)"));
}

// An edge whose point or arc lies over a hole in the measured points: around its point, a
// hole of edge_hole sizes within its arc, or a shorter one whose bridge bends so far that
// edge_bridge (a tenth) of that bend exceeds the accuracy (a 1.6 mm hole 0.4 mm from a 2 mm
// LE radius bent 0.15 mm: its bridge strayed 24 um, the LE point 18 um, the chord 14 um).
std::string hole_note(const Edge& e, const EdgeCoverage& cover, const char* which, const SectionFacts& f) {
  if (cover.vertex_hole > 0)
    return std::string(which) + " not measured: its vertex lies in " + format_length(cover.vertex_hole) +
           " of the profile without a measured point (a hole in the data): the corner there is where the "
           "curve bridging the hole turns, not the blade's edge";
  const double size = edge_size(e), unmeasured = cover.around;
  if (!(size > 0)) return std::string();  // a vertex, or an edge given radius 0: no scale to judge by
  if (unmeasured > size)
    return std::string(which) + " not measured: " + format_length(unmeasured) +
           " of the profile around it has no measured point (edge " + (e.radius > 0 ? "radius " : "face ") +
           format_length(size) + "); its point and radius bridge a hole in the data";
  if (cover.hole > 0 && cover.hole >= f.options.edge_hole * size)
    return std::string(which) + " partly not measured: " + format_length(cover.hole) +
           " of the profile without a measured point begins " + format_length(cover.hole_distance) +
           " from the edge point (edge " + (e.radius > 0 ? "radius " : "face ") + format_length(size) +
           "); its radius and point rest partly on the curve bridging that hole";
  const double stray = f.options.edge_bridge * cover.bend;
  if (!(f.accuracy > 0 && stray > f.accuracy)) return std::string();
  return std::string(which) + " partly not measured: the curve bridging " + format_length(cover.bend_hole) +
         " of the profile without a measured point, " + format_length(cover.bend_distance) +
         " from the edge point, bends " + format_length(cover.bend) +
         " from a straight line: a bridge strays from the blade by a tenth of its bend or more, here " +
         format_length(stray) + " (at most " + format_length(f.accuracy) +
         "), and the edge's point and angle and the chord with it";
}

// The points the gap fill carried onto the plane about an edge whose slab points alone
// leave a hole there: how far they came from, and whether they all came from one side.
struct CarriedAbout {
  bool any = false, one_side = false;
  double far = 0, hole = 0;  // the largest |offset|; the slab's own hole about the edge
};

CarriedAbout carried_about(const SectionFacts& f, const Edge& e) {
  const Measured& q = f.measured;
  CarriedAbout c;
  if (q.carried.empty()) return c;
  const EdgeCoverage own =
      edge_coverage(f.fast, e, q.in_slab, f.options.edge_hole_reach, f.options.thickness_hole_spacings);
  if (hole_note(e, own, "", f).empty()) return c;
  const double size = edge_size(e);
  const Eigen::Vector2d at = f.curve.point(e.t);
  bool above = false, below = false;
  for (std::size_t i = 0; i < q.carried.size(); ++i) {
    if (!((q.carried[i] - at).norm() <= 3 * size + own.around)) continue;
    const double offset = q.carried_offset[i];
    c.far = std::max(c.far, std::abs(offset));
    (offset > 0 ? above : below) = true;
  }
  c.any = above || below;
  c.one_side = above != below;
  c.hole = std::max(own.around, own.hole);
  return c;
}

// An edge covered only thanks to points the gap fill carried onto the plane: say so, with
// how far they came from (their positions rest on the drift fitted beside the gap). When
// they all came from one side of the plane, the plane passes beyond the scanned surface
// there (a plane tilted across a blade's tip carried the TE 0.2 mm above the part's end,
// its values a smooth continuation of the blade below, flagged by nothing): the edge is
// extrapolated, not measured (edge_flags sets le/te_measured).
std::string carried_note(const CarriedAbout& c, const std::string& hole_message, const char* which) {
  if (!hole_message.empty() || !c.any) return std::string();
  char text[512];
  if (c.one_side)
    std::snprintf(text, sizeof text,
                  "%s not measured: the slab leaves %s of the profile there without a point, and the points "
                  "slice's gap fill carried onto the plane to close it all come from one side of it (up to "
                  "%s off): the plane passes beyond the scanned surface there (the part's end, or a hole's "
                  "edge) and the edge is extrapolated",
                  which, format_length(c.hole).c_str(), format_length(c.far).c_str());
  else
    std::snprintf(text, sizeof text,
                  "%s measured with points carried onto the plane from up to %s off it (slice's gap fill: "
                  "the slab alone leaves %s of the profile there without a point)",
                  which, format_length(c.far).c_str(), format_length(c.hole).c_str());
  return std::string(text);
}

// A round edge whose circle leaves the profile by much more than the profile's noise.
std::string circularity_note(const Edge& e, const char* which, double profile_noise) {
  if (e.circular || e.shape != EdgeShape::round) return std::string();
  char text[256];
  std::snprintf(
      text, sizeof text,
      "%s is not circular: the circle fitted to its %.0f-degree arc leaves it by %s rms, %.0f times "
      "the points' rms distance to the profile; its radius and point depend on the arc taken",
      which, e.arc, format_length(e.fit_rms).c_str(), e.fit_rms / profile_noise);
  return std::string(text);
}

// Everything said of one edge, joined by commas (`carried`: carried_about it).
std::string edge_note(const SectionFacts& f, const Edge& e, const EdgeCoverage& cover,
                      const CarriedAbout& carried, const char* which) {
  const std::string hole = hole_note(e, cover, which, f);
  return join(join(join(shape_note(e, which, f.options.edge), hole), carried_note(carried, hole, which)),
              circularity_note(e, which, f.options.profile_noise));
}

}  // namespace

// Where a section's other loops lie, for the message that refuses it: a small loop close
// outside the profile is usually a piece of it cut off by a gap in the data.
std::string other_loops(const std::map<std::pair<int, int>, BSpline>& curves, int section,
                        const std::map<int, double>& listed) {
  const auto main = curves.find({section, 0});
  if (main == curves.end()) return "";
  const std::vector<Eigen::Vector2d> p0 = sample(main->second, 400);
  Eigen::Vector2d low = p0[0], high = p0[0];
  for (const auto& q : p0) low = low.cwiseMin(q), high = high.cwiseMax(q);
  auto area = [](const std::vector<Eigen::Vector2d>& p) {
    double a = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const Eigen::Vector2d& b = p[(i + 1) % p.size()];
      a += p[i].x() * b.y() - p[i].y() * b.x();
    }
    return std::abs(0.5 * a);
  };
  std::string out;
  bool cut = false;
  for (const auto& [key, curve] : curves) {
    if (key.first != section || key.second == 0) continue;
    const std::vector<Eigen::Vector2d> p = sample(curve, 400);
    double gap = std::numeric_limits<double>::infinity();
    for (const auto& a : p)
      for (const auto& b : p0) gap = std::min(gap, (a - b).norm());
    char text[160];
    std::snprintf(text, sizeof text, "%sloop %d: area %.3g against %.3g mm2, %s from loop 0",
                  out.empty() ? "" : "; ", key.second, area(p), area(p0), format_length(gap).c_str());
    out += text;
    cut = cut || (area(p) < 0.2 * area(p0) && gap < 0.1 * (high - low).norm());
  }
  // Loops slice found that fitspline could not fit: loop 0 may be only a piece of the profile.
  bool unfitted = false;
  for (const auto& [loop, loop_area] : listed) {
    if (loop == 0 || curves.count({section, loop})) continue;
    char text[120];
    std::snprintf(text, sizeof text, "%sloop %d: area %.3g mm2, not fitted (see fitspline's issue)",
                  out.empty() ? "" : "; ", loop, loop_area);
    out += text;
    unfitted = true;
  }
  if (out.empty()) return "";
  if (unfitted)
    return " (" + out + "); a loop left unfitted may be a piece of the profile the data split from it: " +
           "loop 0 alone is not the section";
  return " (" + out + ")" +
         (cut ? "; a small loop this close is often a piece of the profile cut off by a gap in the data, "
                "else an object beside the blade (a fixture: crop it from the scan)"
              : "; an object beside the blade (a fixture, a neighbouring blade) is to be cropped from the "
                "scan, or missed by the plane");
}

namespace {

// An LE taken as the blunter end while an edge is not measured, and the thickness does not
// back the choice (the thickest circle in the half toward the TE, or near mid-chord): a
// hole over a round edge bridged to a corner makes it the sharp end (a compressor's 0.3 mm
// LE over a hole, its 0.25 mm TE then taken as the LE, every end's value swapped and its
// LE radius 17 % off unflagged). "" when not.
std::string bluntness_over_hole_note(const SectionFacts& f, CheckBits flags) {
  const CheckBits unmeasured = bit(Check::le_measured) | bit(Check::te_measured);
  const double pos = f.params.max_thickness_pos;
  if (!f.camber.le_by_bluntness || !(flags & unmeasured) || !(pos > 0.5 - f.options.le_thickness_margin))
    return "";
  char text[320];
  std::snprintf(text, sizeof text,
                "the leading edge was taken as the blunter end, but the %s edge is not measured and the "
                "maximum thickness lies at %s of the camber line from it: a hole bridged to a corner may "
                "have made the sharp end; give the leading-edge direction",
                flags & bit(Check::te_measured) ? "trailing" : "leading", format_share(pos).c_str());
  return text;
}

// The flags of an edge's notes: a hole at it (or closed by points carried from one side of
// the plane), a circle that does not fit it (not circular, or a blunt edge fitted as round
// anyway).
CheckBits edge_flags(const SectionFacts& f, const Edge& e, const EdgeCoverage& cover,
                     const CarriedAbout& carried, bool le) {
  CheckBits flags = 0;
  if (!hole_note(e, cover, "", f).empty() || carried.one_side)
    flags |= bit(le ? Check::le_measured : Check::te_measured);
  const bool blunt_as_round = e.shape == EdgeShape::blunt && e.face == 0 && e.radius > 0;
  if (blunt_as_round || !circularity_note(e, "", f.options.profile_noise).empty())
    flags |= bit(le ? Check::le_circle : Check::te_circle);
  return flags;
}

// A failed check of an end angle (inlet_angle, outlet_angle, inlet_fit, outlet_fit) in words.
std::string angle_note(const Finding& k, const SectionParams& p) {
  char text[320];
  const bool in = k.check == Check::inlet_angle || k.check == Check::inlet_fit;
  const double angle = in ? p.inlet_angle : p.outlet_angle;
  const char* edge = in ? "leading edge" : "trailing edge";
  if (k.check == Check::inlet_fit || k.check == Check::outlet_fit)
    std::snprintf(text, sizeof text,
                  "%s angle %s fails check %s: a quartic fitted to the camber line next to the %s turns "
                  "the cubic's end direction by %s (at most %s): the camber bends unevenly there and the "
                  "angle, the edge point and the chord depend on the fit",
                  in ? "inlet" : "outlet", format_angle(angle).c_str(), check_name(k.check), edge,
                  format_angle(k.value).c_str(), format_angle(k.limit).c_str());
  else
    std::snprintf(text, sizeof text,
                  "%s angle %s fails check %s: it is %s off the camber line's direction next to the "
                  "%s (at most %s): the camber line bends there",
                  in ? "inlet" : "outlet", format_angle(angle).c_str(), check_name(k.check),
                  format_angle(k.value).c_str(), edge, format_angle(k.limit).c_str());
  return text;
}

// A failed le_radius/te_radius check by the radius's spread (Finding::spread), in words.
std::string spread_note(const Finding& k, const SectionParams& p) {
  char text[320];
  const bool le = k.check == Check::le_radius;
  const char* which = le ? "leading-edge" : "trailing-edge";
  const std::string radius = format_length(le ? p.le_radius : p.te_radius);
  if (!std::isfinite(k.value))
    std::snprintf(text, sizeof text,
                  "%s radius %s fails check %s: under 3 measured points lie on its arc, too few to fix a "
                  "circle: it rests on the fitted curve alone",
                  which, radius.c_str(), check_name(k.check));
  else
    std::snprintf(
        text, sizeof text,
        "%s radius %s fails check %s: its points fix it to +-%s only (twice its standard error, or, "
        "where its arc holds under 8 points, that of a circle on them at their noise or the curve's "
        "stray from the circle; at most %s): it "
        "may be off by more than its tolerance",
        which, radius.c_str(), check_name(k.check), format_length(k.value).c_str(),
        format_length(k.limit).c_str());
  return text;
}

// The noise check's words: a fit that follows few points' noise, or a dense scan's noise
// that leaves the profile uncertain beyond the accuracy.
std::string noise_note(const Finding& k, const SectionFacts& f) {
  const char* name = check_name(k.check);
  char text[480];
  if (few_points(f.measured.all.size(), f.curve.control.size()))
    std::snprintf(text, sizeof text,
                  "its lengths and angles fail check %s: the fit has about as many coefficients as measured "
                  "points and follows their noise, which its rms hides: the profile may stray %s from their "
                  "smooth curve (at most %s), and its thickness, edges and chord by as much",
                  name, format_length(k.value).c_str(), format_length(k.limit).c_str());
  else
    std::snprintf(text, sizeof text,
                  "its lengths and angles fail check %s: the points' noise (the fit's rms) leaves the "
                  "profile uncertain by up to %s (4 times it over the square root of the points a "
                  "coefficient rests on; at most %s), and its thickness, edges and chord by as much",
                  name, format_length(k.value).c_str(), format_length(k.limit).c_str());
  return text;
}

// The *_noise checks' words: the value, its standard error, and the tolerance those exceed.
std::string value_noise_note(const Finding& k, const SectionFacts& f) {
  const SectionParams& p = f.params;
  const bool angle = k.check == Check::inlet_noise || k.check == Check::outlet_noise;
  const char* what = k.check == Check::chord_noise       ? "chord"
                     : k.check == Check::thickness_noise ? "maximum thickness"
                     : k.check == Check::inlet_noise     ? "inlet angle"
                                                         : "outlet angle";
  const double value = k.check == Check::chord_noise       ? p.chord
                       : k.check == Check::thickness_noise ? p.max_thickness
                       : k.check == Check::inlet_noise     ? p.inlet_angle
                                                           : p.outlet_angle;
  const double sigmas = f.value_sigmas > 0 ? f.value_sigmas : 1;
  const auto amount = [angle](double v) { return angle ? format_angle(v) : format_length(v); };
  char text[480];
  std::snprintf(
      text, sizeof text,
      "%s %.6g%s fails check %s: the points' noise leaves it uncertain by %s (%.3g standard errors of "
      "%s; at most %s): a new scan of the same surface may move it that far",
      what, value, angle ? " deg" : " mm", check_name(k.check), amount(k.value).c_str(), sigmas,
      amount(k.value / sigmas).c_str(), amount(k.limit).c_str());
  return text;
}

// The airfoil check's words: the section's thickness over its chord (the check's value is
// that ratio, computed alike), or the flat faces at both its ends.
std::string airfoil_note(const Finding& k, const SectionFacts& f) {
  const SectionParams& p = f.params;
  char why[200];
  if (k.value == p.max_thickness / std::max(p.chord, 1e-300))
    std::snprintf(why, sizeof why, "its maximum thickness %s is %s of its chord %s (at most %s)",
                  format_length(p.max_thickness).c_str(), format_share(k.value).c_str(),
                  format_length(p.chord).c_str(), format_share(k.limit).c_str());
  else
    std::snprintf(
        why, sizeof why, "it ends in flat faces %s and %s wide, %s of its maximum thickness %s (at most %s)",
        format_length(f.camber.le.face).c_str(), format_length(f.camber.te.face).c_str(),
        format_share(k.value).c_str(), format_length(p.max_thickness).c_str(), format_share(k.limit).c_str());
  char text[480];
  std::snprintf(text, sizeof text,
                "the section is no airfoil: %s; the plane cuts something other than the blade (a platform, a "
                "root or shroud, a fixture): every value fails check airfoil; place the planes on the "
                "airfoil (slice --at)",
                why);
  return text;
}

// A failed check of section_check in words, with its values.
std::string finding_note(const Finding& k, const SectionFacts& f) {
  const SectionParams& p = f.params;
  char text[480];
  const char* name = check_name(k.check);
  switch (k.check) {
    case Check::le_radius:
    case Check::te_radius: {
      const bool le = k.check == Check::le_radius;
      if (k.spread) return spread_note(k, p);
      std::snprintf(text, sizeof text,
                    "%s radius %s fails check %s: its circle passes or leaves the profile by %s (at most "
                    "%s): it does not fit the blade there",
                    le ? "leading-edge" : "trailing-edge",
                    format_length(le ? p.le_radius : p.te_radius).c_str(), name,
                    format_length(k.value).c_str(), format_length(k.limit).c_str());
      break;
    }
    case Check::le_circle:
    case Check::te_circle:  // the arc's shortfall from the flanks' turning
      std::snprintf(
          text, sizeof text,
          "%s circle fails check %s: its arc falls %s short of the turning between the flanks (at most %s): "
          "it fits a bump at the tip or a nose not circular; its radius, point and angle depend on the arc",
          k.check == Check::le_circle ? "leading-edge" : "trailing-edge", name, format_angle(k.value).c_str(),
          format_angle(k.limit).c_str());
      break;
    case Check::le_point:
    case Check::te_point:
      std::snprintf(text, sizeof text, "%s point fails check %s: it lies %s off the profile (at most %s)",
                    k.check == Check::le_point ? "leading-edge" : "trailing-edge", name,
                    format_length(k.value).c_str(), format_length(k.limit).c_str());
      break;
    case Check::chord:
      std::snprintf(
          text, sizeof text,
          "chord %.6g mm fails check %s: the profile reaches %s beyond an edge point along the camber "
          "line's end direction (at most %s): the edge points are not at the ends of the profile",
          p.chord, name, format_length(k.value).c_str(), format_length(k.limit).c_str());
      break;
    case Check::caliper:
      std::snprintf(text, sizeof text,
                    "caliper chord %.6g mm fails check %s: the profile's extent along its line differs by %s "
                    "(at most %s)",
                    p.caliper_chord, name, format_length(k.value).c_str(), format_length(k.limit).c_str());
      break;
    case Check::le_vertex:
    case Check::te_vertex:
      std::snprintf(
          text, sizeof text,
          "%s vertex fails check %s: it moves by %s (at most %s) with a shift of the profile within "
          "its noise (its flanks meeting at a thin wedge) or with the flanks taken farther out: the "
          "edge point, chord and the camber line's end are uncertain by that much",
          k.check == Check::le_vertex ? "sharp leading-edge" : "sharp trailing-edge", name,
          format_length(k.value).c_str(), format_length(k.limit).c_str());
      break;
    case Check::noise:
      return noise_note(k, f);
    case Check::chord_noise:
    case Check::thickness_noise:
    case Check::inlet_noise:
    case Check::outlet_noise:
      return value_noise_note(k, f);
    case Check::airfoil:
      return airfoil_note(k, f);
    case Check::layers:  // value: the layers' distance, limit: the profile length they cover
      std::snprintf(
          text, sizeof text,
          "the measured points lie in two layers %s apart over %s of the profile (fitspline: "
          "views merged with a misregistration, or a slab so wide that the profile moves across "
          "it?): the profile runs between them, so its thickness may be off by up to half that, and "
          "its edges, chord, camber line and angles by more (check %s)",
          format_length(k.value).c_str(), format_length(k.limit).c_str(), name);
      break;
    default:
      return angle_note(k, p);
  }
  return text;
}

}  // namespace

std::string jump_note(const Jump& j) {
  const char* column = "";
  for (const auto& c : check_names)
    if (c.check == j.check) column = c.columns;
  char text[256];
  std::snprintf(
      text, sizeof text,
      "%s %.5g fails check %s: it jumps by %.3g from the %.5g its neighbouring sections give (at most "
      "%.3g)",
      column, j.value, check_name(j.check), j.value - j.expected, j.expected, j.limit);
  return text;
}

// A sharp edge whose measured points are too sparse about its vertex to tell it from a round
// edge of the radius under which an edge counts as sharp (sharp_ratio of the thickness):
// fewer than 6 points within 5 such radii (a half-circle of it would hold under 2 points at
// their spacing there). "" when not.
std::string sharp_unresolved(const SectionFacts& f, const Edge& e, const char* which, const char* check) {
  const double sharp = f.options.sharp_ratio * f.params.max_thickness, reach = 5 * sharp;
  if (e.shape != EdgeShape::sharp || !(sharp > 0) || f.measured.all.empty()) return "";
  int near = 0;
  for (const auto& q : f.measured.all) near += (q - e.point).norm() <= reach;
  if (near >= 6) return "";
  const std::string points = near == 0 ? "no measured point lies"
                                       : "only " + std::to_string(near) + " measured point" +
                                             (near > 1 ? "s lie" : " lies"),
                    apart = near > 1 ? ", about " + format_length(2 * reach / near) + " apart" : "";
  char text[400];
  std::snprintf(text, sizeof text,
                "%s radius 0 fails check %s: the edge was taken as sharp, but %s within %s of its vertex%s: "
                "they cannot tell it from a round edge of radius %s (%s of the largest inscribed diameter, "
                "under which an edge counts as sharp) or more; its radius is not measured",
                which, check, points.c_str(), format_length(reach).c_str(), apart.c_str(),
                format_length(sharp).c_str(), format_share(f.options.sharp_ratio).c_str());
  return text;
}

// A sharp edge (its end circle under sharp_ratio of the thickness, radius reported 0) where
// the profile turns over a radius the measured points resolve: more than 4 x the noise, and
// 5 or more points within twice it of the edge point. "" when not.
std::string sharp_but_round(const SectionFacts& f, const Edge& e, const char* which, const char* check) {
  const double r = e.curvature_radius;
  if (e.shape != EdgeShape::sharp || !(r > 4 * f.options.profile_noise) || !(f.options.profile_noise > 0))
    return "";
  int near = 0;
  for (const auto& q : f.measured.all) near += (q - e.point).norm() <= 2 * r;
  if (near < 5) return "";
  char text[320];
  std::snprintf(
      text, sizeof text,
      "%s radius 0 fails check %s: the edge was taken as sharp (under %s of the largest "
      "inscribed diameter), but the profile turns there over a radius of %s that %d measured points "
      "resolve: a small round edge",
      which, check, format_share(f.options.sharp_ratio).c_str(), format_length(r).c_str(), near);
  return text;
}

namespace {

// The thickest circle touching the profile within or beside a hole in the data (a stretch
// without measured points longer than thickness_hole of the chord and
// thickness_hole_spacings times the points' mean distance there, beginning within half
// that length of a contact): the maximum thickness rests on the fit's bridge, not on
// measurements. "" when none is.
std::string thickness_hole_note(const SectionFacts& f) {
  const CamberOptions& opt = f.options;
  const double limit = opt.thickness_hole * f.params.chord;
  const ContactCoverage* worst = nullptr;
  for (const ContactCoverage& c : f.thickest)
    if (unmeasured(c, limit, opt.thickness_hole_spacings) && (!worst || c.hole > worst->hole)) worst = &c;
  if (!worst) return std::string();
  const std::string where = worst->hole_distance > 0
                                ? format_length(worst->hole_distance) + " from a stretch of "
                                : "within a stretch of ";
  const std::string apart = worst->spacing > 0
                                ? "the points about it lie " + format_length(worst->spacing) + " apart"
                                : "no point lies";
  char text[480];
  std::snprintf(text, sizeof text,
                "max thickness %s fails check thickness_measured: the thickest circle touches the profile "
                "%s%s%s that no measured point covers (a hole in the data, where %s; a hole over %s, %s of "
                "the chord, is not measured): the thickness there rests on the fit's bridge",
                format_length(f.params.max_thickness).c_str(), where.c_str(),
                worst->hole >= 3 * limit ? "at least " : "", format_length(worst->hole).c_str(),
                apart.c_str(), format_length(limit).c_str(), format_share(opt.thickness_hole).c_str());
  return text;
}

// A hole in the data anywhere along the profile, by the thickness's rule: the area and the
// centroid integrate the fit's bridge over it (an 8 mm hole in a mesh's flank moved the area
// by 0.2-0.6 %, flagged by nothing). "" when none is.
std::string area_hole_note(const SectionFacts& f) {
  const CamberOptions& opt = f.options;
  const double limit = opt.thickness_hole * f.params.chord;
  if (!unmeasured(f.longest, limit, opt.thickness_hole_spacings)) return std::string();
  char text[320];
  std::snprintf(
      text, sizeof text,
      "area %.6g mm2 fails check area_measured: %s%s of the profile has no measured point (a hole in "
      "the data; over %s, %s of the chord, and 4 times the points' mean distance beside it): the "
      "area and centroid include the fit's bridge over it",
      f.params.area, f.longest.hole >= 6 * limit ? "at least " : "", format_length(f.longest.hole).c_str(),
      format_length(limit).c_str(), format_share(opt.thickness_hole).c_str());
  return text;
}

}  // namespace

CheckBits describe_issues(const SectionFacts& f, const std::vector<Finding>& findings,
                          std::vector<SectionIssue>& issues) {
  const CamberResult& r = f.camber;
  const CamberOptions& opt = f.options;
  // What the gap fill carried about each edge, for its flags and its note.
  const CarriedAbout le_carried = carried_about(f, r.le), te_carried = carried_about(f, r.te);
  CheckBits flags =
      edge_flags(f, r.le, f.le, le_carried, true) | edge_flags(f, r.te, f.te, te_carried, false);
  for (const bool le : {true, false}) {
    const char *which = le ? "leading-edge" : "trailing-edge", *check = le ? "le_sharp" : "te_sharp";
    std::string note = sharp_but_round(f, le ? r.le : r.te, which, check);
    if (note.empty()) note = sharp_unresolved(f, le ? r.le : r.te, which, check);
    if (note.empty()) continue;
    issues.push_back({f.section, 0, "camber", note});
    flags |= bit(le ? Check::le_sharp : Check::te_sharp);
  }
  const std::string le_msg = edge_note(f, r.le, f.le, le_carried, "leading edge"),
                    te_msg = edge_note(f, r.te, f.te, te_carried, "trailing edge");
  if (!le_msg.empty() || !te_msg.empty())
    issues.push_back(
        {f.section, 0, "camber", le_msg + (le_msg.empty() || te_msg.empty() ? "" : ", ") + te_msg});
  if (const std::string note = thickness_hole_note(f); !note.empty()) {
    issues.push_back({f.section, 0, "camber", note});
    flags |= bit(Check::thickness_measured);
  }
  if (const std::string note = area_hole_note(f); !note.empty()) {
    issues.push_back({f.section, 0, "camber", note});
    flags |= bit(Check::area_measured);
  }
  // A camber line that strays from the medial axis (no inscribed circle solved there)
  // is not a measured one: say where and by how much.
  if (r.off_axis > 0) {
    std::size_t k = 0;
    while (k + 1 < r.s.size() && r.s[k] < r.off_axis_s) ++k;
    if (k < r.radius.size() && r.off_axis > opt.off_axis * r.radius[k]) {
      char text[256];
      std::snprintf(text, sizeof text,
                    "the camber line strays from the medial axis by up to %s at %s of its length (no "
                    "inscribed circle could be solved there): its shape and the thickness stations there are "
                    "interpolated",
                    format_length(r.off_axis).c_str(),
                    format_share(r.off_axis_s / std::max(r.length, 1e-300)).c_str());
      issues.push_back({f.section, 0, "camber", text});
      flags |= bit(Check::off_axis);
    }
  }
  // The thickness rule is a near tie: say so rather than let the orientation pass as known.
  if (!r.le_by_direction && !r.le_by_bluntness &&
      std::abs(f.params.max_thickness_pos - 0.5) <= opt.le_thickness_margin) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "the leading edge was taken as the end nearer the maximum thickness, which lies at %s of "
                  "the camber line: too near mid-chord to tell; give the leading-edge direction",
                  format_share(f.params.max_thickness_pos).c_str());
    issues.push_back({f.section, 0, "camber", text});
    flags |= bit(Check::le_choice);
  }
  if (const std::string note = bluntness_over_hole_note(f, flags); !note.empty()) {
    issues.push_back({f.section, 0, "camber", note});
    flags |= bit(Check::le_choice);
  }
  for (const Finding& k : findings) {
    issues.push_back({f.section, 0, "camber", finding_note(k, f)});
    flags |= bit(k.check);
  }
  return flags;
}

}  // namespace section::pipe
