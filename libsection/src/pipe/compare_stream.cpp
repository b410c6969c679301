// SPDX-License-Identifier: GPL-3.0-or-later
// Stream stage of compare: measured sections and their nominals in; fit, deviations, zones,
// compared values and verdicts out.
#include "section/pipe/compare_stream.h"

#include "section/checks.h"
#include "section/error.h"
#include "section/io/stream.h"
#include "section/pipe/fit_spline_stream.h"
#include "section/pipe/schema.h"
#include "pipe/adapter.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <optional>
#include <set>
#include <string>

namespace section {

namespace {

// A compared value: its params column (or fit_*), the zones it needs measured (bits 1 LE,
// 2 TE, 4 pressure, 8 suction) and whether it is an angle.
struct Item {
  const char* name;
  int zones;
  bool angle;
};
constexpr int le = 1, te = 2, ps = 4, ss = 8, all_zones = 15;
const Item items[] = {
    {"chord", le | te, false},
    {"camber_length", all_zones, false},
    {"max_thickness", ps | ss, false},
    {"max_thickness_pos", all_zones, false},
    {"le_radius", le, false},
    {"te_radius", te, false},
    {"le_curvature_radius", le, false},
    {"te_curvature_radius", te, false},
    {"stagger", le | te, true},
    {"inlet_angle", le, true},
    {"outlet_angle", te, true},
    {"camber_angle", le | te, true},
    {"area", all_zones, false},
    {"caliper_chord", le | te | ps, false},
    {"caliper_stagger", le | te | ps, true},
    {"fit_shift", 0, false},
    {"fit_rotation", 0, true},
    {"wall", 0, false},           // a hollow section's thinnest wall (camber's walls table)
    {"pressure_wall", 0, false},  // ... its thinnest to the pressure side
    {"suction_wall", 0, false},   // ... and to the suction side
    {"core_shift", 0, false},     // ... its cavities' centroids moved off the nominal's
};
const char* const zone_suffix[] = {"", "_le", "_te", "_pressure", "_suction"};

using Row = std::map<std::string, double>;

// The rows of a table by section, as column name -> value.
std::map<int, Row> by_section(const Table* t) {
  std::map<int, Row> out;
  if (!t) return out;
  const std::size_t cs = t->column(schema::col::section);
  for (std::size_t r = 0; r < t->rows(); ++r) {
    Row& row = out[static_cast<int>(t->at(r, cs))];
    for (std::size_t c = 0; c < t->columns.size(); ++c) row[t->columns[c]] = t->at(r, c);
  }
  return out;
}

// Each section's thinnest cavity wall (camber's walls table: a hollow blade's) into its
// params row as `wall`, `wall_sigma` and `wall_flags` (that wall's row's checks), and its
// thinnest to each side as `pressure_wall` and `suction_wall` (with `_sigma` and `_flags`):
// none for a section without a cavity, nor the sides' from a stream written without them.
void add_thinnest_walls(const Stream& stream, std::map<int, Row>& params) {
  const Table* t = schema::walls.find(stream);
  if (!t) return;
  const std::size_t cs = t->column(schema::col::section), cg = t->column("wall_sigma");
  for (const char* side : {"", "pressure_", "suction_"}) {
    const std::string wall = side + std::string("wall");
    const long cw = t->find_column(wall), cf = t->find_column(*side ? side + std::string("flags") : "flags");
    if (cw < 0 || cf < 0) continue;
    for (std::size_t r = 0; r < t->rows(); ++r) {
      const auto row = params.find(static_cast<int>(t->at(r, cs)));
      if (row == params.end()) continue;
      const double value = t->at(r, static_cast<std::size_t>(cw));
      const auto least = row->second.find(wall);
      if (least != row->second.end() && !(value < least->second)) continue;
      row->second[wall] = value;
      row->second[wall + "_sigma"] = t->at(r, cg);
      row->second[wall + "_flags"] = t->at(r, static_cast<std::size_t>(cf));
    }
  }
}

// A cavity's centroid (camber's walls table), its standard error, and the checks that flag
// its walls.
struct CavityAt {
  Eigen::Vector2d centroid;
  double sigma;  // 0 from a stream written without it
  CheckBits flags;
};

// Each section's cavities: none from a stream without walls, or written without centroids.
std::map<int, std::vector<CavityAt>> cavity_centroids(const Stream& stream) {
  std::map<int, std::vector<CavityAt>> out;
  const Table* t = schema::walls.find(stream);
  if (!t) return out;
  const long cu = t->find_column("centroid_u"), cv = t->find_column("centroid_v"),
             cf = t->find_column("flags"), cg = t->find_column("centroid_sigma");
  if (cu < 0 || cv < 0 || cf < 0) return out;
  const std::size_t cs = t->column(schema::col::section);
  for (std::size_t r = 0; r < t->rows(); ++r)
    out[static_cast<int>(t->at(r, cs))].push_back(
        {{t->at(r, std::size_t(cu)), t->at(r, std::size_t(cv))},
         cg >= 0 ? t->at(r, std::size_t(cg)) : 0.0,
         checks_flagging(flags_mask(t->at(r, std::size_t(cf))), "wall")});
  return out;
}

// The core shift of a section: each measured cavity's centroid, moved by the fit onto the
// nominal, from the nearest nominal cavity's; the largest. `flags` gets the checks of the
// measured cavities' walls, `sigma2` the variance of the largest (both centroids' standard
// errors; the fit's motion, from all the profile's points, is far surer).
double core_shift(const Motion2& motion, const std::vector<CavityAt>& measured,
                  const std::vector<CavityAt>& nominal, CheckBits& flags, double& sigma2) {
  double worst = -1;
  for (const CavityAt& m : measured) {
    const Eigen::Vector2d at = motion.apply(m.centroid);
    double least = INFINITY, nominal_sigma = 0;
    for (const CavityAt& n : nominal)
      if (const double d = (at - n.centroid).norm(); d < least) least = d, nominal_sigma = n.sigma;
    if (least > worst) worst = least, sigma2 = m.sigma * m.sigma + nominal_sigma * nominal_sigma;
    flags |= m.flags;
  }
  return std::max(worst, 0.0);
}

// Everything compare_stream needs of both streams.
struct Input {
  std::map<int, Frame> frames;
  std::vector<int> ids;
  std::map<std::pair<int, int>, pipe::LoopRows> points;
  std::map<std::pair<int, int>, BSpline> curves;
  std::map<int, Row> params, nominal_params;
  std::map<int, NominalSection> nominals;
  std::map<int, std::string> nominal_issue;
  std::map<int, std::vector<CavityAt>> cavities, nominal_cavities;
};

// A nominal from nominal_stream holds the frames it was made on: they must be the stream's
// (frames of a stream in metres, passed as they were, made a nominal in the wrong unit).
void check_same_frames(const std::map<int, Frame>& ours, const Stream& nominal, double tolerance) {
  if (ours.empty() || !schema::frames.find(nominal)) return;
  for (const auto& [id, g] : frames(nominal)) {
    const auto f = ours.find(id);
    if (f == ours.end()) continue;
    const double off = (f->second.origin - g.origin).norm();
    if (off <= tolerance && f->second.n.dot(g.n) > 1 - 1e-9) continue;
    char text[200];
    std::snprintf(text, sizeof text,
                  "the nominal was made on other frames than this stream's: section %d's origin lies %.6g mm "
                  "from the nominal's (nominal_stream takes the measured frames in mm)",
                  id, off);
    throw Error(text);
  }
}

Input gather(const Stream& stream, const Stream& nominal, double plane_tolerance) {
  Input in;
  if (schema::frames.find(stream)) in.frames = frames(stream);
  check_same_frames(in.frames, nominal, plane_tolerance);
  if (const Table* t = schema::points.find(stream)) in.points = pipe::loop_rows(*t, "compare");
  if (schema::splines.find(stream)) in.curves = splines(stream);
  in.params = by_section(schema::params.find(stream));
  in.nominal_params = by_section(schema::params.find(nominal));
  add_thinnest_walls(stream, in.params);
  add_thinnest_walls(nominal, in.nominal_params);
  in.cavities = cavity_centroids(stream);
  in.nominal_cavities = cavity_centroids(nominal);
  const auto curves =
      schema::splines.find(nominal) ? splines(nominal) : std::map<std::pair<int, int>, BSpline>{};
  for (const auto& [id, row] : in.nominal_params) {
    const auto c = curves.find({id, 0});
    if (c == curves.end()) continue;
    NominalSection& n = in.nominals[id];
    n.curve = c->second;
    n.le_point = {row.at("le_u"), row.at("le_v")};
    n.te_point = {row.at("te_u"), row.at("te_v")};
    n.pressure_side = row.at("pressure_side") > 0 ? 1 : -1;
  }
  for (const auto& i : nominal.issues)
    if (!in.nominal_issue.count(i.section)) in.nominal_issue[i.section] = i.stage + ": " + i.message;
  for (const auto& [id, f] : in.frames) in.ids.push_back(id);
  if (in.frames.empty())
    for (const auto& [key, c] : in.curves)
      if (key.second == 0) in.ids.push_back(key.first);
  return in;
}

// A section's measured points: loop 0 of the points table, else 2000 samples of its spline;
// `index` gets each point's index.
std::vector<Eigen::Vector2d> measured_points(const Input& in, int id, std::vector<double>& index) {
  std::vector<Eigen::Vector2d> out;
  if (const auto p = in.points.find({id, 0}); p != in.points.end()) {
    for (const auto& [i, q] : p->second) {
      index.push_back(i);
      out.push_back(q);
    }
  } else if (const auto c = in.curves.find({id, 0}); c != in.curves.end()) {
    out = sample(c->second, 2000);
    for (std::size_t i = 0; i < out.size(); ++i) index.push_back(static_cast<double>(i));
  }
  return out;
}

double diagonal(const std::vector<Eigen::Vector2d>& points) {
  Eigen::AlignedBox2d box;
  for (const auto& p : points) box.extend(p);
  return box.isEmpty() ? 0 : box.diagonal().norm();
}

// Measured and nominal profiles of sizes no fit can match: mostly a nominal in another unit,
// whose fit hunted feet for a minute to report millimetres of deviation. A measured profile
// smaller than its nominal may be a partial scan, so that side is given room.
std::string size_mismatch(const Input& in, int id) {
  const auto measured = in.curves.find({id, 0});
  if (measured == in.curves.end()) return "";
  const double m = diagonal(measured->second.control), n = diagonal(in.nominals.at(id).curve.control);
  if (m <= 1.5 * n && n <= 8 * m) return "";
  char text[240];
  std::snprintf(
      text, sizeof text,
      "the measured profile is %.4g across and its nominal %.4g, %.3g times %s (a nominal in another "
      "unit? see --nominal-units)",
      m, n, m > n ? m / n : n / m, m > n ? "smaller" : "larger");
  return text;
}

// A measured profile farther from its nominal than ten times the larger one's size: no fit
// reaches it (one 2.2 sizes off did not settle), and the distances to the nominal, far
// beyond the curves' scale, leave the nearest-point searches nothing to prune (a frame's
// origin edited by 1e14 took 47 s to say the fit did not settle).
std::string position_mismatch(const Input& in, int id) {
  const auto measured = in.curves.find({id, 0});
  if (measured == in.curves.end()) return "";
  Eigen::AlignedBox2d m, n;
  for (const auto& p : measured->second.control) m.extend(p);
  for (const auto& p : in.nominals.at(id).curve.control) n.extend(p);
  if (m.isEmpty() || n.isEmpty()) return "";
  const double size = std::max(m.diagonal().norm(), n.diagonal().norm());
  const double apart = (m.center() - n.center()).norm();
  if (!(apart > 10 * size)) return "";
  char text[240];
  std::snprintf(text, sizeof text,
                "the measured profile lies %.4g from its nominal, %.3g times its size: are the section's "
                "frame and the nominal in one coordinate system?",
                apart, apart / size);
  return text;
}

// Why a section cannot be compared ("" when it can).
std::string unusable(const Input& in, int id, std::size_t points) {
  if (!in.nominals.count(id)) {
    const auto i = in.nominal_issue.find(id);
    return "no nominal for this section" +
           (i != in.nominal_issue.end() ? " (" + i->second + ")" : std::string());
  }
  if (points == 0) return "no measured profile (loop 0) in the stream";
  if (!in.params.count(id)) return "no params row: the measured section has not been through camber";
  const std::string size = size_mismatch(in, id);
  return size.empty() ? position_mismatch(in, id) : size;
}

enum : std::size_t { fit_rows, deviation_rows, zone_rows, compared_rows, verdict_rows };

// Counts verdicts toward the section's.
struct Tally {
  int passed = 0, failed = 0, not_measured = 0, uncertain = 0;
  int add(Verdict v) {
    (v == Verdict::pass        ? passed
     : v == Verdict::fail      ? failed
     : v == Verdict::uncertain ? uncertain
                               : not_measured)++;
    return static_cast<int>(v);
  }
  int verdict() const { return failed ? 1 : not_measured ? 2 : uncertain ? 3 : passed ? 0 : -1; }
};

// A params value of a row: its column, else `otherwise`.
double value_of(const Row& row, const std::string& column, double otherwise = 0) {
  const auto v = row.find(column);
  return v != row.end() ? v->second : otherwise;
}

// The checks of a params row (its `flags` column; a wall's own, for the walls) that flag
// `column`.
CheckBits flagging(const Row& row, const char* column) {
  const std::string name = column;
  const bool wall = name == "wall" || name == "pressure_wall" || name == "suction_wall";
  return checks_flagging(flags_mask(value_of(row, wall ? name + "_flags" : "flags")), wall ? "wall" : column);
}

double wrapped(double degrees) {
  double d = std::fmod(degrees, 360.0);
  if (d > 180) d -= 360;
  if (d <= -180) d += 360;
  return d;
}

// The tolerance rows of every section, and each named section's with them: judging a
// section looks through its own, not the whole file's (32 000 rows took minutes).
class SectionTolerances {
public:
  explicit SectionTolerances(const std::vector<Tolerance>& all) {
    for (const Tolerance& t : all)
      if (t.section < 0) every_.push_back(t);
    for (const Tolerance& t : all) {
      if (t.section < 0) continue;
      auto [it, fresh] = named_.try_emplace(t.section);
      if (fresh) it->second = every_;
      it->second.push_back(t);
    }
  }
  const std::vector<Tolerance>& of(int section) const {
    const auto it = named_.find(section);
    return it == named_.end() ? every_ : it->second;
  }

private:
  std::vector<Tolerance> every_;
  std::map<int, std::vector<Tolerance>> named_;
};

// The rows of the zones and compared tables, and the verdict row, of one section; `c` is
// null for a section that could not be compared (every toleranced value not measured).
// `tol`: the tolerance rows that apply to it.
void judge(int id, const SectionComparison* c, const Input& in, const std::vector<Tolerance>& tol,
           const CompareStreamOptions& o, pipe::Slot& slot) {
  Tally tally;
  const ZoneResult none;
  for (int z = 0; z < zone_count; ++z) {
    const ZoneResult& r = c ? c->zones[z] : none;
    const Tolerance* band = find_tolerance(tol, std::string("profile") + zone_suffix[z], id);
    const Tolerance* form = find_tolerance(tol, std::string("form") + zone_suffix[z], id);
    const int v = band ? tally.add(verdict(*band, r.min, r.max, r.measured && c)) : -1;
    const int fv = form ? tally.add(verdict(*form, r.form, r.form, r.measured && c)) : -1;
    schema::zones.append(slot.rows[zone_rows], {id, z, r, band, v, form, fv});
  }
  const auto p = in.params.find(id);
  const auto n = in.nominal_params.find(id);
  for (std::size_t k = 0; k < std::size(items); ++k) {
    const Item& item = items[k];
    double value = 0, nominal = 0;
    bool measured = c != nullptr;
    for (int z = 1; z < zone_count && measured; ++z)
      if (item.zones >> (z - 1) & 1) measured = c->zones[z].measured;
    const Tolerance* t = find_tolerance(tol, item.name, id);
    const bool on_value = t && t->on_value;
    double sigma2 = 0;  // the variance of what the limits bound
    CheckBits flags = 0, nominal_flags = 0;
    if (c && item.name == std::string("fit_shift")) {
      value = c->fit.motion.translation.norm();
    } else if (c && item.name == std::string("fit_rotation")) {
      value = c->fit.motion.angle;
    } else if (c && item.name == std::string("core_shift")) {
      const auto mc = in.cavities.find(id), nc = in.nominal_cavities.find(id);
      measured = mc != in.cavities.end() && nc != in.nominal_cavities.end();
      if (measured) value = core_shift(c->fit.motion, mc->second, nc->second, flags, sigma2);
    } else if (c) {
      const auto mv = p->second.find(item.name);
      // A deviation needs the nominal's value too (a measured cavity against a solid nominal).
      measured = measured && mv != p->second.end() && (on_value || n->second.count(item.name));
      value = mv != p->second.end() ? mv->second : 0.0;
      nominal = value_of(n->second, item.name);
      // The standard errors camber gives (the edge radii's, the wall's), and the checks it failed.
      const std::string sigma = item.name + std::string("_sigma");
      sigma2 =
          std::pow(value_of(p->second, sigma), 2) + (on_value ? 0 : std::pow(value_of(n->second, sigma), 2));
      flags = flagging(p->second, item.name);
      nominal_flags = on_value ? 0 : flagging(n->second, item.name);
    }
    if (!measured) value = 0;
    const double deviation = measured ? (item.angle ? wrapped(value - nominal) : value - nominal) : 0.0;
    const double uncertainty = measured ? o.coverage * std::sqrt(sigma2) : 0.0;
    int v = -1;
    if (t) {
      const double x = on_value ? value : deviation;
      // A measured value camber flagged may be off by an amount nobody knows, so no limit can
      // judge it. The nominal's flags are reported beside the verdict, not counted: on exact or
      // faceted geometry camber's checks also see the spline's and the facets' sub-micrometre
      // departures (docs/COMPARE.md).
      v = tally.add(!measured ? Verdict::not_measured
                    : flags
                        ? Verdict::uncertain
                        : verdict(*t, x, x, true, o.decision == DecisionRule::guarded ? uncertainty : 0.0));
    }
    schema::compared.append(slot.rows[compared_rows], {id, static_cast<int>(k), measured, value, nominal,
                                                       deviation, t, v, uncertainty, flags, nominal_flags});
  }
  schema::verdicts.append(slot.rows[verdict_rows], {id, tally.verdict(), tally.passed, tally.failed,
                                                    tally.not_measured, tally.uncertain});
}

// The fit and deviations rows of a compared section.
void describe(int id, const SectionComparison& c, const std::vector<double>& index, const Frame& f,
              const CompareStreamOptions& o, const Eigen::Vector3d* blade_shift, pipe::Slot& slot) {
  Eigen::Vector3d shift;
  if (blade_shift) {
    shift = *blade_shift;
  } else {
    const Eigen::Matrix3d r =
        Eigen::AngleAxisd(c.fit.motion.angle * 3.14159265358979323846 / 180, f.n).toRotationMatrix();
    shift = f.origin - r * f.origin + f.direction_to_world(c.fit.motion.translation);
  }
  schema::fits.append(slot.rows[fit_rows], {id, c.fit, static_cast<int>(o.compare.fit.method),
                                            static_cast<int>(o.compare.fit.freedom), o.whole, shift,
                                            static_cast<int>(c.points.size()), c.outliers});
  for (std::size_t i = 0; i < c.points.size(); ++i)
    schema::deviations.append(slot.rows[deviation_rows], {id, static_cast<std::size_t>(index[i]), c.points[i],
                                                          f.to_world(c.points[i].foot)});
}

Frame frame_of(const Input& in, int id) {
  const auto f = in.frames.find(id);
  return f != in.frames.end() ? f->second : Frame{};
}

}  // namespace

const std::vector<std::string>& compared_items() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const Item& i : items) out.emplace_back(i.name);
    return out;
  }();
  return names;
}

