// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file io/slice_file.h
/// Slicing a cloud file as it is read, without holding the whole cloud.
#include "section/io/cloud_io.h"
#include "section/slice.h"

#include <functional>
#include <optional>
#include <string>
#include <string_view>

namespace section {

/// True when `head` (the start of a file) is a plain 2D profile: text whose data lines
/// (after blank lines, `#` lines and up to 8 title lines; the first 16 looked at) hold
/// exactly two numbers each, x y.
bool looks_like_profile(std::string_view head);

/// A plain 2D profile (parse_profile: x y a line, ordered or not) as a cloud at z = 0, when
/// `text` is one (looks_like_profile); nothing otherwise. Throws as parse_profile, naming `name`.
std::optional<Cloud> profile_cloud(std::string_view text, const std::string& name);

/// profile_cloud of a file, read whole only when its first 64 kB look like a profile.
/// Throws section::Error naming the file when it cannot be opened.
std::optional<Cloud> read_profile_cloud(const std::string& path);

/// Planes for slice_file: explicit, or spread over the cloud (known only once it is read).
struct PlaneSpec {
  std::vector<Plane> planes;                          ///< explicit planes, used when count is 0
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< normal of the spread planes (count > 0)
  int count = 0;                                      ///< planes spread as planes_across; 0 = `planes`
};

/// Slices the cloud of a file without holding it: reads it in chunks and keeps only the
/// slab points of each plane. A file is read once when the planes and the slab width are
/// given, or when those guessed from a first look at a binary PLY file hold; twice
/// otherwise (first for the extent along the normal, a random sample of 50000 points for a
/// dense scan's spacing and the first SamplingOptions::max_points points for the sampling,
/// sampling_of). Sparse rows are held in memory (read a second time when the file holds
/// more than those first points) and sliced as slice(Cloud) slices them. Standard input
/// ("-") is held in memory (within the memory limit, io/limits.h) and sliced by
/// slice(Cloud); a named pipe or a process substitution is first copied to a temporary
/// file (read_cloud_chunks) and then read as a file is. Same results in meaning as
/// slice(read_cloud(path), ...); the estimated slab width may differ slightly (another
/// random sample). Throws as read_cloud and slice.
/// The points held for the planes (slabs, the points beside them that gaps and bands take,
/// the sections made) stay within half of memory_limit() (io/limits.h): about 4 kB a plane
/// is counted before any point, so that a plane count the memory cannot take is refused at
/// once, and the rest as it is read (`slice: the points held for N planes pass the memory
/// limit ...`).
/// `sink`, when set, receives each section in plane order as soon as it and those before
/// it are done, from one thread at a time (the slice tool writes it to the pipe while the
/// others are still being ordered); the result holds them all the same. `on_sampling`, when
/// set, receives the sampling found (slab 0) before any section.
SliceResult slice_file(const std::string& path, const PlaneSpec& planes, const SliceOptions& options = {},
                       const CloudReadOptions& read = {}, const SectionSink& sink = {},
                       const SamplingSink& on_sampling = {});

}  // namespace section
