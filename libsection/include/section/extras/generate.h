#pragma once
/// @file extras/generate.h
/// Synthetic blades with exact ground truth, for tests, examples and benchmarks.
///
/// A section is the envelope of circles of radius r(s) centred on a camber curve c(s),
/// s in [0, 1], closed by the arcs of the end circles. Its medial axis is c(s) exactly,
/// so the true mean-camber line, inscribed radii, edge radii (r(0), r(1)), edge points
/// (the camber line extended along its end tangents to the profile), chord and thickness
/// are known. A blade stacks such sections along z with parameters varying smoothly with
/// z: the cut of the blade by the plane z = z0 is exactly the section designed at z0.
#include "section/cloud.h"
#include "section/mesh.h"

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace section {

namespace detail {
struct PolylineIndex;  // search grid over a polyline, built by section_truth (generate.cpp)
}

/// Design of one 2D section (lengths in mm, angles in degrees against the +u axis).
struct SectionDesign {
  double chord = 40;               ///< distance between the camber curve's end centres
  double stagger = 30;             ///< angle of the line from c(0) to c(1)
  double inlet_angle = 50;         ///< camber tangent angle at c(0)
  double outlet_angle = 10;        ///< camber tangent angle at c(1)
  double le_radius = 1.0;          ///< r(0): leading-edge radius
  double te_radius = 0.3;          ///< r(1): trailing-edge radius
  double max_thickness = 4.0;      ///< 2 max r(s)
  double max_thickness_pos = 0.35; ///< s of the thickest point (of the camber curve c)
  Eigen::Vector2d offset{0, 0};    ///< position of c(0)
};

/// A blade: section designs at the hub (z = 0) and the tip (z = span), blended smoothly.
struct BladeDesign {
  SectionDesign hub;               ///< design at z = 0
  SectionDesign tip;               ///< design at z = span
  double span = 60;                ///< blade height along z
  SectionDesign at(double z) const;  ///< the design of the section at height z
};

/// Turbine-like blade: high turning (~110 deg), thick, round leading edge.
BladeDesign turbine_blade();
/// Compressor-like blade: low turning (~30 deg), thin, edge radii 0.2-0.35 mm.
BladeDesign compressor_blade();

/// Five sections spanning the shapes a measure must hold on: a moderate one (40 deg
/// turning), the turbine preset's hub (thick, 110 deg), the compressor preset at mid
/// span (thin, small edges), a thin low-turning one with a 0.15 mm TE, and a thick
/// 115-degree one with large edges.
std::vector<SectionDesign> design_family();

/// Exact ground truth of one section.
struct SectionTruth {
  std::vector<Eigen::Vector2d> profile;  ///< dense closed profile, counterclockwise, no repeated end point
  std::vector<double> profile_s;         ///< arc length along `profile` from its first point
  std::vector<Eigen::Vector2d> profile_normal;  ///< exact outward unit normal at each profile point
  double perimeter = 0;                  ///< length of the closed profile
  std::vector<Eigen::Vector2d> camber;   ///< dense camber line from LE point to TE point, extensions included
  std::vector<double> camber_radius;     ///< inscribed radius at each camber point (the edge radius on the extensions)
  std::vector<double> camber_s;          ///< arc length along `camber` from the LE point
  std::size_t camber_begin = 0, camber_end = 0;  ///< camber[camber_begin, camber_end) are on c(s) (no extension points)
  Eigen::Vector2d le_point, te_point;    ///< edge points on the profile
  Eigen::Vector2d le_center, te_center;  ///< edge circle centres c(0), c(1)
  double le_radius = 0, te_radius = 0;   ///< edge radii
  double chord = 0;                      ///< |te_point - le_point|
  double camber_length = 0;              ///< length of `camber`
  double max_thickness = 0;              ///< largest inscribed diameter
  double max_thickness_pos = 0;          ///< its arc-length position along `camber`, 0 at LE, 1 at TE
  double stagger = 0;                    ///< angle of te_point - le_point against +u, degrees
  double inlet_angle = 0, outlet_angle = 0;  ///< camber tangent angles at LE and TE, degrees
  double area = 0;                       ///< enclosed area
  Eigen::Vector2d centroid{0, 0};        ///< area centroid
  double te_s = 0;                       ///< arc length of te_point along `profile` (le_point is profile[0], at 0)
  std::shared_ptr<const detail::PolylineIndex> profile_index;  ///< speeds up locate()
  std::shared_ptr<const detail::PolylineIndex> camber_index;   ///< speeds up camber_distance()
};

/// The exact section of a design, sampled with `samples` profile points (camber: samples/2).
/// Profile and camber points lie on the exact curves, equally spaced in arc length; the
/// profile starts at the LE point. Throws section::Error when the design is invalid: radii
/// not positive, an edge radius not below max_thickness/2, max_thickness_pos outside
/// (0, 1), or a thickness law the envelope cannot follow (|r'| >= |c'|, a side with a cusp,
/// or a side curving more tightly than its inscribed circle, after which c(s) would no
/// longer be the medial axis).
SectionTruth section_truth(const SectionDesign& design, int samples = 20000);

/// Where a point lies relative to a true profile.
struct ProfileLocation {
  double distance = 0;   ///< unsigned distance to the profile
  double s = 0;          ///< arc length of the foot point along SectionTruth::profile
};
/// Distance and foot position of `p` on the true profile (exact to well below 0.1 um).
/// The nearest polyline segment is found with a box tree over `profile`, then the foot is
/// refined on the exact curve (~1e-14 mm); ~ 3 us per query. Without the index built by
/// section_truth (e.g. an edited profile) it falls back on brute force over the polyline.
ProfileLocation locate(const SectionTruth& truth, const Eigen::Vector2d& p);
/// Distance of `p` to the true camber line (extensions included), measured on the dense
/// camber polyline: within its sagitta, ~0.2 um for the default 10000 camber points.
double camber_distance(const SectionTruth& truth, const Eigen::Vector2d& p);

/// How a synthetic scan is made. Defaults: a clean, dense, uniform scan.
struct ScanOptions {
  double spacing = 0.08;           ///< mm, mean distance between neighbouring scan points
  double noise = 0;                ///< mm, standard deviation of the noise along the surface normal
  int holes = 0;                   ///< number of unscanned patches (each 0.5-2 mm across)
  double density_min = 1;          ///< lowest local density relative to the nominal (e.g. 0.25)
  double misregistration = 0;      ///< mm, offset of the second view (half the surface) from the truth
  double outlier_fraction = 0;     ///< fraction of points replaced by outliers (e.g. 0.0002)
  double z_min = 0, z_max = -1;    ///< scanned height range; z_max < z_min = the whole span
  std::uint64_t seed = 1;          ///< random seed
};

/// A synthetic scan with per-point ground truth flags.
struct Scan {
  Cloud cloud;                     ///< the points
  std::vector<std::uint8_t> outlier;  ///< 1 where the point is an outlier
  std::vector<std::uint8_t> view;  ///< 0 or 1: which scanner view produced the point
};

/// The scan's points apart by view (index 0 and 1), as a scanner delivers them.
std::vector<Cloud> views_of(const Scan& scan);

/// Samples the blade's side surface as a scanner would (no end caps).
/// - Rows of points `spacing` apart in z; within a row, points `spacing` apart in profile
///   arc length, each jittered. Heights take one of 64 levels per row (steps of
///   spacing/64) and every clean point lies exactly on the section designed at its z.
/// - Noise: Gaussian along the 3D surface normal, sigma `noise`.
/// - Density: a smooth keep-probability field between density_min and 1 (a few waves
///   over the surface); holes: discs of 0.25-1 mm radius in (arc length, z) removed.
/// - Two views: view 1 covers the right side of the camber (the pressure side of the
///   presets, concave) from the LE point to the TE point, view 0 the rest, each extended
///   1.5 mm past the edge points, so both views overlap in 3 mm bands around LE and TE.
///   View 1 is shifted by `misregistration` in-plane, normal to the mid-camber chord
///   towards the pressure side.
/// - Outliers replace kept points: uniform in the blade's bounding box (over the scanned
///   z range) grown by 2 mm in x, y and z, and at least 0.2 mm (in-plane) from the
///   section at their height, clamped to [0, span].
/// Deterministic for a seed (own transforms over std::mt19937_64, independent of the
/// thread count); the options other than the seed change which points are kept and how
/// they move, not where candidates fall. ~0.35 us of CPU per point, spread over the cores.
/// Throws section::Error on bad options or a blade design invalid in the scanned range.
Scan generate_scan(const BladeDesign& blade, const ScanOptions& options = {});

/// The scan of the accuracy evaluations: realistic and hostile (0.08 mm spacing, 5 um
/// noise, 5 holes, density 25-100 %, 0.02 % outliers, no misregistration, whole span).
ScanOptions inspection_scan();

/// Scans only the bands z +- `half_band` around `heights` (what the slabs of a full scan
/// there would hold, for a fraction of the points): band at z uses seed
/// `options.seed * 100 + floor(z)`, the other options as given, z_min/z_max ignored.
Cloud scan_bands(const BladeDesign& blade, const std::vector<double>& heights, const ScanOptions& options,
                 double half_band = 0.5);

/// Closed triangle mesh of the blade (side surface plus end caps), `profile_points` per
/// section and `layers` sections along the span.
/// Ring k lies at z = span k / (layers - 1); its vertices are exact profile points at equal
/// arc-length steps from the LE point, so vertex i of every ring is at the same fraction of
/// the perimeter. Triangles are counterclockwise seen from outside; caps by ear clipping.
Mesh generate_mesh(const BladeDesign& blade, int profile_points = 400, int layers = 60);

}  // namespace section
