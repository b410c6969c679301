#include "section/pipe/slice_stream.h"

#include "section/pipe/schema.h"
#include "section/io/stream.h"

#include <cstdio>
#include <map>
#include <string>

namespace section {

Stream to_stream(const SliceResult& result, const std::string& command, const std::string& units) {
  Stream stream;
  stream.units = units;
  stream.history.push_back(command);
  std::map<int, Frame> frame_map;
  Table loops{"loops", {"section", "loop", "points", "dropped", "area", "length", "cell"}, {}};
  Table points{"points", {"section", "loop", "index", "u", "v", "nu", "nv", "offset"}, {}};
  Table skeleton{"skeleton", {"section", "loop", "index", "u", "v", "radius"}, {}};
  for (const auto& s : result.sections) {
    frame_map[s.id] = s.frame;
    if (!s.error.empty()) {
      stream.issues.push_back({s.id, -1, "slice", s.error});
      continue;
    }
    const auto& m = s.morphology;
    if (s.band_points > 0) {
      char buf[200];
      std::snprintf(buf, sizeof buf, "band section=%d half_width=%.6g points=%zu slab_points=%zu", s.id,
                    s.band_half_width, s.band_points, s.slab_points);
      stream.notes.push_back(buf);
    }
    if (s.fill.gaps > 0) {
      char buf[200];
      std::snprintf(buf, sizeof buf, "fill section=%d gaps=%d filled=%d points=%zu largest_gap=%.6g max_offset=%.6g", s.id,
                    s.fill.gaps, s.fill.gaps_filled, s.fill.points, s.fill.largest_gap, s.fill.max_offset);
      stream.notes.push_back(buf);
    }
    if (m.loops.size() > 1)
      stream.notes.push_back("loops section=" + std::to_string(s.id) + " count=" + std::to_string(m.loops.size()) +
                             " profile=0");
    for (std::size_t l = 0; l < m.loops.size(); ++l) {
      const Loop& loop = m.loops[l];
      loops.add_row({double(s.id), double(l), double(loop.points.size()), l == 0 ? double(m.dropped) : 0.0, loop.area,
                     loop.length, m.cell});
      for (std::size_t k = 0; k < loop.points.size(); ++k) {
        const Eigen::Vector2d nrm = k < loop.normals.size() ? loop.normals[k] : Eigen::Vector2d(0, 0);
        // A point the gap fill carried onto the plane: its distance from it, else 0. Its
        // index follows those of the points ordered before the fill (the band's or the slab's).
        const std::size_t base = s.band_points > 0 ? s.band_points : s.slab_points;
        const std::size_t carried = k < loop.index.size() && loop.index[k] >= base ? loop.index[k] - base
                                                                                 : s.fill.offsets.size();
        const double offset = carried < s.fill.offsets.size() ? s.fill.offsets[carried] : 0.0;
        points.add_row({double(s.id), double(l), double(k), loop.points[k].x(), loop.points[k].y(), nrm.x(), nrm.y(),
                        offset});
      }
    }
    for (std::size_t k = 0; k < m.skeleton.size(); ++k)
      skeleton.add_row({double(s.id), 0.0, double(k), m.skeleton[k].x(), m.skeleton[k].y(),
                        k < m.skeleton_radius.size() ? m.skeleton_radius[k] : 0.0});
  }
  put_frames(stream, frame_map);
  stream.put(std::move(loops));
  stream.put(std::move(points));
  stream.put(std::move(skeleton));
  return stream;
}

}  // namespace section
