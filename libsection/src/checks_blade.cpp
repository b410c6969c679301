// SPDX-License-Identifier: GPL-3.0-or-later
// The blade check (check_blade): each section's values against the line through its
// neighbours along the blade.
#include "section/checks.h"

#include "detail/sampled_profile.h"
#include "section/error.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace section {

namespace {

// One value of the blade check: how to read it, compare it and the least jump flagged.
struct Quantity {
  Check check;
  double (*get)(const SectionParams&);
  bool angle;
  double (*least)(const SectionParams&, const BladeCheckOptions&);
};

const Quantity quantities[] = {
    {Check::jump_chord, [](const SectionParams& p) { return p.chord; }, false,
     [](const SectionParams& p, const BladeCheckOptions& o) { return o.length * p.chord; }},
    {Check::jump_thickness, [](const SectionParams& p) { return p.max_thickness; }, false,
     [](const SectionParams& p, const BladeCheckOptions& o) { return o.thickness * p.max_thickness; }},
    {Check::jump_stagger, [](const SectionParams& p) { return p.stagger; }, true,
     [](const SectionParams&, const BladeCheckOptions& o) { return o.angle; }},
    {Check::jump_inlet, [](const SectionParams& p) { return p.inlet_angle; }, true,
     [](const SectionParams&, const BladeCheckOptions& o) { return o.angle; }},
    {Check::jump_outlet, [](const SectionParams& p) { return p.outlet_angle; }, true,
     [](const SectionParams&, const BladeCheckOptions& o) { return o.angle; }},
    {Check::jump_camber, [](const SectionParams& p) { return p.camber_angle; }, true,
     [](const SectionParams&, const BladeCheckOptions& o) { return o.angle; }},
    {Check::jump_le_radius, [](const SectionParams& p) { return p.le_radius; }, false,
     [](const SectionParams& p, const BladeCheckOptions& o) { return o.radius * p.le_radius; }},
    {Check::jump_te_radius, [](const SectionParams& p) { return p.te_radius; }, false,
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
  std::vector<double> expected, residual, weight;
  for (const Quantity& q : quantities) {
    std::vector<std::size_t> active;
    for (std::size_t k : order)
      if (std::isfinite(q.get(sections[k].params))) active.push_back(k);
    const std::size_t m = active.size();
    if (m < least) continue;
    // The blade's own spread of residuals (median absolute, robust to the jumps themselves).
    residuals(sections, active, q, expected, residual, weight);
    std::vector<double> spread_of;
    for (std::size_t k = 0; k < m; ++k) spread_of.push_back(std::abs(residual[k]) * weight[k]);
    std::nth_element(spread_of.begin(), spread_of.begin() + m / 2, spread_of.end());
    const double spread = m >= 7 ? options.spread * 1.4826 * spread_of[m / 2] : 0.0;
    // The section departing most (against its limit) is flagged and left out, and the
    // others compared again: a jump drags its neighbours' residuals, never flags them.
    while (active.size() >= least) {
      residuals(sections, active, q, expected, residual, weight);
      std::size_t worst = 0;
      double worst_ratio = 0, worst_limit = 0;
      for (std::size_t k = 0; k < active.size(); ++k) {
        const double limit = std::max(q.least(sections[active[k]].params, options), spread);
        const double ratio = std::abs(residual[k]) * weight[k] / std::max(limit, 1e-300);
        if (ratio > worst_ratio) worst_ratio = ratio, worst = k, worst_limit = limit / weight[k];
      }
      if (!(worst_ratio > 1)) break;
      out.push_back(
          {active[worst], q.check, q.get(sections[active[worst]].params), expected[worst], worst_limit});
      active.erase(active.begin() + static_cast<long>(worst));
    }
  }
  std::stable_sort(out.begin(), out.end(), [](const Jump& a, const Jump& b) { return a.index < b.index; });
  return out;
}

}  // namespace section
