// SPDX-License-Identifier: GPL-3.0-or-later
// Stream stage of camber: splines in, camber line and section parameters out.
#include "section/pipe/camber_stream.h"

#include "section/camber.h"
#include "section/checks.h"
#include "section/error.h"
#include "section/fit_spline.h"
#include "section/params.h"
#include "section/io/stream.h"
#include "section/pipe/schema.h"
#include "section/pipe/fit_spline_stream.h"
#include "detail/camber_line.h"
#include "detail/local_origin.h"
#include "detail/section_checks.h"
#include "pipe/adapter.h"
#include "pipe/camber_issues.h"
#include "pipe/camber_walls.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace section {

namespace {

using pipe::Measured;
namespace col = schema::col;

// Loop-0 skeleton of each section, ordered by index (the slice stage's camber seed).
std::map<int, std::vector<Eigen::Vector2d>> skeletons(const Stream& stream) {
  std::map<int, std::vector<Eigen::Vector2d>> out;
  const Table* t = schema::skeleton.find(stream);
  if (!t) return out;
  // A table without the columns it needs is refused, not left out unremarked.
  const long cs = long(t->column(col::section)), cl = t->find_column(col::loop),
             ci = t->find_column(col::index), cu = long(t->column(col::u)), cv = long(t->column(col::v));
  // Each section's rows in table order (a section's rows come together: the last one's
  // entry is reused), ordered by index unless already in order (a repeated index: its
  // last row).
  std::map<int, std::vector<std::pair<int, Eigen::Vector2d>>> rows;
  std::vector<std::pair<int, Eigen::Vector2d>>* at = nullptr;
  int at_section = 0;
  for (std::size_t r = 0; r < t->rows(); ++r) {
    if (cl >= 0 && t->at(r, cl) != 0) continue;
    const int index = ci >= 0 ? static_cast<int>(t->at(r, ci)) : static_cast<int>(r);
    const int section = static_cast<int>(t->at(r, cs));
    if (!at || section != at_section) at = &rows[section], at_section = section;
    at->push_back({index, {t->at(r, cu), t->at(r, cv)}});
  }
  for (const auto& [section, pts] : rows) {
    std::vector<Eigen::Vector2d>& p = out[section];
    const auto repeat_or_back = [](const auto& a, const auto& b) { return a.first >= b.first; };
    if (std::adjacent_find(pts.begin(), pts.end(), repeat_or_back) == pts.end()) {  // strictly increasing
      for (const auto& x : pts) p.push_back(x.second);
      continue;
    }
    std::map<int, Eigen::Vector2d> by_index;
    for (const auto& x : pts) by_index[x.first] = x.second;
    for (const auto& x : by_index) p.push_back(x.second);
  }
  return out;
}

// Loop-0 measured points of each section (the slice stage's "points" table), if present;
// the other loops' into `others`, by section and loop.
std::map<int, Measured> measured_points(const Stream& stream,
                                        std::map<std::pair<int, int>, std::vector<Eigen::Vector2d>>& others) {
  std::map<int, Measured> out;
  const Table* t = schema::points.find(stream);
  if (!t) return out;
  // A table without the columns it needs is refused: the edges would silently be fitted to
  // the spline alone.
  const std::size_t cs = t->column(col::section), cl = t->column(col::loop), cu = t->column(col::u),
                    cv = t->column(col::v);
  const long co = t->find_column(col::offset);
  Measured* at = nullptr;  // the last row's section (a section's rows come together)
  int at_section = 0;
  for (std::size_t r = 0; r < t->rows(); ++r) {
    if (t->at(r, cl) != 0) {
      others[{static_cast<int>(t->at(r, cs)), static_cast<int>(t->at(r, cl))}].emplace_back(t->at(r, cu),
                                                                                            t->at(r, cv));
      continue;
    }
    const int section = static_cast<int>(t->at(r, cs));
    if (!at || section != at_section) at = &out[section], at_section = section;
    Measured& m = *at;
    const Eigen::Vector2d q(t->at(r, cu), t->at(r, cv));
    const double offset = co >= 0 ? t->at(r, co) : 0.0;
    m.all.push_back(q);
    if (offset != 0 && std::isfinite(offset)) {
      m.carried.push_back(q);
      m.carried_offset.push_back(offset);
    } else {
      m.in_slab.push_back(q);
    }
  }
  return out;
}

// What fitspline found of each section's loop 0: the rms distance of the measured points
// to the curve (the profile's noise), and two layers of points (distance, profile length).
struct LoopFit {
  double noise = 0, layers = 0, layers_length = 0;
};

std::map<int, LoopFit> loop_fits(const Stream& stream) {
  std::map<int, LoopFit> fits;
  const Table* t = schema::splines.find(stream);
  if (!t) return fits;
  const long cr = t->find_column(col::rms), cd = t->find_column(col::layers),
             cn = t->find_column(col::layers_length);
  const std::size_t cs = t->column(col::section), cl = t->column(col::loop);
  const auto at = [&](std::size_t i, long c) { return c >= 0 ? t->at(i, std::size_t(c)) : 0.0; };
  for (std::size_t i = 0; i < t->rows(); ++i) {
    if (t->at(i, cl) != 0) continue;
    LoopFit& f = fits[static_cast<int>(t->at(i, cs))];
    f.noise = std::max(at(i, cr), 0.0);
    if (cn >= 0 && at(i, cd) > 0) f.layers = at(i, cd), f.layers_length = at(i, cn);
  }
  return fits;
}

// What camber_stream measures the sections with, gathered from the stream.
struct CamberInput {
  std::map<std::pair<int, int>, BSpline> curves;
  std::map<int, Frame> frames;
  std::map<int, std::vector<Eigen::Vector2d>> seeds;
  std::map<int, Measured> measured;
  std::map<std::pair<int, int>, std::vector<Eigen::Vector2d>>
      loop_points;  // the other loops' measured points
  std::map<int, LoopFit> fits;
  std::map<int, int> loops;                     // loops per section: fitted, or listed by slice (table loops)
  std::map<int, std::map<int, double>> listed;  // slice's loops of each section and their areas
};

// The loops slice found in each section (table loops), by id, with their areas: a loop that
// fitspline could not fit is still one (a profile split by a gap leaves loop 0 a piece).
std::map<int, std::map<int, double>> listed_loops(const Stream& stream) {
  std::map<int, std::map<int, double>> out;
  const Table* t = schema::loops.find(stream);
  if (!t) return out;
  const long cs = t->find_column(col::section), cl = t->find_column(col::loop), ca = t->find_column("area");
  if (cs < 0 || cl < 0) return out;
  for (std::size_t r = 0; r < t->rows(); ++r)
    out[static_cast<int>(t->at(r, std::size_t(cs)))][static_cast<int>(t->at(r, std::size_t(cl)))] =
        ca < 0 ? std::numeric_limits<double>::quiet_NaN() : t->at(r, std::size_t(ca));
  return out;
}

CamberInput gather(const Stream& stream) {
  CamberInput in;
  in.curves = splines(stream);
  if (schema::frames.find(stream)) in.frames = frames(stream);
  in.seeds = skeletons(stream);
  in.measured = measured_points(stream, in.loop_points);
  in.fits = loop_fits(stream);
  in.listed = listed_loops(stream);
  for (const auto& [key, curve] : in.curves) ++in.loops[key.first];
  for (const auto& [section, loops] : in.listed)
    if (in.loops.count(section)) in.loops[section] = std::max(in.loops[section], int(loops.size()));
  return in;
}

// A section's options: the leading-edge direction in its plane, its profile's noise, and
// its skeleton as the medial axis's seed.
CamberOptions section_options(const CamberOptions& options, const CamberInput& in, int section,
                              const Frame& f) {
  CamberOptions opt = options;
  if (opt.le_direction.norm() == 0 && opt.le_direction_3d.norm() > 0) {
    const Eigen::Vector3d& d = opt.le_direction_3d;
    opt.le_direction = {d.dot(f.u), d.dot(f.v)};
    if (!(opt.le_direction.norm() > 1e-6 * d.norm()))
      throw Error("camber: the leading-edge direction (" + format_number(d.x()) + ", " +
                  format_number(d.y()) + ", " + format_number(d.z()) +
                  ") is normal to the plane of section " + std::to_string(section) +
                  ": it cannot tell the edges apart there");
  }
  if (const auto n = in.fits.find(section);
      n != in.fits.end() && n->second.noise > 0 && opt.profile_noise <= 0)
    opt.profile_noise = n->second.noise;
  const auto seed = in.seeds.find(section);
  if (seed != in.seeds.end() && seed->second.size() >= 4) opt.medial.seed = seed->second;
  return opt;
}

// One section measured: camber line, parameters, thickness stations, sides, edge coverage.
struct SectionCamber {
  CamberResult camber;
  SectionParams params;
  std::vector<ThicknessStation> stations;
  Sides sides;
  detail::EdgeCoverage le, te;
  detail::ContactCoverage thickest[2];   // about the thickest circle's contacts
  detail::ContactCoverage longest;       // about the longest stretch without measured points
  std::vector<bool> station_unmeasured;  // a station's circle touches a hole in the data
};

// Measures a section on `pr`, `curve` sampled with opt.medial.samples; a poor skeleton
// seed falls back to the Delaunay seed (`opt` then holds no seed).
SectionCamber measure(const BSpline& curve, const detail::SampledProfile& pr, CamberOptions& opt,
                      const Measured& q) {
  SectionCamber m;
  detail::check_profile_degree(curve);
  // The camber line's samples and final axis serve the thickness stations too when they
  // sample the profile alike (the default).
  std::unique_ptr<detail::CamberAxis> axis;
  try {
    m.camber = detail::camber_line(pr, opt, q.all, &axis);
  } catch (const Error&) {
    if (opt.medial.seed.empty()) throw;
    opt.medial.seed.clear();
    m.camber = detail::camber_line(pr, opt, q.all, &axis);
  }
  m.params = detail::section_params(curve, pr.fast, m.camber);
  m.stations = opt.medial.samples == detail::thickness_samples
                   ? detail::thickness_stations(pr, *axis, m.camber, opt.stations)
                   : thickness_stations(curve, m.camber, opt.stations);
  m.sides = detail::split_sides(pr.fast, m.camber, opt.side_samples);
  m.le = detail::edge_coverage(pr.fast, m.camber.le, q.all, opt.edge_hole_reach, opt.thickness_hole_spacings);
  m.te = detail::edge_coverage(pr.fast, m.camber.te, q.all, opt.edge_hole_reach, opt.thickness_hole_spacings);
  // Holes beginning within half the longest the thickness may bridge, over a window three
  // times that length (for the points' mean distance there), sampled every 3 % of it
  // (0.06 mm at the default 5 % of a 40 mm chord) to tell its length to that.
  const double limit = opt.thickness_hole * m.params.chord;
  const detail::ProfileCoverage cover(pr.fast, q.all, 0.03 * limit);
  const auto contact = [&](double t) { return cover.about(t, 3 * limit, limit / 2); };
  if (m.camber.thickest.radius > 0)
    for (int side = 0; side < 2; ++side)
      m.thickest[side] = contact(side == 0 ? m.camber.thickest.t_left : m.camber.thickest.t_right);
  // A sharp edge's vertex over a hole (a TE cut off by it closes at the bridge's corner: a
  // mesh's 3.3 mm hole at a TE gave a sharp TE, the chord and caliper chord 2.8 mm short).
  const double sharp = opt.sharp_ratio * m.params.max_thickness;
  for (auto [edge, coverage] : {std::pair{&m.camber.le, &m.le}, std::pair{&m.camber.te, &m.te}}) {
    if (!edge->vertex) continue;
    const detail::ContactCoverage c = contact(edge->t);
    if (c.hole_distance == 0 && detail::unmeasured(c, 10 * sharp, opt.thickness_hole_spacings))
      coverage->vertex_hole = c.hole;
  }
  m.longest = cover.longest(3 * limit);
  for (const ThicknessStation& st : m.stations)
    m.station_unmeasured.push_back(
        detail::unmeasured(contact(st.pressure_t), limit, opt.thickness_hole_spacings) ||
        detail::unmeasured(contact(st.suction_t), limit, opt.thickness_hole_spacings));
  return m;
}

// The slots' tables, in order.
enum : std::size_t { camber_rows, params_rows, thickness_rows, sides_rows, walls_rows, wall_map_rows };

// A measured section's rows of the tables camber, params, thickness and sides.
void add_rows(int section, const Frame& f, const SectionCamber& m, const ValueSigmas& sigmas, CheckBits flags,
              pipe::Slot& slot) {
  const CamberResult& r = m.camber;
  for (std::size_t i = 0; i < r.points.size(); ++i)
    schema::camber.append(slot.rows[camber_rows],
                          {section, i, r.s[i], r.points[i], f.to_world(r.points[i]), r.radius[i]});
  const SectionParams& p = m.params;
  schema::params.append(slot.rows[params_rows],
                        {section, p, r, f.to_world(p.le_point), f.to_world(p.te_point),
                         f.to_world(p.centroid), m.le.around, m.te.around, flags, sigmas});
  const CheckBits section_flags = checks_flagging(flags, "thickness");
  for (std::size_t i = 0; i < m.stations.size(); ++i)
    schema::thickness.append(
        slot.rows[thickness_rows],
        {section, i, m.stations[i],
         section_flags | (m.station_unmeasured[i] ? bit(Check::thickness_measured) : CheckBits(0))});
  for (int side = 0; side < 2; ++side) {
    const auto& pts = side == 0 ? m.sides.pressure : m.sides.suction;
    for (std::size_t i = 0; i < pts.size(); ++i)
      schema::sides.append(slot.rows[sides_rows], {section, side, i, pts[i]});
  }
}

// `m`'s points moved by `by` (the positions the rows hold; lengths and angles stay).
void move(SectionCamber& m, const Eigen::Vector2d& by) {
  for (auto& p : m.camber.points) p += by;
  for (Edge* e : {&m.camber.le, &m.camber.te}) e->point += by, e->center += by;
  for (Eigen::Vector2d* p : {&m.params.centroid, &m.params.le_point, &m.params.te_point, &m.params.caliper_le,
                             &m.params.caliper_te})
    *p += by;
  for (auto& t : m.stations) t.point += by, t.pressure += by, t.suction += by;
  for (auto* side : {&m.sides.pressure, &m.sides.suction})
    for (auto& p : *side) p += by;
}

// The measured points moved by -origin.
Measured moved(const Measured& q, const Eigen::Vector2d& origin) {
  Measured out = q;
  for (auto* list : {&out.all, &out.in_slab, &out.carried}) *list = detail::moved(*list, origin);
  return out;
}

// Loop 0 of a section into its slot: rows and issues. Far from the origin of its (u, v)
// (a stream not written by slice), it is measured about a local origin and moved back.
void camber_section(int section, const BSpline& curve, const CamberInput& in, const CamberOptions& options,
                    pipe::Slot& slot) {
  const auto fit = in.frames.find(section);
  const Frame f = fit != in.frames.end() ? fit->second : Frame{};
  CamberOptions opt = section_options(options, in, section, f);
  const auto points = in.measured.find(section);
  const Measured none;
  const Eigen::Vector2d origin = detail::local_origin(curve.control);
  BSpline local = curve;
  local.control = detail::moved(curve.control, origin);
  const std::vector<pipe::SectionCavity> cavities =
      pipe::cavities_of(section, local, origin, in.curves, in.listed, in.loops.at(section));
  opt.medial.seed = detail::moved(opt.medial.seed, origin);
  const Measured q = moved(points != in.measured.end() ? points->second : none, origin);
  // One piecewise form of the profile for every sampling of it and the params.
  const detail::SampledProfile pr(local, opt.medial.samples);
  SectionCamber m = measure(local, pr, opt, q);
  CheckOptions checks;
  checks.noise = opt.profile_noise;
  const detail::SampledProfile sampled(local, pr.fast, detail::check_samples, false);  // for both checks
  // Few points for the fit's coefficients: their own scatter, which its rms may hide.
  if (pipe::few_points(q.all.size(), local.control.size())) {
    const PointsNoise scatter = detail::points_noise(sampled, q.all);
    checks.points_noise = scatter.rms, checks.points = scatter.points, checks.point_params = scatter.params;
    // The distance limits see the noise the rms hides (a noise left unknown stays so).
    if (checks.noise > 0) checks.noise = std::max(checks.noise, scatter.rms);
  } else if (checks.noise > 0) {
    // Many points: the fit's rms is their noise, which the fit averages over the points
    // each coefficient rests on.
    checks.points_noise = checks.noise, checks.points = double(q.all.size());
  }
  SectionCheck check = detail::check_section(sampled, m.camber, m.params, checks);
  if (const auto l = in.fits.find(section); l != in.fits.end() && l->second.layers > 0)
    check.findings.push_back({Check::layers, l->second.layers, l->second.layers_length});
  const CheckBits flags = pipe::describe_issues({section,
                                                 local,
                                                 pr.fast,
                                                 m.camber,
                                                 m.params,
                                                 m.le,
                                                 m.te,
                                                 {m.thickest[0], m.thickest[1]},
                                                 m.longest,
                                                 q,
                                                 opt,
                                                 checks.accuracy * sampled.scale,
                                                 checks.value_sigmas},
                                                check.findings, slot.issues);
  if (origin != Eigen::Vector2d::Zero()) move(m, origin);
  add_rows(section, f, m, check.sigmas, flags, slot);
  // The walls' own noise check, as the thickness's: the points' noise over both curves.
  pipe::WallNoise wall_noise;
  if (checks.points > 0 && checks.points_noise > 0) {
    wall_noise.sigma = std::max(checks.points_noise, checks.noise);
    wall_noise.profile_share = std::min(1.0, double(local.control.size()) / checks.points);
    wall_noise.limit = checks.accuracy * sampled.scale;
  }
  pipe::add_walls(
      {section, f, local, pr.fast, m.camber.le.t, m.camber.te.t, detail::pressure_runs_forward(m.camber),
       q.all, in.loop_points, opt, m.params.chord, checks_flagging(flags, "wall"), origin, wall_noise},
      cavities, slot.rows[walls_rows], slot.rows[wall_map_rows], slot.issues);
}

}  // namespace

