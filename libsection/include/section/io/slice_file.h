#pragma once
/// @file io/slice_file.h
/// Slicing a cloud file as it is read, without holding the whole cloud.
#include "section/io/cloud_io.h"
#include "section/slice.h"

#include <functional>
#include <string>

namespace section {

/// Planes for slice_file: explicit, or spread over the cloud (known only once it is read).
struct PlaneSpec {
  std::vector<Plane> planes;                          ///< explicit planes, used when count is 0
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< normal of the spread planes (count > 0)
  int count = 0;                                      ///< planes spread as planes_across; 0 = `planes`
};

/// Receives each section of slice_file as soon as it and the sections before it are done.
using SectionSink = std::function<void(const SectionSlice&)>;

/// Slices the cloud of a file without holding it: reads it in chunks and keeps only the
/// slab points of each plane. A file is read once when the planes and the slab width are
/// given, or when those guessed from a first look at a binary PLY file hold; twice
/// otherwise (first for the extent along the normal and a random sample of 50000 points
/// for the spacing). Standard input ("-"), a named pipe or a process substitution is first
/// copied to a temporary file (read_cloud_chunks) and then read as a file is, with the same
/// results. Same results in meaning as slice(read_cloud(path), ...); the estimated
/// slab width may differ slightly (another random sample). Throws as read_cloud and slice.
/// The points held for the planes (slabs, the points beside them that gaps and bands take,
/// the sections made) stay within half of memory_limit() (io/limits.h): about 4 kB a plane
/// is counted before any point, so that a plane count the memory cannot take is refused at
/// once, and the rest as it is read (`slice: the points held for N planes pass the memory
/// limit ...`).
/// `sink`, when set, receives each section in plane order as soon as it and those before
/// it are done, from one thread at a time (the slice tool writes it to the pipe while the
/// others are still being ordered); the result holds them all the same.
SliceResult slice_file(const std::string& path, const PlaneSpec& planes, const SliceOptions& options = {},
                       const CloudReadOptions& read = {}, const SectionSink& sink = {});

}  // namespace section
