// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file io/progress_io.h
/// Reading and slicing a scan file with a progress and cancel hook (progress.h).
#include "section/io/cloud_io.h"
#include "section/io/slice_file.h"
#include "section/progress.h"

#include <string>

namespace section {

/// read_cloud, telling `progress` the points read after each chunk (stage "read"; total:
/// the count a binary PLY file declares, 0 for text). Throws Cancelled when `progress`
/// returns false (the reading stops at the next chunk), else as read_cloud.
Cloud read_cloud(const std::string& path, const CloudReadOptions& options, const ProgressFn& progress);

/// slice_file, telling `progress` each section done (stage "slice"; total: the planes) as
/// `sink` receives it, in plane order. Throws Cancelled when `progress` returns false: no
/// further section is started (those under way finish first), else as slice_file. The
/// file's reading is not reported (docs/API.md says where that hook goes). `on_sampling`
/// as slice_file's.
SliceResult slice_file(const std::string& path, const PlaneSpec& planes, const SliceOptions& options,
                       const CloudReadOptions& read, const SectionSink& sink, const ProgressFn& progress,
                       const SamplingSink& on_sampling = {});

}  // namespace section