namespace {

// Sets `check`'s bit in a params row's flags cell; false when it was set already (its
// issue was said then).
bool set_flag(double& flags, Check check) {
  const CheckBits bits = static_cast<CheckBits>(flags);
  if (bits & bit(check)) return false;
  flags = double(bits | bit(check));
  return true;
}

// A params row of one of the streams, as check_blade reads it: the stream, the section.
struct HeldRow {
  Stream* stream;
  int section;
};

// The mean normal of the frames of all streams (oriented as the first), or +z.
Eigen::Vector3d mean_normal(const std::vector<Stream*>& streams) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (Stream* s : streams)
    if (schema::frames.find(*s))
      for (const auto& [id, f] : frames(*s)) n += n.dot(f.n) < 0 ? Eigen::Vector3d(-f.n) : f.n;
  return n.norm() > 0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::UnitZ();
}

}  // namespace

void check_blade_stream(const std::vector<Stream*>& streams, const BladeCheckOptions& options) {
  for (const Stream* s : streams)
    if (!s) throw Error("pipe: a stream to check is missing (a null pointer)");
  std::vector<HeldRow> rows;
  std::vector<BladeSection> sections;
  const Eigen::Vector3d n = mean_normal(streams);
  for (Stream* s : streams) {
    const Table* t = schema::params.find(*s);
    if (!t) continue;
    auto get = [&](std::size_t r, const char* name) { return t->at(r, t->column(name)); };
    for (std::size_t r = 0; r < t->rows(); ++r) {
      // A section that is no airfoil (a platform's) is no neighbour of the blade's: as one
      // it made 8 sections' thicknesses jump from it.
      const CheckBits flags = flags_mask(get(r, "flags"));
      if (flags & bit(Check::airfoil)) continue;
      BladeSection b;
      b.flags = flags;
      b.height = Eigen::Vector3d(get(r, "centroid_x"), get(r, "centroid_y"), get(r, "centroid_z")).dot(n);
      SectionParams& p = b.params;
      p.chord = get(r, "chord");
      p.max_thickness = get(r, "max_thickness");
      p.le_radius = get(r, "le_radius");
      p.te_radius = get(r, "te_radius");
      p.stagger = get(r, "stagger");
      p.inlet_angle = get(r, "inlet_angle");
      p.outlet_angle = get(r, "outlet_angle");
      p.camber_angle = get(r, "camber_angle");
      sections.push_back(b);
      rows.push_back({s, static_cast<int>(get(r, col::section))});
    }
  }
  for (const Jump& j : check_blade(sections, options))  // a jump flags its params column alone
    pipe::flag_section(*rows[j.index].stream, rows[j.index].section, j.check, pipe::jump_note(j));
}

