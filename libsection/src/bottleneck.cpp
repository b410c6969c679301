// SPDX-License-Identifier: GPL-3.0-or-later
#include "bottleneck.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace section::morph {

namespace {

/// Sets b2 to -1 (not yet reached) on the spans, -2 on their gaps, and to cap off them,
/// their bottleneck (their row leads to the border through cells at cap), and seeds each
/// span cell next to an off-span one with its own d2, like a border cell.
template <class Seed>
void seed_spans(const Raster& r, const Spans& spans, int cap, Buffer<int>& b2, const Seed& seed) {
  for (int j = 0; j < r.h; ++j) {
    int* row = b2.data() + std::size_t(j) * r.w;
    const int lo = std::min(spans.lo[j], r.w), hi = std::max(spans.hi[j], lo - 1);
    std::fill(row, row + lo, cap);
    std::fill(row + lo, row + hi + 1, -1);
    std::fill(row + hi + 1, row + r.w, cap);
    if (spans.has_gap(j)) std::fill(row + spans.gap_lo[j], row + spans.gap_hi[j] + 1, -2);
  }
  for (int j = 0; j < r.h; ++j) {
    const int lo = spans.lo[j], hi = spans.hi[j];
    if (lo > hi) continue;
    seed(lo, j);
    seed(hi, j);
    // The cells whose neighbour above or below is off its row's span.
    for (const int k : {j - 1, j + 1})
      if (k >= 0 && k < r.h) each_beside_off_span(spans, j, k, [&](int i) { seed(i, j); });
  }
}

/// The bucket queue of bottleneck: each bucket is a stack threaded through `next` from
/// `head` (a cell enters one bucket, once; its entry is written before it is read). b2 is -1
/// at the cells not yet reached, -2 at the gap cells not yet reached. A gap's cells are all
/// at cap (d2): the first path into one reaches every gap cell 4-connected to it at its
/// level, and from them the span cells around, so they are filled by rows, without a visit
/// each.
struct Widest {
  const Raster& r;
  const Spans* spans;
  const int* d2;
  int* b2;
  int* next;
  std::int32_t* head;
  std::int32_t gaps = -1;                 // gap cells reached at this level, a stack through `next`
  std::vector<std::uint8_t> filled = {};  // per row: its gap filled
  std::vector<int> rows = {};             // gap rows filled, the cells around not yet reached

  void push(std::size_t c) {
    next[c] = head[b2[c]];
    head[b2[c]] = std::int32_t(c);
  }
  void reach(std::size_t e, int level) {
    if (b2[e] >= 0) return;
    b2[e] = std::min(level, d2[e]);
    push(e);
  }
  void fill(int j, int level) {
    int* row = b2 + std::size_t(j) * r.w;
    std::fill(row + spans->gap_lo[j], row + spans->gap_hi[j] + 1, level);
    filled[std::size_t(j)] = 1;
    rows.push_back(j);
  }
  void drain(int level);
  void fill_gaps(int level);
};

// Not inlined: a call in its loop nest (fill_gaps) would spill the loop's pointers to the
// stack (+40 % of bottleneck's instructions).
[[gnu::noinline]] void Widest::drain(int level) {
  int* const b = b2;
  int* const nx = next;
  std::int32_t* const hd = head;
  const int* const d = d2;
  std::int32_t g = gaps;
  const std::size_t size = r.size(), w = std::size_t(r.w);
  // Cell e, its b2 at *be (an address from the popped cell's: one load for the cells
  // already set, most of them), the level in a local (a store to next may alias b2).
  const auto step = [&](int* be, std::size_t e) {
    if (*be >= 0) return;
    if (*be == -2) {  // put aside for fill_gaps
      *be = level;
      nx[e] = g;
      g = std::int32_t(e);
      return;
    }
    const int at = std::min(level, d[e]);
    *be = at;
    nx[e] = hd[at];
    hd[at] = std::int32_t(e);
  };
  while (hd[level] >= 0) {
    const std::size_t c = std::size_t(hd[level]);
    hd[level] = nx[c];
    // Every border cell was seeded, so a step that wraps to the other side of the raster
    // lands on a cell already set; only the steps of the first and last rows' cells may
    // leave it.
    if (c >= w && c + w < size) {
      int* const bc = b + c;
      step(bc - 1, c - 1);
      step(bc + 1, c + 1);
      step(bc - w, c - w);
      step(bc + w, c + w);
      continue;
    }
    for (const std::size_t e : {c - 1, c + 1, c - w, c + w})
      if (e < size) step(b + e, e);
  }
  gaps = g;
}

void Widest::fill_gaps(int level) {
  const std::size_t w = std::size_t(r.w);
  if (filled.empty()) filled.assign(std::size_t(r.h), 0);
  for (; gaps >= 0; gaps = next[std::size_t(gaps)]) {
    const int j0 = int(std::size_t(gaps) / w);
    if (!filled[std::size_t(j0)]) fill(j0, level);
    while (!rows.empty()) {
      const int j = rows.back();
      rows.pop_back();
      const int g0 = spans->gap_lo[j], g1 = spans->gap_hi[j];
      const std::size_t row = std::size_t(j) * w;
      reach(row + g0 - 1, level);
      reach(row + g1 + 1, level);
      for (const int k : {j - 1, j + 1}) {  // on the spans: gaps keep off the border rows
        const std::size_t krow = std::size_t(k) * w;
        // The part k0..k1 of row k's gap above or below this one (none: k0 = g1 + 1).
        int k0 = g1 + 1, k1 = g1;
        if (spans->has_gap(k)) k0 = std::max(g0, spans->gap_lo[k]), k1 = std::min(g1, spans->gap_hi[k]);
        if (k0 > k1) k0 = g1 + 1, k1 = g1;
        for (int i = g0; i < k0; ++i) reach(krow + i, level);
        for (int i = k1 + 1; i <= g1; ++i) reach(krow + i, level);
        if (k0 <= k1 && !filled[std::size_t(k)]) fill(k, level);
      }
    }
  }
}

}  // namespace

Buffer<int> bottleneck(const Raster& r, const Buffer<int>& d2, int cap, Buffer<int>& next,
                       const Spans* spans) {
  Buffer<int> b2(r.size());
  // Each bucket is a stack threaded through `next` (a cell enters one bucket, once; its
  // entry is written before it is read).
  std::vector<std::int32_t> head(std::size_t(cap) + 1, -1);
  next.resize(r.size());
  Widest q{r, spans, d2.data(), b2.data(), next.data(), head.data()};
  const auto seed = [&](int i, int j) {
    const std::size_t c = std::size_t(j) * r.w + i;
    if (b2[c] >= 0) return;
    b2[c] = d2[c];
    q.push(c);
  };
  if (spans)
    seed_spans(r, *spans, cap, b2, seed);
  else
    std::fill(b2.begin(), b2.end(), -1);
  for (int i = 0; i < r.w; ++i) {
    seed(i, 0);
    seed(i, r.h - 1);
  }
  for (int j = 0; j < r.h; ++j) {
    seed(0, j);
    seed(r.w - 1, j);
  }
  for (int level = cap; level >= 0; --level) {
    for (;;) {
      q.drain(level);
      if (q.gaps < 0) break;
      q.fill_gaps(level);  // may reach cells at this level
    }
  }
  return b2;
}

}  // namespace section::morph
