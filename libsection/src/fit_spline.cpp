// SPDX-License-Identifier: GPL-3.0-or-later
#include "section/fit_spline.h"

#include "detail/fit_points.h"
#include "detail/local_origin.h"
#include "fit_spline_steps.h"
#include "section/error.h"
#include "section/units.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace section {

namespace {

using fit::Feet;
using fit::Points;
using fit::Refinement;

double polygon_area(const Points& p) {
  double a = 0;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++)
    a += p[j].x() * p[i].y() - p[i].x() * p[j].y();
  return 0.5 * a;
}

// Squared-distance minimisation iterations on fixed knots until the RMS settles.
// `start`: feet on a curve of nearly the same shape and parameter (the curve before a
// change of knots), tracked instead of searched afresh.
Refinement refine(BSpline c, const Points& q, const FitSplineOptions& o, const Feet* start = nullptr) {
  const std::vector<double> all(q.size(), 1.0);
  auto weights_for = [&](Feet& ft) {
    double threshold = o.outlier_distance;
    if (threshold <= 0) threshold = std::max(6 * (ft.noise_all = fit::noise_sigma(ft, all)), o.outlier_floor);
    return fit::outlier_weights(ft, q, threshold);
  };
  Refinement now;
  // The feet, the next step and the knots of the next round evaluate the current curve:
  // converted once.
  now.pc = detail::PiecewiseCurve(c, true);  // the basis kept: the steps move the control points only
  now.feet = fit::foot_points(c, now.pc, q, start);
  now.weights = weights_for(now.feet);
  now.rms = fit::weighted_rms(now.feet, now.weights);
  now.curve = std::move(c);
  // The best state is set aside only when a worse one replaces it (states are moved, not copied).
  Refinement best;
  bool now_best = true;
  double best_rms = now.rms;
  int it = 0;
  for (; it < o.max_iterations; ++it) {
    BSpline next = fit::sdm_step(now.curve, now.pc, q, now.feet, now.weights, o.fairness, o.smoothing_length);
    detail::PiecewiseCurve npc(next, now.pc);
    Feet nf = fit::foot_points(next, npc, q, &now.feet);
    std::vector<double> nw = weights_for(nf);
    const double nrms = fit::weighted_rms(nf, nw);
    const double change = std::abs(now.rms - nrms);
    if (now_best) best = std::move(now);
    now = {std::move(next), std::move(npc), std::move(nf), std::move(nw), nrms, 0};
    now_best = nrms <= best_rms;
    if (now_best) best_rms = nrms;
    if (change <= o.convergence * nrms + 1e-3 * o.tolerance) {
      ++it;
      break;
    }
  }
  if (now_best) best = std::move(now);
  best.iterations = it;
  return best;
}

// The area inside the closed curve of r: of the polygon through 16 points per control
// point, at the parameters `sample` takes, evaluated on the polynomials.
double curve_area(const Refinement& r) {
  const int count = 16 * static_cast<int>(r.curve.control.size());
  const double a = r.curve.t_min(), b = r.curve.t_max();
  Points dense;
  dense.reserve(static_cast<std::size_t>(count));
  detail::PiecewiseCurve::Local at{0, 0};
  for (int i = 0; i < count; ++i)
    dense.push_back(r.pc.point(at = r.pc.locate(a + (b - a) * i / count, at.span)));
  return polygon_area(dense);
}

struct FoldError : Error {
  using Error::Error;
};

