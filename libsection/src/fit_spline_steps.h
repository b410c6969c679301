// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The steps of fit_spline (src/fit_spline.cpp): the feet of the measured points on the
// curve (fit_spline_feet.cpp), one distance-minimisation step (fit_spline_step.cpp), knot
// placement (fit_spline_knots.cpp) and the checks and measures of a fitted curve
// (fit_spline_checks.cpp).
#include "detail/flann_nearest.h"
#include "detail/piecewise_curve.h"
#include "section/fit_spline.h"

#include <Eigen/Core>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <cstddef>
#include <limits>
#include <vector>

namespace section::fit {

using Points = std::vector<Eigen::Vector2d>;

/// The median of v (the upper one for an even count); 0 when empty.
double median(std::vector<double> v);

/// The same value as `median`, faster, for non-negative numbers.
double median_nonnegative(std::vector<double> v);

/// The feet of the measured points on a curve.
struct Feet {
  std::vector<double> t;                // curve parameter of the foot
  std::vector<double> signed_distance;  // positive on the outer side (tangent turned clockwise)
  std::vector<std::size_t> order;       // point indices sorted by t
  double noise_all = std::numeric_limits<double>::quiet_NaN();  // noise_sigma of all the points, once known
};

/// The full search of foot_points on one curve: its dense samples (8 per span) and their
/// kd-tree. foot_points builds it per call; a curve searched many times (compare's nominal)
/// keeps one.
struct FootSearch {
  FootSearch(const BSpline& c, const detail::PiecewiseCurve& pc);
  std::vector<double> ts;  // sample parameters
  Points points;           // the samples
  detail::NearestPoints<2> tree;
};

/// Foot points of the measured points q on curve c (`pc`: c as polynomials): nearest dense
/// curve sample from a kd-tree, then a local minimisation. With `previous` (the feet on a
/// curve that moved a little since), each foot is tracked by Newton from its old
/// parameter; a point whose Newton leaves the old foot's neighbourhood or meets a
/// non-convex stretch gets the full search. `search`: c's, when kept (else built here).
Feet foot_points(const BSpline& c, const detail::PiecewiseCurve& pc, const Points& q,
                 const Feet* previous = nullptr, const FootSearch* search = nullptr);

/// Robust noise sigma: from differences of residuals consecutive along the curve, which
/// cancel the smooth (model) part of the residual and keep the noise. Points of weight 0
/// are left out.
double noise_sigma(const Feet& f, const std::vector<double>& w);

/// Weights (1 or 0) that leave out isolated points farther than `threshold` from the
/// curve; runs of far points on one side are kept, as they mean the curve is not there
/// yet (a cut edge), not outliers. So is a lone far point on the line through its two
/// neighbours (in the order along the curve): the data agree with it, the curve does not
/// (a sharp edge's tip point).
std::vector<double> outlier_weights(const Feet& f, const Points& q, double threshold);

/// Weighted RMS of the signed distances.
double weighted_rms(const Feet& f, const std::vector<double>& w);

/// The analysis of a step's system, which every step with the same matrix pattern takes
/// over: the fill-reducing ordering P (the one SimplicialLDLT would choose), the matrix
/// P H P' (upper triangle) and where each term of H lands in it, so that a step writes its
/// terms straight into P H P'. The pattern is the number of control points, the degree
/// and the band's blocks left out; sdm_step keeps the analyses of the last few patterns
/// met on its thread (see fit_spline_step.cpp).
struct StepSolver {
  int n = 0, p = 0;
  std::vector<char> skipped;  // the band's blocks left out of the pattern analysed
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> P, Pinv;
  Eigen::SparseMatrix<double> permuted;
  std::vector<int> slot;  // per term: its entry in `permuted`, -1 - entry for the entry's first term
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Upper, Eigen::NaturalOrdering<int>> ldlt;
};

/// One Gauss-Newton step of squared-distance minimisation (Wang, Pottmann and Liu 2006)
/// from curve c (`pc`: c as polynomials) toward the points q with feet f and weights w;
/// see fit_spline_step.cpp. Throws section::Error when the system is singular.
BSpline sdm_step(const BSpline& c, const detail::PiecewiseCurve& pc, const Points& q, const Feet& f,
                 const std::vector<double>& w, double fairness, double smoothing_length);

/// The curve on new knots: least squares on dense samples of the old curve c (`pc`: c as
/// polynomials).
BSpline reknot(const BSpline& c, const detail::PiecewiseCurve& pc, const std::vector<double>& knots);

/// Fewest measured points per knot span at noise sigma.
double points_per_span(const FitSplineOptions& o, double sigma);

/// Knots spread by curvature and point density (fit_spline_knots.cpp) on curve c (`pc`: c
/// as polynomials).
std::vector<double> curvature_knots(const BSpline& c, const detail::PiecewiseCurve& pc, const Feet& feet,
                                    double sigma, const FitSplineOptions& o);

/// The knots of c with every hole (a stretch without measured points q longer than
/// `factor` median spacings) holding no more than its bridge needs: one span per 30
/// degrees of turning across it, at least two. Points of weight 0 do not count.
std::vector<double> bridge_holes(const BSpline& c, const Feet& feet, const Points& q,
                                 const std::vector<double>& w, double factor, int degree);

/// Knots after splitting every span whose residuals hold more than noise.
std::vector<double> split_spans(const BSpline& c, const Feet& f, const std::vector<double>& w, double sigma,
                                const FitSplineOptions& o);

/// A curve with the feet and weights of the measured points on it.
struct Refinement {
  BSpline curve;
  detail::PiecewiseCurve pc;  // curve as polynomials, for the steps that evaluate it next
  Feet feet;
  std::vector<double> weights;
  double rms = 0;
  int iterations = 0;
};

/// The measured points (outliers left out) in the order of their feet along the curve:
/// the foot parameters, and the chord from each foot to the next (the last to the first),
/// close to the arc for all but the holes.
struct Along {
  std::vector<std::size_t> points;
  std::vector<double> ts, chords;
};

Along along_curve(const Refinement& r);

/// The holes (result.gaps, max_gap, gap_start, gap_end) and the median spacing.
void measure_gaps(const Refinement& r, const Along& along, double gap_factor, FitSplineResult& result);

/// Two layers of points along the profile (result.layers, layers_length).
void measure_layers(const Refinement& r, const Along& along, const FitSplineOptions& o,
                    FitSplineResult& result);

/// True when the closed polyline p runs out and back alongside itself (a finger).
bool doubles_back(const Points& p);

/// section::self_intersects on curve c as polynomials (`pc`), which the fit has at hand.
bool self_intersects(const BSpline& c, const detail::PiecewiseCurve& pc);

/// True when two segments of the closed polyline p that are not neighbours cross.
bool polyline_crosses(const Points& p);

}  // namespace section::fit
