// SPDX-License-Identifier: GPL-3.0-or-later
// A first look at a cloud file's extent, from points spread over it (for its likely unit);
// an E57 file's from all its points (its standard fixes metres: a part under 1 m across is
// then read as metres).
#include "section/io/cloud_io.h"

#include "section/error.h"
#include "section/slice.h"
#include "io/byte_source.h"
#include "io/formats.h"

#include <algorithm>
#include <string>

namespace section {

namespace {

constexpr std::size_t block_bytes = 1 << 16;
constexpr int blocks = 16;

// The whole lines of a block read at `at` (from the first line start on, unless at 0).
std::string_view whole_lines(std::string_view block, bool at_start, bool at_end) {
  if (!at_start) {
    const std::size_t nl = block.find('\n');
    block = nl == std::string_view::npos ? std::string_view{} : block.substr(nl + 1);
  }
  if (!at_end) {
    const std::size_t nl = block.rfind('\n');
    block = nl == std::string_view::npos ? std::string_view{} : block.substr(0, nl + 1);
  }
  return block;
}

// Points of a text cloud read in `blocks` blocks spread over the file (CSV blocks behind the
// header line); empty when any block does not parse as the format's lines.
std::vector<Eigen::Vector3d> text_sample(const std::string& path, const detail::InputFormat& format,
                                         const CloudReadOptions& options) {
  detail::ByteSource src(path, "read_cloud: ", [](std::string_view) {});  // a pipe: its spooled copy
  const int fd = src.regular_fd();
  if (fd < 0 || src.size() <= 0) return {};
  const unsigned long long size = static_cast<unsigned long long>(src.size());
  std::string header;
  std::vector<Eigen::Vector3d> out;
  std::string block(block_bytes, '\0');
  for (int b = 0; b < blocks; ++b) {
    const unsigned long long at = b == 0 ? 0 : size * static_cast<unsigned long long>(b) / blocks;
    const std::size_t got = detail::pread_full(fd, block.data(), block_bytes, at);
    const std::string_view lines = whole_lines({block.data(), got}, at == 0, at + got >= size);
    if (b == 0 && format.cloud == CloudFormat::csv)
      header = std::string(lines.substr(0, lines.find('\n') + 1));
    std::string text = (b == 0 ? std::string() : header) + std::string(lines);
    if (text.find_first_not_of(" \t\r\n") == std::string::npos) continue;
    CloudReadOptions one = options;
    one.threads = 1;
    one.format = format.cloud;
    const Cloud part = parse_cloud(text, path, one);
    out.insert(out.end(), part.points.begin(), part.points.end());
    if (at + got >= size) break;
  }
  return out;
}

}  // namespace

double sample_extent(const std::string& path, const CloudReadOptions& options) {
  if (path == "-") return 0;
  std::vector<Eigen::Vector3d> points = peek_cloud(path, 4096, options).points;
  try {
    if (points.empty()) {
      detail::ByteSource src(path, "read_cloud: ", [](std::string_view) {});
      src.fetch(block_bytes);
      const detail::InputFormat& format = detail::cloud_format(path, src.bytes(), options.format);
      if (format.text) points = text_sample(path, format, options);
      if (format.cloud == CloudFormat::e57) {  // metres by its standard: read whole, for an exact extent
        Eigen::AlignedBox3d box;
        read_cloud_chunks(
            path,
            [&](const Eigen::Vector3d* p, std::size_t n) {
              std::for_each(p, p + n, [&](auto& q) { box.extend(q); });
            },
            options);
        return box.isEmpty() ? 0 : box.sizes().maxCoeff();
      }
    }
  } catch (const Error&) {
    return 0;  // the reader proper reports what is wrong with the file
  }
  return points_extent(points);
}

double points_extent(const std::vector<Eigen::Vector3d>& points) {
  double largest = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const PartExtent e = extent_along(points, Eigen::Vector3d::Unit(axis));
    largest = std::max(largest, e.hi - e.lo);
  }
  return largest;
}

}  // namespace section
