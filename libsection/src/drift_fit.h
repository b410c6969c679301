// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What gap filling (src/gap_fill.cpp) and the drift-corrected band (src/drift_band.cpp)
// share: a hash grid over 2D points, the slab's ordered points, the span of the slab's
// curve beside a point, and the trimmed least squares of the drift fits.
#include "section/gap_fill.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace section::drift {

using Vec = Eigen::Vector2d;

// Uniform grid over 2D points, each cell the head of a list of its points threaded
// through `next_` (no allocation per cell): a plain array of the cells over the points'
// box when that holds at most `dense` cells a point, else (and once points are added) an
// open-addressed table of the occupied cells (a query probes a few table slots instead of
// hashing into a node-based map).
class Grid {
public:
  Grid(const std::vector<Vec>& points, double cell, double dense = 32) : points_(points), cell_(cell) {
    next_.assign(points.size(), -1);
    if (!make_dense(dense)) rehash(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) insert(int(i));
  }
  void add(int i) {
    if (!heads_.empty()) to_table();
    if (2 * (used_ + 1) > slots_.size()) rehash(2 * slots_.size());
    insert(i);
  }
  // Calls f(i) for every point within r of c, in no particular order.
  template <class F>
  void for_each_within(const Vec& c, double r, F&& f) const {
    const std::int64_t x0 = coord(c.x() - r), x1 = coord(c.x() + r), y0 = coord(c.y() - r),
                       y1 = coord(c.y() + r);
    for_each_in_cells(x0, x1, y0, y1, [&](int i) {
      if ((points_[std::size_t(i)] - c).squaredNorm() <= r * r) f(i);
    });
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
    const double r2 = r * r;
    const Vec at = c;  // local copies: no store through `take` can change them
    const Vec* const points = points_.data();
    const int* const next = next_.data();
    const auto take = [&](int i) {
      const double d = (points[i] - at).squaredNorm();
      if (d <= r2 && (best < 0 || d < bd || (d == bd && i < best))) best = i, bd = d;
    };
    // The 3 x 3 cells about c first: every point outside them lies at least a cell away
    // (0.999 of one: the cells come from rounded quotients), so a nearer one found there,
    // or a radius under a cell, settles it in 9 probes instead of up to (2 r / cell + 2)^2.
    const double sure = 0.999 * cell_;
    if (std::max(std::abs(c.x()), std::abs(c.y())) < 1e12 * cell_) {  // far from coord's clamp
      const std::int64_t cx = near_coord(c.x()), cy = near_coord(c.y());
      if (!heads_.empty() && cx > x0_ && cx + 1 < x0_ + nx_ && cy > y0_ && cy + 1 < y0_ + ny_) {
        // All 9 inside the array: three runs of three cells, no bounds to clip (the
        // clipping and the cells' loops were half of the drift band's nearest searches).
        const int* row = heads_.data() + (cx - 1 - x0_) * ny_ + (cy - 1 - y0_);
        for (int a = 0; a < 3; ++a, row += ny_)
          for (int b = 0; b < 3; ++b)
            for (int i = row[b]; i >= 0; i = next[i]) take(i);
      } else {
        for_each_in_cells(cx - 1, cx + 1, cy - 1, cy + 1, take);
      }
      if (r < sure || (best >= 0 && bd < sure * sure)) return best;
      best = -1;
    }
    for_each_within(c, r, take);
    return best;
  }

private:
  struct Slot {
    std::int64_t key = 0;
    int head = -1;  // -1: an empty slot
  };
  // Clamped: a cell index must fit an int64 whatever the coordinates and cell.
  std::int64_t coord(double v) const { return std::int64_t(std::clamp(std::floor(v / cell_), -1e15, 1e15)); }
  // coord for |v| under 1e12 cells, where the clamp does nothing: floor as the truncation,
  // less one when that rounded up (a quarter of the instructions).
  std::int64_t near_coord(double v) const {
    const double q = v / cell_;
    const std::int64_t t = std::int64_t(q);
    return t - std::int64_t(double(t) > q);
  }
  static std::int64_t pack(std::int64_t x, std::int64_t y) {
    return std::int64_t((std::uint64_t(x) << 32) ^ (std::uint64_t(y) & 0xffffffffULL));
  }
  std::int64_t key(const Vec& p) const { return pack(coord(p.x()), coord(p.y())); }
  // Calls f(i) for every point of the cells [x0, x1] x [y0, y1]. The array's rows are
  // clipped to its box once, not each cell tested against it (a quarter of the drift
  // band's nearest searches went to the cells' bounds and offsets).
  template <class F>
  void for_each_in_cells(std::int64_t x0, std::int64_t x1, std::int64_t y0, std::int64_t y1, F&& f) const {
    if (heads_.empty()) {
      for (std::int64_t x = x0; x <= x1; ++x)
        for (std::int64_t y = y0; y <= y1; ++y)
          for (int i = head(x, y); i >= 0; i = next_[std::size_t(i)]) f(i);
      return;
    }
    const std::int64_t xa = std::max(x0, x0_) - x0_, xb = std::min(x1, x0_ + nx_ - 1) - x0_;
    const std::int64_t ya = std::max(y0, y0_) - y0_, yb = std::min(y1, y0_ + ny_ - 1) - y0_;
    for (std::int64_t x = xa; x <= xb; ++x) {
      const int* row = heads_.data() + x * ny_;
      for (std::int64_t y = ya; y <= yb; ++y)
        for (int i = row[y]; i >= 0; i = next_[std::size_t(i)]) f(i);
    }
  }
  // The first point of cell (x, y)'s list in the table, -1 for none.
  int head(std::int64_t x, std::int64_t y) const {
    const Slot* s = find(pack(x, y));
    return s ? s->head : -1;
  }
  // The array of cells over the points' box, when it holds at most `dense` cells a point
  // (4096 at least): false, nothing made, else.
  bool make_dense(double dense) {
    if (points_.empty()) return false;
    Vec lo = points_[0], hi = lo;
    for (const Vec& p : points_) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    if (!lo.allFinite() || !hi.allFinite()) return false;
    x0_ = coord(lo.x()), y0_ = coord(lo.y());
    nx_ = coord(hi.x()) - x0_ + 1, ny_ = coord(hi.y()) - y0_ + 1;
    if (double(nx_) * double(ny_) > std::max(4096.0, dense * double(points_.size()))) return false;
    heads_.assign(std::size_t(nx_ * ny_), -1);
    return true;
  }
  // From the array to the table, the lists made again in the same order.
  void to_table() {
    heads_.clear();
    const std::size_t n = next_.size();
    rehash(n);
    for (std::size_t i = 0; i < n; ++i) insert(int(i));
  }
  std::size_t home(std::int64_t k) const {
    const std::uint64_t h = std::uint64_t(k) * 0x9E3779B97F4A7C15ULL;
    return std::size_t(h ^ (h >> 32)) & (slots_.size() - 1);
  }
  const Slot* find(std::int64_t k) const {
    for (std::size_t h = home(k);; h = (h + 1) & (slots_.size() - 1)) {
      const Slot& s = slots_[h];
      if (s.head < 0) return nullptr;
      if (s.key == k) return &s;
    }
  }
  void insert(int i) {
    if (next_.size() <= std::size_t(i)) next_.resize(std::size_t(i) + 1, -1);
    if (!heads_.empty()) {
      const Vec& p = points_[std::size_t(i)];
      int& h = heads_[std::size_t((coord(p.x()) - x0_) * ny_ + (coord(p.y()) - y0_))];
      next_[std::size_t(i)] = h;
      h = i;
      return;
    }
    const std::int64_t k = key(points_[std::size_t(i)]);
    for (std::size_t h = home(k);; h = (h + 1) & (slots_.size() - 1)) {
      Slot& s = slots_[h];
      if (s.head >= 0 && s.key != k) continue;
      if (s.head < 0) {
        s.key = k;
        ++used_;
      }
      next_[std::size_t(i)] = s.head;
      s.head = i;
      return;
    }
  }
  // A table of at least 2 n slots (a power of two), the points' lists kept.
  void rehash(std::size_t n) {
    std::size_t size = 16;
    while (size < 2 * n) size *= 2;
    std::vector<Slot> old(size);
    old.swap(slots_);
    for (const Slot& s : old) {
      if (s.head < 0) continue;
      for (std::size_t h = home(s.key);; h = (h + 1) & (slots_.size() - 1))
        if (slots_[h].head < 0) {
          slots_[h] = s;
          break;
        }
    }
  }
  const std::vector<Vec>& points_;
  double cell_;
  std::vector<Slot> slots_;
  std::vector<int> next_;   // the next point of the same cell, -1 at a list's end
  std::size_t used_ = 0;    // occupied slots
  std::vector<int> heads_;  // the array of cells (x0_ + a, y0_ + b) at a ny_ + b; empty: the table
  std::int64_t x0_ = 0, y0_ = 0, nx_ = 0, ny_ = 0;
};

