// SPDX-License-Identifier: GPL-3.0-or-later
#include "section/smooth.h"

#include "section/error.h"
#include "detail/cholmod_solver.h"
#include "detail/local_origin.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <utility>

namespace section {

namespace {

using Points = std::vector<Eigen::Vector2d>;
constexpr double two_pi = 6.283185307179586;

/// Index arithmetic of a closed or open polyline. Segment k joins point k-1 to point k
/// (segment 0 exists only when closed); curvature term i sits at point i and uses
/// segments i and i+1 (interior points only when open).
struct Topology {
  int n = 0;
  bool closed = true;
  int prev(int i) const { return i == 0 ? n - 1 : i - 1; }
  int next(int i) const { return i + 1 == n ? 0 : i + 1; }
  int first_segment() const { return closed ? 0 : 1; }
  int first_term() const { return closed ? 0 : 1; }
  int end_term() const { return closed ? n : n - 1; }
};

/// Segment lengths `l`, floored so that a collapsed segment cannot divide by zero, and unit
/// tangents `u` (each used by two curvature terms); the storage is reused across iterations.
struct Segments {
  std::vector<double> l;
  Points u;
};

void segments_of(const Points& q, const Topology& t, double floor, Segments& s) {
  s.l.assign(t.n, 0.0);
  s.u.resize(t.n);
  for (int k = t.first_segment(); k < t.n; ++k) {
    const Eigen::Vector2d e = q[k] - q[t.prev(k)];
    s.l[k] = std::max(e.norm(), floor);
    s.u[k] = e / s.l[k];
  }
}

/// E of q; `s` is scratch, left with q's segments.
double energy_of(const Points& q, const Points& q0, double a, double b, const Topology& t, double floor,
                 Segments& s) {
  segments_of(q, t, floor, s);
  const std::vector<double>& l = s.l;
  double curvature = 0;
  for (int i = t.first_term(); i < t.end_term(); ++i) {
    const int j = t.next(i);
    // kappa_i^2 (l_i + l_j) / 4 with kappa_i = 2 |d_i| / (l_i + l_j).
    const Eigen::Vector2d d = s.u[j] - s.u[i];
    curvature += d.squaredNorm() / (l[i] + l[j]);
  }
  double closeness = 0;
  for (int i = 0; i < t.n; ++i) closeness += (q[i] - q0[i]).squaredNorm();
  return a * curvature + b * closeness;
}

/// The frozen-length system matrix as a band: band[i][2 + o] = A(i, i + o), o in -2..2
/// (indices wrap when closed). A = a * sum_i w_i r_i r_i^T + b I, r_i the second-difference
/// row of term i, w_i = 1 / (l_i + l_{i+1}); A q = b q0 is grad E = 0 at frozen lengths.
using Band = std::vector<std::array<double, 5>>;

/// `inv` is scratch for the inverse lengths (each is needed by two terms).
void assemble_band(const std::vector<double>& l, double a, double b, const Topology& t, Band& band,
                   std::vector<double>& inv) {
  band.assign(t.n, {0, 0, b, 0, 0});
  inv.resize(t.n);
  for (int k = t.first_segment(); k < t.n; ++k) inv[k] = 1 / l[k];
  for (int i = t.first_term(); i < t.end_term(); ++i) {
    const int j = t.next(i);
    const double w = a / (l[i] + l[j]);
    const std::array<int, 3> id{t.prev(i), i, j};
    const std::array<double, 3> r{inv[i], -inv[i] - inv[j], inv[j]};
    for (int x = 0; x < 3; ++x)
      for (int y = 0; y < 3; ++y) band[id[x]][2 + y - x] += w * r[x] * r[y];
  }
}

/// Column index of band entry (i, o), or -1 outside an open curve.
int band_column(int i, int o, const Topology& t) {
  const int c = i + o;
  if (c >= 0 && c < t.n) return c;
  if (!t.closed) return -1;
  return c < 0 ? c + t.n : c - t.n;
}

/// An elimination order that turns the band into a plain band of half-width 4, whose
/// factor has no fill outside it: open curves in their own order, closed ones from both
/// ends inwards (0, n-1, 1, n-2, ...), which puts the wrap-around neighbours side by side.
/// Known in advance, it spares the search for a fill-reducing order (AMD) on every curve.
std::vector<int> band_order(const Topology& t) {
  std::vector<int> order(t.n);
  for (int k = 0; k < t.n; ++k) order[k] = !t.closed ? k : (k % 2 == 0 ? k / 2 : t.n - 1 - k / 2);
  return order;
}

/// The global solver (CHOLMOD) for the band's pattern, given to it in the band order: P A P'
/// in upper form, each entry read from the band row of the larger of its two points (the
/// lower triangle of A, as a factorisation of A itself would read it). Its columns are
/// filled row by row, so each column's rows come out in order.
std::unique_ptr<detail::CholmodSolver> band_solver(const Topology& t) {
  const int n = t.n;
  std::vector<int> order = band_order(t), at(n);
  for (int k = 0; k < n; ++k) at[order[k]] = k;
  // Entry (at[j], at[i]) for each band neighbour i of point j eliminated no earlier than j
  // (j itself included); j = band_column(i, -o) when i = band_column(j, o).
  auto each_entry = [&](auto&& add) {
    for (int row = 0; row < n; ++row) {
      const int j = order[row];
      for (int o = -2; o <= 2; ++o) {
        const int i = band_column(j, o, t);  // A(i, j) = band[i][2 - o] = band[j][2 + o]
        if (i >= 0 && at[i] >= row) add(row, at[i], j < i ? 5 * i + 2 - o : 5 * j + 2 + o);
      }
    }
  };
  std::vector<int> ap(n + 1, 0);
  each_entry([&](int, int col, int) { ++ap[col + 1]; });
  for (int col = 0; col < n; ++col) ap[col + 1] += ap[col];
  std::vector<int> ai(ap[n]), source(ap[n]), fill(ap.begin(), ap.end() - 1);
  each_entry([&](int row, int col, int from) {
    const int k = fill[col]++;
    ai[k] = row;
    source[k] = from;
  });
  return std::make_unique<detail::CholmodSolver>(n, ap, ai, std::move(source), "smooth", std::move(order));
}

/// The paper's point-by-point iteration on the same frozen-length system, warm-started
/// from x; sweeps until the largest update is below `tol`. Returns the sweeps done.
int gauss_seidel(const Band& band, const Eigen::MatrixX2d& rhs, const Topology& t, double tol, int max_sweeps,
                 Eigen::MatrixX2d& x) {
  std::vector<std::array<int, 5>> cols(t.n);
  for (int i = 0; i < t.n; ++i)
    for (int o = -2; o <= 2; ++o) cols[i][2 + o] = band_column(i, o, t);
  for (int sweep = 1; sweep <= max_sweeps; ++sweep) {
    double largest = 0;
    for (int i = 0; i < t.n; ++i) {
      double su = rhs(i, 0), sv = rhs(i, 1);
      for (int k = 0; k < 5; ++k) {
        const int c = cols[i][k];
        if (k == 2 || c < 0) continue;
        su -= band[i][k] * x(c, 0);
        sv -= band[i][k] * x(c, 1);
      }
      const double nu = su / band[i][2], nv = sv / band[i][2];
      largest = std::max(largest, std::max(std::abs(nu - x(i, 0)), std::abs(nv - x(i, 1))));
      x(i, 0) = nu;
      x(i, 1) = nv;
    }
    if (largest <= tol) return sweep;
  }
  return max_sweeps;
}

/// Largest displacement across the curve (along the local normal of the new points).
double normal_move(const Points& before, const Points& after, const Topology& t) {
  double largest = 0;
  for (int i = 0; i < t.n; ++i) {
    const int h = (t.closed || i > 0) ? t.prev(i) : i;
    const int j = (t.closed || i + 1 < t.n) ? t.next(i) : i;
    Eigen::Vector2d tangent = after[j] - after[h];
    const double norm = tangent.norm();
    const Eigen::Vector2d d = after[i] - before[i];
    if (norm == 0) {
      largest = std::max(largest, d.norm());
      continue;
    }
    tangent /= norm;
    largest = std::max(largest, std::abs(d.x() * tangent.y() - d.y() * tangent.x()));
  }
  return largest;
}

double mean_spacing(const Points& p, bool closed) {
  double total = 0;
  const std::size_t n = p.size();
  for (std::size_t k = 1; k < n; ++k) total += (p[k] - p[k - 1]).norm();
  std::size_t segments = n - 1;
  if (closed) {
    total += (p[0] - p[n - 1]).norm();
    ++segments;
  }
  return segments ? total / static_cast<double>(segments) : 0.0;
}

/// Drops each point that stands alone far off a profile whose points on either side of it
/// lie close together: over 50 median spacings from both neighbours, which are nearer each
/// other than a twentieth of that (a spike under 3 degrees wide). A stray point of a
/// hand-edited loop was kept as a 60 mm spike (fitspline: "the loop crosses itself"); one
/// 1e8 away made the merge distance, from the mean spacing, swallow the whole loop. A
/// sharp edge has its neighbours both near it or wide apart. Returns how many were dropped.
int drop_strays(Points& p, bool closed) {
  const std::size_t n = p.size();
  if (n < 5) return 0;
  std::vector<double> gaps;
  gaps.reserve(n);
  for (std::size_t k = 1; k < n; ++k) gaps.push_back((p[k] - p[k - 1]).norm());
  if (closed) gaps.push_back((p[0] - p[n - 1]).norm());
  std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
  const double far = 50 * gaps[gaps.size() / 2];
  if (!(far > 0)) return 0;
  std::vector<char> stray(n, 0);
  int count = 0;
  for (std::size_t k = closed ? 0 : 1; k < (closed ? n : n - 1); ++k) {
    const Eigen::Vector2d& before = p[(k + n - 1) % n];
    const Eigen::Vector2d& after = p[(k + 1) % n];
    const double a = (p[k] - before).norm(), b = (p[k] - after).norm();
    if (a > far && b > far && (after - before).norm() < std::min(a, b) / 20) stray[k] = 1, ++count;
  }
  if (count == 0) return 0;
  Points kept;
  kept.reserve(n - count);
  for (std::size_t k = 0; k < n; ++k)
    if (!stray[k]) kept.push_back(p[k]);
  p.swap(kept);
  return count;
}

/// Merges runs of consecutive points closer than `threshold` into their mean (the closing
/// pair too when closed); returns how many points were removed.
int merge_duplicates(Points& p, bool closed, double threshold) {
  const std::size_t n_in = p.size();
  Points out;
  std::vector<int> weight;
  for (const auto& x : p) {
    if (!out.empty() && (x - out.back()).norm() <= threshold) {
      const int w = weight.back();
      out.back() = (out.back() * w + x) / (w + 1);
      ++weight.back();
    } else {
      out.push_back(x);
      weight.push_back(1);
    }
  }
  while (closed && out.size() > 1 && (out.back() - out.front()).norm() <= threshold) {
    const int wf = weight.front(), wb = weight.back();
    out.front() = (out.front() * wf + out.back() * wb) / (wf + wb);
    weight.front() += wb;
    out.pop_back();
    weight.pop_back();
  }
  p = std::move(out);
  return static_cast<int>(n_in - p.size());
}

void check_options(const SmoothOptions& o) {
  auto bad = [](const std::string& what) { throw Error("smooth: " + what); };
  if (!(std::isfinite(o.a) && o.a >= 0)) bad("a must be a finite number >= 0");
  if (!(std::isfinite(o.b) && o.b > 0)) bad("b must be a finite number > 0");
  if (!(std::isfinite(o.smoothing_length) && o.smoothing_length >= 0))
    bad("smoothing_length must be a finite number >= 0");
  if (!(std::isfinite(o.relative_length) && o.relative_length >= 0))
    bad("relative_length must be a finite number >= 0");
  if (o.max_iterations < 1) bad("max_iterations must be at least 1");
  if (!(o.tolerance >= 0) || !(o.move_tolerance >= 0) || !(o.sweep_tolerance >= 0))
    bad("tolerances must be >= 0");
  if (!(o.merge_distance >= 0 && o.merge_distance < 1)) bad("merge_distance must be in [0, 1)");
  if (o.max_sweeps < 1) bad("max_sweeps must be at least 1");
}

}  // namespace

SmoothSolver parse_smooth_solver(const std::string& name) {
  if (name == "cholmod") return SmoothSolver::cholmod;
  if (name == "gauss-seidel" || name == "gauss_seidel") return SmoothSolver::gauss_seidel;
  throw Error("smooth: unknown solver '" + name + "' (use cholmod or gauss-seidel)");
}

double smoothing_weight(double length, double spacing, double b) {
  if (!(length >= 0) || !(spacing > 0) || !(b > 0) || !std::isfinite(length + spacing + b))
    throw Error(
        "smooth: a smoothing weight needs a length of 0 or more, and a spacing and b above 0, all finite");
  const double x = length / two_pi;
  return 2 * b * x * x * x * x / spacing;
}

double smoothing_length(double a, double spacing, double b) {
  if (!(a >= 0) || !(spacing > 0) || !(b > 0) || !std::isfinite(a + spacing + b))
    throw Error("smooth: a smoothing length needs a of 0 or more, and a spacing and b above 0, all finite");
  return two_pi * std::pow(a * spacing / (2 * b), 0.25);
}

double smooth_energy(const Points& points, const Points& reference, double a, double b, bool closed) {
  if (!(a >= 0) || !(b >= 0) || !std::isfinite(a + b))
    throw Error("smooth: a and b must be 0 or more and finite");
  if (points.size() != reference.size())
    throw Error("smooth: energy of " + std::to_string(points.size()) + " points against " +
                std::to_string(reference.size()) + " reference points");
  const Topology t{static_cast<int>(points.size()), closed};
  if (t.n < 3) {
    double closeness = 0;
    for (int i = 0; i < t.n; ++i) closeness += (points[i] - reference[i]).squaredNorm();
    return b * closeness;
  }
  // Zero-length segments: a tiny floor keeps E finite; their unit tangent is then ~0.
  Segments s;
  return energy_of(points, reference, a, b, t, 1e-300, s);
}

namespace {

/// The frozen-length problem of one curve: the merged input and the weights.
struct Problem {
  Points q0;  // the input after merging
  Topology topo;
  double a = 0, b = 0;
  double h = 0;      // mean spacing
  double floor = 0;  // least segment length
  double size = 0;   // diagonal of the bounding box
};

Problem prepare(const Points& points, const SmoothOptions& options, SmoothResult& result) {
  constexpr int min_points = 5;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!points[i].allFinite()) throw Error("smooth: point " + std::to_string(i) + " is not finite");
  if (points.size() < static_cast<std::size_t>(min_points))
    throw Error("smooth: " + std::to_string(points.size()) + " points, at least " +
                std::to_string(min_points) + " are needed");
  Problem p;
  p.q0 = points;
  const int strays = drop_strays(p.q0, options.closed);
  const double raw_spacing = mean_spacing(p.q0, options.closed);
  if (!(raw_spacing > 0)) throw Error("smooth: all points coincide");
  result.repaired = strays + merge_duplicates(p.q0, options.closed, options.merge_distance * raw_spacing);
  if (p.q0.size() < static_cast<std::size_t>(min_points))
    throw Error("smooth: " + std::to_string(p.q0.size()) + " distinct points (after merging " +
                std::to_string(result.repaired) + " duplicates), at least " + std::to_string(min_points) +
                " are needed");
  p.topo = Topology{static_cast<int>(p.q0.size()), options.closed};
  p.h = result.repaired ? mean_spacing(p.q0, options.closed) : raw_spacing;  // nothing merged: the same
  result.spacing = p.h;
  p.a = options.smoothing_length > 0 ? smoothing_weight(options.smoothing_length, p.h, options.b)
        : options.a > 0              ? options.a
                                     : smoothing_weight(options.relative_length * p.h, p.h, options.b);
  p.b = options.b;
  result.a = p.a;
  // Lengths never fall below this: merged input has none shorter than merge_distance * h.
  p.floor = 1e-6 * p.h;
  Eigen::Vector2d lo = p.q0[0], hi = p.q0[0];
  for (const auto& x : p.q0) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  p.size = (hi - lo).norm();
  // Far longer than the loop, the strain term swamps the springs: the solve loses its
  // precision and the shape would be gone even if it did not.
  const double length =
      options.smoothing_length > 0 ? options.smoothing_length : smoothing_length(p.a, p.h, p.b);
  if (!(length <= 10 * p.size)) {
    char text[160];
    std::snprintf(
        text, sizeof text,
        "smooth: a smoothing length of %.4g is over 10 times the loop's extent (%.4g): it would smooth "
        "the shape away",
        length, p.size);
    throw Error(text);
  }
  return p;
}

/// The outer iterations from q = q0: each freezes the lengths, solves, and takes the step
/// (or a shorter one) when it lowers E. Returns the final E.
double minimise(const Problem& p, const SmoothOptions& options, Points& q, SmoothResult& result) {
  const Topology& topo = p.topo;
  Segments segments;  // scratch, reused by every iteration
  std::vector<double> inv;
  double energy = energy_of(q, p.q0, p.a, p.b, topo, p.floor, segments);
  result.energy_before = energy;
  result.energy_history.push_back(energy);
  Eigen::MatrixX2d rhs(topo.n, 2), x(topo.n, 2);
  for (int i = 0; i < topo.n; ++i) rhs.row(i) = p.b * p.q0[i].transpose();
  std::unique_ptr<detail::CholmodSolver> cholmod;
  if (options.solver == SmoothSolver::cholmod && p.a > 0) cholmod = band_solver(topo);
  Band band;
  Points next(topo.n);
  static_assert(sizeof(Band::value_type) == 5 * sizeof(double), "band rows are packed");
  for (int it = 1; p.a > 0 && it <= options.max_iterations; ++it) {
    // segments holds q's: the last energy_of was of q (before the loop, or the step taken).
    assemble_band(segments.l, p.a, p.b, topo, band, inv);
    if (cholmod) {
      cholmod->factor(band.front().data());
      cholmod->solve(rhs, x);
    } else {
      for (int i = 0; i < topo.n; ++i) x.row(i) = q[i].transpose();
      result.sweeps += gauss_seidel(band, rhs, topo, options.sweep_tolerance * p.size, options.max_sweeps, x);
    }
    if (!x.allFinite()) throw Error("smooth: the solve produced non-finite points");
    // The frozen-length step minimises E with the lengths of the current points, not E
    // itself: near the fixed point it can raise E. Then try shorter steps along it, and
    // stop when none lowers E, so that E decreases monotonically.
    double next_energy = energy;
    bool lowered = false;
    for (double t = 1; t >= 1.0 / 16 && !lowered; t /= 2) {
      for (int i = 0; i < topo.n; ++i) next[i] = q[i] + t * (x.row(i).transpose() - q[i]);
      next_energy = energy_of(next, p.q0, p.a, p.b, topo, p.floor, segments);
      lowered = next_energy < energy;
    }
    if (!lowered) {
      result.converged = true;
      break;
    }
    const double moved = normal_move(q, next, topo);
    std::swap(q, next);
    const double change = std::abs(energy - next_energy);
    energy = next_energy;
    result.energy_history.push_back(energy);
    result.iterations = it;
    if (change <= options.tolerance * energy || moved <= options.move_tolerance * p.h) {
      result.converged = true;
      break;
    }
  }
  if (p.a == 0) result.converged = true;
  return energy;
}

}  // namespace

SmoothResult smooth(const Points& points, const SmoothOptions& options) {
  // Far from the origin, smoothed about a local origin and moved back.
  const Eigen::Vector2d origin = detail::local_origin(points);
  if (origin != Eigen::Vector2d::Zero()) {
    SmoothResult r = smooth(detail::moved(points, origin), options);
    for (auto& q : r.points) q += origin;
    return r;
  }
  check_options(options);
  SmoothResult result;
  const Problem p = prepare(points, options, result);
  Points q = p.q0;
  result.energy_after = minimise(p, options, q, result);
  double sum = 0;
  for (int i = 0; i < p.topo.n; ++i) {
    const double d = (q[i] - p.q0[i]).norm();
    sum += d * d;
    result.max_move = std::max(result.max_move, d);
  }
  result.rms_move = std::sqrt(sum / p.topo.n);
  result.points = std::move(q);
  return result;
}

}  // namespace section
