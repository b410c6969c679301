// SPDX-License-Identifier: GPL-3.0-or-later
// compare's nominal on the stream: a mesh sliced on the measured planes, a stream's
// sections matched by plane, or sections of points, each through the same fitspline and
// camber code as the measurement.
#include "section/pipe/compare_stream.h"

#include "section/cavity.h"
#include "section/error.h"
#include "section/io/stream.h"
#include "section/pipe/camber_stream.h"
#include "section/fit_spline.h"
#include "section/pipe/fit_spline_stream.h"
#include "section/pipe/schema.h"
#include "section/slice.h"
#include "detail/sampled_profile.h"
#include "io/text.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace section {

namespace {

using Loops = std::map<int, std::vector<Eigen::Vector2d>>;

// The triangles of `mesh` that reach the plane of `f` (a vertex on each side, or on it):
// all that its section passes through, so that slicing them alone gives the same polylines
// for a fraction of the cost (the slicer's setup grows with the mesh).
Mesh crossing(const Mesh& mesh, const Frame& f) {
  Mesh band;
  std::vector<int> index(mesh.vertices.size(), -1);
  for (const auto& t : mesh.triangles) {
    double lo = INFINITY, hi = -INFINITY;
    for (int v : t) {
      const double h = f.height(mesh.vertices[static_cast<std::size_t>(v)]);
      lo = std::min(lo, h);
      hi = std::max(hi, h);
    }
    if (!(lo <= 0 && hi >= 0)) continue;
    std::array<int, 3> kept;
    for (int k = 0; k < 3; ++k) {
      int& i = index[static_cast<std::size_t>(t[k])];
      if (i < 0) {
        i = static_cast<int>(band.vertices.size());
        band.vertices.push_back(mesh.vertices[static_cast<std::size_t>(t[k])]);
      }
      kept[k] = i;
    }
    band.triangles.push_back(kept);
  }
  return band;
}

// Loop 0 of the mesh's section on each measured plane, in the measured frame; its other
// loops (a hollow blade's cavities, camber then measures their walls) into `others` by
// section and loop.
Loops mesh_sections(const Mesh& mesh, const std::map<int, Frame>& frames, std::vector<SectionIssue>& misses,
                    std::map<std::pair<int, int>, std::vector<Eigen::Vector2d>>& others) {
  Loops loops;
  for (const auto& [id, f] : frames) {
    const Mesh band = crossing(mesh, f);
    SectionSlice s;
    if (band.triangles.empty())
      s.error = "no triangle reaches the plane";
    else
      s = slice(band, {Plane{f.origin, f.n}}).sections.front();
    if (!s.error.empty() || s.morphology.loops.empty()) {
      misses.push_back({id, -1, "compare",
                        "the nominal mesh has no section on this plane" +
                            (s.error.empty() ? std::string() : ": " + s.error)});
      continue;
    }
    for (const auto& p : s.morphology.loops[0].points) loops[id].push_back(f.to_plane(s.frame.to_world(p)));
    // Only loops inside the profile: anything beside it (a neighbouring blade, a fixture in
    // the nominal's mesh) is no part of this section's nominal, as before cavities were kept.
    const std::vector<Eigen::Vector2d>& profile = s.morphology.loops[0].points;
    for (std::size_t l = 1; l < s.morphology.loops.size(); ++l) {
      const std::vector<Eigen::Vector2d>& loop = s.morphology.loops[l].points;
      if (!std::all_of(loop.begin(), loop.end(),
                       [&](const Eigen::Vector2d& p) { return detail::inside_polygon(profile, p); }))
        continue;
      for (const auto& p : loop) others[{id, int(l)}].push_back(f.to_plane(s.frame.to_world(p)));
    }
  }
  return loops;
}

// Throws for a value of row r in columns `cols` that no reader passes (a table made in
// memory): not finite or beyond +-1e15 (one such point read as 'all points equal'), or a
// section id that is not a whole number of 0 or more (a NaN id read as -2147483648).
void check_point_row(const Table& t, std::size_t r, std::initializer_list<long> cols, long id_col) {
  for (const long c : cols) {
    const double v = t.at(r, std::size_t(c));
    if (!(std::abs(v) <= detail::max_coordinate))
      throw Error("compare: nominal point " + std::to_string(r + 1) + ": column '" +
                  t.columns[std::size_t(c)] + "' is " + format_number(v) +
                  ", not a coordinate (finite, within +-1e15)");
  }
  if (id_col < 0) return;
  const double id = t.at(r, std::size_t(id_col));
  if (!detail::is_section_id(id))
    throw Error("compare: nominal point " + std::to_string(r + 1) + ": section " + format_number(id) +
                " is not a section id (a whole number of 0 or more)");
}

// The points of a table by section: section, u, v as they are, or x, y, z on the plane
// they lie on.
Loops point_sections(const Table& t, const std::map<int, Frame>& frames, const CompareStreamOptions& o) {
  Loops loops;
  const long cs = t.find_column("section"), cu = t.find_column("u"), cv = t.find_column("v");
  const long cx = t.find_column("x"), cy = t.find_column("y"), cz = t.find_column("z");
  if (cs >= 0 && cu >= 0 && cv >= 0) {
    for (std::size_t r = 0; r < t.rows(); ++r) {
      check_point_row(t, r, {cu, cv}, cs);
      loops[static_cast<int>(t.at(r, cs))].push_back({t.at(r, cu), t.at(r, cv)});
    }
    return loops;
  }
  if (cx < 0 || cy < 0 || cz < 0)
    throw Error("compare: the nominal points need the columns section, u, v or x, y, z");
  for (std::size_t r = 0; r < t.rows(); ++r) {
    check_point_row(t, r, {cx, cy, cz}, -1);
    const Eigen::Vector3d p(t.at(r, cx), t.at(r, cy), t.at(r, cz));
    for (const auto& [id, f] : frames)
      if (std::abs(f.height(p)) <= o.plane_tolerance) loops[id].push_back(f.to_plane(p));
  }
  return loops;
}

// The nominal stream's section on each measured plane: its splines moved into the measured
// frame (the same plane, facing the same way).
void matched_sections(const Stream& nominal, const std::map<int, Frame>& frames,
                      const CompareStreamOptions& o, Stream& out, std::vector<SectionIssue>& misses) {
  const std::map<int, Frame> theirs =
      schema::frames.find(nominal) ? section::frames(nominal) : std::map<int, Frame>{};
  const auto curves = splines(nominal);
  Table head = schema::splines.table("iterations"), knots = schema::spline_knots.table(),
        ctrl = schema::spline_ctrl.table();
  for (const auto& [id, f] : frames) {
    int match = -1;
    for (const auto& [their_id, g] : theirs)
      if (g.n.dot(f.n) > 1 - 1e-9 && std::abs(f.height(g.origin)) <= o.plane_tolerance) match = their_id;
    if (theirs.empty() && curves.count({id, 0})) match = id;  // no frames: matched by id
    if (!curves.count({match, 0})) {
      misses.push_back({id, -1, "compare", "the nominal stream has no section on this plane"});
      continue;
    }
    // Loop 0, and its other loops inside it (a hollow blade's cavities: camber measures
    // their walls); a loop beside it is no part of this section's nominal.
    const BSpline& profile = curves.at({match, 0});
    for (auto curve = curves.find({match, 0}); curve != curves.end() && curve->first.first == match;
         ++curve) {
      const int loop = curve->first.second;
      if (loop != 0 && measure_cavity(profile, curve->second).place != LoopPlace::inside) continue;
      BSpline b = curve->second;
      if (!theirs.empty())
        for (auto& p : b.control) p = f.to_plane(theirs.at(match).to_world(p));
      FitSplineResult fit;
      fit.spline = b;
      schema::splines.add(head, {id, loop, fit});
      for (std::size_t i = 0; i < b.knots.size(); ++i)
        schema::spline_knots.add(knots, {id, loop, i, b.knots[i]});
      for (std::size_t i = 0; i < b.control.size(); ++i)
        schema::spline_ctrl.add(ctrl, {id, loop, i, b.control[i]});
    }
  }
  out.put(head);
  out.put(knots);
  out.put(ctrl);
}

}  // namespace