std::vector<std::string> tolerance_items() {
  std::vector<std::string> out = compared_items();
  for (const char* what : {"profile", "form"})
    for (const char* z : zone_suffix) out.push_back(what + std::string(z));
  return out;
}

int stream_verdict(const Stream& stream) {
  const Table* t = schema::verdicts.find(stream);
  if (!t) return 0;
  const std::size_t cv = t->column("verdict");
  int worst = 0;
  for (std::size_t r = 0; r < t->rows(); ++r) {
    const double x = t->at(r, cv);
    // A verdict that is not one of the codes (a NaN counted as a pass) is not measured.
    const int v = x >= -1 && x <= 3 && x == std::floor(x) ? static_cast<int>(x) : 2;
    if (v == 1) return 1;
    if (v == 2) worst = 2;
    if (v == 3 && worst == 0) worst = 3;
  }
  return worst;
}

void compare_stream(Stream& stream, const Stream& nominal_any, const CompareStreamOptions& options) {
  // Both in mm, the unit of the options, the tolerances and the tables written: a stream in
  // metres compared as it is gave deviations a thousandth of the true ones.
  convert_to_mm(stream);
  Stream copy;
  const Stream& nominal = in_mm(nominal_any, copy);
  pipe::restage(stream, "compare");
  const Input in = gather(stream, nominal, options.plane_tolerance);
  Table fit = schema::fits.table(), deviations = schema::deviations.table(), zones = schema::zones.table(),
        compared = schema::compared.table(), verdicts = schema::verdicts.table();
  const std::vector<Table*> tables{&fit, &deviations, &zones, &compared, &verdicts};
  std::vector<std::vector<double>> index(in.ids.size());
  std::vector<std::vector<Eigen::Vector2d>> pts(in.ids.size());
  std::vector<std::string> why(in.ids.size());
  for (std::size_t k = 0; k < in.ids.size(); ++k) {
    pts[k] = measured_points(in, in.ids[k], index[k]);
    why[k] = unusable(in, in.ids[k], pts[k].size());
  }
  std::optional<BladeComparison> blade;
  if (options.whole) {
    std::vector<ComparedSection> sections;
    for (std::size_t k = 0; k < in.ids.size(); ++k)
      if (why[k].empty()) sections.push_back({&in.nominals.at(in.ids[k]), &pts[k], frame_of(in, in.ids[k])});
    if (!sections.empty()) blade = compare_blade(sections, options.compare);
  }
  std::vector<std::size_t> position(in.ids.size(), 0);  // the section's place among the blade's
  for (std::size_t k = 0, b = 0; k < in.ids.size(); ++k)
    if (why[k].empty()) position[k] = b++;
  const SectionTolerances by_section(options.tolerances);
  pipe::run_slots(
      in.ids.size(), options.whole ? 1 : options.threads, tables, stream.issues, "compare",
      [&](std::size_t k, pipe::Slot& slot) {
        const int id = in.ids[k];
        if (!why[k].empty()) {
          judge(id, nullptr, in, by_section.of(id), options, slot);
          slot.issues.push_back({id, -1, "compare", why[k] + "; its values are not measured"});
          return;
        }
        try {
          const SectionComparison c = blade ? blade->sections[position[k]]
                                            : compare_section(in.nominals.at(id), pts[k], options.compare);
          if (!c.fit.converged) {  // its deviations are not the best fit's: no verdict rests on them
            char text[240];
            std::snprintf(
                text, sizeof text,
                "the fit did not settle in %d iterations (rms %.4g mm, %.4g before): is the nominal "
                "this section's, and near it?",
                c.fit.iterations, c.fit.rms_after, c.fit.rms_before);
            throw Error(text);
          }
          describe(id, c, index[k], frame_of(in, id), options, blade ? &blade->translation : nullptr, slot);
          judge(id, &c, in, by_section.of(id), options, slot);
        } catch (const Error& e) {
          // The section's values are then not measured: listed so, with the reason.
          for (auto& rows : slot.rows) rows.clear();
          judge(id, nullptr, in, by_section.of(id), options, slot);
          std::string message = e.what();
          if (message.rfind("compare: ", 0) == 0) message = message.substr(9);
          slot.issues.push_back({id, -1, "compare", message + "; its values are not measured"});
        }
      },
      [&](std::size_t k, const std::string& message) {
        return SectionIssue{in.ids[k], -1, "compare", message};
      });
  for (Table* t : tables) stream.put(std::move(*t));
}

