// SPDX-License-Identifier: GPL-3.0-or-later
// Reading and slicing a scan file with a progress and cancel hook.
#include "section/io/progress_io.h"

#include <utility>
#include <vector>

namespace section {

Cloud read_cloud(const std::string& path, const CloudReadOptions& options, const ProgressFn& progress) {
  const CloudPeek peek = peek_cloud(path, 1, options);  // a binary PLY's vertex count
  ProgressCounter counter(progress, "read", static_cast<std::size_t>(peek.total));
  Cloud cloud;
  read_cloud_chunks(
      path,
      [&](const Eigen::Vector3d* p, std::size_t n) {
        cloud.points.insert(cloud.points.end(), p, p + n);
        counter.add(n);
      },
      options);
  return cloud;
}

SliceResult slice_file(const std::string& path, const PlaneSpec& planes, const SliceOptions& options,
                       const CloudReadOptions& read, const SectionSink& sink, const ProgressFn& progress,
                       const SamplingSink& on_sampling) {
  const std::size_t total = planes.count > 0 ? static_cast<std::size_t>(planes.count) : planes.planes.size();
  ProgressCounter counter(progress, "slice", total);
  return slice_file(
      path, planes, options, read,
      [&](const SectionSlice& s) {
        if (sink) sink(s);
        counter.add(1);
      },
      on_sampling);
}

}  // namespace section