Stream nominal_stream(const NominalSource& source, const std::map<int, Frame>& frames,
                      const CompareStreamOptions& options) {
  Stream out;
  put_frames(out, frames);
  std::vector<SectionIssue> misses;  // planes without a nominal section, said after the stages
  if (source.stream) {
    Stream copy;
    matched_sections(in_mm(*source.stream, copy), frames, options, out, misses);
  } else {
    Loops loops;
    std::map<std::pair<int, int>, std::vector<Eigen::Vector2d>> cavities;
    if (source.mesh) loops = mesh_sections(*source.mesh, frames, misses, cavities);
    if (source.points) {
      // Each section's points from their canonical start: the nominal's curve is then the same
      // whichever point its file starts the section at (fit_spline's curve depends on it).
      loops = point_sections(*source.points, frames, options);
      for (auto& [id, loop] : loops) loop = canonical_loop(std::move(loop));
    }
    Table pts = schema::points.table();
    for (const auto& [id, loop] : loops) {
      if (!frames.count(id)) continue;
      for (std::size_t i = 0; i < loop.size(); ++i)
        schema::points.add(pts, {id, 0, i, loop[i], Eigen::Vector2d(0, 0), 0.0});
      for (auto c = cavities.lower_bound({id, 1}); c != cavities.end() && c->first.first == id; ++c)
        for (std::size_t i = 0; i < c->second.size(); ++i)
          schema::points.add(pts,
                             {id, std::size_t(c->first.second), i, c->second[i], Eigen::Vector2d(0, 0), 0.0});
    }
    for (const auto& [id, f] : frames)
      if (!loops.count(id) && !source.mesh)
        misses.push_back({id, -1, "compare", "the nominal points have no section on this plane"});
    out.put(pts);
    FitSplineOptions fo = options.fit_spline;
    fo.threads = options.threads;
    fit_spline_stream(out, fo);
  }
  CamberOptions co = options.camber;
  co.threads = options.threads;
  co.across_sections = false;  // the nominal's sections are the reference, not a measurement to check
  camber_stream(out, co);
  // After the stages: fitspline's restage dropped them as a later stage's, and the reason
  // compare gave was then fitspline's "no points in the stream for this section".
  out.issues.insert(out.issues.begin(), misses.begin(), misses.end());
  return out;
}

