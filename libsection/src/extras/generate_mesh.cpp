// SPDX-License-Identifier: GPL-3.0-or-later
// Closed triangle meshes of a generated blade (generate.h): rings of exact profile points
// along the span, end caps by ear clipping.
#include "generate_section.h"
#include "section/error.h"

#include <array>
#include <vector>

namespace section {

using namespace detail::gen;

namespace {

/// Ear clipping of a simple counterclockwise polygon; triangles as indices into `poly`.
std::vector<std::array<int, 3>> ear_clip(const std::vector<Vector2d>& poly) {
  const int n = int(poly.size());
  std::vector<int> prev(poly.size()), next(poly.size());
  for (int i = 0; i < n; ++i) {
    prev[i] = (i + n - 1) % n;
    next[i] = (i + 1) % n;
  }
  auto area2 = [&](int a, int b, int c) { return cross(poly[b] - poly[a], poly[c] - poly[a]); };
  auto inside = [&](int a, int b, int c, int p) {  // p in the closed triangle abc (ccw)
    return area2(a, b, p) >= 0 && area2(b, c, p) >= 0 && area2(c, a, p) >= 0;
  };
  std::vector<std::array<int, 3>> tris;
  tris.reserve(poly.size());
  int remaining = n, i = 0, failures = 0;
  while (remaining > 3) {
    const int a = prev[i], c = next[i];
    bool ear = area2(a, i, c) > 0;
    if (ear)
      for (int k = next[c]; k != a; k = next[k]) {
        if (area2(prev[k], k, next[k]) > 0) continue;  // only reflex vertices can lie inside an ear
        if (inside(a, i, c, k) && poly[k] != poly[a] && poly[k] != poly[c]) {
          ear = false;
          break;
        }
      }
    if (ear || failures > remaining) {  // clip anyway on degenerate input rather than loop
      tris.push_back({a, i, c});
      next[a] = c;
      prev[c] = a;
      --remaining;
      failures = 0;
    } else {
      ++failures;
    }
    i = c;
  }
  tris.push_back({prev[i], i, next[i]});
  return tris;
}

}  // namespace

Mesh generate_mesh(const BladeDesign& blade, int profile_points, int layers) {
  if (profile_points < 16) throw Error("generate_mesh: profile_points must be at least 16");
  if (layers < 2) throw Error("generate_mesh: layers must be at least 2");
  if (!(blade.span > 0)) throw Error("generate_mesh: the blade span must be positive");
  Mesh mesh;
  const int n = profile_points;
  mesh.vertices.reserve(std::size_t(n) * std::size_t(layers));
  std::vector<Vector2d> bottom, top;
  for (int k = 0; k < layers; ++k) {
    const double z = blade.span * k / (layers - 1);
    // Equal arc-length steps from the LE point: ring vertex i matches across layers.
    const SectionTruth t = section_truth(blade.at(z), n);
    for (const Vector2d& p : t.profile) mesh.vertices.emplace_back(p.x(), p.y(), z);
    if (k == 0) bottom = t.profile;
    if (k == layers - 1) top = t.profile;
  }
  for (int k = 0; k + 1 < layers; ++k)
    for (int i = 0; i < n; ++i) {
      const int a = k * n + i, b = k * n + (i + 1) % n, c = (k + 1) * n + (i + 1) % n, d = (k + 1) * n + i;
      mesh.triangles.push_back({a, b, c});
      mesh.triangles.push_back({a, c, d});
    }
  for (const auto& tri : ear_clip(bottom)) mesh.triangles.push_back({tri[0], tri[2], tri[1]});  // faces -z
  const int off = (layers - 1) * n;
  for (const auto& tri : ear_clip(top)) mesh.triangles.push_back({off + tri[0], off + tri[1], off + tri[2]});
  return mesh;
}

}  // namespace section
