// SPDX-License-Identifier: GPL-3.0-or-later
// The blade check (check_blade): each section's values against the line through its
// neighbours along the blade.
#include "section/checks.h"

#include "detail/sampled_profile.h"
#include "section/error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <vector>

namespace section {

namespace {

// One value of the blade check: how to read it, compare it and the least jump flagged.
struct Quantity {
  Check check;
  const char* column;  // in the params table
  double (*get)(const SectionParams&);
  bool angle;
  double (*least)(const SectionParams&, const BladeCheckOptions&);
};

const Quantity quantities[] = {
    {Check::jump_chord, "chord", [](const SectionParams& p) { return p.chord; }, false,
     [](const SectionParams& p, const BladeCheckOptions& o) { return o.length * p.chord; }},
    {Check::jump_thickness, "max_thickness", [](const SectionParams& p) { return p.max_thickness; }, false,
     [](const SectionParams& p, const BladeCheckOptions& o) { return o.thickness * p.max_thickness; }},
    {Check::jump_stagger, "stagger", [](const SectionParams& p) { return p.stagger; }, true,
     [](const SectionParams&, const BladeCheckOptions& o) { return o.angle; }},
    {Check::jump_inlet, "inlet_angle", [](const SectionParams& p) { return p.inlet_angle; }, true,
     [](const SectionParams&, const BladeCheckOptions& o) { return o.angle; }},
    {Check::jump_outlet, "outlet_angle", [](const SectionParams& p) { return p.outlet_angle; }, true,
     [](const SectionParams&, const BladeCheckOptions& o) { return o.angle; }},
    {Check::jump_camber, "camber_angle", [](const SectionParams& p) { return p.camber_angle; }, true,
     [](const SectionParams&, const BladeCheckOptions& o) { return o.angle; }},
    {Check::jump_le_radius, "le_radius", [](const SectionParams& p) { return p.le_radius; }, false,
     [](const SectionParams& p, const BladeCheckOptions& o) { return o.radius * p.le_radius; }},
    {Check::jump_te_radius, "te_radius", [](const SectionParams& p) { return p.te_radius; }, false,
     [](const SectionParams& p, const BladeCheckOptions& o) { return o.radius * p.te_radius; }},
};

// The value expected at height h from (h1, v1) and (h2, v2): the line through them (angles
// unwrapped about v1).
double line_at(double h, double h1, double v1, double h2, double v2, bool angle) {
  if (angle) v2 = v1 + detail::wrap_degrees(v2 - v1);
  if (!(std::abs(h2 - h1) > 0)) return 0.5 * (v1 + v2);
  return v1 + (v2 - v1) * (h - h1) / (h2 - h1);
}

// Residual of each active section from the line through its two active neighbours (at
// an end, the two nearest: extrapolated, so its weight is halved), by height order.
void residuals(const std::vector<BladeSection>& sections, const std::vector<std::size_t>& active,
               const Quantity& q, std::vector<double>& expected, std::vector<double>& residual,
               std::vector<double>& weight) {
  const std::size_t n = active.size();
  expected.assign(n, 0);
  residual.assign(n, 0);
  weight.assign(n, 1);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t a = k == 0 ? 1 : k == n - 1 ? n - 3 : k - 1;
    const std::size_t b = k == 0 ? 2 : k == n - 1 ? n - 2 : k + 1;
    const BladeSection &s = sections[active[k]], &sa = sections[active[a]], &sb = sections[active[b]];
    // At an end, the line is followed no farther out than twice the neighbours' spacing: a
    // plane far from the others (a stream's origin edited by 1e14) gave a radius of -4.6e11.
    double h = s.height;
    if (k == 0 || k == n - 1) {
      const BladeSection& nearer = k == 0 ? sa : sb;
      const double reach = 2 * std::abs(sb.height - sa.height);
      h = std::clamp(h, nearer.height - reach, nearer.height + reach);
    }
    expected[k] = line_at(h, sa.height, q.get(sa.params), sb.height, q.get(sb.params), q.angle);
    // A length or radius is never negative: neither is what its neighbours give.
    if (!q.angle) expected[k] = std::max(expected[k], 0.0);
    residual[k] =
        q.angle ? detail::wrap_degrees(q.get(s.params) - expected[k]) : q.get(s.params) - expected[k];
    if (k == 0 || k == n - 1) weight[k] = 0.5;
  }
}

// Each active section's departure from its neighbours' line against its limit (the
// quantity's least jump or the blade's spread, doubled at an end), and that limit.
struct Ratios {
  std::vector<double> expected, ratio, limit;
  Ratios(const std::vector<BladeSection>& sections, const std::vector<std::size_t>& active, const Quantity& q,
         double spread, const BladeCheckOptions& options) {
    std::vector<double> residual, weight;
    residuals(sections, active, q, expected, residual, weight);
    for (std::size_t k = 0; k < active.size(); ++k) {
      const double least = std::max(q.least(sections[active[k]].params, options), spread);
      ratio.push_back(std::abs(residual[k]) * weight[k] / std::max(least, 1e-300));
      limit.push_back(least / weight[k]);
    }
  }
};

}  // namespace

