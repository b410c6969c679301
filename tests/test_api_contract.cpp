// SPDX-License-Identifier: GPL-3.0-or-later
// The public API's contract with a program that embeds it: whatever it is handed, a call
// returns a sound result or throws section::Error naming the problem. Each case below
// crashed (SIGSEGV, a read past a vector), hung, threw a std:: exception, or returned a
// wrong value without a word, in a probe of the headers with degenerate input (2026-12-04).
#include "section/bspline.h"
#include "section/camber.h"
#include "section/checks.h"
#include "section/compare.h"
#include "section/drift_band.h"
#include "section/error.h"
#include "section/extras/generate.h"
#include "section/fit_spline.h"
#include "section/frame.h"
#include "section/io/csv.h"
#include "section/io/json.h"
#include "section/io/params_text.h"
#include "section/io/stream.h"
#include "section/medial_axis.h"
#include "section/params.h"
#include "section/pipe/camber_stream.h"
#include "section/pipe/compare_stream.h"
#include "section/pipe/fit_spline_stream.h"
#include "section/pipe/schema.h"
#include "section/pipe/slice_stream.h"
#include "section/revolution.h"
#include "section/sampling.h"
#include "section/slice.h"
#include "section/smooth.h"
#include "section/stacking.h"

#include "thrown.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <climits>
#include <functional>
#include <cmath>
#include <limits>
#include <vector>

using namespace section;

namespace {

using Points = std::vector<Eigen::Vector2d>;
const double not_a_number = std::numeric_limits<double>::quiet_NaN();

Points circle(int n, double r = 1) {
  Points p;
  for (int i = 0; i < n; ++i) p.emplace_back(r * std::cos(2 * M_PI * i / n), r * std::sin(2 * M_PI * i / n));
  return p;
}

BSpline circle_curve() {
  CurveFitOptions o;
  o.control_points = 12;
  return fit_curve(circle(100), o);
}

// An exact turbine section's points, its fitted profile and camber line.
struct Blade {
  Points points;
  BSpline profile;
  CamberResult camber;
  Blade() {
    const SectionTruth truth = section_truth(turbine_blade().at(20), 4000);
    for (std::size_t i = 0; i < truth.profile.size(); i += 8) points.push_back(truth.profile[i]);
    profile = fit_spline(points, points).spline;
    camber = camber_line(profile);
  }
};

const Blade& blade() {
  static const Blade b;
  return b;
}

// True when `f()` throws section::Error holding `text`.
template <class F>
bool refuses(F&& f, const std::string& text) {
  const std::string m = thrown(std::forward<F>(f));
  INFO(m);
  return m != "no error" && m.find(text) != std::string::npos;
}

}  // namespace

TEST_CASE("api: curves the functions cannot evaluate are refused, not read past", "[api]") {
  // A default BSpline has no knots: t_min() read knots[3] of an empty vector.
  CHECK(refuses([] { (void)BSpline{}.t_min(); }, "0 knots"));
  CHECK(refuses([] { enclosed_area(BSpline{}); }, "bspline:"));
  CHECK(refuses([] { section_params(BSpline{}, blade().camber); }, "bspline:"));
  CHECK(refuses([] { split_sides(BSpline{}, blade().camber, 20); }, "bspline:"));
  CHECK(refuses([] { thickness_stations(blade().profile, CamberResult{}, {0.5}); }, "camber line is empty"));
  InscribedCircle ic;
  CHECK(refuses([&] { inscribed_circle(BSpline{}, {0, 0}, {0, 1}, 0, 1, ic); }, "bspline:"));
  // Equal knots, or knots 1e17 off (the period rounds to 0): self_intersects crashed.
  BSpline flat = circle_curve();
  for (auto& k : flat.knots) k = 1.0;
  CHECK(refuses([&] { self_intersects(flat); }, "parameter range is empty"));
  BSpline far = circle_curve();
  for (auto& k : far.knots) k += 1e17;
  CHECK(refuses([&] { self_intersects(far); }, "bspline:"));
  BSpline nan_control = circle_curve();
  nan_control.control[2].x() = not_a_number;
  CHECK(refuses([&] { enclosed_area(nan_control); }, "control point 2 is not finite"));
}

