// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The extent of values (points' coordinates, or their offsets along a normal) without the
// few far from the rest: a scan's stray points (a reflection, dust, a bit of fixture a
// metre off) otherwise set the extent the units are guessed from and the --count planes
// are spread over.
#include "section/slice.h"

#include <cstddef>
#include <vector>

namespace section::detail {

/// The lowest and highest values seen, at most `keep` of each, and how many were seen.
class Tails {
public:
  explicit Tails(std::size_t keep = 64) : keep_(keep) {}
  void add(double v);
  /// A block of values: those beyond the tails' thresholds only are looked at one by one.
  void add(const double* v, std::size_t n);
  void merge(const Tails& other);
  std::size_t count() const { return count_; }
  const std::vector<double>& low() const { return low_; }    ///< ascending
  const std::vector<double>& high() const { return high_; }  ///< descending

private:
  std::size_t keep_;
  std::size_t count_ = 0;
  std::vector<double> low_, high_;
};

/// The extent of the values seen by `t` without those far from the rest: at each end, the
/// values beyond the widest gap among the outermost min(keep - 1, count / 1000) of them,
/// when that gap is over 5 % of the rest's extent. A scan's own values lie close together
/// (a blade's offsets along its span, its rows a few per cent of the span apart hold more
/// than 1 in 1 000 of its points each). No values: all 0.
PartExtent trimmed_extent(const Tails& t);

}  // namespace section::detail
