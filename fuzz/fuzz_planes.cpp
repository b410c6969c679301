// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: the planes CSV of slice --planes (parse_planes). What parses must be
// planes with finite origins and non-zero finite normals.
#include "common.h"

#include "section/io/csv.h"

#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    for (const auto& p : section::parse_planes({reinterpret_cast<const char*>(data), size}, "fuzz.csv"))
      if (!p.origin.allFinite() || !p.normal.allFinite() || !(p.normal.norm() > 0)) std::abort();
  } catch (const section::Error&) {
  }
  return 0;
}
