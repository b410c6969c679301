// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Fixtures of the compare tests (test_compare, test_compare_stream): exact generated
// sections as nominals, their points moved, thickened, cut, dented or holed by known
// amounts, and the exact signed distance of a point to the true profile.
#include "camber_fixtures.h"
#include "section/compare.h"
#include "section/extras/generate.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace compare_test {

using camber_test::pi;
using Eigen::Vector2d;
using section::SectionTruth;

/// A generated section: its exact truth and the nominal made of it (a dense spline ~0.1 um
/// from the truth, the exact edge points, the pressure side: the inside of the camber's turn).
struct Case {
  SectionTruth truth;
  section::NominalSection nominal;
};

inline Case make_case(const section::SectionDesign& design) {
  Case c{section::section_truth(design, 20000), {}};
  c.nominal.curve = camber_test::dense_spline(c.truth.profile, 2000);
  c.nominal.le_point = c.truth.le_point;
  c.nominal.te_point = c.truth.te_point;
  c.nominal.pressure_side = c.truth.inlet_angle > c.truth.outlet_angle ? -1 : 1;
  return c;
}

/// Points of the true profile every `spacing` along it, with Gaussian noise of `sigma`
/// along the exact normal; `normals` (when given) gets the exact normal of each.
inline std::vector<Vector2d> profile_points(const SectionTruth& t, double spacing, double sigma = 0,
                                            std::uint64_t seed = 1,
                                            std::vector<Vector2d>* normals = nullptr) {
  return section::noisy_profile(t, spacing, sigma, seed, normals);
}

/// Signed distance of p to the true profile, positive outside (exact to ~1e-14 mm).
inline double exact_deviation(const SectionTruth& t, const Vector2d& p) {
  const section::ProfileLocation l = section::locate(t, p);
  const auto it = std::lower_bound(t.profile_s.begin(), t.profile_s.end(), l.s);
  const std::size_t j = it == t.profile_s.end() ? 0 : static_cast<std::size_t>(it - t.profile_s.begin());
  return (p - t.profile[j]).dot(t.profile_normal[j]) >= 0 ? l.distance : -l.distance;
}

/// The rigid motion p -> R(degrees) p + shift.
inline Vector2d moved(const Vector2d& p, double degrees, const Vector2d& shift) {
  const double a = degrees * pi / 180;
  return Vector2d(std::cos(a) * p.x() - std::sin(a) * p.y(), std::sin(a) * p.x() + std::cos(a) * p.y()) +
         shift;
}

/// The chord fraction of p: 0 at the LE point, 1 at the TE point.
inline double chord_fraction(const SectionTruth& t, const Vector2d& p) {
  const Vector2d c = t.te_point - t.le_point;
  return (p - t.le_point).dot(c) / c.squaredNorm();
}

/// True when p (on the profile) lies on the pressure side between chord fractions lo and hi.
inline bool on_pressure_side(const Case& c, const Vector2d& p, const Vector2d& normal, double lo, double hi) {
  const double x = chord_fraction(c.truth, p);
  const Vector2d chord = c.truth.te_point - c.truth.le_point;
  // The pressure side's normal points to the side of the chord line it lies on.
  const double side = chord.x() * normal.y() - chord.y() * normal.x();
  return x > lo && x < hi && side * c.nominal.pressure_side > 0;
}

}  // namespace compare_test
