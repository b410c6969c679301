// SPDX-License-Identifier: GPL-3.0-or-later
// The values' standard errors through the points' noise (ValueSigmas): the fitted profile's
// error at each place, the points' noise over the points its knot spans hold, carried
// through the camber line's end fits to the angles and edge points, and to the thickness.
#include "detail/inscribed.h"
#include "detail/section_checks.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <vector>

namespace section::detail {

double wedge_sine(const SampledProfile& pr, const Eigen::Vector2d& vertex, double reach) {
  const int n = static_cast<int>(pr.samples.size());
  const int at = pr.nearest(vertex);
  Eigen::Vector2d flank[2];
  for (int side = 0; side < 2; ++side) {
    int k = 1, i = at;
    for (; k < n / 2 && (pr.samples[i] - vertex).norm() < reach; ++k)
      i = ((at + (side ? k : -k)) % n + n) % n;
    if (k >= n / 2) return 0;
    flank[side] = (pr.samples[i] - vertex).normalized();
  }
  const double cosine = std::clamp(flank[0].dot(flank[1]), -1.0, 1.0);
  return std::sin(0.5 * std::acos(cosine));
}

namespace {

// `c`'s distinct knots within one period.
std::vector<double> period_knots(const BSpline& c) {
  std::vector<double> knots;
  for (double k : c.knots)
    if (k >= c.t_min() && k < c.t_max() && (knots.empty() || k > knots.back())) knots.push_back(k);
  return knots;
}

// The share of the points' noise the fit `c` (its `knots`, period_knots) keeps at parameter
// t: 5 over the points (of `point_params`) on the two knot spans either side of t's, at most
// 1. Sparse points between dense edges leave a coefficient per point mid-chord.
double local_share(const BSpline& c, const std::vector<double>& knots,
                   const std::vector<double>& point_params, double t) {
  const double t0 = c.t_min(), period = c.t_max() - t0;
  const long count = long(knots.size());
  if (!(period > 0) || count <= 5) return 1;
  const auto wrap = [&](double x) { return x - period * std::floor((x - t0) / period); };
  t = wrap(t);
  const long j = long(std::upper_bound(knots.begin(), knots.end(), t) - knots.begin()) - 1;
  const auto knot = [&](long i) {  // knot i, unwrapped about span j
    const long k = ((i % count) + count) % count;
    return knots[std::size_t(k)] + period * double((i - k) / count);
  };
  const double a = knot(j - 2), b = knot(j + 3);
  std::size_t inside = 0;
  for (double u : point_params) {
    double d = wrap(u) - wrap(a);  // u's parameter from a, forward
    if (d < 0) d += period;
    if (d < b - a) ++inside;
  }
  return inside > 0 ? std::min(1.0, 5.0 / double(inside)) : 1;
}

// The fitted profile's standard error along its normal at a parameter, and how far (in
// parameter) its errors at two places stay correlated there: a knot span's worth.
struct ProfileNoise {
  const SampledProfile& pr;
  const CheckOptions& o;
  double sigma;
  std::vector<double> knots;  // distinct, within one period

