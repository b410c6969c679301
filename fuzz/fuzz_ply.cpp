// libFuzzer target: the ply point-cloud reader (parse_cloud). Any input must either
// parse into finite points or throw section::Error; anything else is a finding. Inputs whose
// header mentions faces also go through read_mesh (OpenMesh's PLY reader), as slice does.
#include "mesh_common.h"
#include "section/cloud.h"
#include "section/error.h"
#include "section/io/cloud_io.h"

#include <string_view>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  section::CloudReadOptions options;
  options.format = section::CloudFormat::ply;
  options.chunk_points = 7;  // small chunks exercise the chunk boundaries
  try {
    const section::Cloud cloud =
        section::parse_cloud({reinterpret_cast<const char*>(data), size}, "fuzz.ply", options);
    for (const auto& p : cloud.points)
      if (!p.allFinite()) std::abort();  // the reader promises finite coordinates
  } catch (const section::Error&) {
  }
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  if (text.substr(0, text.find("end_header")).find("face") != std::string_view::npos)
    fuzz_read_mesh(data, size, "ply");
  return 0;
}
