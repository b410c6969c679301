#include "section/gap_fill.h"
#include "section/drift_band.h"

#include "section/error.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace section {

namespace {

using Vec = Eigen::Vector2d;

// Uniform hash grid over 2D points.
class Grid {
public:
  Grid(const std::vector<Vec>& points, double cell) : points_(points), cell_(cell) {
    for (std::size_t i = 0; i < points.size(); ++i) bins_[key(points[i])].push_back(int(i));
  }
  void add(int i) { bins_[key(points_[std::size_t(i)])].push_back(i); }
  // Calls f(i) for every point within r of c, in no particular order.
  template <class F>
  void for_each_within(const Vec& c, double r, F&& f) const {
    const std::int64_t x0 = coord(c.x() - r), x1 = coord(c.x() + r), y0 = coord(c.y() - r), y1 = coord(c.y() + r);
    for (std::int64_t x = x0; x <= x1; ++x)
      for (std::int64_t y = y0; y <= y1; ++y) {
        const auto it = bins_.find(pack(x, y));
        if (it == bins_.end()) continue;
        for (int i : it->second)
          if ((points_[std::size_t(i)] - c).squaredNorm() <= r * r) f(i);
      }
  }
  // The points within r of c, in ascending order.
  std::vector<int> within(const Vec& c, double r) const {
    std::vector<int> out;
    for_each_within(c, r, [&](int i) { out.push_back(i); });
    std::sort(out.begin(), out.end());
    return out;
  }
  bool any_within(const Vec& c, double r) const {
    bool any = false;
    for_each_within(c, r, [&](int) { any = true; });
    return any;
  }
  // Nearest point within r (ties: the lower index), or -1.
  int nearest(const Vec& c, double r) const {
    int best = -1;
    double bd = 0;
    for_each_within(c, r, [&](int i) {
      const double d = (points_[std::size_t(i)] - c).squaredNorm();
      if (best < 0 || d < bd || (d == bd && i < best)) best = i, bd = d;
    });
    return best;
  }

private:
  // Clamped: a cell index must fit an int64 whatever the coordinates and cell.
  std::int64_t coord(double v) const { return std::int64_t(std::clamp(std::floor(v / cell_), -1e15, 1e15)); }
  static std::int64_t pack(std::int64_t x, std::int64_t y) {
    return std::int64_t((std::uint64_t(x) << 32) ^ (std::uint64_t(y) & 0xffffffffULL));
  }
  std::int64_t key(const Vec& p) const { return pack(coord(p.x()), coord(p.y())); }
  const std::vector<Vec>& points_;
  double cell_;
  std::unordered_map<std::int64_t, std::vector<int>> bins_;
};

// The slab's ordered points, all loops, with their place in their loop.
struct Reference {
  std::vector<Vec> point, normal;
  std::vector<int> loop, next, prev;  // indices into `point` of the loop neighbours
};

Reference reference_of(const MorphologyResult& ordered) {
  Reference r;
  for (std::size_t l = 0; l < ordered.loops.size(); ++l) {
    const Loop& loop = ordered.loops[l];
    const int base = int(r.point.size()), n = int(loop.points.size());
    for (int k = 0; k < n; ++k) {
      r.point.push_back(loop.points[std::size_t(k)]);
      r.normal.push_back(std::size_t(k) < loop.normals.size() ? loop.normals[std::size_t(k)] : Vec::Zero());
      r.loop.push_back(int(l));
      r.next.push_back(base + (k + 1) % n);
      r.prev.push_back(base + (k + n - 1) % n);
    }
  }
  return r;
}

// The slab's span beside c: its nearest ordered point within 3 slab widths (k, at pk) and
// that point's neighbour on the side of c, when the span is no gap and c lies beside it
// (a line carried on past a gap's end misses a curving edge); n its unit normal, turned
// like the point's outward normal. False when there is none.
bool span_beside(const Reference& ref, const Grid& ref_grid, const Vec& c, double slab, double gap_min, int& k,
                 Vec& pk, Vec& n) {
  k = ref_grid.nearest(c, 3 * slab);
  if (k < 0) return false;
  pk = ref.point[std::size_t(k)];
  const int a = ref.next[std::size_t(k)], b = ref.prev[std::size_t(k)];
  const bool forward = (c - ref.point[std::size_t(a)]).squaredNorm() <= (c - ref.point[std::size_t(b)]).squaredNorm();
  int m = forward ? a : b;
  // Points that (nearly) coincide make no span: a band carries rows scanned at the same
  // places along the profile onto one another. Step on to the first that stands apart.
  for (int step = 0; step < 8 && (ref.point[std::size_t(m)] - pk).norm() < 0.05 * slab && m != k; ++step)
    m = forward ? ref.next[std::size_t(m)] : ref.prev[std::size_t(m)];
  const Vec t = ref.point[std::size_t(m)] - pk;
  const double len = t.norm();
  if (!(len > 0) || len > gap_min) return false;
  const double along = (c - pk).dot(t) / (len * len);
  if (along < -0.25 || along > 1.25) return false;
  n = Vec(t.y() / len, -t.x() / len);
  if (n.dot(ref.normal[std::size_t(k)]) < 0) n = -n;
  return true;
}

// A step along the profile longer than this is a gap (the fill's threshold; the drift
// fits pair no point with a span that long).
double gap_length(const GapFillOptions& options, double slab, double profile_length) {
  return std::max(options.min_gap * slab, options.min_gap_fraction * profile_length);
}

// Trimmed least squares for the drift fits: three passes, each on the rows within
// 3 robust sigmas (plus 0.05 slab) of the last fit, with a ridge on the first `ridged`
// unknowns (1e-3 of the first two's weight: a direction the pairs do not see, as V . t
// along a straight side, stays near 0; one they see is shrunk by about 0.1 %), and the
// unknowns from `firm` on held firmer, by `firm_ridge` of that weight. False when the
// solve fails or fewer than `min_support` rows are kept.
template <int N>
bool trimmed_fit(const std::vector<Eigen::Matrix<double, N, 1>>& rows, const std::vector<double>& rhs, int ridged,
                 double slab, int min_support, Eigen::Matrix<double, N, 1>& sol, int firm = N, double firm_ridge = 1e-3) {
  std::vector<char> use(rows.size(), 1);
  sol.setZero();
  for (int pass = 0; pass < 3; ++pass) {
    Eigen::Matrix<double, N, N> A = Eigen::Matrix<double, N, N>::Zero();
    Eigen::Matrix<double, N, 1> b = Eigen::Matrix<double, N, 1>::Zero();
    for (std::size_t r = 0; r < rows.size(); ++r)
      if (use[r]) {
        A += rows[r] * rows[r].transpose();
        b += rows[r] * rhs[r];
      }
    const double weight = A(0, 0) + A(1, 1);
    for (int j = 0; j < ridged; ++j) A(j, j) += (j < firm ? 1e-3 : firm_ridge) * weight + 1e-12;
    sol = A.ldlt().solve(b);
    if (!sol.allFinite()) return false;
    std::vector<double> res;
    for (std::size_t r = 0; r < rows.size(); ++r) res.push_back(std::abs(rhs[r] - rows[r].dot(sol)));
    std::vector<double> sorted = res;
    std::nth_element(sorted.begin(), sorted.begin() + long(sorted.size() / 2), sorted.end());
    const double cut = 3 * 1.4826 * sorted[sorted.size() / 2] + 0.05 * slab;
    int kept = 0;
    for (std::size_t r = 0; r < rows.size(); ++r) kept += (use[r] = res[r] <= cut);
    if (kept < min_support) return false;
  }
  return true;
}

struct Drift {
  bool ok = false;
  Vec v = Vec::Zero();
};

// Fits the drift V near a gap: a point at height z beside the gap lies z (V . n) from the
// slab's own curve (the line through its nearest slab point and that point's neighbour, n
// its normal), plus a constant for the chords' sagitta. Rounds widen from the points
// nearest the plane to all, each carrying the points by the last V before it looks for
// their slab neighbours (so that a steep drift does not pair a point with the wrong side).
Drift fit_drift(const std::vector<int>& near, const std::vector<Vec>& uv, const std::vector<double>& dz,
                const Reference& ref, const Grid& ref_grid, double reach, double slab, double gap_min,
                int min_support) {
  Drift d;
  Vec v = Vec::Zero();
  std::size_t last_rows = 0;
  for (int round = 0; round < 3; ++round) {
    const double zmax = reach * (round + 1) / 3.0;
    std::vector<Eigen::Vector3d> rows;
    std::vector<double> rhs;
    for (int i : near) {
      const double z = dz[std::size_t(i)];
      if (std::abs(z) > zmax) continue;
      const Vec raw = uv[std::size_t(i)], c = raw - z * v;
      int k;
      Vec pk, n;
      if (!span_beside(ref, ref_grid, c, slab, gap_min, k, pk, n)) continue;
      rows.emplace_back(z * n.x(), z * n.y(), 1.0);
      rhs.push_back((raw - pk).dot(n));
    }
    if (int(rows.size()) < min_support) return d;
    // Each round takes points from farther off the plane, so it pairs more of them; fewer
    // means the last drift carried them off the slab's curve: a wrong fit.
    if (rows.size() < last_rows) return d;
    last_rows = rows.size();
    Eigen::Vector3d sol;
    if (!trimmed_fit<3>(rows, rhs, 2, slab, min_support, sol)) return d;
    v = sol.head<2>();
    // The constant stands for the chords' sagitta beside the gap: a few um. A large one
    // means the points were paired with the wrong lines.
    if (std::abs(sol(2)) > 0.25 * slab) return d;
  }
  d.ok = true;
  d.v = v;
  return d;
}

// The section's drift over the whole profile (drift_band.h), quadratic in the plane: a
// point p at height z lies z (V(p) . n) + c from the slab's curve, V(p) = sum_j phi_j(q) w_j
// with phi = 1, qx, qy, qx^2, qx qy, qy^2 and q = (p - centre) / scale. Fitted like
// fit_drift (pairs with the profile's spans, trimmed least squares, two rounds widening
// from the plane to `zmax`, a constant c beyond a quarter slab refused). ok is false when
// it cannot be fitted.
struct QuadraticDrift {
  static constexpr int terms = 6, affine_terms = 3;
  bool ok = false;
  Vec centre = Vec::Zero();
  double scale = 1;
  Eigen::Matrix<double, 2, terms> w = Eigen::Matrix<double, 2, terms>::Zero();
  Eigen::Matrix<double, terms, 1> basis(const Vec& p) const {
    const Vec q = (p - centre) / scale;
    Eigen::Matrix<double, terms, 1> phi;
    phi << 1, q.x(), q.y(), q.x() * q.x(), q.x() * q.y(), q.y() * q.y();
    return phi;
  }
  Vec at(const Vec& p) const { return w * basis(p); }
};

QuadraticDrift fit_profile_drift(const std::vector<Vec>& uv, const std::vector<double>& dz, const Reference& ref,
                                 const Grid& ref_grid, double zmax, double slab, double gap_min, int min_support) {
  constexpr int T = QuadraticDrift::terms;
  QuadraticDrift d;
  std::size_t n0 = 0;  // loop 0 comes first in the reference
  for (; n0 < ref.point.size() && ref.loop[n0] == 0; ++n0) d.centre += ref.point[n0];
  if (n0 < 3) return d;
  d.centre /= double(n0);
  double spread = 0;
  for (std::size_t i = 0; i < n0; ++i) spread = std::max(spread, (ref.point[i] - d.centre).norm());
  if (!(spread > 0)) return d;
  d.scale = spread;
  using Row = Eigen::Matrix<double, 2 * T + 1, 1>;
  QuadraticDrift cur = d;
  for (int round = 0; round < 2; ++round) {
    const double zr = zmax * (round + 1) / 2.0;
    std::vector<Row> rows;
    std::vector<double> rhs;
    for (std::size_t i = 0; i < uv.size(); ++i) {
      const double z = dz[i];
      if (std::abs(z) > zr) continue;
      const Vec raw = uv[i], c = raw - z * cur.at(raw);
      int k;
      Vec pk, n;
      if (!span_beside(ref, ref_grid, c, slab, gap_min, k, pk, n) || ref.loop[std::size_t(k)] != 0) continue;
      const Eigen::Matrix<double, T, 1> phi = d.basis(pk);
      Row r;
      for (int j = 0; j < T; ++j) {
        r(2 * j) = z * n.x() * phi(j);
        r(2 * j + 1) = z * n.y() * phi(j);
      }
      r(2 * T) = 1.0;
      rows.push_back(r);
      rhs.push_back((raw - pk).dot(n));
    }
    if (int(rows.size()) < min_support) return d;
    Row sol;
    // The quadratic terms are held firmer: at the tips, where only a few points see them,
    // the constant and the x^2 term look alike, and their split would follow the noise.
    if (!trimmed_fit<2 * T + 1>(rows, rhs, 2 * T, slab, min_support, sol, 2 * QuadraticDrift::affine_terms, 0.05))
      return d;
    if (std::abs(sol(2 * T)) > 0.25 * slab) return d;
    for (int j = 0; j < T; ++j) cur.w.col(j) = sol.segment<2>(2 * j);
  }
  cur.ok = true;
  return cur;
}

}  // namespace

