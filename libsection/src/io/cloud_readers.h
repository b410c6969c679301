// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The point cloud readers (XYZ, PTS and CSV text, PLY, PCD, LAS, E57) and what they share; io/formats.h lists
// them.
#include "io/byte_source.h"
#include "section/io/cloud_io.h"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace section::detail {

/// Collects points and hands them on in chunks.
class Chunker {
public:
  Chunker(const PointChunkFn& fn, std::size_t chunk) : fn_(fn), chunk_(std::max<std::size_t>(chunk, 1)) {
    buf_.reserve(chunk_);
  }
  void add(double x, double y, double z) {
    buf_.emplace_back(x, y, z);
    if (buf_.size() == chunk_) flush();
  }
  /// Adds points in bulk; whole chunks go to the callback straight from `p`.
  void add_many(const Eigen::Vector3d* p, std::size_t n);
  /// Room for up to `n` points at the end of the chunk (n is cut to what fits); fill them,
  /// then call commit().
  Eigen::Vector3d* room(std::size_t& n) {
    const std::size_t old = buf_.size();
    n = std::min(n, chunk_ - old);
    buf_.resize(old + n);
    return buf_.data() + old;
  }
  void commit() {
    if (buf_.size() == chunk_) flush();
  }
  void flush() {
    if (!buf_.empty()) fn_(buf_.data(), buf_.size());
    total_ += buf_.size();
    buf_.clear();
  }
  std::size_t total() const { return total_ + buf_.size(); }

private:
  const PointChunkFn& fn_;
  std::size_t chunk_;
  std::vector<Eigen::Vector3d> buf_;
  std::size_t total_ = 0;
};

/// The value of type T at `p`, little endian (as the host: the binary readers' formats).
template <class T>
T le(const char* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

/// One axis of integer coordinates: x = raw * scale + offset (LAS records, E57 ScaledInteger
/// fields). With a decimal scale (0.001, 0.0001: 1 / scale an integer) and an offset on its
/// grid, (raw + offset / scale) / (1 / scale) is the coordinate correctly rounded: the double
/// that parsing the same decimal from text gives.
struct ScaledAxis {
  double scale, offset, inv = 0, shift = 0;
  bool exact = false;
  ScaledAxis(double s, double o) : scale(s), offset(o) {
    inv = std::round(1 / s);
    shift = std::round(o * inv);
    exact = inv >= 1 && inv <= 1e9 && std::abs(1 / s - inv) <= 1e-9 * inv &&
            std::abs(o * inv - shift) <= 1e-6 && std::abs(shift) < 1e15;
  }
  double operator()(std::int64_t v) const {
    const double d = static_cast<double>(v);
    return exact && std::abs(d) < 1e15 ? (d + shift) / inv : d * scale + offset;
  }
};

/// Throws `read_cloud: NAME:LINE: what`.
[[noreturn]] void fail_line(const std::string& name, std::size_t line, const std::string& what);

constexpr std::size_t block_size = 1 << 24;  ///< bytes read at a time
constexpr std::size_t max_line = 1 << 16;    ///< longest text line accepted

/// Worker threads for options.threads (0 = all cores).
std::size_t worker_count(int threads);

/// Throws for the first vertex of v[0, m) (vertex `first` is v[0]) with a non-finite
/// coordinate or one beyond +-1e15; returns when there is none.
void check_vertices(const Eigen::Vector3d* v, std::size_t m, unsigned long long first,
                    const std::string& name);

std::size_t read_xyz_cloud(ByteSource& src, const CloudReadOptions& opt, const PointChunkFn& fn,
                           const PointChunkFn& raw);
std::size_t read_csv_cloud(ByteSource& src, const CloudReadOptions& opt, const PointChunkFn& fn,
                           const PointChunkFn& raw);
std::size_t read_pts_cloud(ByteSource& src, const CloudReadOptions& opt, const PointChunkFn& fn,
                           const PointChunkFn& raw);
std::size_t read_dat_cloud(ByteSource& src, const CloudReadOptions& opt, const PointChunkFn& fn,
                           const PointChunkFn& raw);
std::size_t read_pcd_cloud(ByteSource& src, const CloudReadOptions& opt, const PointChunkFn& fn,
                           const PointChunkFn& raw);
std::size_t read_las_cloud(ByteSource& src, const CloudReadOptions& opt, const PointChunkFn& fn,
                           const PointChunkFn& raw);
std::size_t read_e57_cloud(ByteSource& src, const CloudReadOptions& opt, const PointChunkFn& fn,
                           const PointChunkFn& raw);
std::size_t read_ply_cloud(ByteSource& src, const CloudReadOptions& opt, const PointChunkFn& fn,
                           const PointChunkFn& raw);

/// Where x, y and z lie in the vertex records of a binary PLY file whose vertices are its
/// only element and fill it exactly (what pread can read anywhere).
struct BinaryVertices {
  unsigned long long start = 0, count = 0;  ///< first vertex's file offset, vertices
  std::size_t record = 0;                   ///< bytes per vertex
  std::size_t offset[3] = {0, 0, 0};        ///< of x, y, z in a record
  int size[3] = {0, 0, 0};                  ///< their scalar sizes
  char kind[3] = {'f', 'f', 'f'};           ///< and kinds
  bool swap = false;                        ///< byte order other than the host's
  /// Little-endian doubles x, y, z and nothing else: a record is an Eigen::Vector3d.
  bool packed() const;
  /// The point of the record at `r`.
  Eigen::Vector3d point(const unsigned char* r) const;
};

/// The layout of `src`'s vertices when it is a regular binary PLY file as above, else
/// nothing. A header that does not parse is nothing too: the reader proper reports it.
std::optional<BinaryVertices> binary_vertices(ByteSource& src, const std::string& path,
                                              const CloudReadOptions& options);

}  // namespace section::detail
