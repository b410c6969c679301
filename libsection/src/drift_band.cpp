// SPDX-License-Identifier: GPL-3.0-or-later
#include "section/drift_band.h"

#include "drift_fit.h"
#include "section/error.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace section {

namespace {

using drift::Grid;
using drift::Reference;
using drift::Vec;

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

QuadraticDrift fit_profile_drift(const std::vector<Vec>& uv, const std::vector<double>& dz,
                                 const Reference& ref, const Grid& ref_grid, double zmax, double slab,
                                 double gap_min, int min_support) {
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
    rows.reserve(uv.size());
    rhs.reserve(uv.size());
    for (std::size_t i = 0; i < uv.size(); ++i) {
      const double z = dz[i];
      if (std::abs(z) > zr) continue;
      const Vec raw = uv[i], c = raw - z * cur.at(raw);
      int k;
      Vec pk, n;
      if (!drift::span_beside(ref, ref_grid, c, slab, gap_min, k, pk, n) || ref.loop[std::size_t(k)] != 0)
        continue;
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
    if (!drift::trimmed_fit<2 * T + 1>(rows, rhs, 2 * T, slab, min_support, sol,
                                       2 * QuadraticDrift::affine_terms, 0.05))
      return d;
    if (std::abs(sol(2 * T)) > 0.25 * slab) return d;
    for (int j = 0; j < T; ++j) cur.w.col(j) = sol.segment<2>(2 * j);
  }
  cur.ok = true;
  return cur;
}

// Beside a sparse stretch of the profile (a low-density patch, a thin edge seen obliquely)
// the band widens locally, up to sparse_half_width, for one point per `spacing` there too:
// the half width at each slab point from the slab's points per length over +-8 neighbours.
std::vector<double> local_half_widths(const Reference& ref, double half_width, double slab, double spacing,
                                      double sparse_half_width) {
  std::vector<double> local(ref.point.size(), half_width);
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
  return local;
}

}  // namespace

std::vector<Eigen::Vector2d> drift_band(const MorphologyResult& ordered,
                                        const std::vector<Eigen::Vector3d>& nearby, double slab,
                                        double half_width, double spacing, double sparse_half_width) {
  const Reference ref = drift::reference_of(ordered);
  if (ref.point.size() < 3 || !(slab > 0)) return {};
  const double gap_min = drift::gap_length(GapFillOptions{}, slab, drift::profile_length(ordered));
  const bool widen = spacing > 0 && sparse_half_width > half_width;
  const double widest = widen ? sparse_half_width : half_width;
  std::vector<Vec> uv;
  std::vector<double> dz;
  const double zfit = std::max(2 * half_width, 3 * slab);
  drift::near_plane(nearby, std::max(zfit, widest), uv, dz);
  // Cells a slab wide (4 times the array of 2 slab ones): a nearest search then looks at
  // half the points, and settles in its 3 x 3 cells 24 times in 25 on a dense scan.
  const Grid ref_grid(ref.point, slab, 128);
  const QuadraticDrift drift = fit_profile_drift(uv, dz, ref, ref_grid, zfit, slab, gap_min, 64);
  if (!drift.ok) return {};
  const std::vector<double> local = widen
                                        ? local_half_widths(ref, half_width, slab, spacing, sparse_half_width)
                                        : std::vector<double>(ref.point.size(), half_width);
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

double band_half_width(std::size_t slab_points, double length, double slab, double spacing,
                       double max_widths) {
  if (!(slab >= 0) || !std::isfinite(slab) || std::isnan(length) || std::isnan(spacing) ||
      std::isnan(max_widths))
    throw Error("drift_band: the slab must be 0 or more and finite, and the lengths numbers");
  if (!(spacing > 0) || !(length > 0) || slab_points == 0) return 0.5 * slab;
  // Points per length grow with the band's width: slab_points / length in the slab.
  const double wanted = 0.5 * slab * (length / double(slab_points)) / spacing;
  return std::clamp(wanted, 0.5 * slab, std::max(0.5, max_widths) * slab);
}

}  // namespace section
