// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the morphology step's raster transforms (src/raster.h) on spans with gaps: the
// distance transform against the distances to the seeds counted cell by cell, the
// bottleneck against widest paths relaxed cell by cell.
#include "bottleneck.h"
#include "raster.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace {

using section::morph::Buffer;
using section::morph::Raster;

constexpr double pi = 3.14159265358979323846;

// Seed cells along a circle of radius 50 cells about (80, 80), about every 2.5 cells, open
// over 20 degrees (an interior reached through a gap 17 cells wide).
std::vector<std::uint8_t> ring_seeds(const Raster& r) {
  std::vector<std::uint8_t> seed(r.size(), 0);
  for (double t = 0; t < 2 * pi; t += 2.5 / 50) {
    if (t > 1.0 && t < 1.0 + 20 * pi / 180) continue;
    const int i = int(std::lround(80 + 50 * std::cos(t))), j = int(std::lround(80 + 50 * std::sin(t)));
    seed[std::size_t(j) * r.w + i] = 1;
  }
  return seed;
}

}  // namespace

TEST_CASE("raster: transforms on spans with gaps equal those counted cell by cell", "[raster]") {
  Raster r;
  r.w = r.h = 161;
  const std::vector<std::uint8_t> seed = ring_seeds(r);
  const int reach = 12, cap = (reach + 1) * (reach + 1);
  std::vector<std::size_t> cells;
  std::vector<int> first(r.h, r.w), last(r.h, -1);
  for (std::size_t c = 0; c < r.size(); ++c) {
    if (!seed[c]) continue;
    cells.push_back(c);
    const int i = int(c % r.w), j = int(c / r.w);
    first[j] = std::min(first[j], i);
    last[j] = std::max(last[j], i);
  }
  // The squared distance of every cell to the nearest seed, clamped to cap.
  std::vector<int> truth(r.size(), cap);
  for (std::size_t c = 0; c < r.size(); ++c)
    for (const std::size_t s : cells) {
      const int dx = int(c % r.w) - int(s % r.w), dy = int(c / r.w) - int(s / r.w);
      truth[c] = std::min(truth[c], dx * dx + dy * dy);
    }

  const section::morph::SeedGaps gaps = section::morph::seed_gaps(r, cells, reach);
  const section::morph::Spans spans = section::morph::spans_of(r, first, last, reach, &gaps);
  std::size_t in_gaps = 0;
  for (int j = 0; j < r.h; ++j)
    for (int i = 0; i < r.w; ++i) {
      const int t = truth[std::size_t(j) * r.w + i];
      const bool on = i >= spans.lo[j] && i <= spans.hi[j];
      const bool gap = spans.has_gap(j) && i >= spans.gap_lo[j] && i <= spans.gap_hi[j];
      if (t < cap) REQUIRE((on && !gap));  // every cell within reach is computed
      if (gap) REQUIRE(t == cap);
      in_gaps += gap;
    }
  // The ring's interior, farther than the reach from the ring (radius 37 and less).
  CHECK(in_gaps > std::size_t(0.8 * pi * 37 * 37));

  section::morph::Scratch scratch;
  Buffer<int> nearest;
  const Buffer<int> d2 = section::morph::distance_transform(r, seed, cap, 0, nearest, scratch, &spans);
  for (std::size_t c = 0; c < r.size(); ++c) {
    REQUIRE(d2[c] == truth[c]);
    if (truth[c] == cap) continue;
    const int s = nearest[c];
    REQUIRE(s >= 0);
    REQUIRE(seed[std::size_t(s)]);
    const int dx = int(c % r.w) - s % r.w, dy = int(c / r.w) - s / r.w;
    REQUIRE(dx * dx + dy * dy == truth[c]);
  }

  // Widest paths from the border, relaxed until nothing changes.
  std::vector<int> widest(r.size(), -1);
  for (int j = 0; j < r.h; ++j)
    for (int i = 0; i < r.w; ++i)
      if (i == 0 || j == 0 || i == r.w - 1 || j == r.h - 1)
        widest[std::size_t(j) * r.w + i] = truth[std::size_t(j) * r.w + i];
  for (bool changed = true; changed;) {
    changed = false;
    for (int j = 1; j + 1 < r.h; ++j)
      for (int i = 1; i + 1 < r.w; ++i) {
        const std::size_t c = std::size_t(j) * r.w + i;
        const int best = std::max({widest[c - 1], widest[c + 1], widest[c - r.w], widest[c + r.w]});
        const int b = std::min(best, truth[c]);
        if (b > widest[c]) widest[c] = b, changed = true;
      }
  }
  Buffer<int> next;
  const Buffer<int> b2 = section::morph::bottleneck(r, d2, cap, next, &spans);
  for (std::size_t c = 0; c < r.size(); ++c) REQUIRE(b2[c] == widest[c]);
  // The interior opens through the gap, 17.4 cells wide and up to a seed step (2.5 cells)
  // more: its cells are reached at the square of half that.
  const std::size_t centre = std::size_t(80) * r.w + 80;
  CHECK(b2[centre] >= 8 * 8);
  CHECK(b2[centre] <= 10 * 10);
}
