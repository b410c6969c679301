// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The LAS public header block as the LAS reader (cloud_las.cpp) reads it, and the LAZ
// reader of its compressed points (cloud_laz.cpp, cloud_laz_codec.cpp).
#include "io/byte_source.h"
#include "section/io/cloud_io.h"

#include <cstddef>
#include <string>

namespace section::detail {

/// What the LAS reader takes from a LAS or LAZ file's public header block.
struct LasHeader {
  int major = 0, minor = 0;
  unsigned header_size = 0;
  unsigned long long data_offset = 0, count = 0;
  int format = 0;           ///< point data record format (0-10), LASzip's bits cleared
  bool compressed = false;  ///< LAZ: LASzip set bit 7 of the format
  std::size_t record = 0;   ///< bytes of a point record (uncompressed)
  double scale[3] = {1, 1, 1}, offset[3] = {0, 0, 0};
};

/// Reads the points of a LAZ file whose header `h` was read from `src` (nothing consumed
/// yet): its LASzip VLR, then its chunks, decoded as LASzip does (point formats 0-3:
/// point10, gpstime11, rgb12 and byte items of version 2; 6-8: the layered point14's
/// coordinates, version 3, its other layers and items skipped). Each point's coordinates go
/// to `fn` through the header's scales and offsets. Throws section::Error for what it cannot
/// read (wave packets, other item versions, variable chunks) and for a truncated or corrupt
/// file.
std::size_t read_laz_points(ByteSource& src, const LasHeader& h, const CloudReadOptions& opt,
                            const PointChunkFn& fn);

}  // namespace section::detail
