// SPDX-License-Identifier: GPL-3.0-or-later
// compare's tolerance file: item, section, low, high, on.
#include "section/io/tolerances.h"

#include "io/text.h"
#include "section/error.h"
#include "section/io/file.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

namespace section {

namespace {

using detail::trim;

std::vector<std::string_view> cells(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    out.push_back(
        trim(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
    if (comma == std::string_view::npos) return out;
    start = comma + 1;
  }
}

// The columns of the header: index of item, section, low, high, on (-1 when absent).
struct Header {
  int item = -1, section = -1, low = -1, high = -1, on = -1;
  std::size_t count = 0;
};

Header header(std::string_view line, const std::string& where) {
  Header h;
  const auto names = cells(line);
  h.count = names.size();
  for (std::size_t c = 0; c < names.size(); ++c) {
    const std::string name = detail::lower(std::string(names[c]));
    int* slot = name == "item"      ? &h.item
                : name == "section" ? &h.section
                : name == "low"     ? &h.low
                : name == "high"    ? &h.high
                : name == "on"      ? &h.on
                                    : nullptr;
    if (!slot) throw Error(where + "unknown column '" + name + "' (columns: item, section, low, high, on)");
    if (*slot >= 0) throw Error(where + "column '" + name + "' twice");
    *slot = static_cast<int>(c);
  }
  if (h.item < 0 || (h.low < 0 && h.high < 0))
    throw Error(where + "the header needs the column item and low or high (item,section,low,high,on)");
  return h;
}

double limit(std::string_view cell, double unbounded, const std::string& where, const char* what) {
  if (cell.empty()) return unbounded;
  double v = 0;
  if (!detail::parse_double(cell, v) || !std::isfinite(v))
    throw Error(where + what + ": expected a number or nothing, found '" + std::string(cell) + "'");
  // Far beyond any blade in any unit: a typo, which would print as a wall of digits.
  if (std::abs(v) > 1e9)
    throw Error(where + what + ": " + std::string(cell) +
                " is beyond +-1e9, not a tolerance (leave it empty for none)");
  return v;
}

Tolerance row(const std::vector<std::string_view>& c, const Header& h, const std::vector<std::string>& items,
              const std::string& where) {
  auto at = [&](int col) {
    return col >= 0 && static_cast<std::size_t>(col) < c.size() ? c[col] : std::string_view();
  };
  Tolerance t;
  t.item = std::string(at(h.item));
  if (std::find(items.begin(), items.end(), t.item) == items.end()) {
    std::string list;
    for (const auto& i : items) list += (list.empty() ? "" : ", ") + i;
    throw Error(where + "unknown item '" + t.item + "' (items: " + list + ")");
  }
  const std::string_view s = at(h.section);
  if (!(s.empty() || s == "*" || s == "all") && (!detail::parse_integer(s, t.section) || t.section < 0))
    throw Error(where + "section: expected a section id, '*' or nothing, found '" + std::string(s) + "'");
  t.low = limit(at(h.low), -INFINITY, where, "low");
  t.high = limit(at(h.high), INFINITY, where, "high");
  if (!std::isfinite(t.low) && !std::isfinite(t.high)) throw Error(where + "neither low nor high is given");
  if (t.low > t.high) throw Error(where + "low is above high");
  const std::string on = detail::lower(std::string(at(h.on)));
  if (!(on.empty() || on == "deviation" || on == "value"))
    throw Error(where + "on: expected 'deviation' or 'value', found '" + on + "'");
  t.on_value = on == "value";
  return t;
}

}  // namespace

std::vector<Tolerance> parse_tolerances(std::string_view text, const std::string& source,
                                        const std::vector<std::string>& items) {
  std::vector<Tolerance> out;
  std::map<std::pair<std::string, int>, std::size_t> row_of;  // (item, section) -> its row in out
  Header h;
  bool have_header = false;
  std::size_t pos = 0, line_no = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    ++line_no;
    const std::string_view line = trim(text.substr(pos, end - pos));
    pos = end + 1;
    if (line.empty() || line[0] == '#') continue;
    const std::string where = "tolerances: " + source + ":" + std::to_string(line_no) + ": ";
    if (!have_header) {
      h = header(line, where);
      have_header = true;
      continue;
    }
    const auto c = cells(line);
    if (c.size() > h.count)
      throw Error(where + std::to_string(c.size()) + " cells for the " + std::to_string(h.count) +
                  " columns");
    Tolerance t = row(c, h, items, where);
    t.where = source + ":" + std::to_string(line_no);
    const auto [first, fresh] = row_of.emplace(std::pair(t.item, t.section), out.size());
    if (!fresh)
      throw Error(where + "a second row for '" + t.item + "'" +
                  (t.section < 0 ? std::string() : " section " + std::to_string(t.section)) +
                  " (the first: " + out[first->second].where + ")");
    out.push_back(std::move(t));
  }
  if (!have_header) throw Error("tolerances: " + source + ": no header line (item,section,low,high,on)");
  return out;
}

std::vector<Tolerance> read_tolerances(const std::string& path, const std::vector<std::string>& items) {
  return parse_tolerances(read_file(path), path == "-" ? "<stdin>" : path, items);
}

}  // namespace section
