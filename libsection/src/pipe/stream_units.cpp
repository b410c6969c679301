// SPDX-License-Identifier: GPL-3.0-or-later
// A stream's lengths in mm: every table's columns scaled by their unit's power of length.
#include "section/pipe/schema.h"

#include "section/units.h"

#include <cmath>
#include <string>
#include <string_view>
#include <vector>

namespace section {

void convert_to_mm(Stream& stream) {
  const double mm = mm_per_unit(stream.units);
  if (mm == 1) return;
  // Each column scales with its unit's power of length.
  const auto power = [](std::string_view unit) {
    return unit == "length" ? 1 : unit == "area" || unit == "length^2" ? 2 : unit == "1/length" ? -1 : 0;
  };
  for (const auto& doc : schema::tables()) {
    Table* t = stream.find(doc.name);
    if (!t) continue;
    if (t->columns.empty()) continue;  // values without columns divided by 0 below (writing refuses them)
    std::vector<double> factor(t->columns.size(), 1.0);
    for (const auto& column : doc.columns) {
      const int p = power(column.unit);
      if (p == 0) continue;
      std::string_view names = column.name;
      while (!names.empty()) {
        const std::size_t comma = names.find(", ");
        const long c = t->find_column(std::string(names.substr(0, comma)));
        if (c >= 0) factor[static_cast<std::size_t>(c)] = std::pow(mm, p);
        names = comma == std::string_view::npos ? std::string_view{} : names.substr(comma + 2);
      }
    }
    for (std::size_t i = 0; i < t->values.size(); ++i) t->values[i] *= factor[i % factor.size()];
    t->source = nullptr;  // its text no longer reads as its values
  }
  stream.units = "mm";
}

const Stream& in_mm(const Stream& stream, Stream& copy) {
  if (mm_per_unit(stream.units) == 1) return stream;
  copy = stream;
  convert_to_mm(copy);
  return copy;
}

}  // namespace section
