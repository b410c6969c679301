// SPDX-License-Identifier: GPL-3.0-or-later
// A plain 2D profile (lines of x y) told from a cloud file and read as one.
#include "section/io/slice_file.h"

#include "section/io/csv.h"
#include "io/byte_source.h"
#include "io/text.h"

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace section {

bool looks_like_profile(std::string_view head) {
  if (head.substr(0, 3) == "ply") return false;
  int titles = 0, rows = 0;
  for (std::size_t pos = 0; pos < head.size() && rows < 16;) {
    const std::size_t nl = head.find('\n', pos);
    if (nl == std::string_view::npos && rows > 0) break;  // a line cut by the end of the look
    const std::string_view line = detail::trim(head.substr(pos, std::min(nl, head.size()) - pos));
    pos = std::min(nl, head.size()) + 1;
    if (line.empty() || line[0] == '#' || line.substr(0, 2) == "//") continue;
    std::vector<std::string_view> fields;
    detail::split_fields(line, [&](std::string_view f) {
      fields.push_back(detail::trim(f));
      return fields.size() < 3;
    });
    double x = 0, y = 0;
    if (rows == 0 && (fields.empty() || !detail::parse_double(fields[0], x))) {
      if (++titles > 8) return false;  // a title line, as in airfoil .dat files
      continue;
    }
    // Two numbers on every data line looked at (a count such as `241 21` over rows of
    // three is a header, not a profile).
    if (fields.size() != 2 || !detail::parse_double(fields[0], x) || !detail::parse_double(fields[1], y))
      return false;
    ++rows;
  }
  return rows > 0;
}

std::optional<Cloud> profile_cloud(std::string_view text, const std::string& name) {
  if (!looks_like_profile(text.substr(0, std::size_t(1) << 16))) return std::nullopt;
  Cloud cloud;
  for (const Eigen::Vector2d& p : parse_profile(text, name)) cloud.points.emplace_back(p.x(), p.y(), 0.0);
  return cloud;
}

std::optional<Cloud> read_profile_cloud(const std::string& path) {
  // Spooled: a pipe looked at here is read again, whole, by read_cloud.
  const auto any = [](std::string_view) {};
  {
    detail::ByteSource src(path, "read_cloud: ", any);
    src.fetch(std::size_t(1) << 16);
    if (!looks_like_profile(src.bytes())) return std::nullopt;
  }
  detail::ByteSource src(path, "read_cloud: ", any);
  return profile_cloud(src.read_all(), src.name());
}

}  // namespace section
