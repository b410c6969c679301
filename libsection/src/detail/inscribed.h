// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The inscribed-circle solver of the camber stages: a circle centred on a given line that
// touches the profile on both sides, solved on the exact spline, and its validity tests.
#include "detail/piecewise_curve.h"
#include "detail/sampled_profile.h"
#include "section/medial_axis.h"

#include <Eigen/Core>

#include <vector>

namespace section::detail {

/// The centres of `circles`, in order.
inline std::vector<Eigen::Vector2d> centers(const std::vector<InscribedCircle>& circles) {
  std::vector<Eigen::Vector2d> c;
  for (const auto& x : circles) c.push_back(x.center);
  return c;
}

/// The circles an end direction is fitted over (camber's end_tangent, and its standard
/// error): from the front or the back of `circles`, those within `span` of arc length along
/// their centres from that end, and more until 6 of them have weight (fit_weight > 0);
/// `s` holds each one's arc length from the end. Empty when fewer than 6 have weight or
/// their arc has no length.
struct EndSpan {
  std::vector<const InscribedCircle*> circles;
  std::vector<double> s;
};

inline EndSpan end_span(const std::vector<InscribedCircle>& circles, bool front, double span) {
  EndSpan out;
  const std::size_t n = circles.size();
  double acc = 0;
  int weighed = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const InscribedCircle& c = circles[front ? k : n - 1 - k];
    if (!out.circles.empty()) acc += (c.center - out.circles.back()->center).norm();
    if (weighed >= 6 && acc > span) break;
    out.circles.push_back(&c);
    out.s.push_back(acc);
    weighed += c.fit_weight > 0;
  }
  if (weighed < 6 || !(out.s.back() > 0)) return {};
  return out;
}

/// Newton on (t_a, t_b, lambda): centre c = p + lambda n, both contacts foot points of c
/// and equally far from it, from the contact guesses ta and tb. `kappa` (optional) gets
/// the signed curvatures at the two contacts. False when it does not converge.
bool solve_circle(const PiecewiseCurve& curve, const Eigen::Vector2d& p, const Eigen::Vector2d& n, double ta,
                  double tb, double scale, InscribedCircle& out, double* kappa = nullptr);

/// True when a solved circle is an inscribed circle of the medial branch: its contacts lie
/// on their sides (left of n, right of n) and are distinct, it does not cross the profile
/// and does not exceed the osculating circle at either contact. `end` (0 or 1, toward
/// that end of the branch; -1 none) adds the test that locates the branch's ends.
bool valid_circle(const SampledProfile& pr, const Eigen::Vector2d& n, const InscribedCircle& c,
                  const double* kappa, int end = -1);

/// The valid inscribed circle centred on the line through p along n, solved from the
/// contacts of `guess`; unless `fresh` is false, falls back to the profile's nearest
/// samples on either side (also when there is no guess).
bool circle_on_normal(const SampledProfile& pr, const Eigen::Vector2d& p, const Eigen::Vector2d& n,
                      const InscribedCircle* guess, InscribedCircle& out, bool fresh = true, int end = -1);

/// A point p of an axis snapped onto the exact medial axis: the valid circle on the axis
/// normal n from the contacts of `guess`, centred within half its radius of p.
bool snap_to_axis(const SampledProfile& pr, const Eigen::Vector2d& p, const Eigen::Vector2d& n,
                  const InscribedCircle& guess, InscribedCircle& out);

struct AxisCurve;

/// section::medial_axis of the profile sampled as `pr` (options.samples samples): camber_line
/// has them already. The axis through the circles (MedialAxis::curve) into `axis` when given.
MedialAxis medial_axis(const SampledProfile& pr, const MedialAxisOptions& options, AxisCurve* axis = nullptr);

}  // namespace section::detail
