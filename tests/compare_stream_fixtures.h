// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Fixtures of the compare stream tests (test_compare_stream, test_compare_units): a measured
// stream sliced from a mesh, and the compared values and issues it gets.
#include "section/pipe/camber_stream.h"
#include "section/pipe/compare_stream.h"
#include "section/pipe/fit_spline_stream.h"
#include "section/pipe/schema.h"
#include "section/pipe/slice_stream.h"
#include "section/slice.h"

#include <algorithm>
#include <array>
#include <map>
#include <string>
#include <vector>

namespace compare_stream_test {

/// The measured stream of a mesh: sliced at `zs`, fitted, through camber.
inline section::Stream measured_stream(const section::Mesh& mesh, const std::vector<double>& zs) {
  section::Stream s = section::to_stream(section::slice(mesh, section::planes_at({0, 0, 1}, zs)), "slice");
  section::fit_spline_stream(s);
  section::camber_stream(s);
  return s;
}

/// True when no issue of stage compare was recorded (camber's notes on edges may be there).
inline bool compared_all(const section::Stream& s) {
  for (const auto& i : s.issues)
    if (i.stage == "compare") return false;
  return true;
}

/// The rows of "compared" for one item: section -> (measured, deviation, verdict).
inline std::map<int, std::array<double, 3>> compared(const section::Stream& s, const std::string& item) {
  const auto& items = section::compared_items();
  const double code = static_cast<double>(std::find(items.begin(), items.end(), item) - items.begin());
  const section::Table& t = section::schema::compared.get(s);
  std::map<int, std::array<double, 3>> out;
  for (std::size_t r = 0; r < t.rows(); ++r)
    if (t.at(r, t.column("item")) == code)
      out[static_cast<int>(t.at(r, 0))] = {t.at(r, t.column("measured")), t.at(r, t.column("deviation")),
                                           t.at(r, t.column("verdict"))};
  return out;
}

}  // namespace compare_stream_test
