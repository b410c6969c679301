// SPDX-License-Identifier: GPL-3.0-or-later
#include "detail/flanks.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace section::detail {

namespace {

// A flank: a curve x = u a + v(u) b in the frame (a, b) of its points' principal axis a
// about the tip, v a quadratic (a line: c(2) = 0) in u / scale.
struct Flank {
  Eigen::Vector2d axis{0, 0};
  Eigen::Vector3d coef{0, 0, 0};
  double scale = 1;
  Eigen::Vector2d at(double u, Eigen::Vector2d& tangent) const {
    const Eigen::Vector2d normal(-axis.y(), axis.x());
    const double w = u / scale;
    tangent = axis + (coef(1) + 2 * coef(2) * w) / scale * normal;
    return u * axis + (coef(0) + coef(1) * w + coef(2) * w * w) * normal;
  }
  double residual(const Eigen::Vector2d& x) const {
    const Eigen::Vector2d normal(-axis.y(), axis.x());
    const double w = x.dot(axis) / scale;
    return x.dot(normal) - (coef(0) + coef(1) * w + coef(2) * w * w);
  }
};

// The flank through the points x (about the tip; `keep` those taken), by least squares;
// false when it is not determined.
bool fit_flank(const std::vector<Eigen::Vector2d>& x, const std::vector<char>& keep, double scale, int degree,
               Flank& f) {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  std::size_t count = 0;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (keep[i]) centre += x[i], ++count;
  if (count < 6) return false;
  centre /= static_cast<double>(count);
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (std::size_t i = 0; i < x.size(); ++i)
    if (keep[i]) cov += (x[i] - centre) * (x[i] - centre).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  f.axis = eig.eigenvectors().col(1);
  if (f.axis.dot(centre) < 0) f.axis = -f.axis;
  f.scale = scale;
  const Eigen::Vector2d normal(-f.axis.y(), f.axis.x());
  Eigen::Matrix3d ata = Eigen::Matrix3d::Zero();
  Eigen::Vector3d atb = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!keep[i]) continue;
    const double w = x[i].dot(f.axis) / scale;  // scaled: the normal equations well conditioned
    const Eigen::Vector3d row(1, w, degree == 2 ? w * w : 0.0);
    ata += row * row.transpose();
    atb += row * x[i].dot(normal);
  }
  if (degree != 2) ata(2, 2) = 1;
  f.coef = ata.ldlt().solve(atb);
  return f.coef.allFinite();
}

// Where two flanks meet (Newton on flank0(u0) = flank1(u1) from the tip), about the tip.
FlankVertex meet(const Flank (&f)[2], double far) {
  const double sine = std::sin(0.5 * std::acos(std::clamp(f[0].axis.dot(f[1].axis), -1.0, 1.0)));
  if (!(sine > 1e-3)) return {};
  double u0 = 0, u1 = 0;
  Eigen::Vector2d t0, t1;
  for (int it = 0; it < 20; ++it) {
    const Eigen::Vector2d r = f[0].at(u0, t0) - f[1].at(u1, t1);
    // t0 du0 - t1 du1 = -r
    const double det = -cross(t0, t1);
    if (!(std::abs(det) > 0)) return {};
    const double du0 = cross(r, t1) / det, du1 = -cross(t0, r) / det;
    u0 += du0;
    u1 += du1;
    if (std::abs(du0) + std::abs(du1) < 1e-12 * far) break;
  }
  const Eigen::Vector2d p = f[0].at(u0, t0);
  if (!p.allFinite() || !(p.norm() < far)) return {};
  FlankVertex v;
  v.found = true;
  v.point = p;
  v.sine = sine;
  return v;
}

// The flanks' meeting as lines, or as parabolas where those meet farther from the lines'
// meeting than 4 times the noise moves it (see flank_meeting); points about the tip. With
// `trim`, a flank's points beyond 3 robust sigmas of its line are left out (measured
// points: outliers), once.
FlankVertex meet_flanks(const std::vector<Eigen::Vector2d> (&x)[2], double far, double noise, bool trim) {
  std::vector<char> keep[2] = {std::vector<char>(x[0].size(), 1), std::vector<char>(x[1].size(), 1)};
  Flank line[2], curve[2];
  for (int side = 0; side < 2; ++side) {
    if (!fit_flank(x[side], keep[side], far, 1, line[side])) return {};
    if (!trim) continue;
    std::vector<double> a;
    for (const auto& q : x[side]) a.push_back(std::abs(line[side].residual(q)));
    std::vector<double> sorted = a;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2), sorted.end());
    const double limit = 3 * 1.4826 * sorted[sorted.size() / 2];
    for (std::size_t i = 0; i < a.size(); ++i) keep[side][i] = a[i] <= limit;
    if (!fit_flank(x[side], keep[side], far, 1, line[side])) return {};
  }
  const FlankVertex by_lines = meet(line, far);
  if (!by_lines.found) return {};
  for (int side = 0; side < 2; ++side)
    if (!fit_flank(x[side], keep[side], far, 2, curve[side])) return by_lines;
  FlankVertex by_curves = meet(curve, far);
  if (!by_curves.found) return by_lines;
  const double apart = (by_curves.point - by_lines.point).norm();
  const bool parabolas = apart > 4 * noise / by_lines.sine;
  FlankVertex v = parabolas ? by_curves : by_lines;
  v.parabolas = parabolas;
  v.models_apart = apart;
  return v;
}

}  // namespace

FlankVertex flank_meeting(const SampledProfile& pr, const Eigen::Vector2d& tip, double near, double far,
                          double noise) {
  const int n = static_cast<int>(pr.samples.size());
  const int at = pr.nearest(tip);
  std::vector<Eigen::Vector2d> x[2];
  for (int side = 0; side < 2; ++side) {
    int k = 1;
    for (; k < n / 4; ++k) {
      const Eigen::Vector2d& q = pr.samples[static_cast<std::size_t>(((at + (side ? k : -k)) % n + n) % n)];
      const double r = (q - tip).norm();
      if (r > far) break;
      if (r >= near) x[side].push_back(q - tip);  // about the tip: no cancellation far from the origin
    }
    if (k >= n / 4) return {};
  }
  FlankVertex v = meet_flanks(x, far, noise, false);
  v.point += tip;
  return v;
}

FlankVertex measured_flank_meeting(const std::vector<Eigen::Vector2d>& measured, const Eigen::Vector2d& tip,
                                   const Eigen::Vector2d& inward, double near, double far, double noise) {
  std::vector<Eigen::Vector2d> x[2];
  for (const auto& q : measured) {
    const Eigen::Vector2d r = q - tip;
    const double d = r.norm();
    if (d < near || d > far || !(r.dot(inward) > 0)) continue;
    x[cross(inward, r) > 0 ? 1 : 0].push_back(r);
  }
  FlankVertex v = meet_flanks(x, far, noise, true);
  v.point += tip;
  return v;
}

}  // namespace section::detail
