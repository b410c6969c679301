// SPDX-License-Identifier: GPL-3.0-or-later
#include "closing.h"
#include "detail/cgal_medial_axis.h"

#include <algorithm>
#include <cstddef>
#include <utility>

namespace section::morph {

namespace {

// Cuts each end of the path back to the last circle, within the end's tenth, that holds
// the end's own circle (within a quarter cell): the medial axis runs on from a round
// edge's centre to its tip inside the edge's circle, where the thinning's branch stopped
// (on a noisy outline the circles near the tip hold less than the end's: part stays).
// Seeded with that spur, camber's edges bridged over holes moved by a micrometre or more,
// and with the input's rounding (tests/tools/test_formats.sh). Cell coordinates.
void trim_ends(Points& path, std::vector<double>& radius) {
  const std::size_t n = path.size(), tenth = n / 10;
  const auto holds = [&](std::size_t i, std::size_t end) {
    return (path[i] - path[end]).norm() + radius[end] <= radius[i] + 0.25;
  };
  std::size_t a = 0, b = n - 1;
  for (std::size_t i = 1; i < tenth; ++i)
    if (holds(i, 0)) a = i;
  for (std::size_t i = 1; i < tenth; ++i)
    if (holds(n - 1 - i, n - 1)) b = n - 1 - i;
  if (b < a + 2) return;
  path = Points(path.begin() + std::ptrdiff_t(a), path.begin() + std::ptrdiff_t(b) + 1);
  radius = std::vector<double>(radius.begin() + std::ptrdiff_t(a), radius.begin() + std::ptrdiff_t(b) + 1);
}

}  // namespace

// The medial axis of the component's outline, not a thinning of its cells: the outline is
// traced anyway, so the fill's interior needs neither a deep distance transform nor a
// thinning (together a sixth of `slice`). The outline in cell coordinates, not the
// boundary moved onto g = 0: it depends on the labels alone, so a scan moved by rounding
// (a float copy of it) keeps its skeleton, as the thinning's did (camber's line, seeded
// by it, moves by a micrometre or so with its seed at an edge bridged over a hole), and
// the triangulation of its many cocircular vertices is the same whatever the raster's
// origin.
void skeleton_of(const Pass& pass, const Component& comp, MorphologyResult& result) {
  const Points cells = outline(pass, comp);
  // The outline has a vertex about every cell (1 800 on a blade at 1 M points); a seed
  // needs no more than camber's own Delaunay seed has (1 000 samples).
  const std::size_t step = (cells.size() + 999) / 1000;
  Points polygon;
  polygon.reserve(cells.size() / std::max<std::size_t>(1, step) + 1);
  for (std::size_t i = 0; i < cells.size(); i += step) polygon.push_back(cells[i]);
  detail::MedialSeed axis = detail::medial_axis_seed(polygon);
  if (axis.points.size() < 2) return;
  Points path = std::move(axis.points);
  std::vector<double> radius = std::move(axis.radius);
  trim_ends(path, radius);
  for (double& r : radius) r *= pass.raster.cell;
  // Light smoothing of the circumcentres' zigzag, ends kept.
  for (int k = 0; k < 2 && path.size() > 2; ++k) {
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
  for (Vec& p : path) p = pass.raster.to_world(p);
  result.skeleton = std::move(path);
  result.skeleton_radius = std::move(radius);
}

}  // namespace section::morph
