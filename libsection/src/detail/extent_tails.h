// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The extent of values (points' coordinates, or their offsets along a normal) without the
// few far from the rest: a scan's stray points (a reflection, dust, a bit of fixture a
// metre off) otherwise set the extent the units are guessed from and the --count planes
// are spread over.
#include "section/slice.h"

#include <cstddef>
#include <limits>
#include <vector>

namespace section::detail {

/// The lowest and highest values seen, `keep` of each, and how many were seen. Values
/// beyond the current limits are buffered and the buffer cut back to `keep` when full; the
/// rest only move the innermost of them. Limits given to start with screen the values (a
/// first look's extent, widened): beyond them a scan has only its strays and a few of its
/// own extremes, and a value costs two compares; without them (the default) a scan
/// written in layers beats the high limit with nearly every value.
class Tails {
public:
  explicit Tails(std::size_t keep = 64, double low_limit = std::numeric_limits<double>::infinity(),
                 double high_limit = -std::numeric_limits<double>::infinity())
      : keep_(keep), low_limit_(low_limit), high_limit_(high_limit) {}
  void add(double v) {
    if (v != v) return;  // NaN
    ++count_;
    take_low(v);
    take_high(v);
  }
  void add(const double* v, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) add(v[i]);
  }
  /// A block of finite values whose least and largest are known: one test when it lies
  /// within the limits.
  void add(const double* v, std::size_t n, double least, double largest) {
    if (!(least >= low_limit_ && largest <= high_limit_)) return add(v, n);
    count_ += n;
    inner_low_ = least < inner_low_ ? least : inner_low_;
    inner_high_ = largest > inner_high_ ? largest : inner_high_;
  }
  void merge(const Tails& other);
  std::size_t count() const { return count_; }
  /// The lowest values, ascending: the `keep` lowest, or all those below the limit and the
  /// lowest of the others (the sequence of the lowest, as far as it is known).
  std::vector<double> low() const;
  std::vector<double> high() const;  ///< as low, descending

private:
  void take_low(double v) {
    if (v < low_limit_)
      push(low_, v, low_limit_, false);
    else if (v < inner_low_)
      inner_low_ = v;
  }
  void take_high(double v) {
    if (v > high_limit_)
      push(high_, v, high_limit_, true);
    else if (v > inner_high_)
      inner_high_ = v;
  }
  void push(std::vector<double>& buffer, double v, double& limit, bool high);
  std::size_t keep_;
  std::size_t count_ = 0;
  double low_limit_, high_limit_;
  std::vector<double> low_, high_;  // every value below low_limit_, above high_limit_
  double inner_low_ = std::numeric_limits<double>::infinity();    // the lowest of the others
  double inner_high_ = -std::numeric_limits<double>::infinity();  // the highest of the others
};

/// The extent of the values seen by `t` without those far from the rest: at each end, the
/// values beyond the widest gap among the outermost min(keep - 1, count / 1000) of them,
/// when that gap is over 5 % of the rest's extent. A scan's own values lie close together
/// (a blade's offsets along its span, its rows a few per cent of the span apart hold more
/// than 1 in 1 000 of its points each). No values: all 0.
PartExtent trimmed_extent(const Tails& t);

}  // namespace section::detail
