// SPDX-License-Identifier: GPL-3.0-or-later
#include "pipe/adapter.h"

#include "section/error.h"
#include "section/pipe/schema.h"
#include "detail/parallel.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace section::pipe {

std::map<std::pair<int, int>, LoopRows> loop_rows(const Table& t, const std::string& component) {
  namespace col = schema::col;
  const std::size_t cs = t.column(col::section), cl = t.column(col::loop), ci = t.column(col::index),
                    cu = t.column(col::u), cv = t.column(col::v);
  std::map<std::pair<int, int>, LoopRows> loops;
  LoopRows* loop = nullptr;  // the last row's, which the next row mostly shares
  std::pair<int, int> last;
  for (std::size_t r = 0; r < t.rows(); ++r) {
    const double s = t.at(r, cs), l = t.at(r, cl);
    if (!std::isfinite(s) || !std::isfinite(l))
      throw Error(component + ": row " + std::to_string(r + 1) + " of the " + t.name +
                  " table has a non-finite section or loop id");
    const std::pair<int, int> key{static_cast<int>(s), static_cast<int>(l)};
    if (!loop || key != last) {
      loop = &loops[key];
      last = key;
    }
    loop->push_back({t.at(r, ci), Eigen::Vector2d(t.at(r, cu), t.at(r, cv))});
  }
  const auto before = [](const auto& x, const auto& y) { return x.first < y.first; };
  const auto finite = [](const auto& x) { return std::isfinite(x.first); };
  for (auto& [key, rows] : loops) {
    // Rows come in index order: left as they are when sorted (finite indices, so the
    // stable sort would keep them too).
    if (!std::all_of(rows.begin(), rows.end(), finite) || !std::is_sorted(rows.begin(), rows.end(), before))
      std::stable_sort(rows.begin(), rows.end(), before);
  }
  return loops;
}

void restage(Stream& stream, const std::string& stage) {
  // The stages whose output rests on each one's (compare and blade both on camber's).
  static const std::map<std::string, std::set<std::string>> later = {
      {"slice", {"smooth", "fitspline", "camber", "compare", "blade"}},
      {"smooth", {"fitspline", "camber", "compare", "blade"}},
      {"fitspline", {"camber", "compare", "blade"}},
      {"camber", {"compare", "blade"}},
      {"compare", {}},
      {"blade", {}}};
  const auto after = later.find(stage);
  const std::set<std::string> none;
  const std::set<std::string>& gone = after != later.end() ? after->second : none;
  auto& issues = stream.issues;
  issues.erase(std::remove_if(issues.begin(), issues.end(),
                              [&](const SectionIssue& i) { return i.stage == stage || gone.count(i.stage); }),
               issues.end());
  // Each table's writer, gathered once: the schema's documents cost a stage's part more than
  // its smoothing on a small section.
  static const std::vector<std::pair<std::string, std::string>> writers = [] {
    std::vector<std::pair<std::string, std::string>> out;
    for (const schema::TableDoc& t : schema::tables()) out.emplace_back(t.name, t.written_by);
    return out;
  }();
  for (const auto& [name, writer] : writers)
    if (gone.count(writer)) stream.erase(name);
}

void vanished_sections(Stream& stream, const std::set<int>& present, const std::string& stage,
                       const std::string& what) {
  const Table* frames = schema::frames.find(stream);
  if (!frames || frames->find_column(schema::col::section) < 0) return;
  const std::size_t cs = frames->column(schema::col::section);
  for (std::size_t r = 0; r < frames->rows(); ++r) {
    const int section = static_cast<int>(frames->at(r, cs));
    if (!present.count(section) && !stream.failed(section))
      stream.issues.push_back({section, -1, stage, "no " + what + " in the stream for this section"});
  }
}

void run_slots(std::size_t count, int threads, const std::vector<Table*>& tables,
               std::vector<SectionIssue>& issues, const std::string& component,
               const std::function<void(std::size_t item, Slot& slot)>& make,
               const std::function<SectionIssue(std::size_t item, const std::string& message)>& fail) {
  std::vector<Slot> slots(count);
  const std::string prefix = component + ": ";
  detail::parallel_for(count, threads, [&](std::size_t item) {
    Slot& slot = slots[item];
    slot.rows.assign(tables.size(), {});
    try {
      make(item, slot);
    } catch (const Error& e) {
      std::string message = e.what();
      if (message.rfind(prefix, 0) == 0) message = message.substr(prefix.size());
      slot = Slot{};
      slot.issues.push_back(fail(item, message));
    }
  });
  for (auto& slot : slots) {
    for (std::size_t k = 0; k < slot.rows.size(); ++k) {
      std::vector<double>& values = tables[k]->values;
      if (values.empty())  // (a part's one section: its rows taken, not copied)
        values = std::move(slot.rows[k]);
      else
        values.insert(values.end(), slot.rows[k].begin(), slot.rows[k].end());
    }
    for (auto& i : slot.issues) issues.push_back(std::move(i));
  }
}

}  // namespace section::pipe