void judge_absent_sections(Stream& compared, const CompareStreamOptions& options) {
  std::set<int> present;
  if (const Table* v = schema::verdicts.find(compared))
    for (std::size_t r = 0; r < v->rows(); ++r) present.insert(static_cast<int>(v->at(r, 0)));
  std::map<int, std::string> absent;  // section -> the first tolerance row naming it
  for (const Tolerance& t : options.tolerances)
    if (t.section >= 0 && !present.count(t.section) && !absent.count(t.section)) absent[t.section] = t.where;
  const Input none;
  const SectionTolerances by_section(options.tolerances);
  for (const auto& [id, where] : absent) {
    pipe::Slot slot;
    slot.rows.resize(verdict_rows + 1);
    judge(id, nullptr, none, by_section.of(id), options, slot);
    for (const auto& [k, schema_name] :
         {std::pair{zone_rows, schema::zones.name}, std::pair{compared_rows, schema::compared.name},
          std::pair{verdict_rows, schema::verdicts.name}}) {
      if (!compared.find(schema_name))
        compared.put(k == zone_rows       ? schema::zones.table()
                     : k == compared_rows ? schema::compared.table()
                                          : schema::verdicts.table());
      Table& t = *compared.find(schema_name);
      t.values.insert(t.values.end(), slot.rows[k].begin(), slot.rows[k].end());
    }
    compared.issues.push_back(
        {id, -1, "compare",
         "the tolerances name this section (" + (where.empty() ? "a row" : where) +
             "), which the measured stream does not have; its values are not measured"});
  }
}

}  // namespace section