void check_options(const FitSplineOptions& o) {
  if (o.degree < 1 || o.degree > max_spline_degree)
    throw Error("fit_spline: degree " + std::to_string(o.degree) + " is not in 1.." +
                std::to_string(max_spline_degree));
  if (o.control_points != 0 && o.control_points < o.degree + 1)
    throw Error("fit_spline: " + std::to_string(o.control_points) + " control points are too few, at least " +
                std::to_string(o.degree + 1) + " are needed");
  if (!(o.tolerance > 0) || !(o.initial_span > 0) || !(o.min_span > 0))
    throw Error("fit_spline: tolerance, initial span and minimum span must be positive");
  if (!(o.smoothing_length >= 0) || !(o.outlier_floor >= 0))
    throw Error("fit_spline: smoothing length and outlier floor must not be negative");
  if (o.first_iterations < 0)
    throw Error("fit_spline: first iterations " + std::to_string(o.first_iterations) +
                " must not be negative");
  if (!(o.bridge_factor >= 0) || !std::isfinite(o.bridge_factor))
    throw Error("fit_spline: bridge factor must be 0 (off) or a positive number of spacings");
  if (o.max_control_points < 8 || o.max_rounds < 0 || o.max_iterations < 1 || !(o.convergence >= 0) ||
      !(o.fairness >= 0) || !(o.gap_factor > 0) || !(o.layer_ratio >= 0) || !(o.layer_separation >= 0) ||
      !(o.min_span_points >= 0) || !(o.exact_min_span_points >= 0) || !(o.exact_noise >= 0) ||
      !(o.outlier_distance >= 0) ||
      !std::isfinite(o.fairness + o.gap_factor + o.convergence + o.layer_ratio + o.layer_separation +
                     o.min_span_points + o.exact_noise))
    throw Error(
        "fit_spline: max_control_points must be 8 or more, max_iterations 1 or more, gap_factor above 0, "
        "and rounds, convergence, fairness, layer and span options 0 or more and finite");
  if (o.samples < 0 || o.samples > FitSplineOptions::max_samples || !(o.sample_spacing >= 0) ||
      !std::isfinite(o.sample_spacing))
    throw Error("fit_spline: samples must be 0 to " + std::to_string(FitSplineOptions::max_samples) +
                " a loop, and the sample spacing 0 or a positive length");
}

// Why the first curve through `profile` crosses itself: the points out of order, or in
// order (their polygon simple) but too sparse where the profile turns for its spans.
std::string crossing_message(const Points& profile) {
  if (fit::polyline_crosses(profile))
    return "fit_spline: the loop crosses itself (its points are not ordered along one profile)";
  std::size_t widest = 0;
  double gap = 0;
  for (std::size_t i = 0; i < profile.size(); ++i) {
    const double d = (profile[(i + 1) % profile.size()] - profile[i]).norm();
    if (d > gap) gap = d, widest = i;
  }
  return "fit_spline: the curve through the points crosses itself, though they lie in order along one "
         "profile: they are too sparse for it where the profile turns (the widest gap " +
         format_length(gap) + ", between points " + std::to_string(widest) + " and " +
         std::to_string((widest + 1) % profile.size()) + " of " + std::to_string(profile.size()) +
         "): measure more points there";
}

// Two profile points farther apart than this many first-curve spans are a hole, not sparse
// sampling: no spans are merged (first_knots). Measured on generated rows: flanks up to
// 3.5 mm apart fit to the targets, 3.9 mm did not; 3 mm leaves a margin.
constexpr double kHoleSpans = 1.5;

