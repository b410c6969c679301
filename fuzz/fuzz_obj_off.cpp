// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: OBJ and OFF meshes through read_mesh; the first byte picks the format.
#include "common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  return fuzz_read_mesh(data + 1, size - 1, (data[0] & 1) ? "off" : "obj");
}