std::vector<Eigen::Vector2d> drift_band(const MorphologyResult& ordered, const std::vector<Eigen::Vector3d>& nearby,
                                        double slab, double half_width, double spacing, double sparse_half_width) {
  const Reference ref = reference_of(ordered);
  if (ref.point.size() < 3 || !(slab > 0)) return {};
  const double profile_length = ordered.loops.empty() ? 0.0 : ordered.loops[0].length;
  const double gap_min = gap_length(GapFillOptions{}, slab, profile_length);
  const bool widen = spacing > 0 && sparse_half_width > half_width;
  const double widest = widen ? sparse_half_width : half_width;
  std::vector<Vec> uv;
  std::vector<double> dz;
  const double zfit = std::max(2 * half_width, 3 * slab);
  for (const auto& p : nearby)
    if (p.allFinite() && std::abs(p.z()) <= std::max(zfit, widest)) {
      uv.emplace_back(p.x(), p.y());
      dz.push_back(p.z());
    }
  const Grid ref_grid(ref.point, 2 * slab);
  const QuadraticDrift drift = fit_profile_drift(uv, dz, ref, ref_grid, zfit, slab, gap_min, 64);
  if (!drift.ok) return {};
  // Beside a sparse stretch of the profile (a low-density patch, a thin edge seen
  // obliquely) the band widens locally, up to sparse_half_width, for one point per
  // `spacing` there too: the half width at each slab point from the slab's points per
  // length over +-8 neighbours.
  std::vector<double> local(ref.point.size(), half_width);
  if (widen) {
    for (std::size_t k = 0; k < ref.point.size(); ++k) {
      double length = 0;
      int a = int(k), b = int(k);
      for (int step = 0; step < 8; ++step) {
        const int na = ref.prev[std::size_t(a)], nb = ref.next[std::size_t(b)];
        length += (ref.point[std::size_t(na)] - ref.point[std::size_t(a)]).norm() +
                  (ref.point[std::size_t(nb)] - ref.point[std::size_t(b)]).norm();
        a = na, b = nb;
      }
      local[k] = std::max(half_width, band_half_width(16, length, slab, spacing, sparse_half_width / slab));
    }
  }
  std::vector<Eigen::Vector2d> out;
  for (std::size_t i = 0; i < uv.size(); ++i) {
    const double z = std::abs(dz[i]);
    if (z > widest) continue;
    const Vec c = uv[i] - dz[i] * drift.at(uv[i]);
    if (z > half_width) {
      const int k = ref_grid.nearest(c, 3 * slab);
      if (k < 0 || z > local[std::size_t(k)]) continue;
    }
    out.push_back(c);
  }
  return out;
}

