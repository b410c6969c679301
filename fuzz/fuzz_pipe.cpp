// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: the pipe parser. Each input goes to parse_stream, parse_csv and
// parse_profile; a stream that parses must format and parse back to the same tables.
#include "section/error.h"
#include "section/io/stream.h"
#include "section/io/csv.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const section::Stream s = section::parse_stream(text, "fuzz");
    for (const auto& t : s.tables) {
      if (t.values.size() != t.rows() * t.columns.size()) std::abort();
      for (double v : t.values)
        if (!std::isfinite(v)) std::abort();
    }
    const std::string again = section::format_stream(s);
    const section::Stream back = section::parse_stream(again, "fuzz-roundtrip");
    if (back.tables.size() != s.tables.size()) std::abort();
    for (std::size_t i = 0; i < s.tables.size(); ++i)
      if (back.tables[i].values != s.tables[i].values || back.tables[i].columns != s.tables[i].columns)
        std::abort();
  } catch (const section::Error&) {
  }
  try {
    const section::Table t = section::parse_csv(text, "fuzz.csv");
    if (t.columns.empty() || t.values.size() % t.columns.size() != 0) std::abort();
  } catch (const section::Error&) {
  }
  try {
    for (const auto& p : section::parse_profile(text, "fuzz.dat"))
      if (!p.allFinite()) std::abort();
  } catch (const section::Error&) {
  }
  return 0;
}