  ProfileNoise(const SampledProfile& p, const CheckOptions& opt)
      : pr(p), o(opt), sigma(std::max(opt.points_noise, opt.noise)), knots(period_knots(p.curve)) {}
  // With many points a coefficient the points are taken as spread evenly in parameter: the
  // period over them times t's knot span is the share (knots inserted at an edge hold fewer).
  double at(double t) const {
    return sigma * std::sqrt(o.point_params.empty() ? std::min(1.0, pr.period / (o.points * span(t)))
                                                    : local_share(pr.curve, knots, o.point_params, t));
  }
  double span(double t) const {
    if (knots.size() < 2) return pr.period;
    t = pr.wrap(t);
    const auto it = std::upper_bound(knots.begin(), knots.end(), t);
    const double b = it == knots.end() ? knots.front() + pr.period : *it;
    const double a = it == knots.begin() ? knots.back() - pr.period : *(it - 1);
    return b - a;
  }
  // A place of the profile: its parameter, standard error and knot span.
  struct Place {
    double t, sigma, span;
  };
  Place place(double t) const { return {pr.wrap(t), at(t), span(t)}; }
  // Covariance of the profile's normal errors at two places.
  double covariance(const Place& a, const Place& b) const {
    double d = std::abs(a.t - b.t);
    d = std::min(d, pr.period - d);
    const double reach = o.noise_correlation * 0.5 * (a.span + b.span);
    const double rho = reach > 0 ? std::max(0.0, 1 - d / reach) : double(d == 0);
    return rho > 0 ? rho * a.sigma * b.sigma : 0;
  }
};

// A centre of the chain, its lateral error (toward its left contact) made of its two
// contacts' normal errors: (left - right) / (2 cos a), a the flanks' half angle; a chain's
// end at an edge circle's centre (both contacts the edge point) has its own.
struct CentreError {
  ProfileNoise::Place left, right;
  double weight;   // 1 / (2 cos a); 0 for an edge centre
  double own = 0;  // an edge centre's variance, apart from the rest
};

CentreError centre_error(const InscribedCircle& c, const ProfileNoise& noise, double edge_sigma) {
  const ProfileNoise::Place l = noise.place(c.t_left), r = noise.place(c.t_right);
  if ((c.left - c.right).norm() <= 1e-9 * noise.pr.scale) {
    const double s = std::max(l.sigma / std::sqrt(2.0), edge_sigma);
    return {l, r, 0, s * s};
  }
  const Eigen::Vector2d u = (c.left - c.center).normalized(), v = (c.right - c.center).normalized();
  const double cosine = std::sqrt(std::max(0.0, 0.5 * (1 - u.dot(v))));
  return {l, r, 0.5 / std::max(cosine, 0.2)};
}

double centre_covariance(const CentreError& a, const CentreError& b, const ProfileNoise& noise, bool same) {
  if (a.weight == 0 || b.weight == 0) return same ? a.own : 0;
  const double c = noise.covariance(a.left, b.left) - noise.covariance(a.left, b.right) -
                   noise.covariance(a.right, b.left) + noise.covariance(a.right, b.right);
  return a.weight * b.weight * c;
}

// Standard error (radians) of the end direction camber's end_tangent fits at the front or
// back end of `chain`: a cubic in arc length over the centres within `span` of that end,
// each weighted by its circle's fit_weight, its slope there.
double end_sigma(const std::vector<InscribedCircle>& chain, bool front, double span,
                 const ProfileNoise& noise, double edge_sigma) {
  const EndSpan fitted = end_span(chain, front, span);
  const std::vector<const InscribedCircle*>& p = fitted.circles;
  const std::vector<double>& s = fitted.s;
  const std::size_t n = p.size();
  if (n == 0) return 0;
  Eigen::MatrixXd A(n, 4);
  Eigen::VectorXd w(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = s[i] / s.back();
    w[long(i)] = std::sqrt(p[i]->fit_weight);
    A.row(long(i)) << 1, x, x * x, x * x * x;
    A.row(long(i)) *= w[long(i)];
  }
  // The slope's weights on the centres: row 1 of the weighted A's pseudo-inverse, times
  // the rows' weights.
  const Eigen::MatrixXd pinv = A.completeOrthogonalDecomposition().pseudoInverse();
  const Eigen::VectorXd g = pinv.row(1).transpose().cwiseProduct(w);
  std::vector<CentreError> e;
  for (const InscribedCircle* c : p) e.push_back(centre_error(*c, noise, edge_sigma));
  double variance = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      variance += g[long(i)] * g[long(j)] * centre_covariance(e[i], e[j], noise, i == j);
  // The slope's length is the chain's over the span.
  return std::sqrt(std::max(variance, 0.0)) / s.back();
}

}  // namespace

ValueSigmas value_sigmas(const SampledProfile& pr, const CamberResult& camber, const SectionParams& params,
                         const CheckOptions& options) {
  ValueSigmas out;
  if (!(options.points > 0) || !(std::max(options.points_noise, options.noise) > 0)) return out;
  const ProfileNoise noise(pr, options);
  const std::vector<InscribedCircle>& chain = camber.medial.circles;
  const double span = camber.tangent_span_length;
  double le = 0, te = 0;  // radians
  if (span > 0 && chain.size() >= 6) {
    le = end_sigma(chain, true, span, noise, camber.le.radius_sigma);
    te = end_sigma(chain, false, span, noise, camber.te.radius_sigma);
  }
  out.inlet_angle = le * 180 / pi, out.outlet_angle = te * 180 / pi;
  // An edge point lies on the end direction from the chain's end centre: turned by the
  // direction's error about that centre, it moves across the chord line by its distance
  // times the error and the sine of the direction's angle to the chord.
  const Eigen::Vector2d along = (params.te_point - params.le_point).normalized();
  const double le_turn = camber.ext_le * std::abs(cross(camber.le_tangent, along)) * le,
               te_turn = camber.ext_te * std::abs(cross(camber.te_tangent, along)) * te;
  // A sharp edge's point is its flanks' meeting: each flank's error moves it along the
  // edge by that over twice the sine of the wedge's half angle (a thin wedge: far).
  // A round edge's point moves with what it rests on, at least as the noise moves it:
  // - its circle refitted on the measured points (camber's final edge point): that
  //   circle's centre and radius along the end direction (Edge::point_sigma, from the same
  //   fit). At 0.12 mm of spacing a compressor TE with its radius 7 um uncertain had its
  //   point 11 um off, the chord counted 2.8 um;
  // - else the fitted curve through the points (too few on the arc, or the circle they fit
  //   too uncertain to take): the spread of that circle, as the le_radius/te_radius check
  //   takes it (a compressor's 0.29 mm LE with its nose points 0.1 mm apart: the curve 21
  //   um off the blade there, the chord 11.8 um, counted 2 um from the noise alone), and the
  //   curve's arc's rms about its circle (a nose between points 0.12 mm apart that strays
  //   8.5 um rms from a circle had its point 17 um off, the chord counted 3.2 um).
  // An edge that is not circular is flagged le_circle/te_circle, which covers the chord:
  // its arc's misfit is its shape, not the points' noise.
  const auto at_edge = [&](const Edge& e) {
    const double sine = e.vertex ? wedge_sine(pr, e.point, options.vertex_reach * camber.length) : 0;
    const double at = sine > 0 ? noise.at(e.t) / (std::sqrt(2.0) * sine) : noise.at(e.t);
    if (e.vertex || !(e.radius > 0)) return at;
    if (e.on_points)
      return e.circular && e.face == 0 && e.shape == EdgeShape::round ? std::max(at, e.point_sigma) : at;
    const double spread = edge_spread(e, options.noise);
    return std::max({at, e.circular ? e.fit_rms : 0.0, std::isfinite(spread) ? spread : 0.0});
  };
  const double le_at = at_edge(camber.le), te_at = at_edge(camber.te);
  out.chord = std::sqrt(le_turn * le_turn + te_turn * te_turn + le_at * le_at + te_at * te_at);
  if (camber.thickest.radius > 0) {
    const double l = noise.at(camber.thickest.t_left), r = noise.at(camber.thickest.t_right);
    out.max_thickness = std::sqrt(l * l + r * r);
  }
  // A value that is no number (a degenerate section's) has no standard error to give: its
  // own checks flag it, and a stream holds no NaN standard error.
  for (double* v : {&out.chord, &out.max_thickness, &out.inlet_angle, &out.outlet_angle})
    if (!std::isfinite(*v)) *v = 0;
  return out;
}

}  // namespace section::detail
