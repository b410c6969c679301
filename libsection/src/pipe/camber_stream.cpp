// Stream stage of camber: splines in, camber line and section parameters out.
#include "section/pipe/camber_stream.h"

#include "section/camber.h"
#include "section/error.h"
#include "section/fit_spline.h"
#include "section/params.h"
#include "section/io/stream.h"
#include "section/pipe/schema.h"
#include "section/pipe/fit_spline_stream.h"
#include "detail/parallel.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <string>

namespace section {

namespace {

Table make_table(const std::string& name, std::vector<std::string> columns) {
  Table t;
  t.name = name;
  t.columns = std::move(columns);
  return t;
}

// Loop-0 skeleton of each section, ordered by index (the slice stage's camber seed).
std::map<int, std::vector<Eigen::Vector2d>> skeletons(const Stream& stream) {
  std::map<int, std::vector<Eigen::Vector2d>> out;
  const Table* t = stream.find("skeleton");
  if (!t) return out;
  const long cs = t->find_column("section"), cl = t->find_column("loop"), ci = t->find_column("index"),
             cu = t->find_column("u"), cv = t->find_column("v");
  if (cs < 0 || cu < 0 || cv < 0) return out;
  std::map<int, std::map<int, Eigen::Vector2d>> rows;
  for (std::size_t r = 0; r < t->rows(); ++r) {
    if (cl >= 0 && t->at(r, cl) != 0) continue;
    const int index = ci >= 0 ? static_cast<int>(t->at(r, ci)) : static_cast<int>(r);
    rows[static_cast<int>(t->at(r, cs))][index] = {t->at(r, cu), t->at(r, cv)};
  }
  for (const auto& [section, pts] : rows)
    for (const auto& [index, p] : pts) out[section].push_back(p);
  return out;
}

// Loop-0 measured points of each section (the slice stage's "points" table), if present,
// and apart those the slab held itself (offset 0: not carried onto the plane by the gap
// fill) with the largest |offset| of the carried ones.
struct Measured {
  std::vector<Eigen::Vector2d> all, in_slab, carried;
  std::vector<double> carried_offset;
};
std::map<int, Measured> measured_points(const Stream& stream) {
  std::map<int, Measured> out;
  const Table* t = stream.find("points");
  if (!t) return out;
  const long cs = t->find_column("section"), cl = t->find_column("loop"), cu = t->find_column("u"),
             cv = t->find_column("v"), co = t->find_column("offset");
  if (cs < 0 || cl < 0 || cu < 0 || cv < 0) return out;
  for (std::size_t r = 0; r < t->rows(); ++r) {
    if (t->at(r, cl) != 0) continue;
    Measured& m = out[static_cast<int>(t->at(r, cs))];
    const Eigen::Vector2d q(t->at(r, cu), t->at(r, cv));
    const double offset = co >= 0 ? t->at(r, co) : 0.0;
    m.all.push_back(q);
    if (offset != 0 && std::isfinite(offset)) {
      m.carried.push_back(q);
      m.carried_offset.push_back(std::abs(offset));
    } else {
      m.in_slab.push_back(q);
    }
  }
  return out;
}

// Where a section's other loops lie, for the message that refuses it: a small loop close
// outside the profile is usually a piece of it cut off by a gap in the data.
std::string other_loops(const std::map<std::pair<int, int>, BSpline>& curves, int section) {
  const auto main = curves.find({section, 0});
  if (main == curves.end()) return "";
  const std::vector<Eigen::Vector2d> p0 = sample(main->second, 400);
  Eigen::Vector2d low = p0[0], high = p0[0];
  for (const auto& q : p0) low = low.cwiseMin(q), high = high.cwiseMax(q);
  auto area = [](const std::vector<Eigen::Vector2d>& p) {
    double a = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const Eigen::Vector2d& b = p[(i + 1) % p.size()];
      a += p[i].x() * b.y() - p[i].y() * b.x();
    }
    return std::abs(0.5 * a);
  };
  std::string out;
  bool cut = false;
  for (const auto& [key, curve] : curves) {
    if (key.first != section || key.second == 0) continue;
    const std::vector<Eigen::Vector2d> p = sample(curve, 400);
    double gap = std::numeric_limits<double>::infinity();
    for (const auto& a : p)
      for (const auto& b : p0) gap = std::min(gap, (a - b).norm());
    char text[160];
    std::snprintf(text, sizeof text, "%sloop %d: area %.3g against %.3g, %.3g from loop 0", out.empty() ? "" : "; ",
                  key.second, area(p), area(p0), gap);
    out += text;
    cut = cut || (area(p) < 0.2 * area(p0) && gap < 0.1 * (high - low).norm());
  }
  if (out.empty()) return "";
  return " (" + out + ")" + (cut ? "; a small loop this close is often a piece of the profile cut off by a gap in the data" : "");
}

// The edge's own scale: its radius, or a blunt edge's face width (0 for a sharp edge).
double edge_size(const Edge& e) { return e.radius > 0 ? e.radius : e.face; }

// How well the measured points cover an edge.
struct EdgeCoverage {
  // Length along the profile of the stretch around the edge point that no measured point
  // covers: a hole over the edge, or an edge sampled more sparsely than its radius. There
  // the edge point and radius come from the fit bridging the hole, not from measurements.
  double around = 0;
  // The longest stretch without measured points that begins within the edge arc, and its
  // distance from the edge point (0 when it holds the edge point), both along the
  // profile: part of the arc the circle is fitted to is a bridge.
  double hole = 0, hole_distance = 0;
};

EdgeCoverage edge_coverage(const BSpline& curve, const Edge& edge, const std::vector<Eigen::Vector2d>& measured,
                           double arc_reach) {
  EdgeCoverage out;
  const double size = edge_size(edge);
  if (measured.empty() || !(size > 0)) return out;
  const int half = 200;
  const double reach = 3 * 3.14159265358979 * size, h = reach / half;
  // Samples every h along the curve, from -reach to +reach around the edge point.
  std::vector<Eigen::Vector2d> samples(2 * half + 1);
  samples[half] = curve.point(edge.t);
  for (int dir : {-1, 1}) {
    double t = edge.t;
    for (int k = 1; k <= half; ++k) {
      const double speed = curve.derivative(t, 1).norm();
      if (!(speed > 0)) return out;
      t += dir * h / speed;
      samples[half + dir * k] = curve.point(t);
    }
  }
  // A point covers its nearest sample if that lies within 2h. Samples are bucketed in
  // cells wider than 2h, so the 3 x 3 cells around a point hold every sample that can
  // count; ties go to the lowest index, as a scan of all samples would give.
  const double cell = 2.5 * h;
  Eigen::Vector2d low = samples[half], high = samples[half];
  for (const auto& s : samples)
    if (s.allFinite()) low = low.cwiseMin(s), high = high.cwiseMax(s);
  const int nx = static_cast<int>((high.x() - low.x()) / cell) + 1, ny = static_cast<int>((high.y() - low.y()) / cell) + 1;
  auto cell_of = [&](double v, double v0, int n) {
    return static_cast<int>(std::clamp(std::floor((v - v0) / cell), -1.0, double(n)));
  };
  std::vector<int> head(static_cast<std::size_t>(nx) * ny, -1), next(samples.size(), -1);
  for (int k = static_cast<int>(samples.size()) - 1; k >= 0; --k) {
    if (!samples[k].allFinite()) continue;
    const std::size_t c = std::size_t(cell_of(samples[k].y(), low.y(), ny - 1)) * nx + cell_of(samples[k].x(), low.x(), nx - 1);
    next[k] = head[c];
    head[c] = k;
  }
  std::vector<char> covered(samples.size(), 0);
  for (const auto& q : measured) {
    if ((q - samples[half]).norm() > reach + 2 * h) continue;
    const int cx = cell_of(q.x(), low.x(), nx), cy = cell_of(q.y(), low.y(), ny);
    int best = -1;
    double best_d = std::numeric_limits<double>::infinity();
    for (int y = std::max(cy - 1, 0); y <= std::min(cy + 1, ny - 1); ++y)
      for (int x = std::max(cx - 1, 0); x <= std::min(cx + 1, nx - 1); ++x)
        for (int k = head[std::size_t(y) * nx + x]; k >= 0; k = next[k]) {
          const double d = (q - samples[k]).squaredNorm();
          if (d < best_d || (d == best_d && k < best)) best_d = d, best = k;
        }
    if (best >= 0 && std::sqrt(best_d) <= 2 * h) covered[best] = 1;
  }
  int lo = half, hi = half;
  while (lo > 0 && !covered[lo]) --lo;
  while (hi < 2 * half && !covered[hi]) ++hi;
  if (!covered[half]) out.around = (hi - lo) * h;
  for (int k = 0; k <= 2 * half;) {
    if (covered[k]) {
      ++k;
      continue;
    }
    int e = k;
    while (e <= 2 * half && !covered[e]) ++e;
    const double length = (e - k + 1) * h,
                 distance = k > half ? (k - 1 - half) * h : e <= half ? (half - e) * h : 0.0;
    if (distance <= arc_reach * size && length > out.hole) out.hole = length, out.hole_distance = distance;
    k = e;
  }
  return out;
}

}  // namespace

