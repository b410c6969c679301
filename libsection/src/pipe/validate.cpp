// SPDX-License-Identifier: GPL-3.0-or-later
// The stream held to its schema: unique ids, counts and flags in range.
#include "section/pipe/validate.h"

#include "section/error.h"
#include "section/pipe/schema.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <vector>

namespace section {

namespace {

// The units of the single columns of every table the schema declares, by table and column.
const std::map<std::string, std::map<std::string, std::string>>& units() {
  static const auto table = [] {
    std::map<std::string, std::map<std::string, std::string>> out;
    for (const schema::TableDoc& t : schema::tables())
      for (const schema::ColumnDoc& c : t.columns) out[t.name][c.name] = c.unit;
    return out;
  }();
  return table;
}

// Throws when two rows of `t` have the same ids: each row of a table is one thing (compare's
// zones and compared values are one per zone and item of a section).
void check_unique_ids(const Table& t, const std::string& source) {
  std::vector<std::size_t> key;
  for (const char* name : {"section", "loop", "side", "zone", "item", "index"})
    if (const long c = t.find_column(name); c >= 0) key.push_back(static_cast<std::size_t>(c));
  const std::size_t rows = t.rows();
  if (key.empty() || rows < 2) return;
  const auto less = [&](std::size_t a, std::size_t b) {
    for (const std::size_t c : key)
      if (t.at(a, c) != t.at(b, c)) return t.at(a, c) < t.at(b, c);
    return false;
  };
  // Tables are written in the order of their ids: one pass then; sorted ids otherwise.
  std::size_t r = 1;
  while (r < rows && less(r - 1, r)) ++r;
  if (r == rows) return;
  std::vector<std::size_t> order(rows);
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(), less);
  for (std::size_t k = 1; k < rows; ++k) {
    if (less(order[k - 1], order[k])) continue;
    std::string ids;
    for (const std::size_t c : key) ids += " " + t.columns[c] + " " + format_number(t.at(order[k], c));
    throw Error("pipe: " + source + ": table '" + t.name + "' has two rows (data rows " +
                std::to_string(order[k - 1] + 1) + " and " + std::to_string(order[k] + 1) + ") for" + ids +
                " (each row of a table is one thing: a duplicated row?)");
  }
}

// Throws for a count that is not a whole number of 0 or more, a flag that is not 0 or 1, a set
// of check bits (flags) that is not a whole number below 2^check_count, or a standard error (_sigma)
// below 0.
void check_values(const Table& t, const std::map<std::string, std::string>& unit, const std::string& source) {
  const long cs = t.find_column("section");
  for (std::size_t c = 0; c < t.columns.size(); ++c) {
    const auto u = unit.find(t.columns[c]);
    if (u == unit.end()) continue;
    const std::string& name = t.columns[c];
    const bool flag = u->second == "flag", count = u->second == "count",
               bits = u->second == "code" && (name == "flags" || name == "nominal_flags"),
               sigma = name.size() > 6 && name.compare(name.size() - 6, 6, "_sigma") == 0;
    if (!flag && !count && !bits && !sigma) continue;
    for (std::size_t r = 0; r < t.rows(); ++r) {
      const double v = t.at(r, c);
      const bool whole = v >= 0 && v == std::floor(v);
      if (flag    ? (v == 0 || v == 1)
          : count ? whole
          : bits  ? whole && v < std::ldexp(1.0, check_count)
                  : v >= 0)
        continue;
      throw Error(
          "pipe: " + source + ": table '" + t.name + "' data row " + std::to_string(r + 1) +
          (cs >= 0 ? " (section " + format_number(t.at(r, std::size_t(cs))) + ")" : std::string()) +
          ": column '" + name + "' is " + format_number(v) + ", " +
          (flag    ? "a flag must be 0 or 1"
           : count ? "a count must be a whole number of 0 or more"
           : bits  ? "check bits must be a whole number from 0 to 2^" + std::to_string(check_count) + " - 1"
                   : "a standard error must not be negative"));
    }
  }
}

// Throws for a params value no section can have: a length or area below 0, a place along the
// camber line outside [0, 1] (NaN, a value not measured, passes). blade, compare, plot and tocad
// showed a chord of -5 as a measurement.
void check_params(const Table& t, const std::string& source) {
  if (t.name != "params") return;
  const long cs = t.find_column("section");
  for (const char* name :
       {"chord", "camber_length", "max_thickness", "max_thickness_pos", "le_radius", "te_radius",
        "le_curvature_radius", "te_curvature_radius", "area", "caliper_chord"}) {
    const long c = t.find_column(name);
    if (c < 0) continue;
    const bool share = std::string(name) == "max_thickness_pos";
    for (std::size_t r = 0; r < t.rows(); ++r) {
      const double v = t.at(r, std::size_t(c));
      if (!(v < 0) && !(share && v > 1)) continue;
      throw Error("pipe: " + source + ": table 'params' data row " + std::to_string(r + 1) +
                  (cs >= 0 ? " (section " + format_number(t.at(r, std::size_t(cs))) + ")" : std::string()) +
                  ": column '" + name + "' is " + format_number(v) + ", " +
                  (share ? "a place along the camber line lies in [0, 1]" : "it cannot be negative"));
    }
  }
}

}  // namespace

void validate_stream(const Stream& stream, const std::string& source) {
  const auto& known = units();
  for (const Table& t : stream.tables) {
    const auto unit = known.find(t.name);
    if (unit == known.end()) continue;
    check_unique_ids(t, source);
    check_values(t, unit->second, source);
    check_params(t, source);
  }
}

}  // namespace section
