// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: STL meshes (ascii and binary) through read_mesh.
#include "common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fuzz_read_mesh(data, size, "stl");
}
