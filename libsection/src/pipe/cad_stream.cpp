// SPDX-License-Identifier: GPL-3.0-or-later
// The curves of a stream for the CAD writers.
#include "section/pipe/cad_stream.h"

#include "section/pipe/fit_spline_stream.h"
#include "section/pipe/schema.h"

#include <map>

namespace section {

std::vector<CadCurve> cad_curves(const Stream& stream, bool all_loops) {
  const std::map<int, Frame> frame = schema::frames.find(stream) ? frames(stream) : std::map<int, Frame>{};
  std::vector<CadCurve> out;
  for (const auto& [key, spline] : splines(stream)) {
    if (!all_loops && key.second != 0) continue;
    const auto f = frame.find(key.first);
    out.push_back({key.first, key.second, f == frame.end() ? Frame{} : f->second, spline});
  }
  return out;
}

}  // namespace section
