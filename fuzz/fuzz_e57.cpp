// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: the E57 point-cloud reader (parse_cloud). Every whole page's CRC-32C is
// made anew before reading (for the page size the header gives), so that a mutation reaches
// the XML and the data packets instead of failing its page's checksum; one input in 16 is
// read as it is, to fuzz the checks themselves.
#include "common.h"

#include "io/cloud_e57.h"

#include <cstring>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  std::uint64_t page = 0;
  if (size >= 48) std::memcpy(&page, bytes.data() + 40, 8);
  if (size % 16 != 0 && page >= 64 && page <= (1u << 20) && page % 4 == 0)
    for (std::size_t at = 0; at + page <= size; at += page) {
      auto* p = reinterpret_cast<unsigned char*>(&bytes[at]);
      const std::uint32_t crc = section::detail::e57_crc32c(p, page - 4);
      for (int k = 0; k < 4; ++k) p[page - 4 + k] = static_cast<unsigned char>(crc >> (24 - 8 * k));
    }
  return fuzz_parse_cloud(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(),
                          section::CloudFormat::e57, "fuzz.e57");
}
