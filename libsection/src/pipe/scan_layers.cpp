// SPDX-License-Identifier: GPL-3.0-or-later
// Views merged with a misregistration: one view's points lie shifted in every section they
// reach, but a section shows two layers only where its views overlap closely enough to
// tell them apart. On the generated turbine scanned in two views 15 um apart
// (evaluate_pipeline --misregistration 0.015 --seeds 40), 332 of 360 sections showed the
// layers; the other 28 carried max thicknesses 11-16 um off with no flag covering them.
// Without a misregistration, 1 section in 1 458 shows layers (noise running high).
#include "pipe/camber_issues.h"
#include "section/checks.h"
#include "section/error.h"
#include "section/io/stream.h"
#include "section/pipe/camber_stream.h"
#include "section/pipe/schema.h"
#include "section/units.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

namespace section {

namespace {

// The median of the layers' distances the fits of loop 0 report (0 when none).
double median_separation(const std::vector<Stream*>& parts) {
  std::vector<double> apart;
  for (const Stream* s : parts) {
    const Table* fits = schema::splines.find(*s);
    if (!fits) continue;
    const long loop = fits->find_column("loop"), layers = fits->find_column("layers");
    if (loop < 0 || layers < 0) continue;
    for (std::size_t r = 0; r < fits->rows(); ++r)
      if (fits->at(r, std::size_t(loop)) == 0 && fits->at(r, std::size_t(layers)) > 0)
        apart.push_back(fits->at(r, std::size_t(layers)));
  }
  if (apart.empty()) return 0;
  const auto middle = apart.begin() + std::ptrdiff_t(apart.size() / 2);
  std::nth_element(apart.begin(), middle, apart.end());
  return *middle;
}

}  // namespace

int flag_scan_layers(const std::vector<Stream*>& parts) {
  for (const Stream* s : parts)
    if (!s) throw Error("pipe: a stream to check is missing (a null pointer)");
  int sections = 0, layered = 0;
  for (const Stream* s : parts) {
    const Table* params = s->find(schema::params.name);
    if (!params || params->rows() == 0) continue;
    const std::size_t flags = params->column("flags");
    for (std::size_t r = 0; r < params->rows(); ++r) {
      const CheckBits bits = flags_mask(params->at(r, flags));
      if (bits & bit(Check::airfoil)) continue;  // a platform's cut is no blade section
      ++sections;
      if (bits & bit(Check::layers)) ++layered;
    }
  }
  // Two sections at least, and half of them: chance (noise) gives one in a thousand.
  if (layered < 2 || 2 * layered < sections || layered == sections) return 0;
  const double apart = median_separation(parts);
  char text[512];
  std::snprintf(text, sizeof text,
                "its values fail check layers: %d of the %d sections of this scan lie in two layers%s "
                "(views merged with a misregistration): this one shows a single layer, but a view's "
                "shift moves its points alike where the views do not overlap, so its thickness may be "
                "off by up to the layers' distance, and its edges, chord, camber line and angles by more",
                layered, sections,
                apart > 0 ? (", a median " + format_length(apart) + " apart").c_str() : "");
  int flagged = 0;
  for (Stream* s : parts) {
    const std::size_t before = s->issues.size();
    pipe::flag_every_row(*s, Check::layers, text);
    flagged += int(s->issues.size() - before);
  }
  return flagged;
}

}  // namespace section