bool units_doubtful(const Stream& stream) {
  for (const auto& note : stream.notes)
    if (note.rfind("units_doubtful", 0) == 0) return true;
  return false;
}

namespace {

// `check` set in column `name` of the rows of `t` of `section` (every row: -1), and the
// sections whose bit it set (none: no such table or column).
std::vector<int> flag_column(Table* t, const char* name, Check check, int section = -1) {
  std::vector<int> set;
  const long column = t ? t->find_column(name) : -1, id = t ? t->find_column(col::section) : -1;
  if (column < 0 || (section >= 0 && id < 0)) return set;
  for (std::size_t r = 0; r < t->rows(); ++r) {
    const int at = id >= 0 ? static_cast<int>(t->at(r, std::size_t(id))) : -1;
    if (section >= 0 && at != section) continue;
    if (set_flag(t->values[r * t->columns.size() + std::size_t(column)], check)) set.push_back(at);
  }
  t->source.reset();  // changed: formatted from its values
  return set;
}

// `check` on the params rows of `section` (every row: -1), an issue saying `why` for each
// row it was not on, and on the same sections' thickness stations and walls where it flags
// them (checks_flagging): they rest on the same points.
void flag_rows(Stream& stream, Check check, const std::string& why, int section) {
  Table* t = stream.find(schema::params.name);
  if (!t || t->rows() == 0) return;
  for (const int id : flag_column(t, "flags", check, section))
    stream.issues.push_back({id, 0, "camber", why});
  if (checks_flagging(bit(check), "thickness"))
    flag_column(stream.find(schema::thickness.name), "flags", check, section);
  if (!checks_flagging(bit(check), "wall")) return;
  Table* walls = stream.find(schema::walls.name);
  for (const char* column : {"flags", "pressure_flags", "suction_flags"})
    flag_column(walls, column, check, section);
  flag_column(stream.find(schema::wall_map.name), "flags", check, section);
}

}  // namespace

