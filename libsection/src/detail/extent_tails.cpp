// SPDX-License-Identifier: GPL-3.0-or-later
#include "detail/extent_tails.h"

#include <algorithm>
#include <cmath>
#include <functional>

namespace section::detail {

namespace {

// Inserts v into `tail`, kept sorted by `before` and at most `keep` long.
template <class Before>
void insert(std::vector<double>& tail, std::size_t keep, double v, Before before) {
  if (tail.size() == keep && !before(v, tail.back())) return;
  tail.insert(std::upper_bound(tail.begin(), tail.end(), v, before), v);
  if (tail.size() > keep) tail.pop_back();
}

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

}  // namespace

void Tails::add(double v) {
  if (std::isnan(v)) return;
  ++count_;
  insert(low_, keep_, v, std::less<double>());
  insert(high_, keep_, v, std::greater<double>());
}

void Tails::add(const double* v, std::size_t n) {
  if (n == 0) return;
  const double* lo = std::min_element(v, v + n);
  const double* hi = std::max_element(v, v + n);
  const bool low_full = low_.size() == keep_, high_full = high_.size() == keep_;
  if (low_full && high_full && !(*lo < low_.back()) && !(*hi > high_.back())) {
    for (std::size_t i = 0; i < n; ++i) count_ += !std::isnan(v[i]);
    return;
  }
  for (std::size_t i = 0; i < n; ++i) add(v[i]);
}

void Tails::merge(const Tails& other) {
  const std::size_t seen = count_ + other.count_;
  for (double v : other.low_) insert(low_, keep_, v, std::less<double>());
  for (double v : other.high_) insert(high_, keep_, v, std::greater<double>());
  count_ = seen;
}

PartExtent trimmed_extent(const Tails& t) {
  PartExtent e;
  if (t.low().empty()) return e;
  e.lowest = e.lo = t.low().front();
  e.highest = e.hi = t.high().front();
  const std::size_t cap = std::min(t.low().size() - 1, t.count() / 1000);
  if (cap == 0) return e;
  const auto [below, gap_below] = widest_gap(t.low(), cap);
  const auto [above, gap_above] = widest_gap(t.high(), cap);
  const double rest = t.high()[above] - t.low()[below];
  if (below > 0 && gap_below > 0.05 * rest) e.lo = t.low()[below], e.strays += below;
  if (above > 0 && gap_above > 0.05 * rest) e.hi = t.high()[above], e.strays += above;
  return e;
}

}  // namespace section::detail
