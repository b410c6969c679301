// SPDX-License-Identifier: GPL-3.0-or-later
// The stream's tables and their columns: the one place that names them (docs/FORMAT.md).
#include "section/pipe/schema.h"

#include "section/revolution.h"

#include "section/error.h"

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace section {
namespace schema {

namespace {

// Columns most tables share.
template <class Row>
constexpr Column<Row> section_id() {
  return {col::section, "id", "the section id (the plane's index)",
          [](const Row& r) { return double(r.section); }};
}
template <class Row>
constexpr Column<Row> loop_id() {
  return {col::loop, "id",
          "the loop id within the section, 0 the profile (the loop enclosing the largest area)",
          [](const Row& r) { return double(r.loop); }};
}
template <class Row>
constexpr Column<Row> index_of(const char* meaning) {
  return {col::index, "id", meaning, [](const Row& r) { return double(r.index); }};
}
template <class Row>
constexpr Column<Row> point_uv(const char* meaning) {
  return {"", uv, "length", meaning, [](const Row& r) { return r.point; }};
}

// Getters of a field of SectionParams, FitSplineResult, SmoothResult.
using Params = SectionParams;
using Fit = FitSplineResult;
template <auto F>
constexpr auto param = [](const ParamsRow& r) { return r.params.*F; };
template <auto F>
constexpr auto fit = [](const SplineRow& r) { return r.fit.*F; };
template <auto F>
constexpr auto smoothing = [](const SmoothStatsRow& r) { return r.result.*F; };

// A table's columns: section (and loop) first, then `more`.
template <class Row, std::size_t N>
constexpr std::array<Column<Row>, N + 1> by_section(const Column<Row> (&more)[N]) {
  std::array<Column<Row>, N + 1> out{section_id<Row>()};
  for (std::size_t k = 0; k < N; ++k) out[k + 1] = more[k];
  return out;
}
template <class Row, std::size_t N>
constexpr std::array<Column<Row>, N + 2> by_loop(const Column<Row> (&more)[N]) {
  std::array<Column<Row>, N + 2> out{section_id<Row>(), loop_id<Row>()};
  for (std::size_t k = 0; k < N; ++k) out[k + 2] = more[k];
  return out;
}

constexpr auto frame_columns = by_section<FrameRow>({
    {"origin_", xyz, "length", "the plane's origin, where u = v = 0", [](auto& r) { return r.frame.origin; }},
    {"u_", xyz, "1", "the first in-plane axis u (a unit vector)", [](auto& r) { return r.frame.u; }},
    {"v_", xyz, "1", "the second in-plane axis v (a unit vector)", [](auto& r) { return r.frame.v; }},
    {"n_", xyz, "1", "the plane's unit normal n = u x v", [](auto& r) { return r.frame.n; }},
    // A section on a surface of revolution (docs/REVOLUTION.md): written only then.
    {"surface", "code",
     "the section's surface of revolution, 1 cylinder, 2 cone, 3 streamline (the columns from here on and "
     "the meridians table are written only for such sections; origin, u, v, n are then its tangent plane at "
     "u = v = 0)",
     [](auto& r) { return r.frame.surface ? double(r.frame.surface->kind) : 0.0; }},
    {"unrolling", "code",
     "how (u, v) unroll it: 1 cylinder (r_ref theta, m), 2 conformal (r_ref m', r_ref theta), "
     "3 arclength (m, r_ref theta)",
     [](auto& r) { return r.frame.surface ? double(r.frame.surface->unrolling) : 0.0; }},
    {"axis_", xyz, "length", "a point of the machine axis (axial position 0)",
     [](auto& r) { return r.frame.surface ? r.frame.surface->axis_point : Eigen::Vector3d::Zero(); }},
    {"axis_d", xyz, "1", "the axis direction (a unit vector)",
     [](auto& r) { return r.frame.surface ? r.frame.surface->axis : Eigen::Vector3d::Zero(); }},
    {"theta0_", xyz, "1", "the radial direction where theta = 0 (a unit vector)",
     [](auto& r) { return r.frame.surface ? r.frame.surface->reference : Eigen::Vector3d::Zero(); }},
    {"r_ref", "length", "the reference radius of the unrolled plane",
     [](auto& r) { return r.frame.surface ? r.frame.surface->r_ref : 0.0; }},
    {"shift_", uv, "length", "the unrolled coordinates of u = v = 0",
     [](auto& r) { return r.frame.surface ? r.frame.surface->shift : Eigen::Vector2d::Zero(); }},
});

constexpr auto meridian_columns = by_section<MeridianRow>({
    index_of<MeridianRow>("order along the meridian (m grows with it)"),
    {"axial", "length", "the point's axial position a along the axis", [](auto& r) { return r.point.x(); }},
    {"radius", "length", "its radius r", [](auto& r) { return r.point.y(); }},
});

const Loop& loop_of(const LoopRow& r) {
  return r.morphology.loops[r.loop];
}
constexpr auto loop_columns = by_loop<LoopRow>({
    {"points", "count", "points kept in the loop", [](auto& r) { return double(loop_of(r).points.size()); }},
    {"dropped", "count", "outliers dropped: the section's count on loop 0, 0 on the others",
     [](auto& r) { return r.loop == 0 ? double(r.morphology.dropped) : 0.0; }},
    {"area", "area", "area enclosed by the loop's traced boundary", [](auto& r) { return loop_of(r).area; }},
    {"length", "length", "length of the traced boundary", [](auto& r) { return loop_of(r).length; }},
    {"cell", "length", "raster cell used to order the section", [](auto& r) { return r.morphology.cell; }},
});

constexpr auto point_columns = by_loop<PointRow>({
    index_of<PointRow>("order along the loop (counterclockwise)"),
    point_uv<PointRow>("the point in the plane"),
    {"n", uv, "1", "the outward unit normal from the image gradient", [](auto& r) { return r.normal; }},
    {col::offset, "length",
     "0 for a point of the slab; for a point the gap fill carried onto the plane, its signed distance "
     "from the plane before (docs/MORPHOLOGY.md; a table without the column reads as all 0)",
     [](auto& r) { return r.offset; }},
});

constexpr auto skeleton_columns = by_section<SkeletonRow>({
    {col::loop, "id", "0: the skeleton is the profile's", [](auto&) { return 0.0; }},
    index_of<SkeletonRow>("order along the main branch, from the blunter end"),
    point_uv<SkeletonRow>("the skeleton point"),
    {"radius", "length", "its distance to the profile's boundary", [](auto& r) { return r.radius; }},
});

constexpr auto smoothed_columns = by_loop<LoopPoint>({
    index_of<LoopPoint>("order along the loop, from 0 (renumbered when duplicate points were merged)"),
    point_uv<LoopPoint>("the smoothed point"),
});

constexpr auto smooth_stats_columns = by_loop<SmoothStatsRow>({
    {"points", "count", "points kept", [](auto& r) { return double(r.result.points.size()); }},
    {"energy_before", "length^2", "the energy E before smoothing", smoothing<&SmoothResult::energy_before>},
    {"energy_after", "length^2", "E after smoothing", smoothing<&SmoothResult::energy_after>},
    {"iterations", "count", "outer iterations done", [](auto& r) { return double(r.result.iterations); }},
    {"rms_move", "length", "root mean square move of the points", smoothing<&SmoothResult::rms_move>},
    {"max_move", "length", "largest move of a point", smoothing<&SmoothResult::max_move>},
    {"repaired", "count", "duplicate points merged, and lone spikes dropped",
     [](auto& r) { return double(r.result.repaired); }},
});

constexpr auto spline_columns = by_loop<SplineRow>({
    {col::degree, "1", "the B-spline's degree", [](auto& r) { return double(r.fit.spline.degree); }},
    {col::closed, "flag", "1 when closed (periodic)",
     [](auto& r) { return r.fit.spline.closed ? 1.0 : 0.0; }},
    {"control_points", "count", "its control points",
     [](auto& r) { return double(r.fit.spline.control.size()); }},
    {col::rms, "length", "RMS distance of the measured points (outliers excluded) to the curve",
     fit<&Fit::rms>},
    {"max", "length", "the largest such distance", fit<&Fit::max>},
    {"p95", "length", "their 95th percentile", fit<&Fit::p95>},
    {"iterations", "count", "distance-minimisation iterations done",
     [](auto& r) { return double(r.fit.iterations); }},
    {"spacing", "length", "median spacing of the measured points along the curve", fit<&Fit::spacing>},
    {"max_gap", "length", "the longest stretch of the curve without a measured point", fit<&Fit::max_gap>},
    {"gap_start", "parameter", "the curve parameter where it begins", fit<&Fit::gap_start>},
    {"gap_end", "parameter", "where it ends (below gap_start when it wraps past the curve's last parameter)",
     fit<&Fit::gap_end>},
    {col::layers, "length",
     "distance between two layers of points found along the loop (views merged with a misregistration: the "
     "curve "
     "runs between them), 0 when none (docs/FITSPLINE.md, step 5)",
     fit<&Fit::layers>},
    {col::layers_length, "length", "the profile length over which they were found, 0 when none",
     fit<&Fit::layers_length>},
});

constexpr auto knot_columns = by_loop<KnotRow>({
    index_of<KnotRow>("order of the knots"),
    {col::knot, "parameter", "the knot", [](auto& r) { return r.knot; }},
});

constexpr auto ctrl_columns = by_loop<LoopPoint>({
    index_of<LoopPoint>("order of the control points"),
    point_uv<LoopPoint>("the control point"),
});

constexpr auto gap_columns = by_loop<GapRow>({
    index_of<GapRow>("0 the longest hole, then shorter ones"),
    {col::t_start, "parameter", "the curve parameter where the hole begins",
     [](auto& r) { return r.gap.start; }},
    {col::t_end, "parameter", "where it ends", [](auto& r) { return r.gap.end; }},
    {col::length, "length", "its length along the curve", [](auto& r) { return r.gap.length; }},
});

constexpr auto sample_columns = by_loop<SampleRow>({
    index_of<SampleRow>("order along the curve"),
    {"t", "parameter", "the curve parameter", [](auto& r) { return r.t; }},
    point_uv<SampleRow>("the curve point"),
    {"", xyz, "length",
     "the point in 3D, through the section's frame (the identity when the stream has no frames)",
     [](auto& r) { return r.world; }},
    {"n", uv, "1", "the outward unit normal (the tangent turned clockwise)",
     [](auto& r) { return r.normal; }},
    {"curvature", "1/length", "signed curvature, positive turning counterclockwise",
     [](auto& r) { return r.curvature; }},
});

constexpr auto camber_columns = by_section<CamberRow>({
    index_of<CamberRow>("order from the LE point to the TE point"),
    {"s", "length", "arc length from the LE point", [](auto& r) { return r.s; }},
    point_uv<CamberRow>("the camber point"),
    {"", xyz, "length", "the camber point in 3D", [](auto& r) { return r.world; }},
    {"radius", "length", "the inscribed radius (the end circle's on the extensions)",
     [](auto& r) { return r.radius; }},
});

// Adding a params column is adding its line here (docs/FORMAT.md then lists it: test_schema).
constexpr auto params_columns = by_section<ParamsRow>({
    {"chord", "length", "the distance between the edge points", param<&Params::chord>},
    {"camber_length", "length", "length of the camber line, LE point to TE point",
     param<&Params::camber_length>},
    {"max_thickness", "length", "the largest inscribed diameter", param<&Params::max_thickness>},
    {"max_thickness_pos", "1", "its place along the camber line, 0 at the LE, 1 at the TE",
     param<&Params::max_thickness_pos>},
    {"le_radius", "length",
     "radius of the circle fitted to the leading edge's arc (0 for a flat face, and with --edge auto unless "
     "le_shape is 0)",
     param<&Params::le_radius>},
    {"te_radius", "length", "the same at the trailing edge", param<&Params::te_radius>},
    {"le_curvature_radius", "length", "1 / the profile's curvature at the LE point (0 when flat)",
     param<&Params::le_curvature_radius>},
    {"te_curvature_radius", "length", "the same at the TE point", param<&Params::te_curvature_radius>},
    {"le_shape", "code", "the leading edge's shape (edge shapes below)",
     [](auto& r) { return double(static_cast<int>(r.camber.le.shape)); }},
    {"te_shape", "code", "the trailing edge's shape",
     [](auto& r) { return double(static_cast<int>(r.camber.te.shape)); }},
    {"le_arc", "degrees", "the arc of the leading edge its circle is fitted to",
     [](auto& r) { return r.camber.le.arc; }},
    {"te_arc", "degrees", "the same at the trailing edge", [](auto& r) { return r.camber.te.arc; }},
    {"le_fit_rms", "length", "rms distance of that arc from its circle",
     [](auto& r) { return r.camber.le.fit_rms; }},
    {"te_fit_rms", "length", "the same at the trailing edge", [](auto& r) { return r.camber.te.fit_rms; }},
    {"le_radius_sigma", "length",
     "standard error of le_radius, from its circle's fit on the measured points; 0 when the circle rests on "
     "the fitted curve alone (too few measured points on the arc, or a gap among them) or le_radius is 0",
     [](auto& r) { return r.camber.le.radius_sigma; }},
    {"te_radius_sigma", "length", "the same at the trailing edge",
     [](auto& r) { return r.camber.te.radius_sigma; }},
    {"chord_sigma", "length",
     "standard error of chord through the points' noise: the end directions' errors turning the edge points "
     "about the end circles, and the profile's own at them; 0 when the noise is unknown",
     [](auto& r) { return r.sigmas.chord; }},
    {"max_thickness_sigma", "length",
     "the same for max_thickness: the profile's at its circle's two contacts",
     [](auto& r) { return r.sigmas.max_thickness; }},
    {"inlet_angle_sigma", "degrees",
     "the same for inlet_angle: the camber line's end fit over its centres' errors",
     [](auto& r) { return r.sigmas.inlet_angle; }},
    {"outlet_angle_sigma", "degrees", "the same for outlet_angle",
     [](auto& r) { return r.sigmas.outlet_angle; }},
    {"stagger", "degrees", "angle of the chord line, LE to TE", param<&Params::stagger>},
    {"inlet_angle", "degrees", "the camber tangent (toward the TE) at the LE", param<&Params::inlet_angle>},
    {"outlet_angle", "degrees", "its tangent at the TE", param<&Params::outlet_angle>},
    {"camber_angle", "degrees", "inlet_angle - outlet_angle: the turning", param<&Params::camber_angle>},
    {"area", "area", "the area the profile encloses", param<&Params::area>},
    {"centroid_", uv, "length", "its centroid", param<&Params::centroid>},
    {"le_", uv, "length", "the LE point", param<&Params::le_point>},
    {"te_", uv, "length", "the TE point", param<&Params::te_point>},
    {"le_center_", uv, "length", "centre of the leading edge's circle",
     [](auto& r) { return r.camber.le.center; }},
    {"te_center_", uv, "length", "centre of the trailing edge's circle",
     [](auto& r) { return r.camber.te.center; }},
    {"le_", xyz, "length", "the LE point in 3D", [](auto& r) { return r.le; }},
    {"te_", xyz, "length", "the TE point in 3D", [](auto& r) { return r.te; }},
    {"centroid_", xyz, "length", "the centroid in 3D", [](auto& r) { return r.centroid; }},
    {"caliper_chord", "length",
     "the profile's extent along the caliper line (touching the pressure side at both ends)",
     param<&Params::caliper_chord>},
    {"caliper_stagger", "degrees", "angle of the caliper line, LE to TE", param<&Params::caliper_stagger>},
    {"caliper_found", "flag", "0 when the pressure side is not concave (the chord line is used)",
     [](auto& r) { return r.params.caliper_found ? 1.0 : 0.0; }},
    {"pressure_side", "code",
     "+1 when the pressure (concave) side lies left of the LE-to-TE direction, -1 right",
     [](auto& r) { return double(r.camber.pressure_side); }},
    {"le_by_direction", "flag",
     "1 when --le-direction set the LE, 0 when the edges or the maximum thickness did",
     [](auto& r) { return r.camber.le_by_direction ? 1.0 : 0.0; }},
    {"le_by_bluntness", "flag", "1 when the LE was taken as the blunter end, 0 otherwise",
     [](auto& r) { return r.camber.le_by_bluntness ? 1.0 : 0.0; }},
    {"le_face", "length",
     "width of the leading edge's flat face (its radius is then 0), 0 for an edge without one",
     [](auto& r) { return r.camber.le.face; }},
    {"te_face", "length", "the same at the trailing edge", [](auto& r) { return r.camber.te.face; }},
    {"le_unmeasured", "length",
     "length of profile around the LE point that no measured point covers, 0 when one "
     "lies at it",
     [](auto& r) { return r.le_unmeasured; }},
    {"te_unmeasured", "length", "the same at the TE point", [](auto& r) { return r.te_unmeasured; }},
    {"flags", "code", "the checks the section's values failed, one bit each (checks below); 0 when none",
     [](auto& r) { return double(r.flags); }},
});

constexpr auto thickness_columns = by_section<ThicknessRow>({
    index_of<ThicknessRow>("order of the stations"),
    {"fraction", "1", "the station: arc length from the LE point / camber length",
     [](auto& r) { return r.station.fraction; }},
    {"s", "length", "arc length from the LE point", [](auto& r) { return r.station.s; }},
    {"", uv, "length", "the inscribed circle's centre", [](auto& r) { return r.station.point; }},
    {"thickness", "length", "its diameter (on an extension: the width across the camber normal)",
     [](auto& r) { return r.station.thickness; }},
    {"pressure_", uv, "length", "its contact with the pressure side",
     [](auto& r) { return r.station.pressure; }},
    {"suction_", uv, "length", "its contact with the suction side",
     [](auto& r) { return r.station.suction; }},
    {"flags", "code",
     "the checks its thickness failed, bits as the params table's flags: the section's that flag the "
     "thickness table (layers, noise, le_choice, units, registration), and thickness_measured when this "
     "station's circle touches a hole in the data; 0 when none",
     [](auto& r) { return double(r.flags); }},
});

constexpr auto side_columns = by_section<SideRow>({
    {"side", "code", "0 the pressure (concave) side, 1 the suction side",
     [](auto& r) { return double(r.side); }},
    index_of<SideRow>("order from the LE point to the TE point"),
    point_uv<SideRow>("the profile point"),
});

// compare's tables (docs/COMPARE.md).
double bounds(const Tolerance* t) {
  return !t ? 0.0 : (std::isfinite(t->low) ? 1.0 : 0.0) + (std::isfinite(t->high) ? 2.0 : 0.0);
}
double finite_or_0(double v) {
  return std::isfinite(v) ? v : 0.0;
}

constexpr auto fit_columns = by_section<FitRow>({
    {"method", "code", "the fit: 0 least squares, 1 minimum zone, 2 weighted",
     [](auto& r) { return double(r.method); }},
    {"freedom", "code",
     "its freedom: 0 none, 1 translation, 2 translation along a direction, 3 rotation, 4 all",
     [](auto& r) { return double(r.freedom); }},
    {"whole", "flag", "1 when one motion fits every section (the whole blade)",
     [](auto& r) { return r.whole ? 1.0 : 0.0; }},
    {"angle", "degrees",
     "the rotation that moves the measured section onto the nominal, counterclockwise in (u, v)",
     [](auto& r) { return r.fit.motion.angle; }},
    {"shift_", uv, "length", "then the translation in the plane: p -> R(angle) p + shift",
     [](auto& r) { return r.fit.motion.translation; }},
    {"shift_", xyz, "length",
     "the same motion's translation in 3D: x -> R x + shift (R about the plane's normal)",
     [](auto& r) { return r.shift; }},
    {"points", "count", "measured points compared", [](auto& r) { return double(r.points); }},
    {"outliers", "count", "isolated points farther off than the outlier distance, left out",
     [](auto& r) { return double(r.outliers); }},
    {"iterations", "count", "fit iterations done", [](auto& r) { return double(r.fit.iterations); }},
    {"rms_before", "length", "rms deviation before the fit (outliers out)",
     [](auto& r) { return r.fit.rms_before; }},
    {"max_before", "length", "largest absolute deviation before the fit",
     [](auto& r) { return r.fit.max_before; }},
    {"rms_after", "length", "rms deviation after the fit", [](auto& r) { return r.fit.rms_after; }},
    {"max_after", "length", "largest absolute deviation after the fit",
     [](auto& r) { return r.fit.max_after; }},
});

constexpr auto deviation_columns = by_section<DeviationRow>({
    index_of<DeviationRow>("the point's order among the section's profile points (table points, loop 0)"),
    {"zone", "code", "the zone of its foot (zones below)",
     [](auto& r) { return double(static_cast<int>(r.point.zone)); }},
    {"outlier", "flag", "1 when left out of the fit and the zones",
     [](auto& r) { return r.point.outlier ? 1.0 : 0.0; }},
    {"", uv, "length", "the measured point moved by the fit", [](auto& r) { return r.point.point; }},
    {"foot_", uv, "length", "its foot: the nearest point of the nominal profile",
     [](auto& r) { return r.point.foot; }},
    {"", xyz, "length", "the foot in 3D", [](auto& r) { return r.world; }},
    {"n", uv, "1", "the nominal's outward unit normal at the foot", [](auto& r) { return r.point.normal; }},
    {"before", "length", "the signed deviation before the fit: positive = material outside the nominal",
     [](auto& r) { return r.point.before; }},
    {"deviation", "length", "the signed deviation after the fit", [](auto& r) { return r.point.after; }},
});

constexpr auto zone_columns = by_section<ZoneRow>({
    {"zone", "code", "0 whole profile, 1 leading edge, 2 trailing edge, 3 pressure side, 4 suction side",
     [](auto& r) { return double(r.zone); }},
    {"points", "count", "points in the zone (outliers out)", [](auto& r) { return double(r.result.points); }},
    {"min", "length", "the smallest deviation after the fit", [](auto& r) { return r.result.min; }},
    {"max", "length", "the largest", [](auto& r) { return r.result.max; }},
    {"form", "length", "max - min: the narrowest band of constant width about the nominal holding the points",
     [](auto& r) { return r.result.form; }},
    {"length", "length", "the zone's length along the nominal", [](auto& r) { return r.result.length; }},
    {"unmeasured", "length", "its longest stretch without a measured point",
     [](auto& r) { return r.result.unmeasured; }},
    {"measured", "flag", "0 when that stretch is a hole (or the zone has no point)",
     [](auto& r) { return r.result.measured ? 1.0 : 0.0; }},
    {"bounds", "code", "the profile tolerance's limits: 0 none, 1 low only, 2 high only, 3 both",
     [](auto& r) { return bounds(r.band); }},
    {"low", "length", "the lowest deviation allowed (0 when unbounded)",
     [](auto& r) { return r.band ? finite_or_0(r.band->low) : 0.0; }},
    {"high", "length", "the highest deviation allowed (0 when unbounded)",
     [](auto& r) { return r.band ? finite_or_0(r.band->high) : 0.0; }},
    {"verdict", "code", "the profile's verdict (verdicts below)", [](auto& r) { return double(r.verdict); }},
    {"form_limit", "length", "the largest form allowed (0 when none)",
     [](auto& r) { return r.form ? finite_or_0(r.form->high) : 0.0; }},
    {"form_verdict", "code", "the form's verdict", [](auto& r) { return double(r.form_verdict); }},
});

constexpr auto compared_columns = by_section<ComparedRow>({
    {"item", "code", "the value compared (compared values below)", [](auto& r) { return double(r.item); }},
    {"measured", "flag", "0 when the value is not measured (a hole over its zone, a section that failed)",
     [](auto& r) { return r.measured ? 1.0 : 0.0; }},
    {"value", "item", "the measured value (0 when not measured)", [](auto& r) { return r.value; }},
    {"nominal", "item", "the nominal's value", [](auto& r) { return r.nominal; }},
    {"deviation", "item", "value - nominal (angles wrapped into (-180, 180])",
     [](auto& r) { return r.deviation; }},
    {"bounds", "code", "the tolerance's limits: 0 none, 1 low only, 2 high only, 3 both",
     [](auto& r) { return bounds(r.tolerance); }},
    {"on_value", "flag", "1 when the limits bound the value, 0 its deviation",
     [](auto& r) { return r.tolerance && r.tolerance->on_value ? 1.0 : 0.0; }},
    {"low", "item", "the lowest allowed (0 when unbounded)",
     [](auto& r) { return r.tolerance ? finite_or_0(r.tolerance->low) : 0.0; }},
    {"high", "item", "the highest allowed (0 when unbounded)",
     [](auto& r) { return r.tolerance ? finite_or_0(r.tolerance->high) : 0.0; }},
    {"verdict", "code", "its verdict (verdicts below)", [](auto& r) { return double(r.verdict); }},
    {"uncertainty", "item", "the expanded uncertainty U of the value judged; 0 when none is known",
     [](auto& r) { return r.uncertainty; }},
    {"flags", "code", "the checks camber flagged the value by (params flags bits; then uncertain); 0 none",
     [](auto& r) { return double(r.flags); }},
    {"nominal_flags", "code", "those of the nominal's value (shown, not counted in the verdict)",
     [](auto& r) { return double(r.nominal_flags); }},
});

constexpr auto verdict_columns = by_section<VerdictRow>({
    {"verdict", "code",
     "1 when a value failed, else 2 when one was not measured, else 3 when one was uncertain, else 0; -1 "
     "when none is toleranced",
     [](auto& r) { return double(r.verdict); }},
    {"passed", "count", "values that passed", [](auto& r) { return double(r.passed); }},
    {"failed", "count", "values that failed", [](auto& r) { return double(r.failed); }},
    {"not_measured", "count", "values not measured", [](auto& r) { return double(r.not_measured); }},
    {"uncertain", "count", "values uncertain", [](auto& r) { return double(r.uncertain); }},
});

// The names of a column: its own, or a point's prefix with each axis.
template <class Row>
std::vector<std::string> names_of(const Column<Row>& c) {
  std::vector<std::string> out;
  for (const char* a = c.axes; *a; ++a) out.push_back(c.name + std::string(1, *a));
  if (out.empty()) out.emplace_back(c.name);
  return out;
}

}  // namespace

template <class Row>
std::vector<std::string> TableSchema<Row>::names(const char* last) const {
  std::vector<std::string> out;
  for (std::size_t k = 0; k < count; ++k)
    for (auto& n : names_of(columns[k])) {
      out.push_back(std::move(n));
      if (last && out.back() == last) return out;
    }
  return out;
}

template <class Row>
void TableSchema<Row>::append(std::vector<double>& values, const Row& row) const {
  // The row gathered first and appended at once: one check of the vector's room a row, not
  // one a column (a table of the smoothed points took 300 instructions a row).
  constexpr std::size_t most = 3 * 64;
  std::array<double, most> out;
  std::size_t n = 0;
  for (std::size_t k = 0; k < count; ++k) {
    if (n + 3 > most) {  // (wider than any table: the rest straight into `values`)
      values.insert(values.end(), out.begin(), out.begin() + long(n));
      n = 0;
    }
    const Column<Row>& c = columns[k];
    if (c.get) {
      out[n++] = c.get(row);
    } else if (c.get2) {
      const Eigen::Vector2d p = c.get2(row);
      out[n++] = p.x(), out[n++] = p.y();
    } else {
      const Eigen::Vector3d p = c.get3(row);
      out[n++] = p.x(), out[n++] = p.y(), out[n++] = p.z();
    }
  }
  values.insert(values.end(), out.begin(), out.begin() + long(n));
}

template <class Row>
void TableSchema<Row>::add(Table& t, const Row& row) const {
  const std::size_t before = t.values.size();
  append(t.values, row);
  t.values.resize(before + t.columns.size());  // a table of the first columns only (table(last))
}

template <class Row>
TableDoc TableSchema<Row>::doc() const {
  TableDoc d{name, written_by, meaning, {}};
  for (std::size_t k = 0; k < count; ++k) {
    std::string joined;
    for (const auto& n : names_of(columns[k])) joined += (joined.empty() ? "" : ", ") + n;
    d.columns.push_back({joined, columns[k].unit, columns[k].meaning});
  }
  return d;
}

template struct TableSchema<FrameRow>;
template struct TableSchema<LoopRow>;
template struct TableSchema<PointRow>;
template struct TableSchema<SkeletonRow>;
template struct TableSchema<LoopPoint>;
template struct TableSchema<SmoothStatsRow>;
template struct TableSchema<SplineRow>;
template struct TableSchema<KnotRow>;
template struct TableSchema<GapRow>;
template struct TableSchema<MeridianRow>;
template struct TableSchema<SampleRow>;
template struct TableSchema<CamberRow>;
template struct TableSchema<ParamsRow>;
template struct TableSchema<ThicknessRow>;
template struct TableSchema<SideRow>;
template struct TableSchema<WallRow>;
template struct TableSchema<WallMapRow>;
template struct TableSchema<FitRow>;
template struct TableSchema<DeviationRow>;
template struct TableSchema<ZoneRow>;
template struct TableSchema<ComparedRow>;
template struct TableSchema<VerdictRow>;
template struct TableSchema<BladeRow>;
template struct TableSchema<StackRow>;

const TableSchema<FrameRow> frames{"frames", "slice", "the plane frame of each section", frame_columns};
const TableSchema<MeridianRow> meridians{
    "meridians", "slice",
    "the meridian (axial, radius) polyline of each section on a surface of revolution (docs/REVOLUTION.md)",
    meridian_columns};
const TableSchema<LoopRow> loops{"loops", "slice", "one row per loop of each section", loop_columns};
const TableSchema<PointRow> points{"points", "slice",
                                   "the measured points projected onto the plane, ordered along their loop",
                                   point_columns};
const TableSchema<SkeletonRow> skeleton{
    "skeleton", "slice", "the skeleton of the filled profile along its main branch (the camber seed)",
    skeleton_columns};
const TableSchema<LoopPoint> smoothed{
    "smoothed", "smooth", "the points of each loop after energy-minimising smoothing (docs/SMOOTH.md)",
    smoothed_columns};
const TableSchema<SmoothStatsRow> smooth_stats{"smooth_stats", "smooth", "one row per smoothed loop",
                                               smooth_stats_columns};
const TableSchema<SplineRow> splines{
    "splines", "fitspline",
    "one row per fitted loop: the B-spline and how close it runs to the measured points", spline_columns};
const TableSchema<KnotRow> spline_knots{"spline_knots", "fitspline", "each spline's knot vector",
                                        knot_columns};
const TableSchema<LoopPoint> spline_ctrl{"spline_ctrl", "fitspline", "each spline's control points",
                                         ctrl_columns};
const TableSchema<GapRow> gaps{"gaps", "fitspline", "the holes in the data along each curve", gap_columns};
const TableSchema<SampleRow> samples{
    "samples", "fitspline", "points of each curve at even arc-length steps (with --samples or --spacing)",
    sample_columns};
const TableSchema<CamberRow> camber{
    "camber", "camber",
    "the mean-camber line of each profile (loop 0) from the LE point to the TE point, straight extensions "
    "included, at even arc-length steps (docs/CAMBER.md)",
    camber_columns};
const TableSchema<ParamsRow> params{"params", "camber", "one row per section: its parameters",
                                    params_columns};
const TableSchema<ThicknessRow> thickness{
    "thickness", "camber", "the thickness at stations along the camber line", thickness_columns};
const TableSchema<SideRow> sides{
    "sides", "camber",
    "the profile split at the LE and TE points, each side sampled evenly in curve parameter", side_columns};

// compare's tables.
const TableSchema<FitRow> fits{"fits", "compare",
                               "one row per section: the best fit of the measured section onto the nominal",
                               fit_columns};
const TableSchema<DeviationRow> deviations{
    "deviations", "compare", "each measured profile point's deviation from the nominal along its normal",
    deviation_columns};
const TableSchema<ZoneRow> zones{"zones", "compare", "each zone's deviations, form, coverage and verdicts",
                                 zone_columns};
const TableSchema<ComparedRow> compared{
    "compared", "compare", "each compared value of a section: measured, nominal, deviation and verdict",
    compared_columns};
const TableSchema<VerdictRow> verdicts{"verdicts", "compare", "one row per section: its verdict",
                                       verdict_columns};

// The tables of slice, smooth, fitspline and camber.
static std::vector<TableDoc> stage_tables() {
  return {frames.doc(),   meridians.doc(),    loops.doc(),   points.doc(),       skeleton.doc(),
          smoothed.doc(), smooth_stats.doc(), splines.doc(), spline_knots.doc(), spline_ctrl.doc(),
          gaps.doc(),     samples.doc(),      camber.doc(),  params.doc(),       thickness.doc(),
          sides.doc(),    walls.doc(),        wall_map.doc()};
}

std::vector<TableDoc> tables() {
  std::vector<TableDoc> out = stage_tables();
  for (TableDoc d : {fits.doc(), deviations.doc(), zones.doc(), compared.doc(), verdicts.doc()})
    out.push_back(std::move(d));                                                 // compare's tables
  for (TableDoc d : {blade.doc(), stacking.doc()}) out.push_back(std::move(d));  // blade's
  return out;
}

}  // namespace schema

}  // namespace section
