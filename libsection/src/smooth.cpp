#include "section/smooth.h"

#include "section/error.h"
#include "detail/parallel.h"

#include <cholmod.h>

#include <algorithm>
#include <array>
#include <cmath>
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

/// Segment lengths, floored so that a collapsed segment cannot divide by zero.
std::vector<double> segment_lengths(const Points& q, const Topology& t, double floor) {
  std::vector<double> l(t.n, 0.0);
  for (int k = t.first_segment(); k < t.n; ++k)
    l[k] = std::max((q[k] - q[t.prev(k)]).norm(), floor);
  return l;
}

double energy_of(const Points& q, const Points& q0, double a, double b, const Topology& t,
                 double floor) {
  const auto l = segment_lengths(q, t, floor);
  double curvature = 0;
  for (int i = t.first_term(); i < t.end_term(); ++i) {
    const int h = t.prev(i), j = t.next(i);
    // kappa_i^2 (l_i + l_j) / 4 with kappa_i = 2 |d_i| / (l_i + l_j).
    const Eigen::Vector2d d = (q[j] - q[i]) / l[j] - (q[i] - q[h]) / l[i];
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

void assemble_band(const std::vector<double>& l, double a, double b, const Topology& t,
                   Band& band) {
  band.assign(t.n, {0, 0, 0, 0, 0});
  for (int i = 0; i < t.n; ++i) band[i][2] = b;
  for (int i = t.first_term(); i < t.end_term(); ++i) {
    const int j = t.next(i);
    const double w = a / (l[i] + l[j]);
    const std::array<int, 3> id{t.prev(i), i, j};
    const std::array<double, 3> r{1 / l[i], -1 / l[i] - 1 / l[j], 1 / l[j]};
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

/// Global solve with CHOLMOD (simplicial LL'). The pattern is analysed once per curve. The
/// factorisation of A with the fill-reducing permutation P first builds P A P' (a sparse
/// transpose) at every call; here P A P' is built once, its values refilled in place per
/// outer iteration, and factored with the natural ordering: CHOLMOD then does the same
/// arithmetic on the same matrix, without the transpose and the allocations around it,
/// so the points are bit for bit those of the permuting factorisation.
class CholmodSolver {
public:
  explicit CholmodSolver(const Topology& t) : topo_(t) {
    cholmod_start(&common_);
    common_.final_asis = 0;
    common_.supernodal = CHOLMOD_SIMPLICIAL;
    common_.final_ll = 1;
    try {
      setup(t.n);
    } catch (...) {
      release();
      throw;
    }
  }
  CholmodSolver(const CholmodSolver&) = delete;
  CholmodSolver& operator=(const CholmodSolver&) = delete;
  ~CholmodSolver() { release(); }

  void solve(const Band& band, const Eigen::MatrixX2d& rhs, Eigen::MatrixX2d& x) {
    double* px = static_cast<double*>(pap_->x);
    static_assert(sizeof(Band::value_type) == 5 * sizeof(double), "band rows are packed");
    const double* values = band.front().data();
    for (std::size_t k = 0; k < from_.size(); ++k) px[k] = values[from_[k]];
    double beta[2] = {0, 0};
    cholmod_factorize_p(pap_, beta, nullptr, 0, factor_, &common_);
    if (common_.status < CHOLMOD_OK || factor_->minor != factor_->n)
      throw Error("smooth: CHOLMOD could not factor the system (not positive definite?)");
    const int n = topo_.n;
    double* b = static_cast<double*>(rhs_->x);
    for (int k = 0; k < n; ++k) {
      b[k] = rhs(perm_[k], 0);
      b[n + k] = rhs(perm_[k], 1);
    }
    if (!cholmod_solve2(CHOLMOD_A, factor_, rhs_, nullptr, &x_, nullptr, &y_, &e_, &common_))
      throw Error("smooth: CHOLMOD solve failed");
    const double* s = static_cast<const double*>(x_->x);
    const std::size_t d = x_->d;
    x.resize(n, 2);
    for (int k = 0; k < n; ++k) {
      x(perm_[k], 0) = s[k];
      x(perm_[k], 1) = s[d + k];
    }
  }

private:
  void setup(int n) {
    const Topology& t = topo_;
    // A: all band entries (both triangles, columns sorted), read as its lower triangle.
    std::vector<int> ap(n + 1, 0), ai;
    for (int col = 0; col < n; ++col) {
      std::vector<int> rows;
      for (int o = -2; o <= 2; ++o) {
        const int r = band_column(col, o, t);  // symmetric pattern: row r of column col
        if (r >= 0) rows.push_back(r);
      }
      std::sort(rows.begin(), rows.end());
      rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
      for (int r : rows) {
        ai.push_back(r);
        int o = col - r;  // band entry (r, col) = band[r][2 + o]
        if (o > 2) o -= n;
        if (o < -2) o += n;
        source_.push_back(5 * r + 2 + o);
      }
      ap[col + 1] = static_cast<int>(ai.size());
    }
    std::vector<double> ax(ai.size());
    for (std::size_t k = 0; k < ax.size(); ++k) ax[k] = double(k);  // entry numbers, to follow them
    cholmod_sparse a{};
    a.nrow = a.ncol = n;
    a.nzmax = ai.size();
    a.p = ap.data();
    a.i = ai.data();
    a.x = ax.data();
    a.stype = -1;
    a.itype = CHOLMOD_INT;
    a.xtype = CHOLMOD_REAL;
    a.dtype = CHOLMOD_DOUBLE;
    a.sorted = 1;
    a.packed = 1;
    // The fill-reducing ordering, as an analysis of A picks it.
    cholmod_factor* ordered = cholmod_analyze(&a, &common_);
    if (!ordered) throw Error("smooth: CHOLMOD could not analyse the system");
    perm_.assign(static_cast<int*>(ordered->Perm), static_cast<int*>(ordered->Perm) + n);
    // P A P' in upper form, as the permuting factorisation builds it; each of its entries
    // carries the number of the entry of A it came from.
    pap_ = cholmod_ptranspose(&a, 1, perm_.data(), nullptr, 0, &common_);
    cholmod_free_factor(&ordered, &common_);
    if (!pap_) throw Error("smooth: CHOLMOD could not permute the system");
    const std::size_t nz = cholmod_nnz(pap_, &common_);
    const double* px = static_cast<const double*>(pap_->x);
    from_.resize(nz);
    for (std::size_t k = 0; k < nz; ++k) from_[k] = source_[static_cast<std::size_t>(px[k])];
    // Natural ordering of the permuted matrix, no postordering: P A P' is factored as given.
    common_.nmethods = 1;
    common_.method[0].ordering = CHOLMOD_NATURAL;
    common_.postorder = 0;
    factor_ = cholmod_analyze(pap_, &common_);
    if (!factor_ || factor_->ordering != CHOLMOD_NATURAL)
      throw Error("smooth: CHOLMOD could not analyse the permuted system");
    const int* natural = static_cast<const int*>(factor_->Perm);
    for (int k = 0; natural && k < n; ++k)
      if (natural[k] != k) throw Error("smooth: CHOLMOD reordered the permuted system");
    rhs_ = cholmod_allocate_dense(n, 2, n, CHOLMOD_REAL, &common_);
    if (!rhs_) throw Error("smooth: CHOLMOD could not allocate the right-hand side");
  }

  void release() {
    cholmod_free_dense(&x_, &common_);
    cholmod_free_dense(&y_, &common_);
    cholmod_free_dense(&e_, &common_);
    cholmod_free_dense(&rhs_, &common_);
    cholmod_free_factor(&factor_, &common_);
    cholmod_free_sparse(&pap_, &common_);
    cholmod_finish(&common_);
  }

  Topology topo_;
  cholmod_common common_;
  std::vector<int> source_;  // entry of A -> its value in the band, 5 * row + 2 + offset
  std::vector<int> from_;    // entry of P A P' -> its value in the band
  std::vector<int> perm_;
  cholmod_sparse* pap_ = nullptr;
  cholmod_factor* factor_ = nullptr;
  cholmod_dense *rhs_ = nullptr, *x_ = nullptr, *y_ = nullptr, *e_ = nullptr;
};

/// The paper's point-by-point iteration on the same frozen-length system, warm-started
/// from x; sweeps until the largest update is below `tol`. Returns the sweeps done.
int gauss_seidel(const Band& band, const Eigen::MatrixX2d& rhs, const Topology& t, double tol,
                 int max_sweeps, Eigen::MatrixX2d& x) {
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
  const double x = length / two_pi;
  return 2 * b * x * x * x * x / spacing;
}

double smoothing_length(double a, double spacing, double b) {
  return two_pi * std::pow(a * spacing / (2 * b), 0.25);
}

double smooth_energy(const Points& points, const Points& reference, double a, double b,
                     bool closed) {
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
  return energy_of(points, reference, a, b, t, 1e-300);
}

SmoothResult smooth(const Points& points, const SmoothOptions& options) {
  check_options(options);
  constexpr int min_points = 5;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!points[i].allFinite())
      throw Error("smooth: point " + std::to_string(i) + " is not finite");
  if (points.size() < static_cast<std::size_t>(min_points))
    throw Error("smooth: " + std::to_string(points.size()) + " points, at least " +
                std::to_string(min_points) + " are needed");

  SmoothResult result;
  Points q0 = points;
  const double raw_spacing = mean_spacing(q0, options.closed);
  if (!(raw_spacing > 0)) throw Error("smooth: all points coincide");
  result.repaired = merge_duplicates(q0, options.closed, options.merge_distance * raw_spacing);
  if (q0.size() < static_cast<std::size_t>(min_points))
    throw Error("smooth: " + std::to_string(q0.size()) + " distinct points (after merging " +
                std::to_string(result.repaired) + " duplicates), at least " +
                std::to_string(min_points) + " are needed");

  const Topology topo{static_cast<int>(q0.size()), options.closed};
  const double h = mean_spacing(q0, options.closed);
  result.spacing = h;
  const double a = options.smoothing_length > 0 ? smoothing_weight(options.smoothing_length, h, options.b)
                   : options.a > 0              ? options.a
                                                : smoothing_weight(options.relative_length * h, h, options.b);
  const double b = options.b;
  result.a = a;
  // Lengths never fall below this: merged input has none shorter than merge_distance * h.
  const double floor = 1e-6 * h;

  Eigen::Vector2d lo = q0[0], hi = q0[0];
  for (const auto& p : q0) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double size = (hi - lo).norm();

  Points q = q0;
  double energy = energy_of(q, q0, a, b, topo, floor);
  result.energy_before = energy;
  result.energy_history.push_back(energy);

  Eigen::MatrixX2d rhs(topo.n, 2), x(topo.n, 2);
  for (int i = 0; i < topo.n; ++i) rhs.row(i) = b * q0[i].transpose();
  std::unique_ptr<CholmodSolver> cholmod;
  if (options.solver == SmoothSolver::cholmod && a > 0)
    cholmod = std::make_unique<CholmodSolver>(topo);
  Band band;
  Points next(topo.n);

  for (int it = 1; a > 0 && it <= options.max_iterations; ++it) {
    assemble_band(segment_lengths(q, topo, floor), a, b, topo, band);
    if (cholmod) {
      cholmod->solve(band, rhs, x);
    } else {
      for (int i = 0; i < topo.n; ++i) x.row(i) = q[i].transpose();
      result.sweeps += gauss_seidel(band, rhs, topo, options.sweep_tolerance * size,
                                    options.max_sweeps, x);
    }
    if (!x.allFinite()) throw Error("smooth: the solve produced non-finite points");
    // The frozen-length step minimises E with the lengths of the current points, not E
    // itself: near the fixed point it can raise E. Then try shorter steps along it, and
    // stop when none lowers E, so that E decreases monotonically.
    double next_energy = energy;
    bool lowered = false;
    for (double t = 1; t >= 1.0 / 16 && !lowered; t /= 2) {
      for (int i = 0; i < topo.n; ++i) next[i] = q[i] + t * (x.row(i).transpose() - q[i]);
      next_energy = energy_of(next, q0, a, b, topo, floor);
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
    if (change <= options.tolerance * energy || moved <= options.move_tolerance * h) {
      result.converged = true;
      break;
    }
  }
  if (a == 0) result.converged = true;

  result.energy_after = energy;
  double sum = 0;
  for (int i = 0; i < topo.n; ++i) {
    const double d = (q[i] - q0[i]).norm();
    sum += d * d;
    result.max_move = std::max(result.max_move, d);
  }
  result.rms_move = std::sqrt(sum / topo.n);
  result.points = std::move(q);
  return result;
}

}  // namespace section