// n uniform spans over the loop of chord-length parameters s (its last the loop's length),
// merged where the profile is sparse: a run of spans holding fewer than `per_span` of the
// profile's points joins the spans after it until it holds that many, so that no span is
// shaped by the fairness term alone between points (a sparse CMM or CFD row: points 2.3 mm
// apart mid-chord, spans of 2 mm). Where every span holds enough points, or two points lie
// more than `hole` apart, the knots are the uniform ones: bridged as before, or refused
// when the curve crosses itself there. Merged spans over flanks 3.9 mm apart fitted a thin
// section 8-9 um too thick with nothing flagged, and no later check flags the area a long
// flank hole spoils (tests/test_fit_spline_sparse.cpp).
std::vector<double> first_knots(const std::vector<double>& s, int n, double per_span, double hole,
                                int fewest) {
  const double length = s.back();
  std::vector<double> uniform(std::size_t(n) + 1);
  for (int i = 0; i <= n; ++i) uniform[std::size_t(i)] = length * i / n;
  if (!(length > 0) || !std::isfinite(length)) return uniform;
  std::vector<std::size_t> count(std::size_t(n), 0);
  for (std::size_t k = 0; k + 1 < s.size(); ++k)  // the last closes the loop
    ++count[std::min<std::size_t>(std::size_t(s[k] / length * n), std::size_t(n) - 1)];
  if (*std::min_element(count.begin(), count.end()) >= per_span) return uniform;
  for (std::size_t k = 1; k < s.size(); ++k)
    if (s[k] - s[k - 1] > hole) return uniform;
  std::vector<double> knots{0.0};
  double held = 0;
  for (int i = 0; i < n; ++i) {
    held += double(count[std::size_t(i)]);
    if (held >= per_span && i + 1 < n) {
      knots.push_back(uniform[std::size_t(i) + 1]);
      held = 0;
    }
  }
  knots.push_back(length);
  // The last run, if short, joins the one before it.
  if (held < per_span && knots.size() > 2) knots.erase(knots.end() - 2);
  if (int(knots.size()) - 1 < fewest) return uniform;
  return knots;
}

// First curve: least squares through the ordered profile on chord-length knots, uniform
// where the points allow (first_knots; always with a given number of control points). The
// uniform knots and parameters are fit_curve's, so its curve is the same.
BSpline first_curve(const Points& profile, const FitSplineOptions& o) {
  const std::vector<double> s = chord_length_parameters(profile, true);
  int n = o.control_points;
  if (n == 0) n = static_cast<int>(std::ceil(s.back() / o.initial_span));
  n = std::max(n, std::max(8, o.degree + 1));
  if (o.control_points == 0) n = std::min<int>(n, static_cast<int>(profile.size()) / 2);
  if (n > static_cast<int>(profile.size()))
    throw Error("fit_spline: " + std::to_string(n) + " control points are more than the " +
                std::to_string(profile.size()) + " points of the loop");
  try {
    detail::check_fit_points(profile, true);
    BSpline shape;
    shape.degree = o.degree;
    shape.closed = true;
    shape.knots = first_knots(s, n, o.control_points == 0 ? o.min_span_points : 0,
                              kHoleSpans * o.initial_span, std::max(8, o.degree + 1));
    shape.control.assign(shape.knots.size() - 1, Eigen::Vector2d::Zero());
    return fit_control_points(profile, s, shape, o.fairness);
  } catch (const Error& e) {
    std::string m = e.what();
    if (m.rfind("fit_curve: ", 0) == 0) m = m.substr(11);
    throw Error("fit_spline: " + m);
  }
}

// Adaptive knots from the refined first curve r: by curvature first (a few passes: an edge
// sharpens as it gets knots), then splits where the residuals still hold more than noise.
// With `stop_at_fold`, a round whose curve folds is not taken and ends the rounds.
void adapt_knots(const Points& measured, const FitSplineOptions& o, bool stop_at_fold, Refinement& r,
                 FitSplineResult& result) {
  for (int pass = 0; pass < 3; ++pass) {
    const std::vector<double> knots =
        fit::curvature_knots(r.curve, r.pc, r.feet, fit::noise_sigma(r.feet, r.weights), o);
    Refinement next = refine(fit::reknot(r.curve, r.pc, knots), measured, o, &r.feet);
    result.iterations += next.iterations;
    if (stop_at_fold && fit::self_intersects(next.curve, next.pc)) break;
    const bool same = knots.size() == r.curve.knots.size();
    r = std::move(next);
    if (same) break;
  }
  for (int round = 0; round < o.max_rounds; ++round) {
    const double sigma = fit::noise_sigma(r.feet, r.weights);
    const std::vector<double> knots = fit::split_spans(r.curve, r.feet, r.weights, sigma, o);
    if (knots.size() == r.curve.knots.size() || static_cast<int>(knots.size()) - 1 > o.max_control_points)
      break;
    Refinement next = refine(fit::reknot(r.curve, r.pc, knots), measured, o, &r.feet);
    result.iterations += next.iterations;
    if (stop_at_fold && fit::self_intersects(next.curve, next.pc)) break;
    result.rounds = round + 1;
    r = std::move(next);
  }
  // Holes holding more knots than their bridge needs get fewer (see bridge_holes), and the
  // curve is refined on those. Done on the last knots only: the rounds' knots are left as
  // they were, so that a fit without such a hole is not changed.
  if (!(o.bridge_factor > 0)) return;
  const std::vector<double> bridged =
      fit::bridge_holes(r.curve, r.feet, measured, r.weights, o.bridge_factor, o.degree);
  if (bridged.size() == r.curve.knots.size()) return;
  Refinement next = refine(fit::reknot(r.curve, r.pc, bridged), measured, o, &r.feet);
  result.iterations += next.iterations;
  if (stop_at_fold && fit::self_intersects(next.curve, next.pc)) return;
  r = std::move(next);
}