double band_half_width(std::size_t slab_points, double length, double slab, double spacing, double max_widths) {
  if (!(spacing > 0) || !(length > 0) || slab_points == 0) return 0.5 * slab;
  // Points per length grow with the band's width: slab_points / length in the slab.
  const double wanted = 0.5 * slab * (length / double(slab_points)) / spacing;
  return std::clamp(wanted, 0.5 * slab, std::max(0.5, max_widths) * slab);
}

double gap_fill_reach(const GapFillOptions& options, double slab) {
  return options.reach > 0 ? options.reach : 12 * slab;
}

void check_gap_fill_options(const GapFillOptions& options) {
  if (!(options.reach >= 0) || !std::isfinite(options.reach)) throw Error("gap fill: reach must be >= 0 and finite");
  if (!(options.min_gap > 0) || !std::isfinite(options.min_gap)) throw Error("gap fill: min_gap must be positive");
  if (!(options.min_gap_fraction >= 0) || !(options.min_gap_fraction < 1))
    throw Error("gap fill: min_gap_fraction must be in [0, 1)");
}

GapFillResult fill_gaps(const MorphologyResult& ordered, const std::vector<Eigen::Vector3d>& nearby, double slab,
                        std::size_t first_index, const GapFillOptions& options) {
  if (!(slab > 0) || !std::isfinite(slab)) throw Error("gap fill: the slab width must be positive and finite");
  check_gap_fill_options(options);
  GapFillResult result;
  result.filled = ordered;
  const double reach = gap_fill_reach(options, slab);
  // The profile's length sets a floor: on a dense scan, gaps of a few slab widths are many,
  // cost time, and change nothing a fit would see.
  const double profile_length = ordered.loops.empty() ? 0.0 : ordered.loops[0].length;
  const double gap_min = gap_length(options, slab, profile_length);
  const int min_support = std::max(4, options.min_support);

  const Reference ref = reference_of(ordered);
  if (ref.point.size() < 3) return result;
  struct Gap {
    int from, to;
    double length;
    std::vector<std::pair<double, std::size_t>> fill;  // (angle along the gap, carried point)
  };
  std::vector<Gap> gaps;
  // The profile's gaps only: a small extra loop is often two outliers' or a double
  // layer's, and filled it would pass for a second profile (cooling channels are not
  // filled either; their points stay as measured).
  for (std::size_t k = 0; k < ref.point.size() && ref.loop[k] == 0; ++k) {
    const int to = ref.next[k];
    const double g = (ref.point[std::size_t(to)] - ref.point[k]).norm();
    if (g > gap_min) gaps.push_back({int(k), to, g, {}});
  }
  result.gaps = int(gaps.size());
  for (const Gap& g : gaps) result.largest_gap = std::max(result.largest_gap, g.length);
  if (gaps.empty()) return result;
  // The gap whose chord is nearest to p (a carried point belongs to one gap only).
  const auto nearest_gap = [&](const Vec& p) {
    std::size_t best = 0;
    double bd = INFINITY;
    for (std::size_t q = 0; q < gaps.size(); ++q) {
      const Vec a = ref.point[std::size_t(gaps[q].from)], b = ref.point[std::size_t(gaps[q].to)];
      const Vec t = b - a;
      const double u = std::clamp((p - a).dot(t) / t.squaredNorm(), 0.0, 1.0);
      const double d = (a + u * t - p).squaredNorm();
      if (d < bd) bd = d, best = q;
    }
    return best;
  };

  std::vector<Vec> uv;
  std::vector<double> dz;
  for (const auto& p : nearby)
    if (p.allFinite() && std::abs(p.z()) <= reach) {
      uv.emplace_back(p.x(), p.y());
      dz.push_back(p.z());
    }
  if (uv.empty()) return result;
  const Grid ref_grid(ref.point, 2 * slab);
  const Grid near_grid(uv, 4 * slab);
  std::vector<Vec> taken;  // carried points, in the order taken
  std::vector<double> taken_dz;
  Grid taken_grid(taken, slab);

  for (std::size_t gi = 0; gi < gaps.size(); ++gi) {
    Gap& g = gaps[gi];
    // Points within the reach cannot span a much longer gap; its search would be slow.
    if (g.length > 8 * reach) continue;
    const Vec a = ref.point[std::size_t(g.from)], b = ref.point[std::size_t(g.to)];
    const Vec mid = 0.5 * (a + b);
    // Beyond half the gap: an edge's arc can bulge out of the circle on the gap's chord.
    const double radius = 0.5 * g.length + std::max(g.length, 8 * slab);
    const std::vector<int> near = near_grid.within(mid, radius);
    const Drift drift = fit_drift(near, uv, dz, ref, ref_grid, reach, slab, gap_min, min_support);
    if (!drift.ok) continue;
    std::vector<Vec> carried;
    carried.reserve(near.size());
    for (int i : near) carried.push_back(uv[std::size_t(i)] - dz[std::size_t(i)] * drift.v);
    const Grid carried_grid(carried, slab);
    std::vector<std::pair<double, int>> candidates;
    for (std::size_t j = 0; j < near.size(); ++j) {
      if (ref_grid.nearest(carried[j], 0.5 * gap_min) >= 0) continue;  // the slab has points here
      if (nearest_gap(carried[j]) != gi) continue;
      // Carried by the right drift, points from heights farther apart than this one's own
      // offset land beside it (a wrong drift would part them by twice the error); a stray
      // point has no neighbours at all.
      const double zj = dz[std::size_t(near[j])];
      int agree = 0;
      carried_grid.for_each_within(carried[j], 1.5 * slab, [&](int o) {
        agree += std::abs(dz[std::size_t(near[std::size_t(o)])] - zj) >= std::max(0.5 * std::abs(zj), slab);
      });
      if (agree < 2) continue;
      candidates.emplace_back(std::abs(zj), int(j));
    }
    std::sort(candidates.begin(), candidates.end());
    // Order along the gap: the angle about a point half a gap behind the chord's middle,
    // from a through the outside (loops run counterclockwise: the outside is to the right
    // of a -> b) to b. Seen from behind, both a straight run along the chord and an edge's
    // arc beyond it sweep the angle one way.
    const Vec uo = Vec((b - a).y(), -(b - a).x()).normalized();
    const Vec centre = mid - 0.5 * g.length * uo;
    const Vec ua = (a - centre).normalized();
    const Vec ub = uo - uo.dot(ua) * ua;  // completes ua towards the outside
    const Vec va = ub.normalized();
    for (const auto& [z, j] : candidates) {
      const Vec& c = carried[std::size_t(j)];
      if (taken_grid.any_within(c, slab)) continue;
      taken.push_back(c);
      taken_dz.push_back(dz[std::size_t(near[std::size_t(j)])]);
      taken_grid.add(int(taken.size() - 1));
      double phi = std::atan2((c - centre).dot(va), (c - centre).dot(ua));
      if (phi < -0.5 * M_PI) phi += 2 * M_PI;
      g.fill.emplace_back(phi, taken.size() - 1);
      result.max_offset = std::max(result.max_offset, z);
    }
    result.gaps_filled += !g.fill.empty();
  }
  if (taken.empty()) return result;

  // Insert each gap's points after its first end, in angle order.
  std::vector<const Gap*> after(ref.point.size(), nullptr);
  const auto crosses = [](const Vec& p, const Vec& q, const Vec& r, const Vec& t) {
    const auto side = [](const Vec& a, const Vec& b, const Vec& c) {
      const double x = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
      return (x > 0) - (x < 0);
    };
    return side(p, q, r) * side(p, q, t) < 0 && side(r, t, p) * side(r, t, q) < 0;
  };
  for (Gap& g : gaps) {
    std::sort(g.fill.begin(), g.fill.end());
    // The run a, fill..., b must not cross itself; if it does, the gap stays open.
    std::vector<Vec> run{ref.point[std::size_t(g.from)]};
    for (const auto& f : g.fill) run.push_back(taken[f.second]);
    run.push_back(ref.point[std::size_t(g.to)]);
    bool ok = true;
    for (std::size_t x = 0; ok && x + 1 < run.size(); ++x)
      for (std::size_t y = x + 2; ok && y + 1 < run.size(); ++y) ok = !crosses(run[x], run[x + 1], run[y], run[y + 1]);
    if (!ok) {
      result.gaps_filled -= !g.fill.empty();
      g.fill.clear();
    }
    after[std::size_t(g.from)] = &g;
  }
  result.offsets = taken_dz;
  std::size_t r = 0;
  for (Loop& loop : result.filled.loops) {
    Loop grown = loop;
    grown.points.clear();
    grown.normals.clear();
    grown.index.clear();
    for (std::size_t k = 0; k < loop.points.size(); ++k, ++r) {
      grown.points.push_back(loop.points[k]);
      grown.normals.push_back(k < loop.normals.size() ? loop.normals[k] : Vec::Zero());
      grown.index.push_back(k < loop.index.size() ? loop.index[k] : 0);
      if (!after[r]) continue;
      const Vec mid = 0.5 * (ref.point[std::size_t(after[r]->from)] + ref.point[std::size_t(after[r]->to)]);
      for (const auto& [phi, t] : after[r]->fill) {
        grown.points.push_back(taken[t]);
        const Vec n = taken[t] - mid;  // rough: the slab's normals are not used downstream
        grown.normals.push_back(n.norm() > 0 ? Vec(n.normalized()) : Vec::Zero());
        grown.index.push_back(first_index + t);
      }
    }
    loop = std::move(grown);
  }
  result.points = taken.size();
  return result;
}

}  // namespace section
