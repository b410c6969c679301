// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The steps of slice that slice(Cloud) (src/slice.cpp, where they are defined) and
// slice_file (src/io/slice_file.cpp) share: option checks and the ordering of the slabs.
#include "section/slice.h"
#include "detail/spacing_search.h"

#include <cstddef>
#include <functional>
#include <vector>

namespace section::detail {

/// `count` planes with `normal` spread evenly over [lo, hi]: offsets lo + (hi - lo) (k + 1) /
/// (count + 1), k = 0..count-1 (planes_across, unchecked).
std::vector<Plane> spread(const Eigen::Vector3d& normal, double lo, double hi, int count);

void check_planes(const std::vector<Plane>& planes);
/// Throws for a mesh without triangles, or with a triangle index outside its vertices.
void check_mesh(const Mesh& mesh);
void check_slab(double slab);
void check_band_options(const SliceOptions& options);

/// How far from the plane the points beside it are kept: the fill's reach and the band's
/// drift fit (drift_band); 0 when neither runs.
double fill_reach(const SliceOptions& options, double slab);

/// How far from the plane the drift band's fit reads points (drift_band): 0 without a band.
double band_reach(const SliceOptions& options, double slab);

/// The points beside plane i (fill_reach) as (u, v, signed distance), asked for only when
/// a section has a band to build or a gap to fill.
using NearFn = std::function<std::vector<Eigen::Vector3d>(std::size_t i)>;

/// Told which planes' near points are asked for next, all at once: the planes whose
/// sections wait for them to fill gaps once every other section is ordered (order_slabs).
using NearPrefetch = std::function<void(const std::vector<std::size_t>& planes)>;

/// Receives each finished section (io/slice_file.h's SectionSink).
using SectionFn = std::function<void(const SectionSlice&)>;

/// Orders one section's points into loops: order_section, or order_row for a row.
using OrderFn =
    std::function<MorphologyResult(const std::vector<Eigen::Vector2d>&, const MorphologyOptions&)>;

/// Orders the slab points of every plane into loops (`order`, default order_section),
/// sections in parallel, and fills the profile's gaps from the near points; frees each
/// section's points once done and hands it to `sink` in plane order. Exact copies of a point
/// count once. A section of result.sections set beforehand keeps its row fields, and its
/// error when its slab is empty (why: between rows, say). With `prefetch`, the sections
/// that need near points only to fill gaps ask for them after all the others are ordered,
/// `prefetch` told first which they are. With `band_near_of` (the points within band_reach,
/// at hand without a read of the file), the band is built on those, and a section whose
/// gaps are to be filled waits for near_of's like one without a band: the band reads no
/// point beyond band_reach, so the sections are the same.
void order_slabs(std::vector<std::vector<Eigen::Vector2d>>& slabs, const NearFn& near_of,
                 const std::vector<Plane>& planes, double slab, const SliceOptions& options,
                 SliceResult& result, const SectionFn& sink = {}, const OrderFn& order = {},
                 const NearPrefetch& prefetch = {}, const NearFn& band_near_of = {});

/// A row's points ordered into its profile: the morphology's loop when it closes a single
/// one keeping nearly all of them, in an order that does not cross itself; else (a thin profile sampled
/// sparser than it is thick, which the closing bridges and cuts in pieces) along its chord, side by side
/// (order_along_chord).
MorphologyResult order_row(const std::vector<Eigen::Vector2d>& points, const MorphologyOptions& options);

/// The points of one blade profile ordered along its chord (their main axis): each point on
/// the side of a quartic mean line fitted through them all, one side forward, the other
/// back, counterclockwise, as loop 0 (no skeleton). Throws section::Error when that order
/// crosses itself (the points are no single profile along a chord).
MorphologyResult order_along_chord(const std::vector<Eigen::Vector2d>& points);

/// sampling_of over the points, and over all of them when its first look found rows (a
/// row is a section only with all its points); its searches kept in `search`.
Sampling sample_all(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& normal,
                    const SamplingOptions& options, SpacingSearch& search);

/// The slab of a dense scan or of lines from their sampling: a dense scan's mean spacing
/// (mean_spacing, on the sampling's `search` where it holds the points, or the sampling's
/// nearest distinct neighbour where exact copies shrink it), lines' spacing along the
/// normal. Throws when there is no spacing to take.
double sampled_slab(const std::vector<Eigen::Vector3d>& points, const Sampling& sampling,
                    const SpacingSearch& search);

/// Planes through sparse rows (result.sampling.kind rows): each takes the row it passes
/// through, or fails naming the rows beside it; the rows' points are the slabs.
void slice_through_rows(const std::vector<Eigen::Vector3d>& points, const std::vector<Plane>& planes,
                        const SliceOptions& options, SliceResult& result, const SectionFn& sink);

/// Planes through lines of points close together (result.sampling.kind lines, its rows
/// found over all the points): the section of each is interpolated between the lines below
/// and above it, each line's points carried toward the other line's curve by the other's
/// share of the height (exact lines give the section to second order in their spacing).
void slice_between_lines(const std::vector<Eigen::Vector3d>& points, const std::vector<Plane>& planes,
                         const SliceOptions& options, SliceResult& result, const SectionFn& sink);

/// Each row of result.sampling taken as a section in its own best plane.
void rows_as_sections(const std::vector<Eigen::Vector3d>& points, const SliceOptions& options,
                      SliceResult& result, const SectionFn& sink);

/// The closed polylines of a mesh's cut (each ending on its first point) as a section's
/// loops through `to_plane`: counterclockwise, loop 0 the largest, normals across their
/// chords; an open polyline counts in the section's error.
void mesh_loops(const std::vector<std::vector<Eigen::Vector3d>>& lines,
                const std::function<Eigen::Vector2d(const Eigen::Vector3d&)>& to_plane, SectionSlice& s);

}  // namespace section::detail