// The slab's ordered points, all loops, with their place in their loop.
struct Reference {
  std::vector<Vec> point, normal;
  std::vector<int> loop, next, prev;  // indices into `point` of the loop neighbours
};

/// The reference of the slab's ordered loops (loop 0 first).
Reference reference_of(const MorphologyResult& ordered);

// The slab's span beside c: its nearest ordered point within 3 slab widths (k, at pk) and
// that point's neighbour on the side of c, when the span is no gap and c lies beside it
// (a line carried on past a gap's end misses a curving edge); n its unit normal, turned
// like the point's outward normal. False when there is none.
bool span_beside(const Reference& ref, const Grid& ref_grid, const Vec& c, double slab, double gap_min,
                 int& k, Vec& pk, Vec& n);

// A step along the profile longer than this is a gap (the fill's threshold; the drift
// fits pair no point with a span that long).
double gap_length(const GapFillOptions& options, double slab, double profile_length);

/// The profile's length (loop 0's), 0 when there is no loop.
double profile_length(const MorphologyResult& ordered);

/// The points of `nearby` (u, v, height) within `limit` of the plane: in-plane positions
/// `uv` and heights `dz`, in order.
void near_plane(const std::vector<Eigen::Vector3d>& nearby, double limit, std::vector<Vec>& uv,
                std::vector<double>& dz);