std::vector<Jump> check_blade(const std::vector<BladeSection>& sections, const BladeCheckOptions& options) {
  for (double v : {options.angle, options.length, options.radius, options.thickness, options.spread})
    if (!(v >= 0) || !std::isfinite(v)) throw Error("checks: a blade check option is negative or not finite");
  std::vector<Jump> out;
  const std::size_t n = sections.size();
  const std::size_t least = static_cast<std::size_t>(std::max(options.min_sections, 3));
  if (n < least) return out;
  // A height or value that is not a number stays out of the comparisons (it ordered the
  // sections at random, and as a neighbour it hid a 50 % jump of the chord).
  std::vector<std::size_t> order;
  for (std::size_t k = 0; k < n; ++k)
    if (std::isfinite(sections[k].height)) order.push_back(k);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return sections[a].height < sections[b].height; });
  for (const Quantity& q : quantities) {
    std::vector<std::size_t> active;
    for (std::size_t k : order)
      if (std::isfinite(q.get(sections[k].params))) active.push_back(k);
    const std::size_t m = active.size();
    if (m < least) continue;
    // The blade's own spread of residuals (median absolute, robust to the jumps themselves).
    std::vector<double> expected, residual, weight;
    residuals(sections, active, q, expected, residual, weight);
    std::vector<double> spread_of;
    for (std::size_t k = 0; k < m; ++k) spread_of.push_back(std::abs(residual[k]) * weight[k]);
    std::nth_element(spread_of.begin(), spread_of.begin() + m / 2, spread_of.end());
    const double spread = m >= 7 ? options.spread * 1.4826 * spread_of[m / 2] : 0.0;
    // The section departing most (against its limit) is flagged and left out, and the
    // others compared again: a jump drags its neighbours' residuals, never flags them.
    // Of several beyond their limits, the one whose leaving out leaves the others
    // departing least goes first, then one its own section's checks flag. A value they
    // flag is left out unflagged where that puts the others in line although it is within
    // its own limit (a quarter of an edge radius 1.8 times too large): a 72 mm LE radius
    // at a blade's end (a plane tilted past the tip) made the right radii of two sections
    // beside it jump, a 0.445 mm TE bridged over a hole those of three.
    while (active.size() >= least) {
      const Ratios now(sections, active, q, spread, options);
      std::vector<std::size_t> beyond;
      for (std::size_t k = 0; k < active.size(); ++k)
        if (now.ratio[k] > 1) beyond.push_back(k);
      if (beyond.empty()) break;
      // Leaving one out needs `least` sections after it.
      const bool weigh = active.size() > least;
      std::vector<std::size_t> candidates = beyond;
      std::vector<char> doubted(active.size(), 0);
      for (std::size_t k = 0; k < active.size(); ++k) {
        doubted[k] = checks_flagging(sections[active[k]].flags, q.column) != 0;
        if (weigh && doubted[k] && !(now.ratio[k] > 1)) candidates.push_back(k);
      }
      const auto rank = [&](std::size_t i) {
        return std::make_tuple(now.ratio[i] > 1, doubted[i], now.ratio[i]);
      };
      // The first by rank are weighed (each costs a pass over the sections; a stack of
      // thousands with many values flipped must not cost their square for each).
      std::stable_sort(candidates.begin(), candidates.end(),
                       [&](std::size_t a, std::size_t b) { return rank(a) > rank(b); });
      if (candidates.size() > 16) candidates.resize(16);
      std::size_t worst = candidates[0];
      double worst_left = std::numeric_limits<double>::infinity();
      for (std::size_t k : candidates) {
        double left = 0;  // the largest ratio of the others without k
        if (weigh && candidates.size() > 1) {
          std::vector<std::size_t> rest = active;
          rest.erase(rest.begin() + static_cast<long>(k));
          const Ratios without(sections, rest, q, spread, options);
          left = *std::max_element(without.ratio.begin(), without.ratio.end());
        }
        if (left < worst_left) worst = k, worst_left = left;  // on a tie, the first by rank
      }
      if (now.ratio[worst] > 1)
        out.push_back({active[worst], q.check, q.get(sections[active[worst]].params), now.expected[worst],
                       now.limit[worst]});
      active.erase(active.begin() + static_cast<long>(worst));
    }
  }
  std::stable_sort(out.begin(), out.end(), [](const Jump& a, const Jump& b) { return a.index < b.index; });
  return out;
}

}  // namespace section
