// SPDX-License-Identifier: GPL-3.0-or-later
// The LAS cloud reader: ASPRS LAS 1.0-1.4, point data record formats 0-10, uncompressed,
// and LAZ (LASzip marks its record format with bit 7) of formats 0-3 and 6-8 through
// cloud_laz.cpp.
// Read from the ASPRS LAS 1.4 specification (R15) directly: no LAS library is packaged for
// Debian 12. The public header block gives where the points start, their record format and
// length (taken from the header, never assumed: records may carry extra bytes), their count
// (the 64-bit count of LAS 1.4 when set, else the legacy 32-bit one) and the scale and
// offset that turn each record's 32-bit integers X, Y, Z (the first 12 bytes of every
// record format) into coordinates: x = X * x_scale + x_offset.
#include "io/cloud_laz.h"
#include "io/cloud_readers.h"

#include "section/error.h"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace section::detail {

namespace {

[[noreturn]] void fail(const std::string& name, const std::string& what) {
  throw Error("read_cloud: " + name + ": " + what);
}

// The smallest record of each point data format (LAS 1.4, tables 7-24).
constexpr std::size_t min_record[11] = {20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67};

LasHeader read_header(ByteSource& src, const CloudReadOptions& opt) {
  const std::string& name = src.name();
  while (src.bytes().size() < 375 && src.fetch(375 - src.bytes().size()) > 0) {
  }
  const std::string_view b = src.bytes();
  if (b.size() < 4 || b.compare(0, 4, "LASF") != 0)
    fail(name, "not a LAS file (it does not start with LASF)");
  if (b.size() < 227)
    fail(name, "LAS header ends after " + std::to_string(b.size()) + " bytes (truncated file?)");
  const char* p = b.data();
  LasHeader h;
  h.major = static_cast<unsigned char>(p[24]);
  h.minor = static_cast<unsigned char>(p[25]);
  if (h.major != 1 || h.minor > 4)
    fail(name, "LAS version " + std::to_string(h.major) + "." + std::to_string(h.minor) +
                   " is not supported (1.0 to 1.4 are)");
  h.header_size = le<std::uint16_t>(p + 94);
  h.data_offset = le<std::uint32_t>(p + 96);
  const int id = static_cast<unsigned char>(p[104]);
  h.compressed = (id & 0xC0) != 0;  // LASzip's mark
  h.format = id & 0x3F;
  h.record = le<std::uint16_t>(p + 105);
  h.count = le<std::uint32_t>(p + 107);
  for (int c = 0; c < 3; ++c) {
    h.scale[c] = le<double>(p + 131 + 8 * c);
    h.offset[c] = le<double>(p + 155 + 8 * c);
  }
  if (h.minor >= 4 && h.header_size >= 375 && b.size() >= 375) {
    const auto n = le<std::uint64_t>(p + 247);
    if (n != 0) h.count = n;
  }
  if (h.header_size < 227 || h.data_offset < h.header_size)
    fail(name, "LAS header size " + std::to_string(h.header_size) + " or point data offset " +
                   std::to_string(h.data_offset) + " is impossible (corrupt file?)");
  if (h.format > 10)
    fail(name, "LAS point data format " + std::to_string(h.format) + " is not supported (0 to 10 are)");
  if (h.record < min_record[h.format])
    fail(name, "LAS point record length " + std::to_string(h.record) + " is shorter than format " +
                   std::to_string(h.format) + "'s " + std::to_string(min_record[h.format]) + " bytes");
  for (int c = 0; c < 3; ++c)
    if (!std::isfinite(h.scale[c]) || h.scale[c] == 0 || !std::isfinite(h.offset[c]))
      fail(name, std::string("LAS ") + char('x' + c) + " scale factor or offset is zero or not finite");
  if (h.count == 0) fail(name, "no points (LAS header declares 0 points)");
  if (h.count > opt.max_points)
    fail(name, "LAS header declares " + std::to_string(h.count) + " points, more than the limit of " +
                   std::to_string(opt.max_points));
  if (src.size() >= 0 && !h.compressed) {
    const auto size = static_cast<unsigned long long>(src.size());
    const unsigned long long body = size > h.data_offset ? size - h.data_offset : 0;
    // Bytes after the points are allowed: LAS 1.3 and 1.4 put waveforms and extended VLRs there.
    if (body / h.record < h.count)
      fail(name, "LAS header declares " + std::to_string(h.count) + " points but the file holds only " +
                     std::to_string(body / h.record) + " (truncated file?)");
  }
  return h;
}

}  // namespace

std::size_t read_las_cloud(ByteSource& src, const CloudReadOptions& opt, const PointChunkFn& fn,
                           const PointChunkFn&) {
  const std::string& name = src.name();
  const LasHeader h = read_header(src, opt);
  if (h.compressed) return read_laz_points(src, h, opt, fn);
  // Skip to the points, past the variable length records.
  for (unsigned long long skip = h.data_offset; skip > 0;) {
    if (src.bytes().empty() && src.fetch(block_size) == 0) fail(name, "LAS file ends before its points");
    const std::size_t n = static_cast<std::size_t>(std::min<unsigned long long>(skip, src.bytes().size()));
    src.consume(n);
    skip -= n;
  }
  Chunker out(fn, opt.chunk_points);
  const ScaledAxis axis[3] = {
      {h.scale[0], h.offset[0]}, {h.scale[1], h.offset[1]}, {h.scale[2], h.offset[2]}};
  unsigned long long done = 0;
  while (done < h.count) {
    std::size_t n =
        static_cast<std::size_t>(std::min<unsigned long long>(src.bytes().size() / h.record, h.count - done));
    if (n == 0) {
      if (src.fetch(std::max<std::size_t>(h.record, block_size)) == 0)
        fail(name, "LAS file ends after " + std::to_string(done) + " of " + std::to_string(h.count) +
                       " points (truncated file?)");
      continue;
    }
    const char* r = src.bytes().data();
    Eigen::Vector3d* dst = out.room(n);
    for (std::size_t k = 0; k < n; ++k, r += h.record)
      for (int c = 0; c < 3; ++c) dst[k][c] = axis[c](le<std::int32_t>(r + 4 * c));
    out.commit();
    done += n;
    src.consume(n * h.record);
  }
  out.flush();
  return out.total();
}

}  // namespace section::detail