TEST_CASE("api: counts and bounds that ran out of memory or time are refused", "[api]") {
  const BSpline c = circle_curve();
  CHECK(refuses([&] { span_samples(c, -1); }, "samples a knot span"));
  CHECK(refuses([&] { span_samples(c, INT_MAX); }, "samples a knot span"));
  CHECK(refuses([&] { sample(c, INT_MAX); }, "at most 100000000"));
  CHECK(refuses([&] { closest_point(c, {2, 0}, 100000000); }, "at most 1000000"));
  CHECK(refuses([&] { closest_point(c, {not_a_number, 0}); }, "not finite"));
  CHECK(refuses([&] { closest_point(c, {1e155, 0}); }, "too far"));
  // Arc length over 1e12 periods walked every span (hours); over an infinite range, forever.
  const double one = arc_length(c, c.t_min(), c.t_max());
  CHECK(arc_length(c, c.t_min(), c.t_min() + 1e6 * (c.t_max() - c.t_min())) ==
        Approx(1e6 * one).epsilon(1e-9));
  CHECK(refuses([&] { arc_length(c, 0, std::numeric_limits<double>::infinity()); }, "not finite"));
  BSpline backwards = c;  // knots falling: a period below 0 recursed until the stack ran out
  std::reverse(backwards.knots.begin(), backwards.knots.end());
  CHECK(refuses([&] { arc_length(backwards, 0, 1); }, "period is not above 0"));
  CHECK(refuses([] { split_sides(blade().profile, blade().camber, INT_MAX); }, "samples a side"));
  CHECK(refuses([] { planes_across({{0, 0, 0}, {0, 0, 1}}, {0, 0, 1}, INT_MAX); }, "--count must be 1 to"));
  // fit_control_points read past a weights vector shorter than its points.
  const Points p = circle(100);
  CHECK(refuses([&] { fit_control_points(p, chord_length_parameters(p, true), c, 1e-6, {1.0}); },
                "1 weights for 100 points"));
  CHECK(refuses([&] { fit_control_points({}, {}, c); }, "no points"));
}

TEST_CASE("api: camber options out of range are refused by name", "[api]") {
  // A medial tolerance of 1e-16 or 0 hung; INT_MAX samples hung; an edge_prune of 90 degrees
  // gave a camber length of 10.8 for 49.4, an edge_arc of 720 edge radii of 24 for 2 and 0.5.
  const auto with = [](auto set) {
    CamberOptions o;
    set(o);
    return [o] { camber_line(blade().profile, o); };
  };
  CHECK(refuses(with([](CamberOptions& o) { o.medial.tolerance = 1e-16; }), "medial.tolerance is 1e-16"));
  CHECK(refuses(with([](CamberOptions& o) { o.medial.tolerance = 0; }), "medial.tolerance"));
  CHECK(refuses(with([](CamberOptions& o) { o.samples = INT_MAX; }), "samples is"));
  CHECK(refuses(with([](CamberOptions& o) { o.medial.samples = 100000000; }), "medial.samples"));
  CHECK(refuses(with([](CamberOptions& o) { o.edge_core = not_a_number; }), "edge_core is nan"));
  CHECK(refuses(with([](CamberOptions& o) { o.edge_prune = 90; }), "edge_prune is 90"));
  CHECK(refuses(with([](CamberOptions& o) { o.edge_arc = 720; }), "edge_arc is 720"));
  // A degree-1 profile's corners passed for edges: its LE point 6.7 mm off, without a word.
  CurveFitOptions polygon;
  polygon.degree = 1;
  polygon.control_points = 300;
  const BSpline corners = fit_curve(blade().points, polygon);
  CHECK(refuses([&] { camber_line(corners); }, "degree 1"));
  MedialAxisOptions m;
  m.tolerance = 0;
  CHECK(refuses([&] { medial_axis(blade().profile, m); }, "medial.tolerance"));
  // The defaults and the documented ends of the ranges are taken.
  CHECK_NOTHROW(camber_line(blade().profile));
  CamberOptions edges;
  edges.edge_prune = 0;
  edges.tangent_span = 0;
  CHECK_NOTHROW(camber_line(blade().profile, edges));
}

