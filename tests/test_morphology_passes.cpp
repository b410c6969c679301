// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of order_section's passes (section/morphology.h): the loops a later pass finds
// beside an earlier pass's.
#include "section/morphology.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

using section::MorphologyResult;
using section::order_section;
using Vec = Eigen::Vector2d;
using Points = std::vector<Vec>;

namespace {
constexpr double pi = 3.14159265358979323846;
}  // namespace

TEST_CASE("morphology: a later pass finding several loops beside an earlier one", "[morphology]") {
  // A dense circle, and two circles of short dashes 18 mm apart: the first pass closes the
  // dense one, a second pass (its reach widened) the dashed ones. Each of the second pass's
  // loops is tested against the first pass's (strays_beside), which were held by pointers
  // into the list the found loops are appended to: the first append moved them, and the
  // second loop's test read freed memory (std::length_error here; a comma-decimal file read
  // as garbage said "out of memory").
  Points points;
  // A circle of `dash` points 0.05 apart every `spacing` along it.
  const auto circle = [&](const Vec& c, double r, double spacing, int dash) {
    const int n = int(2 * pi * r / spacing);
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < dash; ++k) {
        const double t = 2 * pi * i / n + 0.05 * k / r;
        points.push_back(c + r * Vec(std::cos(t), std::sin(t)));
      }
  };
  circle({0, 0}, 30, 0.05, 1);
  circle({120, 0}, 40, 18, 6);
  circle({240, 0}, 40, 18, 6);
  const MorphologyResult m = order_section(points);
  REQUIRE(m.loops.size() == 3);
  int dense = 0;
  for (const auto& loop : m.loops) dense += std::abs(loop.area / (pi * 900) - 1) < 0.02;
  CHECK(dense == 1);
}
