// SPDX-License-Identifier: GPL-3.0-or-later
// Synthetic scans of a generated blade (generate.h): rows of candidate points on the exact
// surface, thinned by a density field and holes, some replaced by outliers, in two views.
#include "detail/parallel.h"
#include "generate_index.h"
#include "generate_sample.h"
#include "generate_section.h"
#include "section/error.h"

#include <atomic>
#include <cstdint>
#include <limits>
#include <string>
#include <thread>
#include <tuple>
#include <utility>

namespace section {

using namespace detail::gen;
using Eigen::Vector3d;

std::pair<double, double> detail::gen::checked_span_range(const BladeDesign& blade, double z_min,
                                                          double z_max, const std::string& who) {
  if (!(blade.span > 0)) throw Error(who + ": the blade span must be positive");
  double z_lo = 0, z_hi = blade.span;
  if (z_max >= z_min) {
    z_lo = z_min;
    z_hi = z_max;
  }
  if (z_lo < 0 || z_hi > blade.span + 1e-12 || z_hi <= z_lo)
    throw Error(who + ": z range [" + num(z_lo) + ", " + num(z_hi) +
                "] must be a non-empty part of the span [0, " + num(blade.span) + "]");
  for (int i = 0; i <= 8; ++i) check_design(blade.at(z_lo + (z_hi - z_lo) * i / 8), who);
  return {z_lo, z_hi};
}

namespace {

/// For each node of `table`, the z component of the unnormalised surface normal
/// (u, -u . dp/dz), from the sections of the same table layout at zl and zh.
std::vector<double> normal_z(const ArcTable& table, const Section& lo, const Section& hi, double dz) {
  std::vector<double> gz(table.cum.size());
  for (std::size_t k = 0; k < gz.size(); ++k) {
    const std::size_t piece = std::min<std::size_t>(6, k / ArcTable::per_piece);
    const double lam = double(k - piece * ArcTable::per_piece) / ArcTable::per_piece;
    const PieceEval e = piece_eval(table.sec, table.sec.pieces[piece], lam);
    const Vector2d dpdz =
        (piece_eval(hi, hi.pieces[piece], lam).p - piece_eval(lo, lo.pieces[piece], lam).p) / dz;
    gz[k] = -e.normal.dot(dpdz);
  }
  return gz;
}

/// Coarse but accurate (< 2 um) distance from p to the profile of a section.
double coarse_distance(const Section& sec, const Vector2d& p) {
  constexpr int m = 128;
  double best = std::numeric_limits<double>::infinity();
  Vector2d prev = piece_eval(sec, sec.pieces[0], 0).p;
  for (const Piece& pc : sec.pieces)
    for (int k = 1; k <= m; ++k) {
      const Vector2d q = piece_eval(sec, pc, double(k) / m).p;
      best = std::min(best, segment_foot(prev, q, p).d2);
      prev = q;
    }
  return std::sqrt(best);
}

struct Hole {
  double sigma, z, radius;  // position as a fraction of the perimeter, height, radius (mm)
};

struct Field {  // smooth keep-probability in [density_min, 1]
  double dmin = 1;
  int m1 = 1, m2 = 2;
  double k1 = 0, k2 = 0, f1 = 0, f2 = 0;
  double operator()(double sigma, double z) const {
    const double f = 0.5 + 0.25 * (std::cos(2 * pi * m1 * sigma + k1 * z + f1) +
                                   std::cos(2 * pi * m2 * sigma + k2 * z + f2));
    return dmin + (1 - dmin) * f;
  }
};

constexpr double overlap = 1.5;  // mm each side of the view boundaries at LE and TE
constexpr int levels = 64;       // point heights per row

// What every row of a scan shares: the range, the random features drawn once per scan
// (density field, holes, outlier box), the shift of view 1.
struct ScanPlan {
  const BladeDesign& blade;
  const ScanOptions& o;
  ScanPlan(const BladeDesign& b, const ScanOptions& options) : blade(b), o(options) {}
  double z_lo = 0, z_hi = 0, dz = 0;
  int rows = 0;
  Field field;
  std::vector<Hole> holes;
  Vector3d box_lo, box_hi;
  Vector2d shift{0, 0};
};

// The scanned range [z_lo, z_hi], after checking the options and the designs in it.
std::pair<double, double> checked_range(const BladeDesign& blade, const ScanOptions& o,
                                        const std::string& who) {
  if (!(o.spacing > 0) || !std::isfinite(o.spacing)) throw Error(who + ": spacing must be positive");
  if (!(o.noise >= 0) || !std::isfinite(o.noise)) throw Error(who + ": noise must be zero or positive");
  if (o.holes < 0) throw Error(who + ": holes must be zero or positive");
  if (!(o.density_min > 0 && o.density_min <= 1)) throw Error(who + ": density_min must be in (0, 1]");
  if (!(o.misregistration >= 0) || !std::isfinite(o.misregistration))
    throw Error(who + ": misregistration must be zero or positive");
  if (!(o.outlier_fraction >= 0 && o.outlier_fraction < 1))
    throw Error(who + ": outlier_fraction must be in [0, 1)");
  return checked_span_range(blade, o.z_min, o.z_max, who);
}

// The density field and the holes, from the scan's own random sequence.
void draw_features(ScanPlan& plan) {
  Rng rng(plan.o.seed ^ 0x5eed0001ULL);
  Field& field = plan.field;
  field.dmin = plan.o.density_min;
  field.m1 = 1 + int(rng.uniform() * 2);
  field.m2 = 2 + int(rng.uniform() * 2);
  field.k1 = 2 * pi / rng.uniform(15, 40);
  field.k2 = -2 * pi / rng.uniform(15, 40);
  field.f1 = rng.uniform(0, 2 * pi);
  field.f2 = rng.uniform(0, 2 * pi);
  plan.holes.resize(std::size_t(plan.o.holes));
  for (Hole& h : plan.holes) h = {rng.uniform(), rng.uniform(plan.z_lo, plan.z_hi), rng.uniform(0.25, 1.0)};
}

// The outliers' box: the sections' bounding box over the range, grown by 2 mm.
void outlier_box(ScanPlan& plan) {
  Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (int i = 0; i <= 8; ++i) {
    const ArcTable t(plan.blade.at(plan.z_lo + (plan.z_hi - plan.z_lo) * i / 8));
    for (const Piece& pc : t.sec.pieces)
      for (int k = 0; k <= 64; ++k) {
        const Vector2d p = piece_eval(t.sec, pc, k / 64.0).p;
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
  }
  plan.box_lo = Vector3d(lo.x() - 2, lo.y() - 2, plan.z_lo - 2);
  plan.box_hi = Vector3d(hi.x() + 2, hi.y() + 2, plan.z_hi + 2);
}

ScanPlan plan_scan(const BladeDesign& blade, const ScanOptions& o) {
  const std::string who = "generate_scan";
  ScanPlan plan(blade, o);
  std::tie(plan.z_lo, plan.z_hi) = checked_range(blade, o, who);
  plan.rows = std::max(1, int(std::lround((plan.z_hi - plan.z_lo) / o.spacing)));
  plan.dz = (plan.z_hi - plan.z_lo) / plan.rows;
  const double mid_perimeter = ArcTable(blade.at(0.5 * (plan.z_lo + plan.z_hi))).perimeter;
  const double estimate = 1.2 * plan.rows * mid_perimeter / o.spacing;
  if (estimate > 4e8)
    throw Error(who + ": about " + num(estimate) +
                " points requested; increase the spacing or reduce the z range");
  draw_features(plan);
  outlier_box(plan);
  // View 1 moves towards the pressure (right, -N) side of the mid camber.
  const Geometry g = make_geometry(blade.at(0.5 * (plan.z_lo + plan.z_hi)));
  Vector2d c, d1, d2;
  camber_eval(g, 0.5, c, d1, d2);
  plan.shift = -o.misregistration * rot90(d1.normalized());
  return plan;
}

// One row of one view at height z0: the section tables there, the sections at each point
// height and the holes that may reach the row.
struct Row {
  int view = 0;
  double z0 = 0;
  ArcTable table;  // arc length -> (piece, lambda) at z0
  std::vector<double> gz;
  std::vector<Section> level_sec;
  std::vector<const Hole*> near_holes;

  Row(const ScanPlan& plan, int task)
      : view(task / plan.rows), z0(plan.z_lo + (task % plan.rows + 0.5) * plan.dz), table(plan.blade.at(z0)) {
    const BladeDesign& blade = plan.blade;
    const double h = std::min(0.5, 0.25 * blade.span);
    const double zl = std::max(0.0, z0 - h), zh = std::min(blade.span, z0 + h);
    gz = normal_z(table, make_section(blade.at(zl)), make_section(blade.at(zh)), std::max(zh - zl, 1e-12));
    // Point heights take one of `levels` values per row, each with its exact section, so
    // every point lies exactly on the blade at its height without rebuilding a section
    // per point (steps of dz/levels, far below the scanner's resolution).
    level_sec.reserve(levels);
    for (int l = 0; l < levels; ++l)
      level_sec.push_back(make_section(blade.at(z0 + ((l + 0.5) / levels - 0.5) * plan.dz)));
    for (const Hole& hl : plan.holes)
      if (std::abs(hl.z - z0) < hl.radius + plan.dz) near_holes.push_back(&hl);
  }

  bool in_hole(double sigma, double z) const {
    bool in = false;
    for (const Hole* hl : near_holes) {
      double ds = sigma - hl->sigma;
      ds -= std::round(ds);
      const double du = ds * table.perimeter, dzh = z - hl->z;
      if (du * du + dzh * dzh < hl->radius * hl->radius) in = true;
    }
    return in;
  }
};

// An outlier: uniform in the box, at least 0.2 mm (in-plane) from the section at its height.
Vector3d outlier(const ScanPlan& plan, Rng& rout) {
  for (;;) {
    const Vector3d q(rout.uniform(plan.box_lo.x(), plan.box_hi.x()),
                     rout.uniform(plan.box_lo.y(), plan.box_hi.y()),
                     rout.uniform(plan.box_lo.z(), plan.box_hi.z()));
    const Section sq = make_section(plan.blade.at(std::clamp(q.z(), 0.0, plan.blade.span)));
    // 0.21: the in-plane distance bounds the 3D one from below up to the surface slope.
    if (coarse_distance(sq, q.head<2>()) >= 0.21) return q;
  }
}

// The surface point at arc length a of the row's level `level` (height z), moved by the
// noise (Box-Muller of u1, u2) along the 3D normal, and by the view's shift.
Vector3d surface_point(const ScanPlan& plan, const Row& row, double a, int level, double z, double u1,
                       double u2) {
  const ArcTable::Where w = row.table.at(a);
  const Section& sec = row.level_sec[std::size_t(level)];
  const PieceEval e = piece_eval(sec, sec.pieces[std::size_t(w.piece)], w.lambda);
  const std::vector<double>& gz = row.gz;
  const double nz = gz[w.node] + w.f * (gz[std::min(w.node + 1, gz.size() - 1)] - gz[w.node]);
  const Vector3d n3 = Vector3d(e.normal.x(), e.normal.y(), nz).normalized();
  Vector3d p(e.p.x(), e.p.y(), z);
  if (plan.o.noise > 0) p += (plan.o.noise * Rng::normal(u1, u2)) * n3;
  if (row.view == 1) p.head<2>() += plan.shift;
  return p;
}

struct RowOutput {
  std::vector<Vector3d> points;
  std::vector<std::uint8_t> outlier;
};

RowOutput scan_row(const ScanPlan& plan, int task) {
  const ScanOptions& o = plan.o;
  const Row row(plan, task);
  const double P = row.table.perimeter;
  // view 1: right (pressure) side with half of each edge; view 0: the rest; overlap bands.
  const double a0 = row.view == 1 ? -overlap : row.table.te_s - overlap;
  const double a1 = row.view == 1 ? row.table.te_s + overlap : P + overlap;
  const int m = std::max(1, int(std::lround((a1 - a0) / o.spacing)));
  const double da = (a1 - a0) / m;
  Rng r(o.seed * 0x100000001b3ULL + std::uint64_t(task) * 0x9e3779b97f4a7c15ULL + 17);
  Rng rout(o.seed * 0x2545f4914f6cdd1dULL + std::uint64_t(task) * 0x9e3779b97f4a7c15ULL + 91);
  RowOutput res;
  res.points.reserve(std::size_t(m));
  for (int j = 0; j < m; ++j) {
    // Draw the same numbers for every candidate, so options change points, not the sequence.
    const double ja = r.uniform(-0.3, 0.3), jz = r.uniform();
    const double keep = r.uniform(), outl = r.uniform(), u1 = r.uniform(), u2 = r.uniform();
    double a = a0 + (j + 0.5 + ja) * da;
    a -= P * std::floor(a / P);
    const int level = std::min(levels - 1, int(jz * levels));
    const double z = row.z0 + ((level + 0.5) / levels - 0.5) * plan.dz;
    const double sigma = a / P;
    if (keep >= plan.field(sigma, z) || row.in_hole(sigma, z)) continue;
    const bool is_outlier = outl < o.outlier_fraction;
    res.points.push_back(is_outlier ? outlier(plan, rout) : surface_point(plan, row, a, level, z, u1, u2));
    res.outlier.push_back(is_outlier ? 1 : 0);
  }
  return res;
}

// Runs task(0 .. tasks-1) on up to 8 threads.
template <class F>
void run_tasks(int tasks, const F& task) {
  const unsigned hw = std::max(1u, std::min(8u, std::thread::hardware_concurrency()));
  std::atomic<int> next{0};
  auto worker = [&] {
    for (int t; (t = next.fetch_add(1)) < tasks;) task(t);
  };
  std::vector<std::thread> threads = detail::start_threads(hw - 1, worker);  // (fewer when refused)
  worker();
  for (auto& th : threads) th.join();
}

}  // namespace

ScanOptions inspection_scan() {
  ScanOptions o;  // its spacing: the default 0.08 mm
  o.noise = 0.005;
  o.holes = 5;
  o.density_min = 0.25;
  o.outlier_fraction = 0.0002;
  return o;
}

Cloud scan_bands(const BladeDesign& blade, const std::vector<double>& heights, const ScanOptions& options,
                 double half_band) {
  Cloud cloud;
  for (double z : heights) {
    ScanOptions o = options;
    o.z_min = z - half_band;
    o.z_max = z + half_band;
    o.seed = options.seed * 100 + static_cast<std::uint64_t>(std::floor(z));
    const Scan s = generate_scan(blade, o);
    cloud.points.insert(cloud.points.end(), s.cloud.points.begin(), s.cloud.points.end());
  }
  return cloud;
}

std::vector<Cloud> views_of(const Scan& scan) {
  std::vector<Cloud> views(2);
  for (std::size_t i = 0; i < scan.cloud.points.size(); ++i)
    views[i < scan.view.size() && scan.view[i] ? 1 : 0].points.push_back(scan.cloud.points[i]);
  return views;
}

Scan generate_scan(const BladeDesign& blade, const ScanOptions& o) {
  const ScanPlan plan = plan_scan(blade, o);
  const int tasks = 2 * plan.rows;  // each row once per view
  std::vector<RowOutput> out(static_cast<std::size_t>(tasks));
  run_tasks(tasks, [&](int task) { out[std::size_t(task)] = scan_row(plan, task); });
  Scan scan;
  std::size_t total = 0;
  for (const RowOutput& r : out) total += r.points.size();
  scan.cloud.points.reserve(total);
  scan.outlier.reserve(total);
  scan.view.reserve(total);
  for (int task = 0; task < tasks; ++task) {
    RowOutput& r = out[std::size_t(task)];
    scan.cloud.points.insert(scan.cloud.points.end(), r.points.begin(), r.points.end());
    scan.outlier.insert(scan.outlier.end(), r.outlier.begin(), r.outlier.end());
    scan.view.insert(scan.view.end(), r.points.size(), std::uint8_t(task / plan.rows));
    r = RowOutput{};
  }
  return scan;
}

}  // namespace section
