#include "section/pipe/smooth_stream.h"

#include "section/error.h"
#include "section/io/stream.h"
#include "detail/parallel.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace section {

namespace {
using Points = std::vector<Eigen::Vector2d>;
}  // namespace

void smooth_stream(Stream& stream, const SmoothOptions& options) {
  const Table& points = stream.get("points", "slice");
  const std::size_t cs = points.column("section"), cl = points.column("loop"),
                    ci = points.column("index"), cu = points.column("u"),
                    cv = points.column("v");

  // Rows grouped by (section, loop), ordered by index.
  std::map<std::pair<int, int>, std::vector<std::pair<double, Eigen::Vector2d>>> loops;
  for (std::size_t r = 0; r < points.rows(); ++r) {
    const double s = points.at(r, cs), l = points.at(r, cl);
    if (!std::isfinite(s) || !std::isfinite(l))
      throw Error("smooth: row " + std::to_string(r + 1) +
                  " of the points table has a non-finite section or loop id");
    loops[{static_cast<int>(s), static_cast<int>(l)}].push_back(
        {points.at(r, ci), Eigen::Vector2d(points.at(r, cu), points.at(r, cv))});
  }

  // A rerun replaces this stage's issues along with its tables.
  auto& issues = stream.issues;
  issues.erase(std::remove_if(issues.begin(), issues.end(),
                              [](const SectionIssue& i) { return i.stage == "smooth"; }),
               issues.end());

  Table smoothed{"smoothed", {"section", "loop", "index", "u", "v"}, {}};
  Table stats{"smooth_stats",
              {"section", "loop", "points", "energy_before", "energy_after", "iterations",
               "rms_move", "max_move", "repaired"},
              {}};
  // Loops are independent: each fills its own slot, merged in key order afterwards, so the
  // output is the same whatever the thread count.
  struct Slot {
    std::vector<double> smoothed, stats;
    bool failed = false;
    SectionIssue issue;
  };
  std::vector<std::pair<std::pair<int, int>, std::vector<std::pair<double, Eigen::Vector2d>>*>> work;
  for (auto& [key, rows] : loops)
    if (!stream.failed(key.first, key.second)) work.push_back({key, &rows});
  std::vector<Slot> slots(work.size());
  detail::parallel_for(work.size(), options.threads, [&](std::size_t w) {
    const auto [section, loop] = work[w].first;
    auto& rows = *work[w].second;
    Slot& slot = slots[w];
    std::stable_sort(rows.begin(), rows.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
    Points q;
    q.reserve(rows.size());
    for (const auto& row : rows) q.push_back(row.second);
    try {
      const SmoothResult r = smooth(q, options);
      for (std::size_t i = 0; i < r.points.size(); ++i)
        slot.smoothed.insert(slot.smoothed.end(), {double(section), double(loop), double(i), r.points[i].x(),
                                                   r.points[i].y()});
      slot.stats = {double(section), double(loop), double(r.points.size()), r.energy_before,
                    r.energy_after, double(r.iterations), r.rms_move, r.max_move,
                    double(r.repaired)};
    } catch (const Error& e) {
      std::string message = e.what();
      if (message.rfind("smooth: ", 0) == 0) message = message.substr(8);
      slot.failed = true;
      slot.issue = {section, loop, "smooth", message};
    }
  });
  std::vector<SectionIssue> new_issues;
  for (auto& slot : slots) {
    if (slot.failed) {
      new_issues.push_back(std::move(slot.issue));
      continue;
    }
    smoothed.values.insert(smoothed.values.end(), slot.smoothed.begin(), slot.smoothed.end());
    stats.values.insert(stats.values.end(), slot.stats.begin(), slot.stats.end());
  }
  for (auto& i : new_issues) issues.push_back(std::move(i));
  stream.put(std::move(smoothed));
  stream.put(std::move(stats));
}

}  // namespace section
