// SPDX-License-Identifier: GPL-3.0-or-later
// Stream stage of smooth: points in, smoothed points and their statistics out.
#include "section/pipe/smooth_stream.h"

#include "section/pipe/schema.h"
#include "section/io/stream.h"
#include "pipe/adapter.h"

#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace section {

namespace {

// Smooths one loop into its slot: rows of the tables smoothed and smooth_stats.
void smooth_loop(int section, int loop, const pipe::LoopRows& rows, const SmoothOptions& options,
                 pipe::Slot& slot) {
  std::vector<Eigen::Vector2d> q;
  q.reserve(rows.size());
  for (const auto& row : rows) q.push_back(row.second);
  const SmoothResult r = smooth(q, options);
  slot.rows[0].reserve(slot.rows[0].size() + 5 * r.points.size());  // (the smoothed table's 5 columns)
  for (std::size_t i = 0; i < r.points.size(); ++i)
    schema::smoothed.append(slot.rows[0], {section, loop, i, r.points[i]});
  schema::smooth_stats.append(slot.rows[1], {section, loop, r});
}

}  // namespace

const std::vector<std::pair<std::string, std::string>>& smooth_unread_columns() {
  static const std::vector<std::pair<std::string, std::string>> columns = {
      {"points", "nu"},  {"points", "nv"},  {"points", "offset"},
      {"skeleton", "u"}, {"skeleton", "v"}, {"skeleton", "radius"}};
  return columns;
}

void smooth_stream(Stream& stream, const SmoothOptions& options) {
  const auto loops = pipe::loop_rows(schema::points.get(stream), "smooth");
  pipe::restage(stream, "smooth");
  Table smoothed = schema::smoothed.table(), stats = schema::smooth_stats.table();
  std::vector<std::pair<std::pair<int, int>, const pipe::LoopRows*>> work;
  std::set<int> present;
  for (const auto& [key, rows] : loops) {
    present.insert(key.first);
    if (!stream.failed(key.first, key.second)) work.push_back({key, &rows});
  }
  pipe::vanished_sections(stream, present, "smooth", "points");
  pipe::run_slots(
      work.size(), options.threads, {&smoothed, &stats}, stream.issues, "smooth",
      [&](std::size_t w, pipe::Slot& slot) {
        smooth_loop(work[w].first.first, work[w].first.second, *work[w].second, options, slot);
      },
      [&](std::size_t w, const std::string& message) {
        return SectionIssue{work[w].first.first, work[w].first.second, "smooth", message};
      });
  stream.put(std::move(smoothed));
  stream.put(std::move(stats));
}

}  // namespace section
