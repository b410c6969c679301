// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The E57 reader's two halves: what the XML section says about each scan (cloud_e57_xml.cpp,
// through tinyxml2) and the binary sections holding its points (cloud_e57.cpp).
#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace section::detail {

/// One field of a scan's point record: a leaf of its CompressedVector's prototype, in the
/// order of the bytestreams of each data packet.
struct E57Field {
  std::string name;
  char kind = 'f';               ///< 'f' Float, 'i' Integer, 's' ScaledInteger
  bool single = false;           ///< a Float of single precision (4 bytes, else 8)
  std::int64_t minimum = 0;      ///< an Integer's or ScaledInteger's smallest raw value
  std::int64_t maximum = 0;      ///< and largest
  double scale = 1, offset = 0;  ///< a ScaledInteger's value = raw * scale + offset
  int bits = 0;                  ///< bits per bit-packed value: enough for maximum - minimum
};

/// One scan (a child of /data3D) and where its points are.
struct E57Scan {
  std::string label;                                       ///< "data3D 1 ('Scan 0')", for messages
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  ///< of its pose (the quaternion's)
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();   ///< of its pose
  bool posed = false;                                      ///< the pose is not the identity
  std::uint64_t offset = 0;                                ///< physical offset of its points' binary section
  std::uint64_t records = 0;                               ///< point records
  std::vector<E57Field> fields;                            ///< the prototype's leaves
  int coord[3] = {-1, -1, -1};  ///< fields of cartesianX, Y, Z (or sphericalRange, Azimuth, Elevation)
  int invalid = -1;             ///< field of cartesianInvalidState (or sphericalInvalidState); -1: none
  bool spherical = false;       ///< coordinates are range, azimuth, elevation (radians)
};

/// The CRC-32C (Castagnoli) of `n` bytes: what an E57 page holds after its logical bytes,
/// big endian.
std::uint32_t e57_crc32c(const unsigned char* p, std::size_t n);

/// The scans of an E57 file from its XML section `xml` (of the file `name`, for messages):
/// each child of /data3D with its pose and its points' prototype. Throws section::Error
/// (`read_cloud: NAME: E57 ...`) for XML that does not parse, a scan without cartesian or
/// spherical coordinates, a prototype field that is not a number, or a codec other than
/// bitPackCodec.
std::vector<E57Scan> e57_scans(std::string_view xml, const std::string& name);

}  // namespace section::detail