namespace pipe {

void flag_every_row(Stream& stream, Check check, const std::string& why) {
  flag_rows(stream, check, why, -1);
}

bool flag_section(Stream& stream, int section, Check check, const std::string& why) {
  const std::size_t before = stream.issues.size();
  flag_rows(stream, check, why, section);
  return stream.issues.size() > before;
}

}  // namespace pipe

void flag_doubtful_units(Stream& stream) {
  pipe::flag_every_row(stream, Check::units,
                       "its values fail check units: the input was read as mm though its extent suggests "
                       "another unit (see slice's warning); give --units");
}

bool registration_unconfirmed(const Stream& stream) {
  const std::string mark = " unconfirmed=1";
  for (const auto& note : stream.notes)
    if (note.rfind("register ", 0) == 0 && note.size() >= mark.size() &&
        note.compare(note.size() - mark.size(), mark.size(), mark) == 0)
      return true;
  return false;
}

void flag_unconfirmed_registration(Stream& stream) {
  pipe::flag_every_row(stream, Check::registration,
                       "its values fail check registration: a view merged into the input was registered but "
                       "not confirmed (see slice's warning), its points may lie slid and turned");
}

Stream profile_stream(const BSpline& spline, double rms, const std::vector<Eigen::Vector2d>& measured) {
  Stream stream;
  FitSplineResult fit;
  fit.spline = spline;
  fit.rms = rms;
  // A plain profile has no measured points: the columns after the fit's iterations are left out.
  Table head = schema::splines.table("iterations");
  schema::splines.add(head, {0, 0, fit});
  Table knots = schema::spline_knots.table();
  for (std::size_t i = 0; i < spline.knots.size(); ++i)
    schema::spline_knots.add(knots, {0, 0, i, spline.knots[i]});
  Table ctrl = schema::spline_ctrl.table();
  for (std::size_t i = 0; i < spline.control.size(); ++i)
    schema::spline_ctrl.add(ctrl, {0, 0, i, spline.control[i]});
  stream.put(head);
  stream.put(knots);
  stream.put(ctrl);
  if (!measured.empty()) {
    Table points = schema::points.table();
    for (std::size_t i = 0; i < measured.size(); ++i)
      schema::points.add(points, {0, 0, i, measured[i], Eigen::Vector2d(0, 0), 0.0});
    stream.put(points);
  }
  return stream;
}