TEST_CASE("api: check_section flags a chord that is not its edge points' distance", "[api]") {
  // A params row edited (or made by other code) is checked against the profile: a chord 20 %
  // long, or not a number, passed unflagged; camber's own is its edge points' distance.
  const SectionParams own = section_params(blade().profile, blade().camber);
  const auto chord_finding = [&](const SectionParams& p) {
    const SectionCheck c = check_section(blade().profile, blade().camber, p);
    for (const Finding& f : c.findings)
      if (f.check == Check::chord) return f.value;
    return -1.0;
  };
  CHECK(chord_finding(own) == -1.0);
  SectionParams edited = own;
  edited.chord *= 1.2;
  CHECK(chord_finding(edited) == Approx(0.2 * own.chord).epsilon(1e-9));
  edited.chord = not_a_number;
  CHECK(std::isnan(chord_finding(edited)));
}

TEST_CASE("api: stations at the edge points have no width; other options are checked", "[api]") {
  // [0, 1] is documented; a station at 1 threw "the camber normal misses the profile".
  const auto st = thickness_stations(blade().profile, blade().camber, {0.0, 1.0});
  REQUIRE(st.size() == 2);
  CHECK(st[0].thickness == 0);
  CHECK(st[0].point == blade().camber.le.point);
  CHECK(st[1].thickness == 0);
  CHECK(st[1].point == blade().camber.te.point);
  // A NaN noise silenced every check; NaN tolerance limits, or a negative uncertainty, passed.
  CheckOptions co;
  co.noise = not_a_number;
  CHECK(refuses(
      [&] {
        check_section(blade().profile, blade().camber, section_params(blade().profile, blade().camber), co);
      },
      "not finite"));
  Tolerance t;
  t.low = not_a_number;
  CHECK(refuses([&] { verdict(t, 0, 0, true); }, "not numbers"));
  Tolerance ok;
  ok.low = -0.1;
  ok.high = 0.1;
  CHECK(refuses([&] { verdict(ok, 0, 0, true, -1); }, "negative uncertainty"));
  CHECK(verdict(ok, 0.2, -0.2, true) == Verdict::fail);  // a range given the other way round
  CHECK(verdict(ok, 0.05, -0.05, true) == Verdict::pass);
  FitSplineOptions fo;
  fo.max_control_points = 0;
  CHECK(refuses([&] { fit_spline(blade().points, blade().points, fo); }, "max_control_points"));
  CHECK(refuses([] { smooth_energy(circle(10), circle(10), not_a_number, 1); }, "a and b"));
  CHECK(refuses([] { smoothing_weight(1, 0); }, "spacing"));
  CHECK(refuses([] { band_half_width(100, 10, not_a_number, 0.03, 2); }, "slab"));
  CHECK(refuses([] { radius_range({}, {0, 0, 0}, {0, 0, 1}); }, "no points"));
  Points noisy = blade().points;
  noisy[4].x() = not_a_number;
  CHECK(refuses([&] { points_noise(blade().profile, noisy); }, "point 4 is not finite"));
  // A finite normal whose length overflows is a direction like any other.
  CHECK(make_frame({0, 0, 0}, {1e300, 1e300, 0}).n.isApprox(Eigen::Vector3d(1, 1, 0).normalized()));
}

TEST_CASE("api: the blade check leaves out values that are not numbers", "[api]") {
  // A NaN chord beside a section 50 % too long hid its jump.
  const SectionParams p = section_params(blade().profile, blade().camber);
  std::vector<BladeSection> v(7);
  for (int i = 0; i < 7; ++i) {
    v[i].height = i;
    v[i].params = p;
  }
  v[3].params.chord *= 1.5;
  v[2].params.chord = not_a_number;
  int chord_jumps = 0;
  for (const Jump& j : check_blade(v)) chord_jumps += j.check == Check::jump_chord && j.index == 3;
  CHECK(chord_jumps == 1);
  BladeCheckOptions o;
  o.length = not_a_number;  // turned every chord check off
  CHECK(refuses([&] { check_blade(v, o); }, "negative or not finite"));
}