// The distances of the measured points (outliers left out) to the final curve r.
void measure_fit(const Refinement& r, std::size_t measured, FitSplineResult& result) {
  std::vector<double> d;
  for (std::size_t k = 0; k < measured; ++k)
    if (r.weights[k] > 0) d.push_back(std::abs(r.feet.signed_distance[k]));
  result.points = static_cast<int>(d.size());
  result.outliers = static_cast<int>(measured - d.size());
  result.noise = fit::noise_sigma(r.feet, r.weights);
  if (!d.empty()) {
    double ss = 0;
    for (double x : d) ss += x * x;
    result.rms = std::sqrt(ss / d.size());
    // Two order statistics of finite numbers: selected, not sorted.
    const auto p95 =
        d.begin() + std::min(d.size() - 1, static_cast<std::size_t>(std::ceil(0.95 * d.size())) - 1);
    std::nth_element(d.begin(), p95, d.end());
    result.p95 = *p95;
    result.max = *std::max_element(p95, d.end());
  }
}

// `stop_at_fold`: a knot round whose curve folds is not taken and ends the rounds (the
// last resort of fit_spline: dense knots on a thin edge can wrap the edge twice).
// `distances`, when given, receives every measured point's distance to the curve
// (outliers included).
FitSplineResult fit_once(const Points& profile, const Points& measured, const FitSplineOptions& o,
                         bool stop_at_fold = false, std::vector<double>* distances = nullptr) {
  check_options(o);
  const std::size_t min_points = 8;
  if (profile.size() < min_points || measured.size() < min_points)
    throw Error("fit_spline: the loop has " + std::to_string(std::min(profile.size(), measured.size())) +
                " points, at least " + std::to_string(min_points) + " are needed");
  for (const auto& p : measured)
    if (!p.allFinite()) throw Error("fit_spline: a measured point is not finite");
  const BSpline curve = first_curve(profile, o);
  const double input_area = polygon_area(profile);
  if (self_intersects(curve)) throw Error(crossing_message(profile));

  FitSplineResult result;
  // In adaptive mode the first curve only has to show where the curvature is: its
  // uniform spans cannot follow the edges, and iterating them to convergence is slow
  // (but 12 iterations make the knots stable to last-bit noise: docs/FITSPLINE.md).
  FitSplineOptions first = o;
  if (o.control_points == 0) first.max_iterations = std::min(o.max_iterations, o.first_iterations);
  Refinement r = refine(curve, measured, first);
  result.iterations = r.iterations;
  if (o.control_points == 0) adapt_knots(measured, o, stop_at_fold, r, result);

  result.spline = r.curve;
  if (fit::self_intersects(r.curve, r.pc))
    throw FoldError("fit_spline: the fitted curve folds or crosses itself");
  // The curve must enclose the profile's region on the same side (no turned-over loop).
  const double area = curve_area(r);
  if (area * input_area <= 0 || std::abs(area - input_area) > 0.5 * std::abs(input_area))
    throw Error("fit_spline: the fitted curve does not enclose the profile's area (fold or wrong ordering)");
  measure_fit(r, measured.size(), result);
  result.control_points = static_cast<int>(result.spline.control.size());
  const fit::Along along = fit::along_curve(r);
  fit::measure_gaps(r, along, o.gap_factor, result);
  fit::measure_layers(r, along, o, result);
  if (distances) {
    distances->clear();
    for (double x : r.feet.signed_distance) distances->push_back(std::abs(x));
  }
  return result;
}

}  // namespace

