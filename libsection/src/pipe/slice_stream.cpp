// SPDX-License-Identifier: GPL-3.0-or-later
// The stream written by slice: frames, loops, points and skeleton of each section.
#include "section/pipe/slice_stream.h"

#include "section/pipe/schema.h"
#include "section/io/stream.h"

#include <cstdio>
#include <map>
#include <string>

namespace section {

namespace {

// A point the gap fill carried onto the plane: its distance from it, else 0. Its index
// follows those of the points ordered before the fill (the band's or the slab's).
double carried_offset(const SectionSlice& s, const Loop& loop, std::size_t k) {
  const std::size_t base = s.band_points > 0 ? s.band_points : s.slab_points;
  const std::size_t carried =
      k < loop.index.size() && loop.index[k] >= base ? loop.index[k] - base : s.fill.offsets.size();
  return carried < s.fill.offsets.size() ? s.fill.offsets[carried] : 0.0;
}

// The `# band`, `# fill` and `# loops` notes of a section (docs/FORMAT.md).
void add_notes(const SectionSlice& s, std::vector<std::string>& notes) {
  if (s.band_points > 0) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "band section=%d half_width=%.6g points=%zu slab_points=%zu", s.id,
                  s.band_half_width, s.band_points, s.slab_points);
    notes.push_back(buf);
  }
  if (s.fill.gaps > 0) {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "fill section=%d gaps=%d filled=%d points=%zu largest_gap=%.6g max_offset=%.6g", s.id,
                  s.fill.gaps, s.fill.gaps_filled, s.fill.points, s.fill.largest_gap, s.fill.max_offset);
    notes.push_back(buf);
  }
  if (s.open_polylines > 0) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "open_mesh section=%d polylines=%zu bridged=%.6g", s.id, s.open_polylines,
                  s.bridged);
    notes.push_back(buf);
  }
  if (s.row >= 0) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "row section=%d row=%d height=%.6g spread=%.6g points=%zu", s.id, s.row,
                  s.row_height, s.row_spread, s.slab_points);
    notes.push_back(buf);
  }
  if (s.morphology.loops.size() > 1)
    notes.push_back("loops section=" + std::to_string(s.id) +
                    " count=" + std::to_string(s.morphology.loops.size()) + " profile=0");
}

// A section's rows of the tables loops, points and skeleton.
void add_rows(const SectionSlice& s, Table& loops, Table& points, Table& skeleton) {
  const MorphologyResult& m = s.morphology;
  for (std::size_t l = 0; l < m.loops.size(); ++l) {
    const Loop& loop = m.loops[l];
    schema::loops.add(loops, {s.id, l, m});
    for (std::size_t k = 0; k < loop.points.size(); ++k) {
      const Eigen::Vector2d normal = k < loop.normals.size() ? loop.normals[k] : Eigen::Vector2d(0, 0);
      schema::points.add(points, {s.id, l, k, loop.points[k], normal, carried_offset(s, loop, k)});
    }
  }
  for (std::size_t k = 0; k < m.skeleton.size(); ++k)
    schema::skeleton.add(skeleton,
                         {s.id, k, m.skeleton[k], k < m.skeleton_radius.size() ? m.skeleton_radius[k] : 0.0});
}

}  // namespace

std::string sampling_note(const Sampling& sampling) {
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "sampling kind=%s spacing=%.6g normal_spacing=%.6g slab=%.6g rows=%zu row_gap=%.6g",
                sampling_kind_name(sampling.kind), sampling.spacing, sampling.normal_spacing, sampling.slab,
                sampling.rows.size(), sampling.row_gap);
  return buf;
}

Stream to_stream(const SliceResult& result, const std::string& command, const std::string& units) {
  Stream stream;
  stream.units = units;
  stream.history.push_back(command);
  std::map<int, Frame> frame_map;
  Table loops = schema::loops.table(), points = schema::points.table(), skeleton = schema::skeleton.table();
  for (const auto& s : result.sections) {
    frame_map[s.id] = s.frame;
    if (!s.error.empty()) {
      stream.issues.push_back({s.id, -1, "slice", s.error});
      continue;
    }
    add_notes(s, stream.notes);
    add_rows(s, loops, points, skeleton);
  }
  put_frames(stream, frame_map);
  stream.put(std::move(loops));
  stream.put(std::move(points));
  stream.put(std::move(skeleton));
  return stream;
}

}  // namespace section