TEST_CASE("api: compare refuses what it cannot measure", "[api]") {
  NominalSection n;
  n.curve = blade().profile;
  n.le_point = blade().camber.le.point;
  n.te_point = blade().camber.te.point;
  Points huge = blade().points;
  for (auto& q : huge) q *= 1e155;  // squared distances overflowed: SIGSEGV in the foot search
  CHECK(refuses([&] { compare_section(n, huge); }, "beyond +-1e15"));
  CompareOptions forever;  // INT_MAX iterations that never converge ran for hours
  forever.fit.max_iterations = INT_MAX;
  forever.fit.convergence = 0;
  CHECK(refuses([&] { compare_section(n, blade().points, forever); }, "1 to 10000"));
  std::vector<ComparedSection> none(2);  // null pointers
  CHECK(refuses([&] { compare_blade(none); }, "no nominal or no measured points"));
  std::vector<ComparedSection> v(2);
  for (auto& s : v) {
    s.nominal = &n;
    s.measured = &blade().points;
    s.frame = make_frame({0, 0, 0}, {0, 0, 1});
  }
  v[1].frame.origin.x() = not_a_number;
  CHECK(refuses([&] { compare_blade(v); }, "frame is not finite"));
  CHECK(std::string(zone_name(static_cast<Zone>(99))) == "unknown");
  CHECK(refuses([] { checks_flagging(1, nullptr); }, "null pointer"));
  CHECK(refuses([] { check_names_text(7, nullptr); }, "null pointer"));
  CHECK(refuses([] { params_flagged(1, nullptr); }, "null pointer"));
  // Nominal points built in memory: one at 1e300 read as 'all points are equal', a NaN
  // section id as section -2147483648.
  std::map<int, Frame> frames{{0, make_frame({0, 0, 0}, {0, 0, 1})}};
  Table uv("nominal", {"section", "u", "v"});
  for (int i = 0; i < 40; ++i) uv.add_row({0, 20 * std::cos(i * 0.157), 3 * std::sin(i * 0.157)});
  uv.values[3 * 7 + 1] = 1e300;
  NominalSource source;
  source.points = &uv;
  CHECK(refuses([&] { nominal_stream(source, frames); },
                "nominal point 8: column 'u' is 1e+300, not a coordinate"));
  uv.values[3 * 7 + 1] = 20;
  uv.values[3 * 9] = not_a_number;
  CHECK(
      refuses([&] { nominal_stream(source, frames); }, "nominal point 10: section nan is not a section id"));
  Table xyz("nominal", {"x", "y", "z"});
  xyz.add_row({1, 2, std::numeric_limits<double>::infinity()});
  source.points = &xyz;
  CHECK(refuses([&] { nominal_stream(source, frames); }, "column 'z' is inf"));
}

TEST_CASE("api: slicing refuses clouds and meshes it would read past", "[api]") {
  Mesh m = generate_mesh(turbine_blade(), 200, 20);
  m.triangles[0] = {0, 1, 99999999};
  CHECK(refuses(
      [&] {
        slice(m, std::vector<Revolution>{cylinder_surface({0, -100, 22}, {1, 0, 0}, 100)});
      },
      "index out of range"));
  Mesh far = generate_mesh(turbine_blade(), 200, 20);  // a spurious loop on the plane below it
  far.vertices[100] = {1e300, 0, 30};
  CHECK(refuses(
      [&] {
        slice(far, planes_at({0, 0, 1}, {10, 30}));
      },
      "mesh vertex 100 is not finite or lies beyond"));
  far.vertices[100].x() = not_a_number;  // open polylines
  CHECK(refuses([&] { slice(far, planes_at({0, 0, 1}, {10, 30})); }, "mesh vertex 100"));
  CHECK(refuses(
      [&] {
        slice(far, std::vector<Revolution>{cylinder_surface({0, -100, 22}, {1, 0, 0}, 100)});
      },
      "mesh vertex 100"));
  const Cloud rows = generate_rows(turbine_blade(), RowsOptions{});
  const Sampling s = sampling_of(rows.points, {0, 0, 1});
  Cloud small;
  small.points.assign(rows.points.begin(), rows.points.begin() + 10);
  CHECK(refuses([&] { slice_rows(small, s); }, "the cloud has 10"));
  ScanOptions so;
  so.spacing = 0.25;
  so.z_min = 20;
  so.z_max = 24;
  Cloud c = generate_scan(turbine_blade(), so).cloud;
  SliceOptions o;
  o.threads = 1;
  o.sampling.queries = 0;  // the whole cloud became one section
  CHECK(refuses([&] { slice(c, planes_at({0, 0, 1}, {22}), o); }, "1 query"));
  c.points[10] = {not_a_number, not_a_number, not_a_number};
  CHECK(refuses([&] { slice(c, planes_at({0, 0, 1}, {22})); }, "point 10 is not finite"));
  // A point the cloud readers refuse, in a cloud built in memory (ls.slice of an array): it
  // made a raster of 1.8e21 cells, refused without naming the point.
  c.points[10] = {1e20, 0, 22};
  for (const auto& cut : std::vector<std::function<void()>>{
           [&] {
             slice(c, planes_at({0, 0, 1}, {22}));
           },
           [&] {
             slice_by_rows(c, {0, 0, 1}, {}, true);
           },
           [&] {
             slice(c, std::vector<Revolution>{cylinder_surface({0, -100, 22}, {1, 0, 0}, 100)});
           }})
    CHECK(refuses(cut, "point 10 lies beyond +-1e15"));
  std::vector<StackedSection> st(3);
  StackingOptions sto;
  sto.samples = INT_MAX;
  CHECK(refuses([&] { stacking(st, sto); }, "samples must be 2 to"));
}

