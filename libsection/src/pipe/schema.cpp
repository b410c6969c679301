#include "section/pipe/schema.h"

#include "section/error.h"

#include <cmath>
#include <string>
#include <vector>

namespace section {

namespace {
const std::vector<std::string> frame_columns = {"section", "origin_x", "origin_y", "origin_z",
                                                "u_x",     "u_y",      "u_z",      "v_x",
                                                "v_y",     "v_z",      "n_x",      "n_y",
                                                "n_z"};
}

std::map<int, Frame> frames(const Stream& stream) {
  const Table& t = stream.get("frames", "slice");
  std::vector<std::size_t> c;
  for (const auto& name : frame_columns) c.push_back(t.column(name));
  std::map<int, Frame> out;
  for (std::size_t r = 0; r < t.rows(); ++r) {
    Frame f;
    const auto v3 = [&](int k) { return Eigen::Vector3d(t.at(r, c[k]), t.at(r, c[k + 1]), t.at(r, c[k + 2])); };
    f.origin = v3(1);
    f.u = v3(4);
    f.v = v3(7);
    f.n = v3(10);
    const auto unit = [](const Eigen::Vector3d& a) { return std::abs(a.norm() - 1) < 1e-6; };
    if (!unit(f.u) || !unit(f.v) || !unit(f.n) || std::abs(f.u.dot(f.v)) > 1e-6 ||
        (f.u.cross(f.v) - f.n).norm() > 1e-6)
      throw Error("pipe: the frame of section " + format_number(t.at(r, c[0])) +
                  " is not a right-handed orthonormal frame");
    out[static_cast<int>(t.at(r, c[0]))] = f;
  }
  return out;
}

void put_frames(Stream& stream, const std::map<int, Frame>& frames) {
  Table t{"frames", frame_columns, {}};
  for (const auto& [id, f] : frames)
    t.add_row({double(id), f.origin.x(), f.origin.y(), f.origin.z(), f.u.x(), f.u.y(), f.u.z(),
               f.v.x(), f.v.y(), f.v.z(), f.n.x(), f.n.y(), f.n.z()});
  stream.put(std::move(t));
}

}  // namespace section
