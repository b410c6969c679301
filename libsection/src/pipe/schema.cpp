// The stream's tables and their columns: the one place that names them (docs/FORMAT.md).
#include "section/pipe/schema.h"

#include "section/error.h"

#include <cmath>
#include <string>
#include <vector>

namespace section {
namespace schema {

namespace {

// Columns most tables share.
template <class Row>
constexpr Column<Row> section_id() {
  return {col::section, "id", "the section id (the plane's index)", [](const Row& r) { return double(r.section); }};
}
template <class Row>
constexpr Column<Row> loop_id() {
  return {col::loop, "id", "the loop id within the section, 0 the profile (the loop enclosing the largest area)",
          [](const Row& r) { return double(r.loop); }};
}
template <class Row>
constexpr Column<Row> index_of(const char* meaning) {
  return {col::index, "id", meaning, [](const Row& r) { return double(r.index); }};
}
template <class Row>
constexpr Column<Row> point_u(const char* meaning) {
  return {col::u, "length", meaning, [](const Row& r) { return r.point.x(); }};
}
template <class Row>
constexpr Column<Row> point_v(const char* meaning) {
  return {col::v, "length", meaning, [](const Row& r) { return r.point.y(); }};
}

constexpr Column<FrameRow> frame_columns[] = {
    section_id<FrameRow>(),
    {"origin_x", "length", "x of the plane's origin, where u = v = 0", [](const FrameRow& r) { return r.frame.origin.x(); }},
    {"origin_y", "length", "y of the plane's origin", [](const FrameRow& r) { return r.frame.origin.y(); }},
    {"origin_z", "length", "z of the plane's origin", [](const FrameRow& r) { return r.frame.origin.z(); }},
    {"u_x", "1", "x of the first in-plane axis u (a unit vector)", [](const FrameRow& r) { return r.frame.u.x(); }},
    {"u_y", "1", "y of u", [](const FrameRow& r) { return r.frame.u.y(); }},
    {"u_z", "1", "z of u", [](const FrameRow& r) { return r.frame.u.z(); }},
    {"v_x", "1", "x of the second in-plane axis v (a unit vector)", [](const FrameRow& r) { return r.frame.v.x(); }},
    {"v_y", "1", "y of v", [](const FrameRow& r) { return r.frame.v.y(); }},
    {"v_z", "1", "z of v", [](const FrameRow& r) { return r.frame.v.z(); }},
    {"n_x", "1", "x of the plane's unit normal n = u x v", [](const FrameRow& r) { return r.frame.n.x(); }},
    {"n_y", "1", "y of n", [](const FrameRow& r) { return r.frame.n.y(); }},
    {"n_z", "1", "z of n", [](const FrameRow& r) { return r.frame.n.z(); }},
};

const Loop& loop_of(const LoopRow& r) { return r.morphology.loops[r.loop]; }
constexpr Column<LoopRow> loop_columns[] = {
    section_id<LoopRow>(),
    loop_id<LoopRow>(),
    {"points", "count", "points kept in the loop", [](const LoopRow& r) { return double(loop_of(r).points.size()); }},
    {"dropped", "count", "outliers dropped: the section's count on loop 0, 0 on the others",
     [](const LoopRow& r) { return r.loop == 0 ? double(r.morphology.dropped) : 0.0; }},
    {"area", "area", "area enclosed by the loop's traced boundary", [](const LoopRow& r) { return loop_of(r).area; }},
    {"length", "length", "length of the traced boundary", [](const LoopRow& r) { return loop_of(r).length; }},
    {"cell", "length", "raster cell used to order the section", [](const LoopRow& r) { return r.morphology.cell; }},
};

constexpr Column<PointRow> point_columns[] = {
    section_id<PointRow>(),
    loop_id<PointRow>(),
    index_of<PointRow>("order along the loop (counterclockwise)"),
    point_u<PointRow>("the point in the plane, along u"),
    point_v<PointRow>("the point in the plane, along v"),
    {"nu", "1", "u of the outward unit normal from the image gradient", [](const PointRow& r) { return r.normal.x(); }},
    {"nv", "1", "v of that normal", [](const PointRow& r) { return r.normal.y(); }},
    {col::offset, "length",
     "0 for a point of the slab; for a point the gap fill carried onto the plane, its signed distance "
     "from the plane before (docs/MORPHOLOGY.md; a table without the column reads as all 0)",
     [](const PointRow& r) { return r.offset; }},
};

constexpr Column<SkeletonRow> skeleton_columns[] = {
    section_id<SkeletonRow>(),
    {col::loop, "id", "0: the skeleton is the profile's", [](const SkeletonRow&) { return 0.0; }},
    index_of<SkeletonRow>("order along the main branch, from the blunter end"),
    point_u<SkeletonRow>("the skeleton point, along u"),
    point_v<SkeletonRow>("the skeleton point, along v"),
    {"radius", "length", "its distance to the profile's boundary", [](const SkeletonRow& r) { return r.radius; }},
};

constexpr Column<LoopPoint> smoothed_columns[] = {
    section_id<LoopPoint>(),
    loop_id<LoopPoint>(),
    index_of<LoopPoint>("order along the loop, from 0 (renumbered when duplicate points were merged)"),
    point_u<LoopPoint>("the smoothed point, along u"),
    point_v<LoopPoint>("the smoothed point, along v"),
};

constexpr Column<SmoothStatsRow> smooth_stats_columns[] = {
    section_id<SmoothStatsRow>(),
    loop_id<SmoothStatsRow>(),
    {"points", "count", "points kept", [](const SmoothStatsRow& r) { return double(r.result.points.size()); }},
    {"energy_before", "length^2", "the energy E before smoothing",
     [](const SmoothStatsRow& r) { return r.result.energy_before; }},
    {"energy_after", "length^2", "E after smoothing", [](const SmoothStatsRow& r) { return r.result.energy_after; }},
    {"iterations", "count", "outer iterations done", [](const SmoothStatsRow& r) { return double(r.result.iterations); }},
    {"rms_move", "length", "root mean square move of the points", [](const SmoothStatsRow& r) { return r.result.rms_move; }},
    {"max_move", "length", "largest move of a point", [](const SmoothStatsRow& r) { return r.result.max_move; }},
    {"repaired", "count", "duplicate points merged", [](const SmoothStatsRow& r) { return double(r.result.repaired); }},
};

constexpr Column<SplineRow> spline_columns[] = {
    section_id<SplineRow>(),
    loop_id<SplineRow>(),
    {col::degree, "1", "the B-spline's degree", [](const SplineRow& r) { return double(r.fit.spline.degree); }},
    {col::closed, "flag", "1 when closed (periodic)", [](const SplineRow& r) { return r.fit.spline.closed ? 1.0 : 0.0; }},
    {"control_points", "count", "its control points",
     [](const SplineRow& r) { return double(r.fit.spline.control.size()); }},
    {col::rms, "length", "RMS distance of the measured points (outliers excluded) to the curve",
     [](const SplineRow& r) { return r.fit.rms; }},
    {"max", "length", "the largest such distance", [](const SplineRow& r) { return r.fit.max; }},
    {"p95", "length", "their 95th percentile", [](const SplineRow& r) { return r.fit.p95; }},
    {"iterations", "count", "distance-minimisation iterations done", [](const SplineRow& r) { return double(r.fit.iterations); }},
    {"spacing", "length", "median spacing of the measured points along the curve", [](const SplineRow& r) { return r.fit.spacing; }},
    {"max_gap", "length", "the longest stretch of the curve without a measured point, along it",
     [](const SplineRow& r) { return r.fit.max_gap; }},
    {"gap_start", "parameter", "the curve parameter where it begins", [](const SplineRow& r) { return r.fit.gap_start; }},
    {"gap_end", "parameter", "where it ends (below gap_start when it wraps past the curve's last parameter)",
     [](const SplineRow& r) { return r.fit.gap_end; }},
    {col::layers, "length",
     "distance between two layers of points found along the loop (views merged with a misregistration: the curve "
     "runs between them), 0 when none (docs/FITSPLINE.md, step 5)",
     [](const SplineRow& r) { return r.fit.layers; }},
    {col::layers_length, "length", "the profile length over which they were found, 0 when none",
     [](const SplineRow& r) { return r.fit.layers_length; }},
};

constexpr Column<KnotRow> knot_columns[] = {
    section_id<KnotRow>(),
    loop_id<KnotRow>(),
    index_of<KnotRow>("order of the knots"),
    {col::knot, "parameter", "the knot", [](const KnotRow& r) { return r.knot; }},
};

constexpr Column<LoopPoint> ctrl_columns[] = {
    section_id<LoopPoint>(),
    loop_id<LoopPoint>(),
    index_of<LoopPoint>("order of the control points"),
    point_u<LoopPoint>("the control point, along u"),
    point_v<LoopPoint>("the control point, along v"),
};

constexpr Column<GapRow> gap_columns[] = {
    section_id<GapRow>(),
    loop_id<GapRow>(),
    index_of<GapRow>("0 the longest hole, then shorter ones"),
    {col::t_start, "parameter", "the curve parameter where the hole begins", [](const GapRow& r) { return r.gap.start; }},
    {col::t_end, "parameter", "where it ends", [](const GapRow& r) { return r.gap.end; }},
    {col::length, "length", "its length along the curve", [](const GapRow& r) { return r.gap.length; }},
};

constexpr Column<SampleRow> sample_columns[] = {
    section_id<SampleRow>(),
    loop_id<SampleRow>(),
    index_of<SampleRow>("order along the curve"),
    {"t", "parameter", "the curve parameter", [](const SampleRow& r) { return r.t; }},
    point_u<SampleRow>("the curve point, along u"),
    point_v<SampleRow>("the curve point, along v"),
    {"x", "length", "x of the point in 3D, through the section's frame (the identity when the stream has no frames)",
     [](const SampleRow& r) { return r.world.x(); }},
    {"y", "length", "y of the point in 3D", [](const SampleRow& r) { return r.world.y(); }},
    {"z", "length", "z of the point in 3D", [](const SampleRow& r) { return r.world.z(); }},
    {"nu", "1", "u of the outward unit normal (the tangent turned clockwise)", [](const SampleRow& r) { return r.normal.x(); }},
    {"nv", "1", "v of that normal", [](const SampleRow& r) { return r.normal.y(); }},
    {"curvature", "1/length", "signed curvature, positive turning counterclockwise",
     [](const SampleRow& r) { return r.curvature; }},
};

constexpr Column<CamberRow> camber_columns[] = {
    section_id<CamberRow>(),
    index_of<CamberRow>("order from the LE point to the TE point"),
    {"s", "length", "arc length from the LE point", [](const CamberRow& r) { return r.s; }},
    point_u<CamberRow>("the camber point, along u"),
    point_v<CamberRow>("the camber point, along v"),
    {"x", "length", "x of the camber point in 3D", [](const CamberRow& r) { return r.world.x(); }},
    {"y", "length", "y of the camber point in 3D", [](const CamberRow& r) { return r.world.y(); }},
    {"z", "length", "z of the camber point in 3D", [](const CamberRow& r) { return r.world.z(); }},
    {"radius", "length", "the inscribed radius (the end circle's on the extensions)",
     [](const CamberRow& r) { return r.radius; }},
};

// Adding a params column is adding its line here (docs/FORMAT.md then lists it: test_schema).
constexpr Column<ParamsRow> params_columns[] = {
    section_id<ParamsRow>(),
    {"chord", "length", "the distance between the edge points", [](const ParamsRow& r) { return r.params.chord; }},
    {"camber_length", "length", "length of the camber line, LE point to TE point",
     [](const ParamsRow& r) { return r.params.camber_length; }},
    {"max_thickness", "length", "the largest inscribed diameter", [](const ParamsRow& r) { return r.params.max_thickness; }},
    {"max_thickness_pos", "1", "its place along the camber line, 0 at the LE, 1 at the TE",
     [](const ParamsRow& r) { return r.params.max_thickness_pos; }},
    {"le_radius", "length", "radius of the circle fitted to the leading edge's arc (0 for a flat face, and with --edge "
     "auto for a blunt or sharp edge)", [](const ParamsRow& r) { return r.params.le_radius; }},
    {"te_radius", "length", "the same at the trailing edge", [](const ParamsRow& r) { return r.params.te_radius; }},
    {"le_curvature_radius", "length", "1 / the profile's curvature at the LE point (0 when flat)",
     [](const ParamsRow& r) { return r.params.le_curvature_radius; }},
    {"te_curvature_radius", "length", "the same at the TE point",
     [](const ParamsRow& r) { return r.params.te_curvature_radius; }},
    {"le_shape", "code", "the leading edge's shape (edge shapes below)",
     [](const ParamsRow& r) { return double(static_cast<int>(r.camber.le.shape)); }},
    {"te_shape", "code", "the trailing edge's shape", [](const ParamsRow& r) { return double(static_cast<int>(r.camber.te.shape)); }},
    {"le_arc", "degrees", "the arc of the leading edge its circle is fitted to", [](const ParamsRow& r) { return r.camber.le.arc; }},
    {"te_arc", "degrees", "the same at the trailing edge", [](const ParamsRow& r) { return r.camber.te.arc; }},
    {"le_fit_rms", "length", "rms distance of that arc from its circle", [](const ParamsRow& r) { return r.camber.le.fit_rms; }},
    {"te_fit_rms", "length", "the same at the trailing edge", [](const ParamsRow& r) { return r.camber.te.fit_rms; }},
    {"stagger", "degrees", "angle of the chord line, LE to TE", [](const ParamsRow& r) { return r.params.stagger; }},
    {"inlet_angle", "degrees", "the camber line's tangent (toward the TE) at the LE",
     [](const ParamsRow& r) { return r.params.inlet_angle; }},
    {"outlet_angle", "degrees", "its tangent at the TE", [](const ParamsRow& r) { return r.params.outlet_angle; }},
    {"camber_angle", "degrees", "inlet_angle - outlet_angle (the turning)", [](const ParamsRow& r) { return r.params.camber_angle; }},
    {"area", "area", "the area the profile encloses", [](const ParamsRow& r) { return r.params.area; }},
    {"centroid_u", "length", "its centroid, along u", [](const ParamsRow& r) { return r.params.centroid.x(); }},
    {"centroid_v", "length", "its centroid, along v", [](const ParamsRow& r) { return r.params.centroid.y(); }},
    {"le_u", "length", "the LE point, along u", [](const ParamsRow& r) { return r.params.le_point.x(); }},
    {"le_v", "length", "the LE point, along v", [](const ParamsRow& r) { return r.params.le_point.y(); }},
    {"te_u", "length", "the TE point, along u", [](const ParamsRow& r) { return r.params.te_point.x(); }},
    {"te_v", "length", "the TE point, along v", [](const ParamsRow& r) { return r.params.te_point.y(); }},
    {"le_center_u", "length", "centre of the leading edge's circle, along u", [](const ParamsRow& r) { return r.camber.le.center.x(); }},
    {"le_center_v", "length", "centre of the leading edge's circle, along v", [](const ParamsRow& r) { return r.camber.le.center.y(); }},
    {"te_center_u", "length", "centre of the trailing edge's circle, along u", [](const ParamsRow& r) { return r.camber.te.center.x(); }},
    {"te_center_v", "length", "centre of the trailing edge's circle, along v", [](const ParamsRow& r) { return r.camber.te.center.y(); }},
    {"le_x", "length", "x of the LE point in 3D", [](const ParamsRow& r) { return r.le.x(); }},
    {"le_y", "length", "y of the LE point in 3D", [](const ParamsRow& r) { return r.le.y(); }},
    {"le_z", "length", "z of the LE point in 3D", [](const ParamsRow& r) { return r.le.z(); }},
    {"te_x", "length", "x of the TE point in 3D", [](const ParamsRow& r) { return r.te.x(); }},
    {"te_y", "length", "y of the TE point in 3D", [](const ParamsRow& r) { return r.te.y(); }},
    {"te_z", "length", "z of the TE point in 3D", [](const ParamsRow& r) { return r.te.z(); }},
    {"centroid_x", "length", "x of the centroid in 3D", [](const ParamsRow& r) { return r.centroid.x(); }},
    {"centroid_y", "length", "y of the centroid in 3D", [](const ParamsRow& r) { return r.centroid.y(); }},
    {"centroid_z", "length", "z of the centroid in 3D", [](const ParamsRow& r) { return r.centroid.z(); }},
    {"caliper_chord", "length", "the profile's extent along the caliper line (touching the pressure side at both ends)",
     [](const ParamsRow& r) { return r.params.caliper_chord; }},
    {"caliper_stagger", "degrees", "angle of the caliper line, LE to TE", [](const ParamsRow& r) { return r.params.caliper_stagger; }},
    {"caliper_found", "flag", "0 when the pressure side is not concave (the chord line is used)",
     [](const ParamsRow& r) { return r.params.caliper_found ? 1.0 : 0.0; }},
    {"pressure_side", "code", "+1 when the pressure (concave) side lies left of the LE-to-TE direction, -1 right",
     [](const ParamsRow& r) { return double(r.camber.pressure_side); }},
    {"le_by_direction", "flag", "1 when --le-direction set the LE, 0 when the maximum thickness did",
     [](const ParamsRow& r) { return r.camber.le_by_direction ? 1.0 : 0.0; }},
    {"le_face", "length", "width of a blunt leading edge's flat face (its radius is then 0), 0 for other edges",
     [](const ParamsRow& r) { return r.camber.le.face; }},
    {"te_face", "length", "the same at the trailing edge", [](const ParamsRow& r) { return r.camber.te.face; }},
    {"le_unmeasured", "length", "length of profile around the LE point that no measured point covers, 0 when one "
     "lies at it", [](const ParamsRow& r) { return r.le_unmeasured; }},
    {"te_unmeasured", "length", "the same at the TE point", [](const ParamsRow& r) { return r.te_unmeasured; }},
};

constexpr Column<ThicknessRow> thickness_columns[] = {
    section_id<ThicknessRow>(),
    index_of<ThicknessRow>("order of the stations"),
    {"fraction", "1", "the station: arc length from the LE point / camber length",
     [](const ThicknessRow& r) { return r.station.fraction; }},
    {"s", "length", "arc length from the LE point", [](const ThicknessRow& r) { return r.station.s; }},
    {col::u, "length", "the inscribed circle's centre, along u", [](const ThicknessRow& r) { return r.station.point.x(); }},
    {col::v, "length", "the inscribed circle's centre, along v", [](const ThicknessRow& r) { return r.station.point.y(); }},
    {"thickness", "length", "its diameter (on an extension: the width across the camber normal)",
     [](const ThicknessRow& r) { return r.station.thickness; }},
    {"pressure_u", "length", "its contact with the pressure side, along u", [](const ThicknessRow& r) { return r.station.pressure.x(); }},
    {"pressure_v", "length", "its contact with the pressure side, along v", [](const ThicknessRow& r) { return r.station.pressure.y(); }},
    {"suction_u", "length", "its contact with the suction side, along u", [](const ThicknessRow& r) { return r.station.suction.x(); }},
    {"suction_v", "length", "its contact with the suction side, along v", [](const ThicknessRow& r) { return r.station.suction.y(); }},
};

constexpr Column<SideRow> side_columns[] = {
    section_id<SideRow>(),
    {"side", "code", "0 the pressure (concave) side, 1 the suction side", [](const SideRow& r) { return double(r.side); }},
    index_of<SideRow>("order from the LE point to the TE point"),
    point_u<SideRow>("the profile point, along u"),
    point_v<SideRow>("the profile point, along v"),
};

}  // namespace

const TableSchema<FrameRow> frames{"frames", "slice", "the plane frame of each section", frame_columns};
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
    "splines", "fitspline", "one row per fitted loop: the B-spline and how close it runs to the measured points",
    spline_columns};
const TableSchema<KnotRow> spline_knots{"spline_knots", "fitspline", "each spline's knot vector", knot_columns};
const TableSchema<LoopPoint> spline_ctrl{"spline_ctrl", "fitspline", "each spline's control points", ctrl_columns};
const TableSchema<GapRow> gaps{"gaps", "fitspline", "the holes in the data along each curve", gap_columns};
const TableSchema<SampleRow> samples{
    "samples", "fitspline", "points of each curve at even arc-length steps (with --samples or --spacing)",
    sample_columns};
const TableSchema<CamberRow> camber{
    "camber", "camber",
    "the mean-camber line of each profile (loop 0) from the LE point to the TE point, straight extensions "
    "included, at even arc-length steps (docs/CAMBER.md)",
    camber_columns};
const TableSchema<ParamsRow> params{"params", "camber", "one row per section: its parameters", params_columns};
const TableSchema<ThicknessRow> thickness{"thickness", "camber", "the thickness at stations along the camber line",
                                          thickness_columns};
const TableSchema<SideRow> sides{
    "sides", "camber", "the profile split at the LE and TE points, each side sampled evenly in curve parameter",
    side_columns};

std::vector<TableDoc> tables() {
  return {frames.doc(),       loops.doc(),  points.doc(),      skeleton.doc(), smoothed.doc(),
          smooth_stats.doc(), splines.doc(), spline_knots.doc(), spline_ctrl.doc(), gaps.doc(),
          samples.doc(),      camber.doc(), params.doc(),      thickness.doc(), sides.doc()};
}

}  // namespace schema