InputUnits nominal_to_mm(Mesh* mesh, Table* points, const std::string& unit) {
  // The extent: the widest range of the coordinates; then every coordinate scaled.
  double extent = 0;
  std::vector<std::size_t> columns;
  if (mesh && !mesh->vertices.empty()) {
    Eigen::AlignedBox3d box;
    for (const auto& v : mesh->vertices) box.extend(v);
    extent = box.sizes().maxCoeff();
  }
  for (const char* name : {"x", "y", "z", "u", "v"}) {
    const long c = points ? points->find_column(name) : -1;
    if (c < 0 || points->rows() == 0) continue;
    columns.push_back(static_cast<std::size_t>(c));
    double low = points->at(0, columns.back()), high = low;
    for (std::size_t r = 1; r < points->rows(); ++r)
      low = std::min(low, points->at(r, columns.back())),
      high = std::max(high, points->at(r, columns.back()));
    extent = std::max(extent, high - low);
  }
  InputUnits in = input_units(unit, extent, "--nominal-units");
  if (in.doubtful) {  // read as mm: said without input_units' word on flagged params (a nominal has none)
    const std::string likely = guess_unit(extent).unit;
    in.warning = "the nominal is " + format_length(extent) + " across if in mm, though it looks like " +
                 (likely == "in" ? "inches" : "micrometres") + ": give --nominal-units " + likely +
                 " if it is (or --nominal-units mm)";
  }
  if (in.mm == 1) return in;
  if (mesh)
    for (auto& v : mesh->vertices) v *= in.mm;
  if (points)
    for (std::size_t r = 0; r < points->rows(); ++r)
      for (const std::size_t c : columns) points->values[r * points->columns.size() + c] *= in.mm;
  return in;
}

}  // namespace section
