// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Fixtures of the camber tests (test_medial_axis, test_edge, test_camber, test_params):
// exact sections built as envelopes of circles and dense splines through them, noisy
// fits, cut-off trailing edges and a NACA 0012.
#include "section/camber.h"
#include "section/checks.h"
#include "section/extras/generate.h"
#include "section/fit_spline.h"
#include "section/params.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <random>
#include <utility>
#include <vector>

namespace camber_test {

using Eigen::Vector2d;
using section::BSpline;
using section::SectionDesign;
using section::SectionTruth;

constexpr double pi = 3.14159265358979323846;

// A dense closed spline through the exact profile (its distance to the truth is ~0.1 um).
inline BSpline dense_spline(const std::vector<Vector2d>& points, int control_points = 2000) {
  section::CurveFitOptions fo;
  fo.control_points = control_points;
  fo.fairness = 1e-9;
  return section::fit_curve(points, fo);
}

// A section measured and checked, with the noise the check is told (test_checks, test_edge).
struct Checked {
  section::CamberResult camber;
  section::SectionParams params;
  section::SectionCheck check;
};

inline Checked measure(const BSpline& spline, double noise, const std::vector<Vector2d>& measured = {}) {
  section::CamberOptions o;
  o.profile_noise = noise;
  Checked c;
  c.camber = section::camber_line(spline, o, measured);
  c.params = section::section_params(spline, c.camber);
  section::CheckOptions k;
  k.noise = noise;
  c.check = section::check_section(spline, c.camber, c.params, k);
  return c;
}

// The checks of a measured section (its values edited, maybe) with another noise.
inline section::SectionCheck recheck(const BSpline& spline, const Checked& c, double noise) {
  section::CheckOptions k;
  k.noise = noise;
  return section::check_section(spline, c.camber, c.params, k);
}

// Points every `spacing` along the exact profile, moved by Gaussian noise (sigma 5 um)
// along the exact normal.
inline std::vector<Vector2d> noisy_profile(const SectionTruth& truth, double spacing, std::uint64_t seed) {
  return section::noisy_profile(truth, spacing, 0.005, seed);
}

inline double relative(double a, double b) {
  return std::abs(a - b) / std::max(std::abs(b), 1e-300);
}

// Thick and thin, high and low turning, large and small edge radii.
inline std::vector<SectionDesign> designs() {
  return section::design_family();
}

// f(design index, seed, truth, points, spline) for each design but the turbine (the
// slowest to fit; the others cover it) and each seed: noisy_profile points every
// `spacing`, and the spline fit_spline makes of them.
template <class F>
void for_noisy_fits(double spacing, std::initializer_list<unsigned> seeds, F&& f) {
  std::vector<SectionDesign> ds = designs();
  ds.erase(ds.begin() + 1);
  int k = 0;
  for (const SectionDesign& design : ds) {
    const SectionTruth truth = section::section_truth(design, 20000);
    for (unsigned seed : seeds) {
      const std::vector<Vector2d> pts = noisy_profile(truth, spacing, seed * 7919 + k);
      f(k, seed, truth, pts, section::fit_spline(pts, pts).spline);
    }
    ++k;
  }
}

// The camber of a noisy fit with its edge circles refitted to the measured points (at
// 5 um of profile noise), and the same with the circles on the spline alone.
inline std::pair<section::CamberResult, section::CamberResult> on_points_and_spline(
    const BSpline& spline, const std::vector<Vector2d>& pts) {
  section::CamberOptions o;
  o.profile_noise = 0.005;
  section::CamberResult on_points = section::camber_line(spline, o, pts);
  o.edge_on_points = false;
  return {std::move(on_points), section::camber_line(spline, o)};
}

// The profile of `truth` cut off by the line normal to the camber line `back` (arc length,
// mm) before the TE centre: a blunt trailing edge whose flat face (sampled at the
// profile's spacing) joins the sides at two corners. `cut` and `width` get the camber
// point on the line and the face width.
inline std::vector<Vector2d> cut_trailing_edge(const SectionTruth& truth, double back, Vector2d& cut,
                                               double& width) {
  const double s_end = truth.camber_s[truth.camber_end - 1] - back;
  std::size_t k = truth.camber_begin;
  while (k + 1 < truth.camber_end && truth.camber_s[k + 1] < s_end) ++k;
  cut = truth.camber[k];
  const Vector2d t = (truth.camber[k + 1] - truth.camber[k]).normalized();
  const auto& p = truth.profile;
  const std::size_t n = p.size();
  auto h = [&](std::size_t i) { return (p[i % n] - cut).dot(t); };
  std::vector<Vector2d> out;
  for (std::size_t i = 0; i < n; ++i) {
    if (h(i) < 0) out.push_back(p[i]);
    if (h(i) < 0 && h(i + 1) >= 0) {  // leaving: the face runs to where the profile comes back
      const Vector2d x = p[i] + (p[(i + 1) % n] - p[i]) * (h(i) / (h(i) - h(i + 1)));
      std::size_t j = i + 1;
      while (!(h(j) >= 0 && h(j + 1) < 0)) ++j;
      const Vector2d y = p[j % n] + (p[(j + 1) % n] - p[j % n]) * (h(j) / (h(j) - h(j + 1)));
      width = (y - x).norm();
      const int m = std::max(2, static_cast<int>(width / (p[1] - p[0]).norm()));
      for (int q = 0; q <= m; ++q) out.push_back(x + (y - x) * (static_cast<double>(q) / m));
    }
  }
  return out;
}

// The unit vector at `degrees` from +u.
inline Vector2d direction(double degrees) {
  const double a = degrees * pi / 180;
  return {std::cos(a), std::sin(a)};
}

// NACA 0012, chord 100, thickness 12; the closed-TE coefficient -0.1036 makes a wedge of
// ~16 deg. Its nose is not a circular arc: the curvature radius grows from the tip.
inline std::vector<Vector2d> naca0012() {
  auto half = [](double x) {
    return 0.6 * (0.2969 * std::sqrt(x) - 0.1260 * x - 0.3516 * x * x + 0.2843 * x * x * x -
                  0.1036 * x * x * x * x);
  };
  std::vector<Vector2d> pts;
  const int m = 2000;
  for (int i = 0; i < m; ++i) {
    const double x = 0.5 * (1 + std::cos(pi * i / m));
    pts.push_back({100 * x, -100 * half(x)});
  }
  for (int i = 0; i < m; ++i) {
    const double x = 0.5 * (1 - std::cos(pi * i / m));
    pts.push_back({100 * x, 100 * half(x)});
  }
  return pts;
}

}  // namespace camber_test
