// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file error.h
/// The one exception type libsection throws for bad input or failed geometry.
#include <stdexcept>
#include <string>

namespace section {

/// Thrown for bad user input (files, streams, options) and for geometry a stage cannot
/// handle. The message starts with the component and says what is wrong and where, e.g.
/// `smooth: section 3 has 4 points, at least 5 are needed` or
/// `read_cloud: blade.xyz:17: expected a number in column 2, found 'abc'`.
class Error : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

}  // namespace section