// The lanes a row adds to in the normal equations, in pairs: pair k is the row's entries
// (2 seg[k], 2 seg[k] + 1) times its entry fac[k] (N: its right side). Column j's pairs
// from the one holding j down (an entry above the diagonal comes along, unused), for odd
// N then the last entry's pairs, then the right side's.
template <int N>
struct NormalPairs {
  static constexpr int P = N / 2, count = (P + 1) * P + (N % 2) * P + P;
  int seg[count] = {}, fac[count] = {};
  constexpr NormalPairs() {
    int k = 0;
    for (int j = 0; j < N; ++j)
      for (int p = j / 2; p < P; ++p) seg[k] = p, fac[k++] = j;
    for (int p = 0; N % 2 == 1 && p < P; ++p) seg[k] = p, fac[k++] = N - 1;
    for (int p = 0; p < P; ++p) seg[k] = p, fac[k++] = N;
  }
};
template <int N>
inline constexpr NormalPairs<N> normal_pairs{};

// With GCC on x86-64 Linux, an AVX clone of a function beside the plain one, picked when
// the library loads: the same multiplies and adds in three-operand form (no copies), and
// no FMA (not in "avx"), so the same numbers on every CPU.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__)
#define SECTION_AVX_CLONE __attribute__((target_clones("avx", "default")))
#else
#define SECTION_AVX_CLONE
#endif

// Pairs [K0, K0 + B) of NormalPairs summed over the used rows, in row order, held in
// registers for the whole sweep (all pairs at once spill most of them: a load and a store
// a pair and row). The last block, for odd N, also sums x(N - 1) x(N - 1) and x(N - 1) y
// into `last`.
template <int N, int K0, int B>
SECTION_AVX_CLONE void add_normal_pairs(const std::vector<Eigen::Matrix<double, N, 1>>& rows,
                                        const std::vector<double>& rhs, const std::vector<char>& use,
                                        Eigen::Matrix<double, 2, NormalPairs<N>::count>& acc,
                                        Eigen::Vector2d& last) {
  constexpr const NormalPairs<N>& pairs = normal_pairs<N>;
  constexpr bool with_last = N % 2 == 1 && K0 + B == NormalPairs<N>::count;
  Eigen::Matrix<double, 2, B> part = Eigen::Matrix<double, 2, B>::Zero();
  double last_x = 0, last_y = 0;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    if (!use[r]) continue;
    const Eigen::Matrix<double, N, 1>& x = rows[r];
    const double y = rhs[r];
#pragma GCC unroll 16
    for (int k = 0; k < B; ++k)
      part.col(k) +=
          x.template segment<2>(2 * pairs.seg[K0 + k]) * (pairs.fac[K0 + k] == N ? y : x(pairs.fac[K0 + k]));
    if constexpr (with_last) {
      last_x += x(N - 1) * x(N - 1);
      last_y += x(N - 1) * y;
    }
  }
  acc.template middleCols<B>(K0) = part;
  if constexpr (with_last) last = Eigen::Vector2d(last_x, last_y);
}

