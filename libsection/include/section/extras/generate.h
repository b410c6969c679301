// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file extras/generate.h
/// Synthetic blades with exact ground truth, for tests, examples and benchmarks.
///
/// A section is the envelope of circles of radius r(s) centred on a camber curve c(s),
/// closed by the end circles' arcs: its medial axis is c(s), so the camber line, radii,
/// edge points, chord and thickness are known exactly. A blade stacks sections along z;
/// its cut at z = z0 is exactly the section designed at z0. The model: docs/GENERATOR.md.
#include "section/cloud.h"
#include "section/mesh.h"

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace section {

namespace detail {
struct PolylineIndex;  // nearest-segment search over a polyline (src/extras/generate_index.h)
}

/// Design of one 2D section (lengths in mm, angles in degrees against the +u axis).
struct SectionDesign {
  double chord = 40;                ///< distance between the camber curve's end centres
  double stagger = 30;              ///< angle of the line from c(0) to c(1)
  double inlet_angle = 50;          ///< camber tangent angle at c(0)
  double outlet_angle = 10;         ///< camber tangent angle at c(1)
  double le_radius = 1.0;           ///< r(0): leading-edge radius; 0 = a sharp edge (one vertex)
  double te_radius = 0.3;           ///< r(1): trailing-edge radius; 0 = a sharp edge (one vertex)
  double max_thickness = 4.0;       ///< 2 max r(s)
  double max_thickness_pos = 0.35;  ///< s of the thickest point (of the camber curve c)
  Eigen::Vector2d offset{0, 0};     ///< position of c(0)
};

/// How a blade's sections are moved along the span on top of the hub-to-tip blend, in mm
/// (docs/BLADE.md): at t = z / span each section moves by sweep t along +u (axial) and by
/// lean t + 4 bow t (1 - t) along +v (tangential). Zero: no move.
struct StackingLaw {
  double lean = 0;   ///< tangential move at the tip, linear in t
  double sweep = 0;  ///< axial move at the tip, linear in t
  double bow = 0;    ///< tangential move at mid-span of the parabola 4 t (1 - t), 0 at hub and tip
};

/// A blade: section designs at the hub (z = 0) and the tip (z = span), blended smoothly.
struct BladeDesign {
  SectionDesign hub;                 ///< design at z = 0
  SectionDesign tip;                 ///< design at z = span
  double span = 60;                  ///< blade height along z
  StackingLaw stacking;              ///< lean, sweep and bow of the sections (twist: hub/tip stagger)
  SectionDesign at(double z) const;  ///< the design of the section at height z
};

/// Turbine-like blade: high turning (~110 deg), thick, round leading edge.
BladeDesign turbine_blade();
/// Compressor-like blade: low turning (~30 deg), thin, edge radii 0.2-0.35 mm.
BladeDesign compressor_blade();

/// Blade with a sharp, closed trailing edge: radius 0, the two sides meeting at one vertex
/// with a finite wedge angle (about 12 degrees); a thin cambered section, round LE.
BladeDesign sharp_te_blade();
/// Mirror-symmetric impulse blade: front and back alike (inlet = stagger + theta, outlet =
/// stagger - theta, equal edge radii, thickest at mid camber), so neither the thickness nor
/// the edges tell the leading edge; chord along +x, 120 degrees of turning.
BladeDesign impulse_blade();
/// Thick root, tiny trailing edge: max thickness 28 % of the chord at the hub (13 % at the
/// tip), TE radius 0.2 mm at the hub and 0.12 mm at the tip.
BladeDesign thick_root_blade();

/// Five sections spanning the shapes a measure must hold on: moderate (40 deg turning),
/// the turbine hub, the compressor at mid span, thin with a 0.15 mm TE, thick at 115 deg.
std::vector<SectionDesign> design_family();

/// Exact ground truth of one section (lengths in mm, angles in degrees).
struct SectionTruth {
  std::vector<Eigen::Vector2d> profile;         ///< dense closed profile, counterclockwise, from the LE point
  std::vector<double> profile_s;                ///< arc length along `profile` from its first point
  std::vector<Eigen::Vector2d> profile_normal;  ///< exact outward unit normal at each profile point
  double perimeter = 0;                         ///< length of the closed profile
  std::vector<Eigen::Vector2d> camber;  ///< dense camber line, LE point to TE point, extensions included
  std::vector<double> camber_radius;    ///< inscribed radius at each camber point (edge radius on extensions)
  std::vector<double> camber_s;         ///< arc length along `camber` from the LE point
  std::size_t camber_begin = 0, camber_end = 0;  ///< camber[camber_begin, camber_end) lie on c(s)
  Eigen::Vector2d le_point, te_point;            ///< edge points on the profile
  Eigen::Vector2d le_center, te_center;          ///< edge circle centres c(0), c(1)
  double le_radius = 0, te_radius = 0;           ///< edge radii
  double chord = 0;                              ///< |te_point - le_point|
  double camber_length = 0;                      ///< length of `camber`
  double max_thickness = 0;                      ///< largest inscribed diameter
  double max_thickness_pos = 0;                  ///< its arc-length fraction along `camber` from the LE
  double stagger = 0;                            ///< angle of te_point - le_point against +u
  double inlet_angle = 0, outlet_angle = 0;      ///< camber tangent angles at LE and TE
  double area = 0;                               ///< enclosed area
  Eigen::Vector2d centroid{0, 0};                ///< area centroid
  double te_s = 0;                               ///< arc length of te_point along `profile`
  std::shared_ptr<const detail::PolylineIndex> profile_index;  ///< speeds up locate()
  std::shared_ptr<const detail::PolylineIndex> camber_index;   ///< speeds up camber_distance()
};

/// The exact section of a design: `samples` profile points (camber: samples/2), on the
/// exact curves, equally spaced in arc length. Throws section::Error when the design is
/// invalid (radii, max_thickness_pos, or a thickness law after which c(s) would no longer
/// be the medial axis).
SectionTruth section_truth(const SectionDesign& design, int samples = 20000);

/// Points every `spacing` (mm, at least) along a true profile, from its LE point, each moved
/// along the exact outward normal by Gaussian noise of standard deviation `sigma` (mm;
/// std::mt19937_64 seeded with `seed`; sigma 0: the exact points): a measured 2D profile whose
/// every error is known. `normals`, when given, gets the exact normal of each point. Throws
/// section::Error unless spacing > 0 and sigma >= 0.
std::vector<Eigen::Vector2d> noisy_profile(const SectionTruth& truth, double spacing, double sigma,
                                           std::uint64_t seed,
                                           std::vector<Eigen::Vector2d>* normals = nullptr);

/// Where a point lies relative to a true profile.
struct ProfileLocation {
  double distance = 0;  ///< unsigned distance to the profile
  double s = 0;         ///< arc length of the foot point along SectionTruth::profile
};
/// Distance and foot position of `p` on the true profile, refined on the exact curve
/// (~1e-14 mm, ~3 us per query); brute force over the polyline without the truth's index.
ProfileLocation locate(const SectionTruth& truth, const Eigen::Vector2d& p);
/// Distance of `p` to the true camber line (extensions included), on the dense camber
/// polyline: within its sagitta, ~0.2 um for the default 10000 camber points.
double camber_distance(const SectionTruth& truth, const Eigen::Vector2d& p);

/// How a synthetic scan is made. Defaults: a clean, dense, uniform scan.
struct ScanOptions {
  double spacing = 0.08;         ///< mm, mean distance between neighbouring scan points
  double noise = 0;              ///< mm, standard deviation of the noise along the surface normal
  int holes = 0;                 ///< number of unscanned patches (each 0.5-2 mm across)
  double density_min = 1;        ///< lowest local density relative to the nominal (e.g. 0.25)
  double misregistration = 0;    ///< mm, offset of the second view (half the surface) from the truth
  double outlier_fraction = 0;   ///< fraction of points replaced by outliers (e.g. 0.0002)
  double z_min = 0, z_max = -1;  ///< scanned height range; z_max < z_min = the whole span
  std::uint64_t seed = 1;        ///< random seed
};

/// A synthetic scan with per-point ground truth flags.
struct Scan {
  Cloud cloud;                        ///< the points
  std::vector<std::uint8_t> outlier;  ///< 1 where the point is an outlier
  std::vector<std::uint8_t> view;     ///< 0 or 1: which scanner view produced the point
};

/// The scan's points apart by view (index 0 and 1), as a scanner delivers them.
std::vector<Cloud> views_of(const Scan& scan);

/// Samples the blade's side surface as a scanner would (no end caps): rows of jittered
/// points `spacing` apart, each clean point exactly on the section at its height; noise
/// along the 3D normal, a smooth density field, holes, outliers, and two views that
/// overlap around LE and TE, view 1 (the pressure side) shifted by `misregistration`.
/// Deterministic for a seed, whatever the thread count. Throws section::Error on bad
/// options or a design invalid in the scanned range. Details: docs/GENERATOR.md.
Scan generate_scan(const BladeDesign& blade, const ScanOptions& options = {});

/// The scan of the accuracy evaluations: realistic and hostile (0.08 mm spacing, 5 um
/// noise, 5 holes, density 25-100 %, 0.02 % outliers, no misregistration, whole span).
ScanOptions inspection_scan();

/// Scans only the bands z +- `half_band` around `heights` (what the slabs of a full scan
/// there would hold, for a fraction of the points): band at z uses seed
/// `options.seed * 100 + floor(z)`, the other options as given, z_min/z_max ignored.
Cloud scan_bands(const BladeDesign& blade, const std::vector<double>& heights, const ScanOptions& options,
                 double half_band = 0.5);

/// A CFD-like structured surface grid: the surface at `heights` heights (hub to tip of the
/// range, ends included) times `around` places around the profile, each point exactly on
/// the section at its height; per side (LE point to TE point and back) the places are
/// denser at the edges, as CFD grids are. The points are written line by line.
struct GridOptions {
  enum class Lines {
    chordwise,  ///< each line at one height, around the profile from the LE point
    spanwise    ///< each line at one place on the profile, from hub to tip
  };
  Lines lines = Lines::chordwise;  ///< how the points are ordered into lines
  int heights = 200;               ///< heights of the grid (>= 2), evenly spaced
  int around = 200;                ///< places around the profile (>= 8): half per side
  /// Edge clustering in [0, 1]: each side's place t in [0, 1) goes to the fraction
  /// (1 - c) t + c (1 - cos(pi t)) / 2 of the side's length: 0 = even, 1 = cosine (the
  /// spacing at the edges ~ (pi / n)^2 / 4 of the side, mid-side pi / 2 times the mean).
  double clustering = 0.8;
  bool repeat_seam = false;      ///< each chordwise line ends with its first point again (an O-grid's seam)
  double noise = 0;              ///< mm, standard deviation along the section's in-plane normal
  double z_min = 0, z_max = -1;  ///< height range; z_max < z_min = the whole span
  std::uint64_t seed = 1;        ///< random seed (the noise)
};

/// The grid's points, line after line (GridOptions). Throws section::Error on bad options
/// or a design invalid in the range.
Cloud generate_grid(const BladeDesign& blade, const GridOptions& options = {});

/// Sparse rows of points, as a CMM or a layered scanner gives them: a few rows, each one
/// section's worth of points about `spacing` apart along the profile, at constant height
/// or (a rotor, hub_radius > 0) at constant radius about the machine axis.
struct RowsOptions {
  int rows = 5;          ///< number of rows (>= 1)
  double pitch = 12;     ///< mm between neighbouring rows (in height, or in radius)
  double first = -1;     ///< mm, height of the first row; < 0 = the rows centred on the span
  double spacing = 1.0;  ///< mm between neighbouring points along a row (arc length, even, random phase)
  double noise = 0;      ///< mm, standard deviation along the section's in-plane normal
  /// mm: > 0 puts each row on the cylinder of radius hub_radius + z_row about the machine
  /// axis, the line parallel to x through (0, 0, -hub_radius) (the designs' u axis is the
  /// axial direction): the row then leaves its plane z = z_row by up to y^2 / (2 R) where it
  /// lies off the axis plane y = 0. 0 = each row at constant height z_row.
  double hub_radius = 0;
  std::uint64_t seed = 1;  ///< random seed (each row's phase and the noise)
};

/// The rows' heights z_row (for a rotor, where each row crosses the plane y = 0); throws
/// section::Error when a row falls outside the span.
std::vector<double> row_heights(const BladeDesign& blade, const RowsOptions& options = {});

/// The rows' points, row after row from the lowest, each point exactly on the blade.
/// Throws section::Error on bad options, a row outside the span, or a rotor row whose
/// cylinder misses the section (|y| above its radius) or leaves the span.
Cloud generate_rows(const BladeDesign& blade, const RowsOptions& options = {});

/// Closed triangle mesh of the blade (side surface plus end caps): `layers` rings along the
/// span of `profile_points` exact profile points each, vertex i of every ring at the same
/// fraction of the perimeter from the LE point; counterclockwise seen from outside.
Mesh generate_mesh(const BladeDesign& blade, int profile_points = 400, int layers = 60);

}  // namespace section
