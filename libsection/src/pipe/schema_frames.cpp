// SPDX-License-Identifier: GPL-3.0-or-later
// The frames table read into section frames and written from them, surfaces of revolution
// included (their meridians in the meridians table; docs/REVOLUTION.md).
#include "section/pipe/schema.h"

#include "io/text.h"
#include "section/error.h"
#include "section/revolution.h"

#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace section {

namespace {

// The meridians table's polylines by section.
std::map<int, std::vector<Eigen::Vector2d>> meridians_of(const Stream& stream) {
  std::map<int, std::vector<Eigen::Vector2d>> out;
  const Table* t = schema::meridians.find(stream);
  if (!t) return out;
  const std::size_t cs = t->column(schema::col::section), ca = t->column("axial"), cr = t->column("radius");
  for (std::size_t r = 0; r < t->rows(); ++r)
    out[static_cast<int>(t->at(r, cs))].emplace_back(t->at(r, ca), t->at(r, cr));
  return out;
}

// Row r's surface of revolution, from the frames table's columns after n_z (c: all columns).
std::shared_ptr<const Revolution> surface_of(const Table& t, std::size_t r, const std::vector<std::size_t>& c,
                                             std::size_t first,
                                             const std::map<int, std::vector<Eigen::Vector2d>>& meridian) {
  const auto v3 = [&](std::size_t k) {
    return Eigen::Vector3d(t.at(r, c[k]), t.at(r, c[k + 1]), t.at(r, c[k + 2]));
  };
  const double kind = t.at(r, c[first]), unrolling = t.at(r, c[first + 1]);
  const int section = static_cast<int>(t.at(r, c[0]));
  if (kind == 0) return nullptr;
  if (!(kind >= 1 && kind <= 3) || !(unrolling >= 1 && unrolling <= 3) || kind != std::floor(kind) ||
      unrolling != std::floor(unrolling))
    throw Error("pipe: the frame of section " + std::to_string(section) +
                " has an unknown surface or unrolling code (docs/REVOLUTION.md)");
  Revolution s;
  s.kind = static_cast<SurfaceKind>(int(kind));
  s.unrolling = static_cast<Unrolling>(int(unrolling));
  s.axis_point = v3(first + 2);
  s.axis = v3(first + 5);
  s.reference = v3(first + 8);
  s.r_ref = t.at(r, c[first + 11]);
  s.shift = {t.at(r, c[first + 12]), t.at(r, c[first + 13])};
  const auto m = meridian.find(section);
  if (m != meridian.end()) s.meridian = m->second;
  try {
    check_surface(s);
  } catch (const Error& e) {
    throw Error("pipe: the surface of section " + std::to_string(section) +
                " (frames and meridians tables): " + e.what());
  }
  return std::make_shared<const Revolution>(std::move(s));
}

}  // namespace

std::map<int, Frame> frames(const Stream& stream) {
  const Table& t = schema::frames.get(stream);
  const std::vector<std::string> plane = schema::frames.names("n_z"), all = schema::frames.names();
  const bool surfaces = t.find_column("surface") >= 0;
  std::vector<std::size_t> c;
  for (const auto& name : surfaces ? all : plane) c.push_back(t.column(name));
  const auto meridian = surfaces ? meridians_of(stream) : std::map<int, std::vector<Eigen::Vector2d>>{};
  std::map<int, Frame> out;
  for (std::size_t r = 0; r < t.rows(); ++r) {
    Frame f;
    const auto v3 = [&](int k) {
      return Eigen::Vector3d(t.at(r, c[k]), t.at(r, c[k + 1]), t.at(r, c[k + 2]));
    };
    f.origin = v3(1);
    f.u = v3(4);
    f.v = v3(7);
    f.n = v3(10);
    const auto unit = [](const Eigen::Vector3d& a) { return std::abs(a.norm() - 1) < 1e-6; };
    if (!unit(f.u) || !unit(f.v) || !unit(f.n) || std::abs(f.u.dot(f.v)) > 1e-6 ||
        (f.u.cross(f.v) - f.n).norm() > 1e-6)
      throw Error("pipe: the frame of section " + format_number(t.at(r, c[0])) +
                  " is not a right-handed orthonormal frame");
    // (parse_stream refuses these; a stream built in memory gave NaN camber points.)
    if (!(f.origin.cwiseAbs().maxCoeff() <= detail::max_coordinate))
      throw Error("pipe: the frame of section " + format_number(t.at(r, c[0])) +
                  " has an origin that is not finite or lies beyond +-1e15");
    if (surfaces) f.surface = surface_of(t, r, c, plane.size(), meridian);
    out[static_cast<int>(t.at(r, c[0]))] = f;
  }
  return out;
}

void put_frames(Stream& stream, const std::map<int, Frame>& frames) {
  bool surfaces = false;
  for (const auto& [id, f] : frames) surfaces = surfaces || f.surface;
  Table t = schema::frames.table(surfaces ? nullptr : "n_z");
  Table m = schema::meridians.table();
  for (const auto& [id, f] : frames) {
    schema::frames.add(t, {id, f});
    if (f.surface)
      for (std::size_t k = 0; k < f.surface->meridian.size(); ++k)
        schema::meridians.add(m, {id, k, f.surface->meridian[k]});
  }
  stream.put(std::move(t));
  if (surfaces) stream.put(std::move(m));
}

}  // namespace section
