// SPDX-License-Identifier: GPL-3.0-or-later
#include "section/gap_fill.h"

#include "detail/segment.h"
#include "drift_fit.h"
#include "section/error.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <utility>

namespace section {

namespace {

using drift::Grid;
using drift::Reference;
using drift::span_beside;
using drift::trimmed_fit;
using drift::Vec;

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

// A gap of the profile: from point `from` to the next, `to`, of the reference, and the
// carried points that fill it: (angle along the gap, index into the points taken).
struct Gap {
  int from, to;
  double length;
  std::vector<std::pair<double, std::size_t>> fill;
};

// The profile's gaps only: a small extra loop is often two outliers' or a double layer's,
// and filled it would pass for a second profile (cooling channels are not filled either;
// their points stay as measured).
std::vector<Gap> find_gaps(const Reference& ref, double gap_min) {
  std::vector<Gap> gaps;
  for (std::size_t k = 0; k < ref.point.size() && ref.loop[k] == 0; ++k) {
    const int to = ref.next[k];
    const double g = (ref.point[std::size_t(to)] - ref.point[k]).norm();
    if (g > gap_min) gaps.push_back({int(k), to, g, {}});
  }
  return gaps;
}

// The gap whose chord is nearest to p (a carried point belongs to one gap only).
std::size_t nearest_gap(const std::vector<Gap>& gaps, const Reference& ref, const Vec& p) {
  std::size_t best = 0;
  double bd = INFINITY;
  for (std::size_t q = 0; q < gaps.size(); ++q) {
    const double d =
        detail::segment_foot(ref.point[std::size_t(gaps[q].from)], ref.point[std::size_t(gaps[q].to)], p).d2;
    if (d < bd) bd = d, best = q;
  }
  return best;
}

// The points beside the plane, and what the gaps have taken of them so far (carried).
struct Nearby {
  std::vector<Vec> uv;
  std::vector<double> dz;
  std::vector<Vec> taken;  // carried points, in the order taken
  std::vector<double> taken_dz;
};

// The slab's curve and the numbers every gap's fill uses.
struct Slab {
  const Reference& ref;
  const Grid& ref_grid;
  double slab, reach, gap_min;
  int min_support;
};

// The carried points (near[j] carried by `v`) that may fill gap gi, as (|height|, j),
// nearest the plane first: where the slab has no points, nearest to this gap, and with
// neighbours from other heights.
std::vector<std::pair<double, int>> candidates(const std::vector<Gap>& gaps, std::size_t gi, const Slab& s,
                                               const Nearby& nb, const std::vector<int>& near,
                                               const std::vector<Vec>& carried) {
  const Grid carried_grid(carried, s.slab);
  std::vector<std::pair<double, int>> out;
  for (std::size_t j = 0; j < near.size(); ++j) {
    if (s.ref_grid.nearest(carried[j], 0.5 * s.gap_min) >= 0) continue;  // the slab has points here
    if (nearest_gap(gaps, s.ref, carried[j]) != gi) continue;
    // Carried by the right drift, points from heights farther apart than this one's own
    // offset land beside it (a wrong drift would part them by twice the error); a stray
    // point has no neighbours at all.
    const double zj = nb.dz[std::size_t(near[j])];
    int agree = 0;
    carried_grid.for_each_within(carried[j], 1.5 * s.slab, [&](int o) {
      agree +=
          std::abs(nb.dz[std::size_t(near[std::size_t(o)])] - zj) >= std::max(0.5 * std::abs(zj), s.slab);
    });
    if (agree < 2) continue;
    out.emplace_back(std::abs(zj), int(j));
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Fills gap gi from the points near it, carried by the drift fitted there; each point goes
// where no point taken before lies within a slab width.
void fill_gap(std::vector<Gap>& gaps, std::size_t gi, const Slab& s, const Grid& near_grid, Nearby& nb,
              Grid& taken_grid, GapFillResult& result) {
  Gap& g = gaps[gi];
  // Points within the reach cannot span a much longer gap; its search would be slow.
  if (g.length > 8 * s.reach) return;
  const Vec a = s.ref.point[std::size_t(g.from)], b = s.ref.point[std::size_t(g.to)];
  const Vec mid = 0.5 * (a + b);
  // Beyond half the gap: an edge's arc can bulge out of the circle on the gap's chord.
  const double radius = 0.5 * g.length + std::max(g.length, 8 * s.slab);
  const std::vector<int> near = near_grid.within(mid, radius);
  const Drift drift =
      fit_drift(near, nb.uv, nb.dz, s.ref, s.ref_grid, s.reach, s.slab, s.gap_min, s.min_support);
  if (!drift.ok) return;
  std::vector<Vec> carried;
  carried.reserve(near.size());
  for (int i : near) carried.push_back(nb.uv[std::size_t(i)] - nb.dz[std::size_t(i)] * drift.v);
  // Order along the gap: the angle about a point half a gap behind the chord's middle,
  // from a through the outside (loops run counterclockwise: the outside is to the right
  // of a -> b) to b. Seen from behind, both a straight run along the chord and an edge's
  // arc beyond it sweep the angle one way.
  const Vec uo = Vec((b - a).y(), -(b - a).x()).normalized();
  const Vec centre = mid - 0.5 * g.length * uo;
  const Vec ua = (a - centre).normalized();
  const Vec ub = uo - uo.dot(ua) * ua;  // completes ua towards the outside
  const Vec va = ub.normalized();
  for (const auto& [z, j] : candidates(gaps, gi, s, nb, near, carried)) {
    const Vec& c = carried[std::size_t(j)];
    if (taken_grid.any_within(c, s.slab)) continue;
    nb.taken.push_back(c);
    nb.taken_dz.push_back(nb.dz[std::size_t(near[std::size_t(j)])]);
    taken_grid.add(int(nb.taken.size() - 1));
    double phi = std::atan2((c - centre).dot(va), (c - centre).dot(ua));
    if (phi < -0.5 * M_PI) phi += 2 * M_PI;
    g.fill.emplace_back(phi, nb.taken.size() - 1);
    result.max_offset = std::max(result.max_offset, z);
  }
  result.gaps_filled += !g.fill.empty();
}

// Sorts each gap's fill by angle; a run a, fill..., b that crosses itself leaves its gap
// open. Returns, per reference point, the gap that follows it (nullptr for none).
std::vector<const Gap*> order_fills(std::vector<Gap>& gaps, const Reference& ref,
                                    const std::vector<Vec>& taken, GapFillResult& result) {
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
    std::vector<Vec> run{ref.point[std::size_t(g.from)]};
    for (const auto& f : g.fill) run.push_back(taken[f.second]);
    run.push_back(ref.point[std::size_t(g.to)]);
    bool ok = true;
    for (std::size_t x = 0; ok && x + 1 < run.size(); ++x)
      for (std::size_t y = x + 2; ok && y + 1 < run.size(); ++y)
        ok = !crosses(run[x], run[x + 1], run[y], run[y + 1]);
    if (!ok) {
      result.gaps_filled -= !g.fill.empty();
      g.fill.clear();
    }
    after[std::size_t(g.from)] = &g;
  }
  return after;
}

// Inserts each gap's points after its first end, in angle order, into result.filled.
void insert_fills(const std::vector<const Gap*>& after, const Reference& ref, const std::vector<Vec>& taken,
                  std::size_t first_index, GapFillResult& result) {
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
}

}  // namespace

double gap_fill_reach(const GapFillOptions& options, double slab) {
  return options.reach > 0 ? options.reach : 12 * slab;
}

void check_gap_fill_options(const GapFillOptions& options) {
  if (!(options.reach >= 0) || !std::isfinite(options.reach))
    throw Error("gap fill: reach must be >= 0 and finite");
  if (!(options.min_gap > 0) || !std::isfinite(options.min_gap))
    throw Error("gap fill: min_gap must be positive");
  if (!(options.min_gap_fraction >= 0) || !(options.min_gap_fraction < 1))
    throw Error("gap fill: min_gap_fraction must be in [0, 1)");
}

GapFillResult fill_gaps(const MorphologyResult& ordered, const std::vector<Eigen::Vector3d>& nearby,
                        double slab, std::size_t first_index, const GapFillOptions& options) {
  if (!(slab > 0) || !std::isfinite(slab))
    throw Error("gap fill: the slab width must be positive and finite");
  check_gap_fill_options(options);
  GapFillResult result;
  result.filled = ordered;
  const double reach = gap_fill_reach(options, slab);
  // The profile's length sets a floor: on a dense scan, gaps of a few slab widths are many,
  // cost time, and change nothing a fit would see.
  const double gap_min = drift::gap_length(options, slab, drift::profile_length(ordered));
  const Reference ref = drift::reference_of(ordered);
  if (ref.point.size() < 3) return result;
  std::vector<Gap> gaps = find_gaps(ref, gap_min);
  result.gaps = int(gaps.size());
  for (const Gap& g : gaps) result.largest_gap = std::max(result.largest_gap, g.length);
  if (gaps.empty()) return result;
  Nearby nb;
  drift::near_plane(nearby, reach, nb.uv, nb.dz);
  if (nb.uv.empty()) return result;
  const Grid ref_grid(ref.point, 2 * slab);
  const Grid near_grid(nb.uv, 4 * slab);
  Grid taken_grid(nb.taken, slab);
  const Slab s{ref, ref_grid, slab, reach, gap_min, std::max(4, options.min_support)};
  for (std::size_t gi = 0; gi < gaps.size(); ++gi) fill_gap(gaps, gi, s, near_grid, nb, taken_grid, result);
  if (nb.taken.empty()) return result;
  const std::vector<const Gap*> after = order_fills(gaps, ref, nb.taken, result);
  result.offsets = nb.taken_dz;
  insert_fills(after, ref, nb.taken, first_index, result);
  result.points = nb.taken.size();
  return result;
}

}  // namespace section
