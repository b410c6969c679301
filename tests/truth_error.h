// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// How far a fitted curve lies from a generated section's exact profile.
#include "section/bspline.h"
#include "section/extras/generate.h"

#include <algorithm>
#include <cmath>
#include <utility>

/// RMS and largest distance of the fitted curve (8000 samples) to the true profile.
inline std::pair<double, double> truth_error(const section::BSpline& c, const section::SectionTruth& t) {
  double ss = 0, worst = 0;
  const auto s = section::sample(c, 8000);
  for (const auto& p : s) {
    const double d = section::locate(t, p).distance;
    ss += d * d;
    worst = std::max(worst, d);
  }
  return {std::sqrt(ss / s.size()), worst};
}