Stream profile_stream(const BSpline& spline, double rms) {
  Stream stream;
  Table head = make_table("splines", {"section", "loop", "degree", "closed", "control_points", "rms",
                                      "max", "p95", "iterations"});
  head.add_row({0, 0, double(spline.degree), spline.closed ? 1.0 : 0.0, double(spline.control.size()),
                rms, 0, 0, 0});
  Table knots = make_table("spline_knots", {"section", "loop", "index", "knot"});
  for (std::size_t i = 0; i < spline.knots.size(); ++i) knots.add_row({0, 0, double(i), spline.knots[i]});
  Table ctrl = make_table("spline_ctrl", {"section", "loop", "index", "u", "v"});
  for (std::size_t i = 0; i < spline.control.size(); ++i)
    ctrl.add_row({0, 0, double(i), spline.control[i].x(), spline.control[i].y()});
  stream.put(head);
  stream.put(knots);
  stream.put(ctrl);
  return stream;
}

void camber_stream(Stream& stream, const CamberOptions& options) {
  const auto curves = splines(stream);
  std::map<int, Frame> frame;
  if (stream.find("frames")) frame = frames(stream);
  const auto seeds = skeletons(stream);
  const auto measured = measured_points(stream);
  // The profile's noise: the rms distance of the measured points to the fitted curve.
  std::map<int, double> noise;
  if (const Table* t = stream.find("splines"); t && t->find_column("rms") >= 0) {
    const std::size_t cs = t->column("section"), cl = t->column("loop"), cr = t->column("rms");
    for (std::size_t i = 0; i < t->rows(); ++i)
      if (t->at(i, cl) == 0 && t->at(i, cr) > 0) noise[static_cast<int>(t->at(i, cs))] = t->at(i, cr);
  }

  Table camber = make_table("camber", {"section", "index", "s", "u", "v", "x", "y", "z", "radius"});
  Table params = make_table(
      "params",
      {"section", "chord", "camber_length", "max_thickness", "max_thickness_pos", "le_radius",
       "te_radius", "le_curvature_radius", "te_curvature_radius", "le_shape", "te_shape",
       "le_arc", "te_arc", "le_fit_rms", "te_fit_rms", "stagger", "inlet_angle", "outlet_angle",
       "camber_angle", "area", "centroid_u", "centroid_v", "le_u", "le_v", "te_u", "te_v",
       "le_center_u", "le_center_v", "te_center_u", "te_center_v", "le_x", "le_y", "le_z", "te_x",
       "te_y", "te_z", "centroid_x", "centroid_y", "centroid_z", "caliper_chord",
       "caliper_stagger", "caliper_found", "pressure_side", "le_by_direction", "le_face", "te_face",
       "le_unmeasured", "te_unmeasured"});
  Table thickness = make_table("thickness", {"section", "index", "fraction", "s", "u", "v", "thickness",
                                             "pressure_u", "pressure_v", "suction_u", "suction_v"});
  Table sides = make_table("sides", {"section", "side", "index", "u", "v"});

  std::map<int, int> loops;
  for (const auto& [key, curve] : curves) ++loops[key.first];
  // Sections are independent: each fills its own slot, merged in section order afterwards,
  // so the output is the same whatever the thread count.
  struct Slot {
    Table camber, params, thickness, sides;
    std::vector<SectionIssue> issues;
  };
  std::vector<std::pair<int, const BSpline*>> work;
  for (const auto& [key, curve] : curves)
    if (key.second == 0) work.push_back({key.first, &curve});
  std::vector<Slot> slots(work.size(), Slot{camber, params, thickness, sides, {}});
  detail::parallel_for(work.size(), options.threads, [&](std::size_t item) {
    const int section = work[item].first;
    const BSpline& curve = *work[item].second;
    Slot& slot = slots[item];
    try {
      if (loops.at(section) > 1)
        throw Error("camber: section " + std::to_string(section) + " has " + std::to_string(loops.at(section)) +
                    " loops; camber measures single-profile sections" + other_loops(curves, section));
      CamberOptions opt = options;
      const auto fit = frame.find(section);
      const Frame f = fit != frame.end() ? fit->second : Frame{};
      if (opt.le_direction.norm() == 0 && opt.le_direction_3d.norm() > 0) {
        const Eigen::Vector3d& d = opt.le_direction_3d;
        opt.le_direction = {d.dot(f.u), d.dot(f.v)};
        if (!(opt.le_direction.norm() > 1e-6 * d.norm()))
          throw Error("camber: the leading-edge direction (" + format_number(d.x()) + ", " + format_number(d.y()) +
                      ", " + format_number(d.z()) + ") is normal to the plane of section " +
                      std::to_string(section) + ": it cannot tell the edges apart there");
      }
      if (const auto n = noise.find(section); n != noise.end() && opt.profile_noise <= 0) opt.profile_noise = n->second;
      const auto seed = seeds.find(section);
      if (seed != seeds.end() && seed->second.size() >= 4) opt.medial.seed = seed->second;
      const auto points = measured.find(section);
      const Measured none;
      const Measured& q = points != measured.end() ? points->second : none;
      CamberResult r;
      try {
        r = camber_line(curve, opt, q.all);
      } catch (const Error&) {
        if (opt.medial.seed.empty()) throw;
        opt.medial.seed.clear();  // a poor skeleton: fall back to the Delaunay seed
        r = camber_line(curve, opt, q.all);
      }
      const SectionParams p = section_params(curve, r);
      const auto st = thickness_stations(curve, r, options.stations);
      const Sides sd = split_sides(curve, r, options.side_samples);
      for (std::size_t i = 0; i < r.points.size(); ++i) {
        const Eigen::Vector3d w = f.to_world(r.points[i]);
        slot.camber.add_row({double(section), double(i), r.s[i], r.points[i].x(), r.points[i].y(), w.x(), w.y(),
                        w.z(), r.radius[i]});
      }
      const EdgeCoverage le_cover = edge_coverage(curve, r.le, q.all, opt.edge_hole_reach),
                         te_cover = edge_coverage(curve, r.te, q.all, opt.edge_hole_reach);
      const double le_unmeasured = le_cover.around, te_unmeasured = te_cover.around;
      const Eigen::Vector3d le = f.to_world(p.le_point), te = f.to_world(p.te_point),
                            cg = f.to_world(p.centroid);
      slot.params.add_row({double(section), p.chord, p.camber_length, p.max_thickness, p.max_thickness_pos,
                      p.le_radius, p.te_radius, p.le_curvature_radius, p.te_curvature_radius,
                      double(static_cast<int>(r.le.shape)), double(static_cast<int>(r.te.shape)), r.le.arc,
                      r.te.arc, r.le.fit_rms, r.te.fit_rms, p.stagger, p.inlet_angle, p.outlet_angle,
                      p.camber_angle, p.area, p.centroid.x(), p.centroid.y(), p.le_point.x(),
                      p.le_point.y(), p.te_point.x(), p.te_point.y(), r.le.center.x(), r.le.center.y(),
                      r.te.center.x(), r.te.center.y(), le.x(), le.y(), le.z(), te.x(), te.y(), te.z(),
                      cg.x(), cg.y(), cg.z(), p.caliper_chord, p.caliper_stagger,
                      p.caliper_found ? 1.0 : 0.0, double(r.pressure_side), r.le_by_direction ? 1.0 : 0.0,
                      r.le.face, r.te.face, le_unmeasured, te_unmeasured});
      for (std::size_t i = 0; i < st.size(); ++i)
        slot.thickness.add_row({double(section), double(i), st[i].fraction, st[i].s, st[i].point.x(),
                           st[i].point.y(), st[i].thickness, st[i].pressure.x(), st[i].pressure.y(),
                           st[i].suction.x(), st[i].suction.y()});
      for (int side = 0; side < 2; ++side) {
        const auto& pts = side == 0 ? sd.pressure : sd.suction;
        for (std::size_t i = 0; i < pts.size(); ++i)
          slot.sides.add_row({double(section), double(side), double(i), pts[i].x(), pts[i].y()});
      }
      // Edges that are not round: a flat face is reported with its width (never a
      // circle); other blunt and sharp edges as the edge model says.
      auto describe = [&](const Edge& e, const char* which) {
        if (e.shape == EdgeShape::round) return std::string();
        if (e.face > 0)
          return std::string(which) + " is blunt: a flat face " + format_number(e.face) + " wide (radius reported as 0)";
        return std::string(which) + " looks " + (e.shape == EdgeShape::blunt ? "blunt" : "sharp") +
               (options.edge == EdgeModel::round ? " (fitted as round anyway)" : " (radius reported as 0)");
      };
      auto hole = [&](const Edge& e, const EdgeCoverage& cover, const char* which) {
        const double size = edge_size(e), unmeasured = cover.around;
        if (!(unmeasured > size)) {
          if (!(cover.hole >= opt.edge_hole * size)) return std::string();
          return std::string(which) + " partly not measured: " + format_number(cover.hole) +
                 " of the profile without a measured point begins " + format_number(cover.hole_distance) +
                 " from the edge point (edge " + (e.radius > 0 ? "radius " : "face ") + format_number(size) +
                 "); its radius and point rest partly on the curve bridging that hole";
        }
        return std::string(which) + " not measured: " + format_number(unmeasured) +
               " of the profile around it has no measured point (edge " + (e.radius > 0 ? "radius " : "face ") +
               format_number(size) + "); its point and radius bridge a hole in the data";
      };
      // An edge covered only thanks to points the gap fill carried onto the plane: say so,
      // with how far they came from (their positions rest on the drift fitted beside the gap).
      auto carried = [&](const Edge& e, const std::string& hole_message, const char* which) {
        if (q.carried.empty() || !hole_message.empty()) return std::string();
        const EdgeCoverage own = edge_coverage(curve, e, q.in_slab, opt.edge_hole_reach);
        if (hole(e, own, which).empty()) return std::string();
        const double size = edge_size(e);
        const Eigen::Vector2d at = curve.point(e.t);
        double far = 0;
        for (std::size_t i = 0; i < q.carried.size(); ++i)
          if ((q.carried[i] - at).norm() <= 3 * size + own.around) far = std::max(far, q.carried_offset[i]);
        char text[256];
        std::snprintf(text, sizeof text,
                      "%s measured with points carried onto the plane from up to %.3g off it (slice's gap fill: "
                      "the slab alone leaves %.3g of the profile there without a point)",
                      which, far, std::max(own.around, own.hole));
        return std::string(text);
      };
      auto circularity = [&](const Edge& e, const char* which) {
        if (e.circular || e.shape != EdgeShape::round) return std::string();
        char text[256];
        std::snprintf(text, sizeof text,
                      "%s is not circular: the circle fitted to its %.0f-degree arc leaves it by %.3g rms, %.0f times "
                      "the points' rms distance to the profile; its radius and point depend on the arc taken",
                      which, e.arc, e.fit_rms, e.fit_rms / opt.profile_noise);
        return std::string(text);
      };
      auto join = [](std::string a, const std::string& b) { return a.empty() ? b : b.empty() ? a : a + ", " + b; };
      const std::string le_hole = hole(r.le, le_cover, "leading edge"), te_hole = hole(r.te, te_cover, "trailing edge");
      const std::string le_msg = join(join(join(describe(r.le, "leading edge"), le_hole),
                                           carried(r.le, le_hole, "leading edge")),
                                      circularity(r.le, "leading edge")),
                        te_msg = join(join(join(describe(r.te, "trailing edge"), te_hole),
                                           carried(r.te, te_hole, "trailing edge")),
                                      circularity(r.te, "trailing edge"));
      if (!le_msg.empty() || !te_msg.empty())
        slot.issues.push_back({section, 0, "camber", le_msg + (le_msg.empty() || te_msg.empty() ? "" : ", ") + te_msg});
      // A camber line that strays from the medial axis (no inscribed circle solved there)
      // is not a measured one: say where and by how much.
      if (r.off_axis > 0) {
        std::size_t k = 0;
        while (k + 1 < r.s.size() && r.s[k] < r.off_axis_s) ++k;
        if (k < r.radius.size() && r.off_axis > opt.off_axis * r.radius[k]) {
          char text[256];
          std::snprintf(text, sizeof text,
                        "the camber line strays from the medial axis by up to %.3g at %.2f of its length (no "
                        "inscribed circle could be solved there): its shape and the thickness stations there are "
                        "interpolated",
                        r.off_axis, r.off_axis_s / std::max(r.length, 1e-300));
          slot.issues.push_back({section, 0, "camber", text});
        }
      }
      // The thickness rule is a near tie: say so rather than let the orientation pass as known.
      if (!r.le_by_direction && std::abs(p.max_thickness_pos - 0.5) <= opt.le_thickness_margin) {
        char text[256];
        std::snprintf(text, sizeof text,
                      "the leading edge was taken as the end nearer the maximum thickness, which lies at %.2f of "
                      "the camber line: too near mid-chord to tell; give the leading-edge direction",
                      p.max_thickness_pos);
        slot.issues.push_back({section, 0, "camber", text});
      }
    } catch (const Error& e) {
      std::string msg = e.what();
      if (msg.rfind("camber: ", 0) == 0) msg = msg.substr(8);
      slot = Slot{camber, params, thickness, sides, {}};
      slot.issues.push_back({section, loops.at(section) > 1 ? -1 : 0, "camber", msg});
    }
  });
  for (auto& slot : slots) {
    camber.values.insert(camber.values.end(), slot.camber.values.begin(), slot.camber.values.end());
    params.values.insert(params.values.end(), slot.params.values.begin(), slot.params.values.end());
    thickness.values.insert(thickness.values.end(), slot.thickness.values.begin(), slot.thickness.values.end());
    sides.values.insert(sides.values.end(), slot.sides.values.begin(), slot.sides.values.end());
    for (auto& i : slot.issues) stream.issues.push_back(std::move(i));
  }
  stream.put(camber);
  stream.put(params);
  stream.put(thickness);
  stream.put(sides);
}

}  // namespace section
