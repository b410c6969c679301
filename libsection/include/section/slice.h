// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file slice.h
/// Step 1 of the method: section planes cut a point cloud (a slab of width d around each
/// plane, points projected onto it, then ordered by morphology) or a mesh (exact
/// intersection polylines).
#include "section/cloud.h"
#include "section/frame.h"
#include "section/drift_band.h"
#include "section/gap_fill.h"
#include "section/mesh.h"
#include "section/morphology.h"
#include "section/sampling.h"

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace section {

/// A section plane: a point of it and its normal (any length but zero).
struct Plane {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();   ///< a point of the plane
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< plane normal
};

/// Planes with one normal at signed offsets along it: origin = offset * normal / |normal|.
std::vector<Plane> planes_at(const Eigen::Vector3d& normal, const std::vector<double>& offsets);

/// The extent of a part's points along a normal: the few far from the rest (strays: a
/// reflection, dust, a bit of fixture; at most 1 in 1 000 points at each end, beyond a gap
/// over 5 % of the rest's extent) are left out.
struct PartExtent {
  double lo = 0, hi = 0;           ///< offsets along the unit normal, the strays left out
  std::size_t strays = 0;          ///< points left out
  double lowest = 0, highest = 0;  ///< offsets of all the points
};
PartExtent extent_along(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& normal);

/// `count` planes with one normal spread evenly over the part's extent along it
/// (extent_along: lo, hi): offsets lo + (hi - lo) * (k + 1) / (count + 1), k = 0..count-1.
std::vector<Plane> planes_across(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& normal,
                                 int count);
/// The same over an extent already taken (extent_along, e.g. to say what it left out).
std::vector<Plane> planes_across(const PartExtent& extent, const Eigen::Vector3d& normal, int count);

/// Options of slice (lengths in the cloud's units; docs/MORPHOLOGY.md for the band and the fill).
struct SliceOptions {
  double slab = 0;               ///< slab width d; 0 = chosen from the points' sampling (docs/SAMPLING.md)
  MorphologyOptions morphology;  ///< ordering of each section's points
  double band_spacing = 0.03;    ///< widen the slab into a band (drift_band.h) to one point per this; 0 = off
  double band_max = 2;           ///< slab widths: the band's largest half width
  double band_sparse_max = 0;    ///< slab widths: the band's half width beside sparse stretches; 0 = off
  bool fill_gaps = true;         ///< fill gaps of the slab from scan points beside the plane (gap_fill.h)
  GapFillOptions fill;           ///< how (reach 0 = 12 slab widths)
  SamplingOptions sampling;      ///< how the points' sampling is told (when slab is 0)
  int threads = 0;               ///< worker threads for the sections; 0 = all cores
};

/// What one section plane gave.
struct SectionSlice {
  int id = 0;                   ///< index of the plane
  Frame frame;                  ///< the plane's frame (u, v in-plane)
  std::size_t slab_points = 0;  ///< points found in the slab
  MorphologyResult morphology;  ///< ordered loops, normals, skeleton (empty on error)
  std::size_t band_points = 0;  ///< points of the band that replaced the slab's (0: the slab alone)
  double band_half_width = 0;   ///< its half width (0: the slab alone)
  GapFillResult fill;           ///< gaps found and filled (counts; the carried points are in the loops)
  int row = -1;                 ///< the row of points taken as the section (Sampling::rows); -1: a slab
  double row_height = 0;        ///< mm, that row's height along the sampling's normal
  double row_spread = 0;        ///< mm, its points' largest distance from the section plane
  std::string error;            ///< why the section failed; empty when it did not
  /// A mesh open at the plane (a hole in a scan's mesh): its open cut polylines, whose
  /// points were ordered as a cloud's slab (0: closed, or not a mesh) ...
  std::size_t open_polylines = 0;
  double bridged = 0;  ///< ... and the longest stretch of loop 0 between two cut points
};

/// What slice returns: one SectionSlice per plane, and the slab used.
struct SliceResult {
  std::vector<SectionSlice> sections;  ///< one per plane, in plane order
  double slab = 0;                     ///< slab width used (0: rows taken as they lie, or a mesh)
  Sampling sampling;                   ///< what the points are (when the slab was chosen from them)
  std::size_t points = 0;              ///< points in the cloud (or mesh vertices)
  int file_passes = 0;                 ///< slice_file: times the file was read (1 to 3); 0 in memory
  PartExtent extent;                   ///< slice_file with a plane count: what they were spread over
};

/// Receives each section as soon as it and the sections before it are done, in plane
/// order, from one thread at a time (slice_file, slice of a cloud or a mesh, on planes or
/// surfaces of revolution, slice_by_rows).
using SectionSink = std::function<void(const SectionSlice&)>;

/// Receives what was found of the points' sampling (with slab 0), before any section.
using SamplingSink = std::function<void(const Sampling&)>;

/// Points of `points` in the closed slab |(p - origin) . n| <= slab / 2 of each plane,
/// projected onto it, in cloud order. All planes in one pass: cost O(points log planes)
/// per distinct normal. Points on a slab boundary are decided by CGAL's exact orientation
/// predicate against the boundary plane and belong to the slab (closed slab).
std::vector<std::vector<Eigen::Vector2d>> slab_points(const std::vector<Eigen::Vector3d>& points,
                                                      const std::vector<Plane>& planes, double slab);

/// Slices a cloud: slab points of every plane ordered into loops by morphology.
/// With slab 0 the slab follows the points' sampling (sampling_of along the first plane's
/// normal): a dense scan's mean spacing (the nearest distinct neighbour's when exact copies
/// would shrink it), lines' spacing along the normal; sparse rows are not bridged: a plane
/// through a row (all of it within SamplingOptions::flatness of its size from the plane)
/// takes that row, and a plane between rows fails, naming the rows beside it.
/// Sections that fail (no points, no closed loop) carry their error; the others go on.
/// Exact copies of a point count once. Throws section::Error for bad options (no planes,
/// a zero normal, a negative slab). `sink` and `on_sampling`, when set, receive each section
/// as it is done and the sampling found before any (the result holds them all the same).
SliceResult slice(const Cloud& cloud, const std::vector<Plane>& planes, const SliceOptions& options = {},
                  const SectionSink& sink = {}, const SamplingSink& on_sampling = {});

/// Each row of points of a cloud taken as a section as it lies (`slice --rows`): the rows
/// across `normal` (sampling_of), each in its best plane (frame origin the plane's point
/// nearest to 0), in height order. A row whose points stray from its best plane by more than
/// SamplingOptions::flatness of its size fails, saying so. Throws section::Error when the
/// points are not rows or lines (a dense scan: it names its spacings).
SliceResult slice_rows(const Cloud& cloud, const Eigen::Vector3d& normal, const SliceOptions& options = {});

/// As above, with the rows of a sampling already found over all the points of `cloud`
/// (sampling_of with max_points at least their number).
SliceResult slice_rows(const Cloud& cloud, const Sampling& sampling, const SliceOptions& options = {});

/// What `slice` does given no planes (no --at, --count or --planes): the rows of the cloud
/// as sections (slice_rows) when its points are sparse rows, each a section's worth, or, with
/// `any_lines` (`--rows`), whatever lines its sampling finds. Throws section::Error saying
/// what the points are and what to give instead, or that they are too few for a row.
/// `sink` and `on_sampling` as slice's (the sampling told with slab 0 only).
SliceResult slice_by_rows(const Cloud& cloud, const Eigen::Vector3d& normal, const SliceOptions& options,
                          bool any_lines, const SectionSink& sink = {}, const SamplingSink& on_sampling = {});

/// Slices a mesh exactly (CGAL's polygon mesh slicer): each closed intersection polyline is
/// a loop, oriented counterclockwise in (u, v), loop 0 the largest; its vertices are the points.
/// `sink`, when set, receives each section as it is done (the result holds them all the same).
SliceResult slice(const Mesh& mesh, const std::vector<Plane>& planes, const SliceOptions& options = {},
                  const SectionSink& sink = {});

}  // namespace section
