// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file sampling.h
/// What a point cloud is, as far as slicing it goes: a dense scan, lines of points close
/// together (a structured surface grid), sparse rows (each one section's worth: a CMM pass,
/// a scanner layer, one 2D profile). slice chooses its slab from it (docs/SAMPLING.md).
#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

namespace section {

/// Options of sampling_of (fractions and counts; no lengths: everything is measured).
struct SamplingOptions {
  std::size_t max_points =
      200'000;                   ///< points looked at: the cloud's first ones, in its order (full density)
  std::size_t queries = 20'000;  ///< of those, at most this many measured for the spacings
  double anisotropy = 2;         ///< spacing along the normal / spacing in the surface beyond which
                                 ///< the points are lines or rows, not a dense scan
  double sparse = 0.05;          ///< rows farther apart than this fraction of a row's size are sparse
  double flatness = 0.05;        ///< a row is planar when no point lies farther than this fraction
                                 ///< of its size from its best plane
  int threads = 0;               ///< worker threads; 0 = all cores
};

/// What kind of sampling the points are.
enum class SamplingKind {
  dense,  ///< about as dense along the normal as across it: slabs of the point spacing
  lines,  ///< lines of points across the normal, close together: slabs of their spacing along the normal
  rows    ///< rows of points far apart, each a section's worth: each row is a section as it lies
};

/// The name of a kind ("dense", "lines", "rows").
const char* sampling_kind_name(SamplingKind kind);

/// One row of points: a section's worth lying across the normal.
struct PointRow {
  std::vector<std::size_t> points;                   ///< indices of its points in the cloud, ascending
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< its best plane's point nearest to 0
  Eigen::Vector3d normal =
      Eigen::Vector3d::UnitZ();  ///< its best plane's unit normal, near the slicing normal
  double height = 0;             ///< mm, mean of normal . p over its points (the slicing normal)
  double low = 0, high = 0;      ///< mm, least and largest normal . p over its points
  double spread = 0;             ///< mm, largest distance of a point from the best plane
  double size = 0;               ///< mm, diagonal of its points' box in the best plane
  bool planar = true;            ///< spread within SamplingOptions::flatness of size
};

/// What sampling_of finds.
struct Sampling {
  SamplingKind kind = SamplingKind::dense;  ///< the kind
  double spacing = 0;                       ///< mm, median distance from a point to its nearest other point
  /// mm, median height from a point to its nearest neighbour within 45 degrees of the normal
  /// (above or below it); infinite when most points have none among their 16 nearest
  double normal_spacing = 0;
  double normal_low = 0, normal_high = 0;  ///< mm, the quartiles of those heights (close together: levels)
  double slab = 0;               ///< mm, the slab for lines (their spacing along the normal); else 0
  double row_gap = 0;            ///< mm, median height between neighbouring rows; 0 for one
  std::vector<PointRow> rows;    ///< lines, rows: the rows found, lowest first (may be empty)
  std::size_t points = 0;        ///< points looked at (the cloud's first ones)
  std::size_t duplicates = 0;    ///< of the points measured, those with an exact copy
  std::size_t measured = 0;      ///< points measured for the spacings
  std::string describe() const;  ///< one line: kind, spacings, rows, slab (for notes and messages)
};

/// Finds what kind of sampling `points` are with respect to planes of normal `normal`:
/// the spacing in the surface (nearest distinct neighbour) against the spacing along the
/// normal (nearest neighbour within 45 degrees of it), both medians over up to `queries` of
/// the first `max_points` points (a first look at 50 000 of them, 5 000 measured, settles a
/// dense scan; a quick one measuring 1 000 of them settles a plainly dense one); when the latter is over
/// `anisotropy` times the former (or over the former, on levels: its quartiles within 20 % of each other),
/// the points are split into rows (points joined to their 16 nearest neighbours across the normal, within 30
/// degrees of the plane; a piece lying in a larger one's plane joins it) and each row gets its best plane.
/// Rows covering 90 % of the points are `rows` when neighbours lie more than `sparse` of a row's size apart
/// (or there is only one), else `lines`; without such rows the points are `lines` with the slab from the
/// spacing along the normal. Exact copies of a point are not neighbours (they do not shrink the spacing).
/// Throws section::Error for a zero or non-finite normal.
Sampling sampling_of(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& normal,
                     const SamplingOptions& options = {});

}  // namespace section
