// libFuzzer target: the csv point-cloud reader (parse_cloud). Any input must either
// parse into finite points or throw section::Error; anything else is a finding.
#include "section/cloud.h"
#include "section/error.h"
#include "section/io/cloud_io.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  section::CloudReadOptions options;
  options.format = section::CloudFormat::csv;
  options.chunk_points = 7;  // small chunks exercise the chunk boundaries
  try {
    const section::Cloud cloud =
        section::parse_cloud({reinterpret_cast<const char*>(data), size}, "fuzz.csv", options);
    for (const auto& p : cloud.points)
      if (!p.allFinite()) std::abort();  // the reader promises finite coordinates
  } catch (const section::Error&) {
  }
  return 0;
}
