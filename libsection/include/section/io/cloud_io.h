// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file io/cloud_io.h
/// Point cloud readers and writers: XYZ/ASC text, CSV with an x,y,z header, PLY (ascii,
/// binary little and big endian, float or double), Leica PTS, PCD (ascii, binary), LAS, LAZ
/// (point formats 0-3, 6-8), E57.
#include "section/cloud.h"

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace section {

/// Which reader a file goes to.
enum class CloudFormat {
  automatic,  ///< by the extension (.xyz .asc .txt .pts .csv .ply .pcd .las .laz .e57 .dat); with none, by
              ///< content
  xyz,  ///< text, one point a line, separated by space, tab or comma (or ';', with decimal commas); extra
        ///< columns ignored
  csv,  ///< text with a header row naming x, y and z columns
  ply,  ///< PLY vertices (ascii or binary, float or double)
  pts,  ///< Leica PTS: lines of one integer count the points after them, then x y z [i [r g b]]
  pcd,  ///< PCL's PCD (ascii or binary; not binary_compressed); NaN points are dropped
  las,  ///< ASPRS LAS 1.0-1.4, point formats 0-10; LAZ (LASzip-compressed) of point formats 0-3, 6-8
  e57,  ///< ASTM E2807 (E57): every scan's points, in the file's frame (each scan's pose applied)
  dat   ///< T-Blade3's text (blade3d.*.dat): rows x y z, after an optional first line `POINTS SECTIONS`
        ///< that counts them (POINTS a section, SECTIONS sections)
};

/// Options of the cloud readers (read_cloud, read_cloud_chunks, parse_cloud).
struct CloudReadOptions {
  CloudFormat format = CloudFormat::automatic;    ///< reader to use; default: by extension
  std::size_t chunk_points = 1 << 20;             ///< points handed to the callback at a time
  std::size_t max_points = std::size_t(1) << 33;  ///< refuse files claiming more points than this
  /// Threads parsing text and reading binary PLY; 0 = all cores (the points do not depend on it).
  int threads = 0;
  double scale = 1;  ///< every coordinate is multiplied by this as read (a unit's mm, units.h)
};

/// Receives the points of a cloud chunk by chunk, in file order.
using PointChunkFn = std::function<void(const Eigen::Vector3d* points, std::size_t count)>;

/// Streams the points of `path` ("-" = standard input) to `on_chunk` without holding the
/// whole cloud. Throws section::Error naming the file and, for text, the line on any
/// malformed, truncated or non-finite input.
/// @return the number of points read
std::size_t read_cloud_chunks(const std::string& path, const PointChunkFn& on_chunk,
                              const CloudReadOptions& options = {});

/// Receives chunk `index` (0, 1, ... in file order) of a cloud read by
/// read_cloud_chunks_parallel.
using IndexedChunkFn =
    std::function<void(std::size_t index, const Eigen::Vector3d* points, std::size_t count)>;
/// Works on chunk `index` for read_cloud_chunks_parallel, with up to `threads` threads of
/// its own (1 when the chunks are read side by side).
using ChunkWorkFn =
    std::function<void(std::size_t index, const Eigen::Vector3d* points, std::size_t count, int threads)>;

/// Whether chunk `index` of a cloud file is wanted (read_cloud_chunks_parallel).
using ChunkFilter = std::function<bool(std::size_t index)>;

/// Reads the points of `path` in chunks of options.chunk_points, several chunks at a time
/// when the file allows it (a binary PLY file of packed little-endian doubles, as
/// write_cloud writes): `work` runs on worker threads, each on a whole chunk, and `merge`
/// after it for every chunk in file order, one at a time. Other files go through
/// read_cloud_chunks, `work` (told it may use options.threads) then `merge` on each chunk.
/// Throws as read_cloud_chunks, for the first bad vertex in file order; `merge` is not
/// called for a chunk at or after it. With `wanted`, a chunk it says false of is passed
/// over, neither worked on nor merged (a packed file's is not even read; a file read once
/// already, whose chunks are known to hold nothing asked for).
/// @return the number of points read
std::size_t read_cloud_chunks_parallel(const std::string& path, const ChunkWorkFn& work,
                                       const IndexedChunkFn& merge, const CloudReadOptions& options = {},
                                       const ChunkFilter& wanted = {});

/// A first look at a cloud file (peek_cloud).
struct CloudPeek {
  std::vector<Eigen::Vector3d> points;  ///< vertices spread over the file, in file order
  unsigned long long total = 0;         ///< vertices the file declares
};

/// About `count` vertices spread over a binary PLY file (evenly, with a deterministic
/// jitter, each read with pread), for estimates before the file is read: its extent and
/// spacing. Empty when that is not possible (standard input, text, ASCII PLY, a file shorter
/// than its header says); non-finite points are left out. Never throws for the content.
CloudPeek peek_cloud(const std::string& path, std::size_t count, const CloudReadOptions& options = {});

/// The largest side of the bounding box of a cloud file, its strays left out (points_extent),
/// estimated from points spread over it (a binary PLY's as peek_cloud reads them; a text file's from blocks
/// read at evenly spaced places; an E57 file's from all its points, read once more), in the file's numbers
/// times options.scale: enough to tell its likely unit (units.h). 0 when no sample can be
/// read (standard input, an unreadable file, LAS).
double sample_extent(const std::string& path, const CloudReadOptions& options = {});

/// The largest side of the bounding box of `points`, the few far from the rest left out
/// along each axis (as extent_along, section/slice.h: a stray point a metre off made a
/// scan in metres look like one in mm); sample_extent's from its sample. 0 when empty.
double points_extent(const std::vector<Eigen::Vector3d>& points);

/// Reads the whole cloud of `path` ("-" = standard input). Throws as read_cloud_chunks.
Cloud read_cloud(const std::string& path, const CloudReadOptions& options = {});

/// Parses a cloud held in memory; `name` is used in error messages.
Cloud parse_cloud(std::string_view bytes, const std::string& name, const CloudReadOptions& options = {});

/// Writes a cloud as XYZ text (shortest round-trip digits) or binary little-endian PLY
/// (double), chosen by the extension of `path` (.ply = PLY, anything else XYZ).
void write_cloud(const std::string& path, const Cloud& cloud);

}  // namespace section
