// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The stages after slice run in process on a stream, each stage's output read back from its
// text as the next tool reads it: for the tests that run the whole pipe.
#include "section/io/stream.h"
#include "section/pipe/camber_stream.h"
#include "section/pipe/fit_spline_stream.h"
#include "section/pipe/smooth_stream.h"

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

}  // namespace section::test
