// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file morphology.h
/// The morphology step of `slice` (Li et al. 2014, section 2.2): the unordered 2D points of
/// one section become ordered closed loops with outward normals, plus the skeleton of the
/// profile (the seed of the mean-camber line). The rasterised points are closed (disc
/// dilation, fill, erosion) and each component traced into a loop: docs/MORPHOLOGY.md.
#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <vector>

namespace section {

struct MorphologyResult;

/// Options of order_section (and of slice, through SliceOptions::morphology); each one's
/// role in the method: docs/MORPHOLOGY.md.
struct MorphologyOptions {
  double cell = 0;                   ///< mm, raster cell h; 0 = the point spacing (at most `auto_cells`)
  std::size_t auto_cells = 250'000;  ///< cells, raster budget when `cell` is 0
  double min_cell = 0;               ///< mm, floor of the cell when `cell` is 0 (slice: a band's)
  int max_dilation = 64;             ///< cells, largest dilation radius tried (closes gaps of 2 r)
  double outlier_distance = 0;       ///< mm, points farther from every loop are dropped; 0 = 2.5 cells
  double isolated_distance = 0;      ///< mm, a point with no other this close is left out; 0 = 6 cells
  double normal_sigma = 1.5;         ///< cells, blur of the fill whose gradient gives the normals
  std::size_t min_points = 8;        ///< points, fewest a loop (and the section) must have
  int max_loops = 16;                ///< loops, most reported per section
  bool skeleton = true;              ///< compute the skeleton of loop 0
  /// With `skeleton`: asked with the loops made, before the skeleton; false leaves it out
  /// (slice: a band's ordering will replace this one). Empty: always computed.
  std::function<bool(const MorphologyResult&)> skeleton_if;
  std::size_t max_cells = 50'000'000;  ///< cells, a larger raster is refused with an error
};

/// One closed loop of a section.
struct Loop {
  std::vector<Eigen::Vector2d> points;    ///< measured points ordered along the loop (counterclockwise)
  std::vector<Eigen::Vector2d> normals;   ///< outward unit normals (smoothed image gradient), one per point
  std::vector<std::size_t> index;         ///< input index of each ordered point
  std::vector<Eigen::Vector2d> boundary;  ///< traced boundary of the closed region, counterclockwise
  double area = 0;                        ///< mm^2, area enclosed by `boundary`
  double length = 0;                      ///< mm, length of `boundary`
  int dilation = 0;                       ///< cells, dilation radius that closed this loop
};

/// What order_section returns: the loops, the skeleton and diagnostics.
struct MorphologyResult {
  std::vector<Loop> loops;                ///< largest area first (loop 0 = the profile)
  std::vector<Eigen::Vector2d> skeleton;  ///< main branch of loop 0's skeleton, blunter end first
  std::vector<double> skeleton_radius;    ///< mm, distance from each skeleton point to the boundary
  double cell = 0;                        ///< mm, raster cell used
  int dilation = 0;                       ///< cells, dilation radius that closed loop 0
  std::size_t dropped = 0;                ///< points dropped as outliers (on no loop)
  std::size_t raster_cells = 0;           ///< cells of the first (largest) raster, for diagnostics
};

/// Orders the unordered points of one section (in-plane coordinates, mm) into closed
/// loops, following Li et al. 2014 (dilation, filling, erosion, boundary tracing).
/// Each loop runs counterclockwise and its normals point out of its own filled region,
/// also for an interior loop such as a cooling channel.
/// Throws section::Error("morphology: ...") when there are no points, fewer than
/// `min_points`, non-finite coordinates, a raster larger than `max_cells`, or when the
/// points do not close into any loop within `max_dilation`.
MorphologyResult order_section(const std::vector<Eigen::Vector2d>& points,
                               const MorphologyOptions& options = {});

/// Estimated mean spacing of 2D points: the median distance from a point to its nearest
/// neighbour, on at most `sample` points (mm; 0 for fewer than two distinct points).
double spacing_2d(const std::vector<Eigen::Vector2d>& points, std::size_t sample = 20000);

}  // namespace section