template <int N, int Width, int... Block>
void add_normal_blocks(const std::vector<Eigen::Matrix<double, N, 1>>& rows, const std::vector<double>& rhs,
                       const std::vector<char>& use, Eigen::Matrix<double, 2, NormalPairs<N>::count>& acc,
                       Eigen::Vector2d& last, std::integer_sequence<int, Block...>) {
  constexpr int count = NormalPairs<N>::count;
  (add_normal_pairs<N, Block * Width, std::min(Width, count - Block * Width)>(rows, rhs, use, acc, last),
   ...);
}

// The normal equations' lower triangle (A) and right side (b) over the used rows, each
// entry summed in row order (the same sums of the same products as one outer product a
// row gives: the same numbers), two entries a step (NormalPairs), a block of 12 pairs a
// sweep over the rows. The scalar form was a load, a multiply, an add and a store an
// entry, 5 % of `slice`; all pairs in one sweep still a load and a store a pair.
template <int N>
void normal_equations(const std::vector<Eigen::Matrix<double, N, 1>>& rows, const std::vector<double>& rhs,
                      const std::vector<char>& use, Eigen::Matrix<double, N, N>& A,
                      Eigen::Matrix<double, N, 1>& b) {
  constexpr int P = N / 2, odd = N % 2, count = NormalPairs<N>::count, width = 12;
  Eigen::Matrix<double, 2, count> acc;
  Eigen::Vector2d last;  // A(N - 1, N - 1) and b(N - 1) for odd N
  add_normal_blocks<N, width>(rows, rhs, use, acc, last,
                              std::make_integer_sequence<int, (count + width - 1) / width>{});
  int k = 0;
  for (int j = 0; j < N; ++j)
    for (int p = j / 2; p < P; ++p, ++k)
      for (int i = std::max(2 * p, j); i < 2 * p + 2; ++i) A(i, j) = acc(i - 2 * p, k);
  if constexpr (odd == 1) {
    for (int p = 0; p < P; ++p, ++k) A(N - 1, 2 * p) = acc(0, k), A(N - 1, 2 * p + 1) = acc(1, k);
    A(N - 1, N - 1) = last(0);
    b(N - 1) = last(1);
  }
  for (int p = 0; p < P; ++p, ++k) b(2 * p) = acc(0, k), b(2 * p + 1) = acc(1, k);
  for (int j = 1; j < N; ++j)
    for (int i = 0; i < j; ++i) A(i, j) = A(j, i);
}

// Trimmed least squares for the drift fits: three passes, each on the rows within
// 3 robust sigmas (plus 0.05 slab) of the last fit, with a ridge on the first `ridged`
// unknowns (1e-3 of the first two's weight: a direction the pairs do not see, as V . t
// along a straight side, stays near 0; one they see is shrunk by about 0.1 %), and the
// unknowns from `firm` on held firmer, by `firm_ridge` of that weight. False when the
// solve fails or fewer than `min_support` rows are kept.
template <int N>
bool trimmed_fit(const std::vector<Eigen::Matrix<double, N, 1>>& rows, const std::vector<double>& rhs,
                 int ridged, double slab, int min_support, Eigen::Matrix<double, N, 1>& sol, int firm = N,
                 double firm_ridge = 1e-3) {
  // Held: for all the compiler knows, a store to `use` could change rows.size().
  const std::size_t n = rows.size();
  std::vector<char> use(n, 1);
  std::vector<double> res(n), sorted;
  sol.setZero();
  for (int pass = 0; pass < 3; ++pass) {
    Eigen::Matrix<double, N, N> A;
    Eigen::Matrix<double, N, 1> b;
    normal_equations(rows, rhs, use, A, b);
    const double weight = A(0, 0) + A(1, 1);
    for (int j = 0; j < ridged; ++j) A(j, j) += (j < firm ? 1e-3 : firm_ridge) * weight + 1e-12;
    sol = A.ldlt().solve(b);
    if (!sol.allFinite()) return false;
    for (std::size_t r = 0; r < n; ++r) res[r] = std::abs(rhs[r] - rows[r].dot(sol));
    sorted = res;
    std::nth_element(sorted.begin(), sorted.begin() + long(sorted.size() / 2), sorted.end());
    const double cut = 3 * 1.4826 * sorted[sorted.size() / 2] + 0.05 * slab;
    int kept = 0;
    bool same = true;
    for (std::size_t r = 0; r < n; ++r) {
      const char u = res[r] <= cut;
      same = same && u == use[r];
      kept += (use[r] = u);
    }
    if (kept < min_support) return false;
    // The same rows kept: a further pass would repeat this one, number for number.
    if (same) break;
  }
  return true;
}

}  // namespace section::drift
