// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// One pass of the morphology step (src/morphology.cpp): the raster of a point subset, the
// closing radius, the closed fill and its components; a component's boundary, normals
// and skeleton.
#include "raster.h"
#include "section/error.h"
#include "section/morphology.h"

#include <cstddef>
#include <string>
#include <vector>

namespace section::morph {

/// A connected component of the closed fill.
struct Component {
  int label = 0;
  std::size_t start = 0;                 // first cell in raster order
  std::size_t area = 0;                  // cells
  std::size_t enclosed = 0;              // cells enclosed by the band at the closing radius
  int i0 = 0, i1 = -1, j0 = 0, j1 = -1;  // bounding box of its cells (columns, rows)
};

/// What one pass made of a point subset.
struct Pass {
  Raster raster;
  int closing = 0;                    // r_c: radius at which the band closed
  int radius = 0;                     // r: radius used (closing plus one step of margin)
  Buffer<int> label;                  // component of the eroded fill, 0 = none
  Buffer<float> g;                    // signed distance to the closing's boundary, cells, > 0 inside
  std::vector<Component> components;  // index = label - 1
};

/// Builds the raster of `subset` (cell h), finds the closing radius and labels the
/// closed fill. Returns false when the band never encloses a substantial interior.
/// g may be left at rmax + 1 (cells) deep inside the fill, where nothing reads it.
/// Throws section::Error when the raster would exceed opt.max_cells.
bool run_pass(const Points& points, const std::vector<std::size_t>& subset, double h,
              const MorphologyOptions& opt, Pass& pass);

/// The Moore trace of one component, counterclockwise, smoothed a little: cell
/// coordinates, a function of the labels alone (empty under 3 vertices).
Points outline(const Pass& pass, const Component& comp);

/// The boundary of one component in world coordinates, counterclockwise: the Moore trace
/// smoothed a little, then each vertex moved along its normal onto the zero level of g.
Points component_boundary(const Pass& pass, const Component& comp);

/// Outward normals from the gradient of one component's filled image blurred by a Gaussian
/// of `sigma` cells: at p, -grad (G * I)(p) is proportional to sum I(c) (p - c) G(p - c).
/// I is the fill anti-aliased with g (coverage clamp(1/2 + g, 0, 1)), so that the
/// direction is not that of the cell staircase.
class ImageNormals {
public:
  ImageNormals(const Pass& pass, int label_id, double sigma);
  /// The unit normal at p (0 when the gradient vanishes).
  Vec at(const Vec& p);

private:
  const Pass& pass_;
  int label_;
  int k_;                // window half width: cells within 3 sigma
  double inv_, shrink_;  // 1 / (2 sigma^2), exp(-2 inv_)
  // The covered cells of the last window (its first cell i0_, j0_; none when i0_ is
  // INT_MIN): by window row b, from row_end_[b - 1] (0 for the first) to row_end_[b], the
  // column a and the cover. Points along a loop share their window with the point before
  // a third of the time or more (a cell holds 1-2 of them): its cells are not tested again.
  int i0_, j0_;
  std::vector<int> column_, row_end_;
  std::vector<double> cover_;
};

/// Signed area of a closed polygon (positive counterclockwise).
double signed_area(const Points& p);

/// Skeleton of a component into result.skeleton and result.skeleton_radius (skeleton.cpp):
/// the main branch of the medial axis of its outline.
void skeleton_of(const Pass& pass, const Component& comp, MorphologyResult& result);

/// x as text for the error messages ("%.6g").
std::string num(double x);

/// The error for a raster of wc x hc cells of size h over `max_cells`.
Error raster_too_large(double wc, double hc, double h, std::size_t max_cells);

}  // namespace section::morph
