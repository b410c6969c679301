// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: a stream read part by part (PartReader, parse_stream_part) and held to
// its schema (validate_stream), as run_stage reads one; a stream not split into parts is
// parsed whole. What parses must hold finite values, each part its own section only.
#include "common.h"

#include "section/io/stream.h"
#include "section/io/stream_reader.h"
#include "section/pipe/validate.h"

#include <cmath>

namespace {

void check(const section::Stream& s, long section) {
  for (const auto& t : s.tables) {
    if (t.values.size() != t.rows() * t.columns.size()) std::abort();
    for (double v : t.values)
      if (!std::isfinite(v)) std::abort();
    const long c = t.find_column("section");
    for (std::size_t r = 0; section >= 0 && c >= 0 && r < t.rows(); ++r)
      if (t.at(r, std::size_t(c)) != double(section)) std::abort();  // a part holds its own section
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz_file(data, size, "csv");
  try {
    section::PartReader reader(path);
    if (!reader.parted()) {
      const section::Stream s = section::parse_stream(reader.whole(), path);
      section::validate_stream(s, path);
      check(s, -1);
    } else {
      reader.preamble();
      for (section::StreamPart part; reader.next(part);) {
        const section::Stream s = section::parse_stream_part(part, path);
        section::validate_stream(s, path);
        check(s, std::stol(part.label));  // (the parser refuses a label that is not an id)
      }
    }
  } catch (const section::Error&) {
  }
  std::remove(path.c_str());
  return 0;
}