const std::vector<std::pair<std::string, std::string>>& camber_unread_columns() {
  static const std::vector<std::pair<std::string, std::string>> columns = {
      {"smoothed", "u"}, {"smoothed", "v"}, {"points", "nu"}, {"points", "nv"}, {"skeleton", "radius"}};
  return columns;
}

void camber_stream(Stream& stream, const CamberOptions& options) {
  detail::check_options(options);
  pipe::restage(stream, "camber");
  const CamberInput in = gather(stream);
  Table camber = schema::camber.table(), params = schema::params.table(),
        thickness = schema::thickness.table(), sides = schema::sides.table(), walls = schema::walls.table(),
        wall_map = schema::wall_map.table();
  std::vector<std::pair<int, const BSpline*>> work;
  std::set<int> present;
  for (const auto& [key, curve] : in.curves) {
    present.insert(key.first);
    if (key.second == 0) work.push_back({key.first, &curve});
  }
  pipe::vanished_sections(stream, present, "camber", "spline");
  pipe::run_slots(
      work.size(), options.threads, {&camber, &params, &thickness, &sides, &walls, &wall_map}, stream.issues,
      "camber",
      [&](std::size_t w, pipe::Slot& slot) {
        camber_section(work[w].first, *work[w].second, in, options, slot);
      },
      [&](std::size_t w, const std::string& message) {
        const int section = work[w].first;
        return SectionIssue{section, in.loops.at(section) > 1 ? -1 : 0, "camber", message};
      });
  stream.put(camber);
  stream.put(params);
  stream.put(thickness);
  stream.put(sides);
  if (walls.rows() > 0) stream.put(walls);  // hollow blades only: every other stream as it was
  if (wall_map.rows() > 0) stream.put(wall_map);
  if (options.across_sections) {
    check_blade_stream({&stream});
    flag_scan_layers({&stream});
    flag_swapped_ends({&stream});
    if (units_doubtful(stream)) flag_doubtful_units(stream);
    if (registration_unconfirmed(stream)) flag_unconfirmed_registration(stream);
  }
}

}  // namespace section