Points canonical_loop(Points loop) {
  const std::size_t n = loop.size();
  if (n < 3) return loop;
  if (polygon_area(loop) < 0) std::reverse(loop.begin(), loop.end());
  // The start depends on the points alone, not on their first index: the centroid is summed
  // in sorted order (to the last bit whatever the order given), and a tie of distance goes to
  // the least x, then y (exact copies do not occur in a loop parsed from a file).
  const auto lesser = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  };
  Points sorted = loop;
  std::sort(sorted.begin(), sorted.end(), lesser);
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (const auto& p : sorted) centre += p;
  centre /= double(n);
  std::size_t start = 0;
  double most = -1;
  for (std::size_t i = 0; i < n; ++i) {
    const double d = (loop[i] - centre).squaredNorm();
    if (d > most || (d == most && lesser(loop[i], loop[start]))) most = d, start = i;
  }
  std::rotate(loop.begin(), loop.begin() + std::ptrdiff_t(start), loop.end());
  return loop;
}

FitSplineResult fit_spline(const Points& profile, const Points& measured, const FitSplineOptions& o) {
  // Far from the origin, the fit is made about a local origin and the curve moved back.
  const Eigen::Vector2d origin = detail::local_origin(profile);
  if (origin != Eigen::Vector2d::Zero()) {
    FitSplineResult r = fit_spline(detail::moved(profile, origin), detail::moved(measured, origin), o);
    for (auto& c : r.spline.control) c += origin;
    return r;
  }
  try {
    return fit_once(profile, measured, o);
  } catch (const FoldError&) {
    if (o.control_points != 0) throw;
  }
  // A fold comes from knots denser than the data support (a thin edge measured sparsely,
  // misregistered views). Candidates: the same knots with the rounds stopped before the
  // first curve that folds, and fewer, longer spans (twice and four times). A coarser
  // curve may not fold yet cut a tight edge short, so the candidate lying closest to all
  // the measured points is taken: truncated squares (10 noise sigmas), so that outliers
  // weigh alike on every candidate.
  struct Candidate {
    FitSplineResult result;
    std::vector<double> distances;
  };
  std::vector<Candidate> candidates;
  auto attempt = [&](const FitSplineOptions& options, bool stop_at_fold) {
    Candidate c;
    try {
      c.result = fit_once(profile, measured, options, stop_at_fold, &c.distances);
      candidates.push_back(std::move(c));
    } catch (const Error&) {
    }
  };
  attempt(o, true);
  FitSplineOptions coarser = o;
  for (int k = 0; k < 2; ++k) {
    coarser.min_span_points *= 2;
    coarser.exact_min_span_points *= 2;
    coarser.min_span *= 2;
    coarser.tolerance *= 4;
    attempt(coarser, false);
  }
  if (candidates.empty()) throw FoldError("fit_spline: the fitted curve folds or crosses itself");
  double sigma = std::numeric_limits<double>::infinity();
  for (const auto& c : candidates)
    if (c.result.noise > 0) sigma = std::min(sigma, c.result.noise);
  const double cap = std::isfinite(sigma) ? 10 * sigma : std::numeric_limits<double>::infinity();
  std::size_t best = 0;
  double best_score = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    double score = 0;
    for (double d : candidates[i].distances) score += std::pow(std::min(d, cap), 2);
    if (score < best_score) best_score = score, best = i;
  }
  return std::move(candidates[best].result);
}

}  // namespace section
