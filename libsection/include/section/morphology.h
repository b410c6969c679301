#pragma once
/// @file morphology.h
/// The morphology step of `slice` (Li et al. 2014, section 2.2): from the unordered 2D
/// points of one section to ordered closed loops with outward normals, plus the skeleton
/// of the profile (the seed of the mean-camber line).
///
/// Method: rasterise the points at cell h; dilate them with a disc (a Euclidean distance
/// transform, the isotropic form of the paper's repeated '+' dilation) until the band
/// encloses an interior, plus one step of margin; flood-fill the outside from the raster
/// border; fill = not outside; erode back by the same radius (a morphological closing);
/// trace each connected component (Moore neighbour) into a closed counterclockwise loop;
/// order the measured points by the arc length of their foot on that loop. Points left
/// far from every loop (an interior ring such as a cooling channel, a second blade that
/// closes at another radius) are processed again on their own and give further loops.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace section {

/// Options of order_section (and of slice, through SliceOptions::morphology).
struct MorphologyOptions {
  double cell = 0;                 ///< mm, raster cell h; 0 = the estimated point spacing (median nearest-neighbour distance), coarsened so the raster has at most `auto_cells` cells
  std::size_t auto_cells = 250'000;  ///< cells, raster budget when `cell` is 0 (speed on very dense sections)
  int max_dilation = 64;           ///< cells, largest dilation radius tried before giving up (a gap of 2 r cells closes)
  double outlier_distance = 0;     ///< mm, points farther than this from every loop are dropped; 0 = 2.5 cells
  double isolated_distance = 0;    ///< mm, a point with no other point this close is left out of the raster (it may still join a loop it lies on); 0 = 6 cells
  double normal_sigma = 1.5;       ///< cells, standard deviation of the Gaussian that smooths the filled image before its gradient gives the normals
  std::size_t min_points = 8;      ///< points, fewest points a loop (and the whole section) must have
  int max_loops = 16;              ///< loops, most loops reported per section
  bool skeleton = true;            ///< compute the skeleton of loop 0
  std::size_t max_cells = 50'000'000;  ///< cells, refuse a raster larger than this (clear error, not an allocation failure)
};

/// One closed loop of a section.
struct Loop {
  std::vector<Eigen::Vector2d> points;    ///< measured points ordered along the loop (counterclockwise)
  std::vector<Eigen::Vector2d> normals;   ///< outward unit normals from the smoothed image gradient, one per point
  std::vector<std::size_t> index;         ///< input index of each ordered point
  std::vector<Eigen::Vector2d> boundary;  ///< traced boundary of the closed (filled) region, counterclockwise, sub-cell corrected and lightly smoothed
  double area = 0;                        ///< mm^2, area enclosed by `boundary`
  double length = 0;                      ///< mm, length of `boundary`
  int dilation = 0;                       ///< cells, dilation radius that closed this loop
};

/// What order_section returns: the loops, the skeleton and diagnostics.
struct MorphologyResult {
  std::vector<Loop> loops;                ///< largest area first (loop 0 = the profile)
  std::vector<Eigen::Vector2d> skeleton;  ///< skeleton of loop 0's filled region, ordered along its main branch, starting at the blunter end (usually the leading edge)
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