TEST_CASE("api: streams built in memory are refused where they would not read back", "[api]") {
  // From a probe of the stream stages with tables edited in memory (parse_stream refuses
  // each of these in text): a NaN frame origin gave NaN camber points without an issue; a
  // partial row or a note "end" was written into a stream that did not read back; a NaN
  // verdict counted as a pass; null tables and streams crashed.
  const Mesh mesh = generate_mesh(turbine_blade(), 400, 20);
  Stream s = to_stream(slice(mesh, planes_at({0, 0, 1}, {10, 20, 30})), "slice");
  fit_spline_stream(s);
  camber_stream(s);
  Stream bad_origin = s;
  Table& frames_table = *bad_origin.find("frames");
  frames_table.values[frames_table.column("origin_x")] = not_a_number;
  CHECK(refuses([&] { frames(bad_origin); }, "origin that is not finite"));
  Stream partial = s;
  partial.find("params")->values.pop_back();
  CHECK(refuses([&] { format_stream(partial); }, "not whole rows"));
  CHECK(refuses([&] { format_csv(*partial.find("params")); }, "csv: refusing to write table 'params'"));
  Table gathered = *s.find("params");
  CHECK(refuses([&] { append_rows(gathered, *partial.find("params")); }, "not whole rows"));
  Stream noted = s;
  noted.notes.push_back("end");
  CHECK(refuses([&] { format_stream(noted); }, "would read as a '# end' line"));
  noted.notes.back() = "ending well";  // a note like any other
  CHECK(parse_stream(format_stream(noted), "noted").notes.back() == "ending well");
  Stream judged = s;
  Table verdicts;
  verdicts.name = "verdicts";
  verdicts.columns = {"section", "loop", "item", "zone", "verdict"};
  verdicts.values = {0, 0, 0, 0, not_a_number};
  judged.put(verdicts);
  CHECK(stream_verdict(judged) == 2);
  CHECK(refuses([&] { format_json(s, {nullptr}); }, "null pointer"));
  CHECK(refuses([] { check_blade_stream({nullptr}); }, "null pointer"));
  Stream inches = s;
  inches.units = "in";
  inches.find("points")->columns.clear();  // values without columns: a division by 0
  CHECK_NOTHROW(convert_to_mm(inches));
  Stream bad_id = s;  // a NaN section id was printed as section -2147483648
  Table& params_table = *bad_id.find("params");
  params_table.values[params_table.columns.size()] = not_a_number;
  CHECK(refuses([&] { format_params_text(bad_id); },
                "table 'params' data row 2: section nan is not a section id"));
  CHECK(
      refuses([&] { format_json(bad_id, {&params_table}); }, "data row 2: section nan is not a section id"));
  params_table.values[params_table.columns.size()] = 1.5;
  CHECK(refuses([&] { format_json(bad_id, {&params_table}); }, "section 1.5 is not a section id"));
}
