// SPDX-License-Identifier: GPL-3.0-or-later
#include "detail/extent_tails.h"

#include <algorithm>
#include <cmath>
#include <functional>

namespace section::detail {

namespace {

// The outermost values of a tail (ascending from its end for `low`) beyond its widest gap
// among the first `cap + 1`: how many, and the gap (0: none).
std::pair<std::size_t, double> widest_gap(const std::vector<double>& tail, std::size_t cap) {
  std::size_t cut = 0;
  double widest = 0;
  for (std::size_t c = 1; c <= cap && c < tail.size(); ++c) {
    const double gap = std::abs(tail[c] - tail[c - 1]);
    if (gap > widest) widest = gap, cut = c;
  }
  return {cut, widest};
}

// The `keep` outermost of `values` (ascending for the low side), sorted outermost first.
std::vector<double> outermost(std::vector<double> values, std::size_t keep, bool high) {
  const auto before = [high](double a, double b) { return high ? a > b : a < b; };
  if (values.size() > keep) {
    std::nth_element(values.begin(), values.begin() + long(keep), values.end(), before);
    values.resize(keep);
  }
  std::sort(values.begin(), values.end(), before);
  return values;
}

}  // namespace

void Tails::push(std::vector<double>& buffer, double v, double& limit, bool high) {
  buffer.push_back(v);
  if (buffer.size() < 64 * keep_) return;
  // Cut back to the outermost `keep`: later values must beat the innermost of them.
  buffer = outermost(std::move(buffer), keep_, high);
  limit = buffer.back();
}

void Tails::merge(const Tails& other) {
  for (double v : other.low_) take_low(v);
  for (double v : other.high_) take_high(v);
  if (other.inner_low_ < std::numeric_limits<double>::infinity()) take_low(other.inner_low_);
  if (other.inner_high_ > -std::numeric_limits<double>::infinity()) take_high(other.inner_high_);
  count_ += other.count_;
}

std::vector<double> Tails::low() const {
  std::vector<double> v = low_;
  if (inner_low_ < std::numeric_limits<double>::infinity()) v.push_back(inner_low_);
  return outermost(std::move(v), keep_, false);
}

std::vector<double> Tails::high() const {
  std::vector<double> v = high_;
  if (inner_high_ > -std::numeric_limits<double>::infinity()) v.push_back(inner_high_);
  return outermost(std::move(v), keep_, true);
}

PartExtent trimmed_extent(const Tails& t) {
  PartExtent e;
  const std::vector<double> low = t.low(), high = t.high();
  if (low.empty()) return e;
  e.lowest = e.lo = low.front();
  e.highest = e.hi = high.front();
  // Each end's values as far as they are known (below the screen's limit and the next).
  const std::size_t share = t.count() / 1000;
  const auto [below, gap_below] = widest_gap(low, std::min(low.size() - 1, share));
  const auto [above, gap_above] = widest_gap(high, std::min(high.size() - 1, share));
  const double rest = high[above] - low[below];
  if (below > 0 && gap_below > 0.05 * rest) e.lo = low[below], e.strays += below;
  if (above > 0 && gap_above > 0.05 * rest) e.hi = high[above], e.strays += above;
  return e;
}

}  // namespace section::detail
