// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: the E57 point-cloud reader (parse_cloud).
#include "common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fuzz_parse_cloud(data, size, section::CloudFormat::e57, "fuzz.e57");
}