std::map<int, Frame> frames(const Stream& stream) {
  const Table& t = schema::frames.get(stream);
  std::vector<std::size_t> c;
  for (const auto& column : schema::frames) c.push_back(t.column(column.name));
  std::map<int, Frame> out;
  for (std::size_t r = 0; r < t.rows(); ++r) {
    Frame f;
    const auto v3 = [&](int k) { return Eigen::Vector3d(t.at(r, c[k]), t.at(r, c[k + 1]), t.at(r, c[k + 2])); };
    f.origin = v3(1);
    f.u = v3(4);
    f.v = v3(7);
    f.n = v3(10);
    const auto unit = [](const Eigen::Vector3d& a) { return std::abs(a.norm() - 1) < 1e-6; };
    if (!unit(f.u) || !unit(f.v) || !unit(f.n) || std::abs(f.u.dot(f.v)) > 1e-6 ||
        (f.u.cross(f.v) - f.n).norm() > 1e-6)
      throw Error("pipe: the frame of section " + format_number(t.at(r, c[0])) +
                  " is not a right-handed orthonormal frame");
    out[static_cast<int>(t.at(r, c[0]))] = f;
  }
  return out;
}

void put_frames(Stream& stream, const std::map<int, Frame>& frames) {
  Table t = schema::frames.table();
  for (const auto& [id, f] : frames) schema::frames.add(t, {id, f});
  stream.put(std::move(t));
}

}  // namespace section
