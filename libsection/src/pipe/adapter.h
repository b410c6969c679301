// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What the stream stages (smooth_stream, fit_spline_stream, camber_stream) share: a table's
// rows by loop, a rerun's issues and later stages' tables cleared, and items run in parallel into slots
// merged in order.
#include "section/io/stream.h"

#include <Eigen/Core>

#include <cstddef>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace section::pipe {

/// The (index, point) rows of one loop.
using LoopRows = std::vector<std::pair<double, Eigen::Vector2d>>;

/// The rows of a table with the columns section, loop, index, u, v by (section, loop), each
/// in index order. Throws section::Error `COMPONENT: row N of the TABLE table has a
/// non-finite section or loop id`.
std::map<std::pair<int, int>, LoopRows> loop_rows(const Table& t, const std::string& component);

/// Readies a stream for `stage` (smooth, fitspline, camber, compare or blade) run on it
/// again: the issues it recorded before go (the rerun replaces them along with its tables),
/// and so do the tables and issues of the stages that rest on its output (fitspline: camber,
/// compare and blade), which would otherwise stand beside the new output they do not
/// describe, or, as issues, hold their sections back as failed.
void restage(Stream& stream, const std::string& stage);

/// Adds the issue `no WHAT in the stream for this section` (stage `stage`) for each section
/// the frames table lists that is not in `present` and has no issue yet: a section does not
/// vanish from the stream unremarked (a part whose points table is empty).
void vanished_sections(Stream& stream, const std::set<int>& present, const std::string& stage,
                       const std::string& what);

/// What a stage made of one item (a loop, a section): its rows of each table it writes, and
/// its issues.
struct Slot {
  std::vector<std::vector<double>> rows;  ///< one list of values per table, in the order given to run_slots
  std::vector<SectionIssue> issues;
};

/// Runs `make(item, slot)` for items 0 .. count-1 on `threads` threads (0 = all cores), each
/// into its own slot; a section::Error from it leaves the slot without rows and with the
/// issue `fail(item, message)` makes, the message without the prefix `component: `. Then
/// appends the slots' rows to `tables` and their issues to `issues`, in item order, so that
/// the output is the same whatever the thread count.
void run_slots(std::size_t count, int threads, const std::vector<Table*>& tables,
               std::vector<SectionIssue>& issues, const std::string& component,
               const std::function<void(std::size_t item, Slot& slot)>& make,
               const std::function<SectionIssue(std::size_t item, const std::string& message)>& fail);

}  // namespace section::pipe
