// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The stages after slice run in process on a stream, each stage's output read back from its
// text as the next tool reads it: for the tests that run the whole pipe.
#include "section/io/stream.h"
#include "section/pipe/camber_stream.h"
#include "section/pipe/fit_spline_stream.h"
#include "section/pipe/slice_stream.h"
#include "section/pipe/smooth_stream.h"
#include "section/slice.h"

#include <stdexcept>
#include <vector>

namespace section::test {

/// `stream` (slice's) through smooth, fitspline and camber with their default options.
inline Stream after_slice(const Stream& stream) {
  Stream s = parse_stream(format_stream(stream), "slice");
  smooth_stream(s);
  s = parse_stream(format_stream(s), "smooth");
  fit_spline_stream(s);
  s = parse_stream(format_stream(s), "fitspline");
  camber_stream(s);
  return parse_stream(format_stream(s), "camber");
}

/// The params table of a plain profile's points (one section) through the whole pipe.
inline Table profile_params(const std::vector<Eigen::Vector2d>& pts) {
  Cloud cloud;
  for (const Eigen::Vector2d& p : pts) cloud.points.emplace_back(p.x(), p.y(), 0.0);
  const SliceResult r = slice_rows(cloud, {0, 0, 1});
  const Stream s = after_slice(to_stream(r, "test", "mm"));
  const Table* params = s.find("params");
  if (!params || params->rows() != 1) throw std::runtime_error("profile_params: no single params row");
  return *params;
}

}  // namespace section::test
