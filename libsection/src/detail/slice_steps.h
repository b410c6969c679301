#pragma once
// The steps of slice that slice(Cloud) (src/slice.cpp, where they are defined) and
// slice_file (src/io/slice_file.cpp) share: option checks and the ordering of the slabs.
#include "section/slice.h"

#include <cstddef>
#include <functional>
#include <vector>

namespace section::detail {

void check_planes(const std::vector<Plane>& planes);
void check_slab(double slab);
void check_band_options(const SliceOptions& options);

/// How far from the plane the points beside it are kept: the fill's reach and the band's
/// drift fit (drift_band); 0 when neither runs.
double fill_reach(const SliceOptions& options, double slab);

/// The points beside plane i (fill_reach) as (u, v, signed distance), asked for only when
/// a section has a band to build or a gap to fill.
using NearFn = std::function<std::vector<Eigen::Vector3d>(std::size_t i)>;

/// Receives each finished section (io/slice_file.h's SectionSink).
using SectionFn = std::function<void(const SectionSlice&)>;

/// Orders the slab points of every plane into loops, sections in parallel, and fills the
/// profile's gaps from the near points; frees each section's points once done and hands
/// it to `sink` in plane order.
void order_slabs(std::vector<std::vector<Eigen::Vector2d>>& slabs, const NearFn& near_of,
                 const std::vector<Plane>& planes, double slab, const SliceOptions& options,
                 SliceResult& result, const SectionFn& sink = {});

}  // namespace section::detail
