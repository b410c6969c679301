// SPDX-License-Identifier: GPL-3.0-or-later
// fit_spline on rows sparser than the first curve's spans (a CMM row, a coarse CFD grid):
// dense at the edges, a point every few mm on the flanks.
#include "section/checks.h"
#include "section/extras/generate.h"
#include "section/fit_spline.h"
#include "section/io/stream.h"
#include "section/pipe/camber_stream.h"
#include "truth_error.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace {

// Points of `truth` 0.05 mm apart within 4 mm of either edge point, `flank` mm apart
// between, each moved along the exact normal by Gaussian noise of `sigma` mm.
std::vector<Eigen::Vector2d> sparse_row(const section::SectionTruth& truth, double flank, double sigma,
                                        unsigned seed) {
  std::vector<Eigen::Vector2d> points;
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0, sigma);
  double next = 0;  // the arc length of the next point
  for (std::size_t i = 0; i < truth.profile.size(); ++i) {
    const double s = truth.profile_s[i];
    if (s < next) continue;
    const double from_edge = std::min({s, std::abs(s - truth.te_s), truth.perimeter - s});
    points.push_back(truth.profile[i] + noise(rng) * truth.profile_normal[i]);
    next = s + (from_edge < 4 ? 0.05 : flank);
  }
  return points;
}

}  // namespace

TEST_CASE("fit_spline: flanks measured sparser than the first curve's spans fit, their thickness within 5 um",
          "[fit_spline]") {
  // Flank points 2.5 mm apart, 1 um of noise. The first curve's 2 mm spans used to leave
  // spans without a point, shaped by the fairness term alone: its curve crossed itself and
  // the fit was refused ("too sparse where the profile turns") on every seed. With a span
  // held by at least min_span_points points wherever they are sparse, it fits, and the
  // thickness, measured mid-chord where the points are sparsest, is within the 5 um target.
  const std::vector<std::pair<std::string, section::SectionDesign>> designs = {
      {"compressor z 30", section::compressor_blade().at(30)},
      {"compressor z 54", section::compressor_blade().at(54)},
      {"turbine z 30", section::turbine_blade().at(30)}};
  for (const auto& [name, design] : designs) {
    const section::SectionTruth truth = section::section_truth(design, 40000);
    for (unsigned seed : {1u, 2u, 3u}) {
      const std::vector<Eigen::Vector2d> points = sparse_row(truth, 2.5, 0.001, seed);
      INFO(name << " seed " << seed << ", " << points.size() << " points");
      section::FitSplineResult fit;
      REQUIRE_NOTHROW(fit = section::fit_spline(points, points));
      const auto [rms, worst] = truth_error(fit.spline, truth);
      INFO("curve to truth: rms " << rms << " worst " << worst);
      CHECK(rms < 0.003);
      CHECK(worst < 0.015);
      section::Stream s = section::profile_stream(fit.spline, fit.rms, points);
      section::camber_stream(s);
      const section::Table& params = s.get("params", "test");
      REQUIRE(params.rows() == 1);
      const double thickness = params.at(0, params.column("max_thickness"));
      INFO("max thickness " << thickness << " against " << truth.max_thickness);
      CHECK(std::abs(thickness - truth.max_thickness) < 0.005);
    }
  }
}

TEST_CASE("fit_spline: flanks measured more than 1.5 first spans apart are refused, not measured",
          "[fit_spline]") {
  // Merged spans over points 3.9 mm apart fitted, and a thin compressor section's thickness
  // came out 8-9 um off with nothing flagged (0.5 um of noise): gaps over 1.5 initial_span
  // keep the first curve's uniform knots, which cross themselves there, and the fit is
  // refused as it was before spans were merged, naming the widest gap.
  const section::SectionTruth truth = section::section_truth(section::compressor_blade().at(54), 40000);
  for (unsigned seed : {1u, 2u, 3u}) {
    const std::vector<Eigen::Vector2d> points = sparse_row(truth, 3.9, 0.0005, seed);
    INFO("seed " << seed);
    CHECK_THROWS_WITH(section::fit_spline(points, points), Catch::Contains("too sparse"));
  }
}
