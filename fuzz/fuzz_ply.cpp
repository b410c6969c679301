// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: the ply point-cloud reader (parse_cloud). Inputs whose header mentions
// faces also go through read_mesh (the PLY mesh reader), as slice does.
#include "common.h"

#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz_parse_cloud(data, size, section::CloudFormat::ply, "fuzz.ply");
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  if (text.substr(0, text.find("end_header")).find("face") != std::string_view::npos)
    fuzz_read_mesh(data, size, "ply");
  return 0;
}
