// SPDX-License-Identifier: GPL-3.0-or-later
#include "closing.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <queue>
#include <utility>

namespace section::morph {

namespace {

/// Zhang-Suen's deletion test of a foreground cell for each of its 256 neighbourhoods
/// (bit k - 2 holds p_k, clockwise from north) in each of the two sub-steps.
struct ThinTable {
  bool remove[2][256] = {};
  ThinTable() {
    for (int bits = 0; bits < 256; ++bits) {
      int p[10] = {};
      for (int k = 2; k <= 9; ++k) p[k] = (bits >> (k - 2)) & 1;
      const int b = p[2] + p[3] + p[4] + p[5] + p[6] + p[7] + p[8] + p[9];
      int a = 0;
      for (int k = 2; k <= 9; ++k) a += !p[k] && p[k == 9 ? 2 : k + 1];
      const bool ok = b >= 2 && b <= 6 && a == 1;
      remove[0][bits] = ok && p[2] * p[4] * p[6] == 0 && p[4] * p[6] * p[8] == 0;
      remove[1][bits] = ok && p[2] * p[4] * p[8] == 0 && p[2] * p[6] * p[8] == 0;
    }
  }
};

/// Calls fn(c) for each nonzero byte c of img, in order; zero words of 8 bytes are passed
/// over whole (most of a crop is background, most of a thinned one too).
template <class Fn>
void for_each_set(const std::vector<std::uint8_t>& img, const Fn& fn) {
  const std::size_t n = img.size();
  for (std::size_t c = 0; c < n;) {
    std::uint64_t word = 1;
    if (c + 8 <= n) std::memcpy(&word, img.data() + c, sizeof word);
    if (word == 0) {
      c += 8;
      continue;
    }
    for (const std::size_t end = std::min(c + 8, n); c < end; ++c)
      if (img[c]) fn(c);
  }
}

/// Zhang-Suen thinning of a binary image (w x h, 1 = foreground, the outermost rows and
/// columns empty), in place. Only cells next to a deletion are looked at again, so the cost
/// is about the area.
void thin(std::vector<std::uint8_t>& img, int w, int h) {
  static const ThinTable table;
  // Foreground cells are never on the image's frame (the caller leaves it empty), so their
  // neighbours are all inside: fixed offsets, no bounds tests.
  const std::ptrdiff_t W = w;
  const std::ptrdiff_t around[8] = {-W - 1, -W, -W + 1, -1, 1, W - 1, W, W + 1};
  std::vector<std::uint32_t> cand;
  std::vector<std::uint8_t> mark(img.size(), 0);
  for_each_set(img, [&](std::size_t c) {
    if (!img[c - 1] || !img[c + 1] || !img[c - W] || !img[c + W]) cand.push_back(std::uint32_t(c));
  });
  // The sub-steps (bit 0, bit 1) a cell was kept in since its neighbourhood last changed:
  // kept in both, it is kept again until a neighbour goes, so it is not tested meanwhile.
  std::vector<std::uint8_t> kept(img.size(), 0);
  std::vector<std::uint32_t> del, keep;
  int idle = 0;
  for (int step = 0; idle < 2; step ^= 1) {
    del.clear();
    keep.clear();
    for (std::uint32_t c : cand) {
      if (!img[c]) continue;
      const std::uint8_t* q = img.data() + c;
      const int bits = q[-W] | q[1 - W] << 1 | q[1] << 2 | q[W + 1] << 3 | q[W] << 4 | q[W - 1] << 5 |
                       q[-1] << 6 | q[-W - 1] << 7;
      if (table.remove[step][bits]) {
        del.push_back(c);
      } else {
        kept[c] |= std::uint8_t(1 << step);
        if (kept[c] != 3) keep.push_back(c);
      }
    }
    for (std::uint32_t c : del) img[c] = 0;
    idle = del.empty() ? idle + 1 : 0;
    // Next candidates: the surviving ones not yet kept in both sub-steps and the foreground
    // neighbours of deleted cells.
    cand.clear();
    for (std::uint32_t c : keep)
      if (!mark[c]) {
        mark[c] = 1;
        cand.push_back(c);
      }
    for (std::uint32_t c : del)
      for (const std::ptrdiff_t o : around) {
        const std::uint32_t e = std::uint32_t(std::ptrdiff_t(c) + o);
        if (!img[e]) continue;
        kept[e] = 0;
        if (!mark[e]) {
          mark[e] = 1;
          cand.push_back(e);
        }
      }
    for (std::uint32_t c : cand) mark[c] = 0;
  }
}

/// A component's cells on an image of their bounding box with one empty cell around.
struct Crop {
  int i0 = 0, j0 = 0, w = 0, h = 0;  // raster cell of image cell (1, 1); image size
  std::vector<std::uint8_t> img;
};

Crop crop(const Pass& pass, const Component& comp) {
  const Raster& r = pass.raster;
  const int i0 = comp.i0, i1 = comp.i1, j0 = comp.j0, j1 = comp.j1;
  Crop c;
  if (i1 < 0) return c;
  c.i0 = i0;
  c.j0 = j0;
  c.w = i1 - i0 + 3;
  c.h = j1 - j0 + 3;
  c.img.assign(std::size_t(c.w) * c.h, 0);
  // By row pointers: the loop over a row is vectorised.
  for (int j = j0; j <= j1; ++j) {
    const int* label = pass.label.data() + std::size_t(j) * r.w + i0;
    std::uint8_t* out = c.img.data() + std::size_t(j - j0 + 1) * c.w + 1;
    for (int i = 0; i <= i1 - i0; ++i) out[i] = label[i] == comp.label;
  }
  return c;
}

/// The longest path over the 8-connected skeleton `cells` of an image `w` wide (two
/// Dijkstra searches, the second from the end the first reaches farthest): its cells
/// from one end to the other.
std::vector<std::uint32_t> longest_path(const std::vector<std::uint8_t>& img, int w,
                                        const std::vector<std::uint32_t>& cells) {
  // Read and written at skeleton cells only (set by each search): left uninitialised, the
  // pages of the other cells are never touched.
  const std::unique_ptr<double[]> dist(new double[img.size()]);
  const std::unique_ptr<std::int64_t[]> prev(new std::int64_t[img.size()]);
  const auto search = [&](std::uint32_t from) {
    for (std::uint32_t c : cells) {
      dist[c] = std::numeric_limits<double>::infinity();
      prev[c] = -1;
    }
    using Item = std::pair<double, std::uint32_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> pq;
    dist[from] = 0;
    pq.emplace(0.0, from);
    std::uint32_t far = from;
    while (!pq.empty()) {
      auto [d, c] = pq.top();
      pq.pop();
      if (d > dist[c]) continue;
      if (d > dist[far]) far = c;
      const int i = int(c % w), j = int(c / w);
      for (int y = j - 1; y <= j + 1; ++y)
        for (int x = i - 1; x <= i + 1; ++x) {
          const std::uint32_t e = std::uint32_t(y) * w + x;
          if (e == c || !img[e]) continue;
          const double nd = d + ((x != i && y != j) ? std::sqrt(2.0) : 1.0);
          if (nd < dist[e]) {
            dist[e] = nd;
            prev[e] = c;
            pq.emplace(nd, e);
          }
        }
    }
    return far;
  };
  const std::uint32_t a = search(cells[0]);
  const std::uint32_t b = search(a);
  std::vector<std::uint32_t> path;
  for (std::int64_t c = b; c >= 0; c = prev[c]) path.push_back(std::uint32_t(c));
  return path;
}

}  // namespace

void skeleton_of(const Pass& pass, const Component& comp, MorphologyResult& result) {
  const Raster& r = pass.raster;
  Crop c = crop(pass, comp);
  if (c.img.empty()) return;
  thin(c.img, c.w, c.h);
  std::vector<std::uint32_t> cells;
  for_each_set(c.img, [&](std::size_t k) { cells.push_back(std::uint32_t(k)); });
  if (cells.empty()) return;
  Points path;
  std::vector<double> radius;
  for (const std::uint32_t k : longest_path(c.img, c.w, cells)) {
    const int i = int(k % c.w) - 1 + c.i0, j = int(k / c.w) - 1 + c.j0;
    path.push_back(r.to_world(Vec(i, j)));
    radius.push_back(std::max(0.0, double(pass.g[std::size_t(j) * r.w + i])) * r.cell);
  }
  // Light smoothing of the staircase, ends kept.
  for (int pass_k = 0; pass_k < 2 && path.size() > 2; ++pass_k) {
    Points q = path;
    for (std::size_t i = 1; i + 1 < path.size(); ++i)
      q[i] = 0.25 * path[i - 1] + 0.5 * path[i] + 0.25 * path[i + 1];
    path.swap(q);
  }
  // Start at the blunter end (usually the leading edge).
  const std::size_t m = std::max<std::size_t>(1, path.size() / 10);
  double head = 0, tail = 0;
  for (std::size_t i = 0; i < m; ++i) {
    head += radius[i];
    tail += radius[radius.size() - 1 - i];
  }
  if (tail > head) {
    std::reverse(path.begin(), path.end());
    std::reverse(radius.begin(), radius.end());
  }
  result.skeleton = std::move(path);
  result.skeleton_radius = std::move(radius);
}

}  // namespace section::morph
