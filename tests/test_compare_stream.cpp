// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of compare on the stream: a blade mesh moved rigidly against its nominal (per
// section and whole-blade fits), nominals from a stream and from points, verdicts over a
// dent and a hole, sections that cannot be compared, and the tolerance file.
#include "compare_fixtures.h"
#include "compare_stream_fixtures.h"
#include "section/checks.h"
#include "section/error.h"
#include "section/extras/generate.h"
#include "section/extras/plot.h"
#include "section/extras/report.h"
#include "section/io/file.h"
#include "section/io/tolerances.h"
#include "section/pipe/camber_stream.h"
#include "section/pipe/compare_stream.h"
#include "section/pipe/fit_spline_stream.h"
#include "section/pipe/schema.h"
#include "section/pipe/slice_stream.h"
#include "section/slice.h"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <regex>
#include <string>
#include <vector>

using namespace compare_test;
namespace schema = section::schema;
using namespace compare_stream_test;

namespace {

// The measured stream of `mesh` at `zs`, compared with `nominal` (default options).
section::Stream compared_with(const section::Mesh& mesh, const section::Mesh& nominal,
                              const std::vector<double>& zs) {
  section::Stream s = measured_stream(mesh, zs);
  section::CompareStreamOptions o;
  section::NominalSource source;
  source.mesh = &nominal;
  section::compare_stream(s, section::nominal_stream(source, section::frames(s), o), o);
  return s;
}

// How many issues of stage compare hold `text`.
int compare_issues(const section::Stream& s, const std::string& text) {
  int count = 0;
  for (const auto& i : s.issues) count += i.stage == "compare" && i.message.find(text) != std::string::npos;
  return count;
}

// A column of a table by section (the first row of each).
std::map<int, double> column(const section::Stream& s, const char* table, const char* name) {
  const section::Table& t = s.get(table, "compare");
  std::map<int, double> out;
  for (std::size_t r = 0; r < t.rows(); ++r)
    out.emplace(static_cast<int>(t.at(r, 0)), t.at(r, t.column(name)));
  return out;
}

// The zones table's `name` for a section and zone.
double zone_value(const section::Stream& s, int section, int zone, const char* name) {
  const section::Table& t = schema::zones.get(s);
  for (std::size_t r = 0; r < t.rows(); ++r)
    if (t.at(r, 0) == section && t.at(r, t.column("zone")) == zone) return t.at(r, t.column(name));
  return std::nan("");
}

std::vector<section::Tolerance> tolerances(const std::string& text) {
  return section::parse_tolerances(text, "tol.csv", section::tolerance_items());
}

}  // namespace

TEST_CASE("compare stream: a blade mesh moved rigidly is fitted back, per section and whole", "[compare]") {
  const section::BladeDesign blade = section::turbine_blade();
  const section::Mesh nominal = section::generate_mesh(blade, 2000, 16);  // rings at z = 4 k
  const double angle = 0.05;
  const Eigen::Vector3d centre(3, 1, 0), shift(0.02, -0.01, 0);
  const Eigen::Matrix3d r0 = Eigen::AngleAxisd(angle * pi / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  section::Mesh moved_mesh = nominal;
  for (auto& v : moved_mesh.vertices) v = r0 * (v - centre) + centre + shift;
  const std::vector<double> zs{12, 20, 28};
  for (bool whole : {false, true}) {
    section::Stream s = measured_stream(moved_mesh, zs);
    section::CompareStreamOptions o;
    o.whole = whole;
    section::NominalSource source;
    source.mesh = &nominal;
    const section::Stream n = section::nominal_stream(source, section::frames(s), o);
    CHECK(compared_all(n));
    section::compare_stream(s, n, o);
    INFO("whole " << whole);
    CHECK(compared_all(s));
    const auto angles = column(s, "fits", "angle"), after = column(s, "fits", "max_after");
    const auto sx = column(s, "fits", "shift_x"), sy = column(s, "fits", "shift_y"),
               sz = column(s, "fits", "shift_z");
    REQUIRE(angles.size() == 3);
    for (const auto& [id, a] : angles) {
      CHECK(std::abs(a + angle) < 0.001);
      CHECK(after.at(id) < 0.002);  // both splines fitted to the mesh's polylines: ~1 um each
      // x -> R x + shift undoes the move.
      const Eigen::Matrix3d r = Eigen::AngleAxisd(a * pi / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      const Eigen::Vector3d x(10, -3, zs[id]);
      CHECK((r * (r0 * (x - centre) + centre + shift) + Eigen::Vector3d(sx.at(id), sy.at(id), sz.at(id)) - x)
                .norm() < 0.001);
    }
    // The params as measured deviate by the move (stagger) or not at all (chord).
    for (const auto& [id, row] : compared(s, "chord")) CHECK(std::abs(row[1]) < 0.001);
    for (const auto& [id, row] : compared(s, "stagger")) CHECK(row[1] == Approx(angle).margin(0.002));
    CHECK(section::stream_verdict(s) == 0);
  }
}

TEST_CASE("compare stream: a fit that does not settle gives no verdict", "[compare]") {
  // A section 100 mm off its nominal ran out of iterations with 76 mm rms and was reported as
  // any other fit. Here the iterations run out at once.
  const section::BladeDesign blade = section::turbine_blade();
  const section::Mesh mesh = section::generate_mesh(blade, 2000, 16);
  section::Mesh moved = mesh;
  for (auto& v : moved.vertices) v += Eigen::Vector3d(0.3, -0.2, 0);
  section::Stream s = measured_stream(moved, {12, 20});
  section::CompareStreamOptions o;
  o.compare.fit.max_iterations = 1;
  section::NominalSource source;
  source.mesh = &mesh;
  section::compare_stream(s, section::nominal_stream(source, section::frames(s), o), o);
  int refused = 0;
  for (const auto& i : s.issues)
    if (i.stage == "compare" && i.message.find("the fit did not settle in 1 iterations") != std::string::npos)
      ++refused;
  CHECK(refused == 2);
  CHECK(column(s, "fits", "angle").empty());
  o.compare.fit.max_iterations = 200;  // the default settles
  section::Stream again = measured_stream(moved, {12, 20});
  section::compare_stream(again, section::nominal_stream(source, section::frames(again), o), o);
  CHECK(column(again, "fits", "angle").size() == 2);
}

TEST_CASE("compare stream: a nominal in another unit is refused per section, not fitted", "[compare]") {
  // The nominal mesh in inches read as millimetres (25.4 times larger), and in micrometres
  // read as millimetres the other way round: the fit hunted feet for a minute and reported
  // millimetres of deviation.
  const section::BladeDesign blade = section::turbine_blade();
  const section::Mesh mesh = section::generate_mesh(blade, 2000, 16);
  const std::vector<double> zs{12, 20, 28};
  for (double scale : {25.4, 1 / 2.0}) {
    INFO("scale " << scale);
    section::Mesh scaled = mesh;
    for (auto& v : scaled.vertices) v = Eigen::Vector3d(v.x() * scale, v.y() * scale, v.z());
    const section::Stream s = compared_with(mesh, scaled, zs);
    CHECK(compare_issues(s, scale > 1 ? "25.4 times larger" : "2 times smaller") == 3);
    CHECK(column(s, "fits", "angle").empty());
  }
  // The same size within the room given: compared.
  section::Mesh larger = mesh;
  for (auto& v : larger.vertices) v = Eigen::Vector3d(v.x() * 1.3, v.y() * 1.3, v.z());
  CHECK(column(compared_with(mesh, larger, zs), "fits", "angle").size() == 3);
}

TEST_CASE("compare stream: a nominal far beyond its size from the section is refused, not fitted",
          "[compare]") {
  // The nominal moved 1e14 mm (a frame's origin edited): the fit's nearest-point searches had
  // nothing to prune, and it took 47 s to say it did not settle. 600 mm (13 sizes) is as far
  // beyond any fit; 30 mm is within reach and fitted.
  const section::BladeDesign blade = section::turbine_blade();
  const section::Mesh mesh = section::generate_mesh(blade, 2000, 16);
  const std::vector<double> zs{12, 20};
  for (double shift : {1e14, 600.0, 3.0}) {
    INFO("shift " << shift);
    section::Mesh moved = mesh;
    for (auto& v : moved.vertices) v += Eigen::Vector3d(shift, 0, 0);
    const section::Stream s = compared_with(mesh, moved, zs);
    CHECK(compare_issues(s, "times its size") == (shift > 100 ? 2 : 0));
    CHECK(column(s, "fits", "angle").size() == (shift > 100 ? 0u : 2u));
  }
}

TEST_CASE("compare stream: nominals from a stream in other frames and from x, y, z points agree",
          "[compare]") {
  const section::Mesh mesh = section::generate_mesh(section::compressor_blade(), 2000, 16);
  section::Stream s = measured_stream(mesh, {16, 32});
  const auto frames = section::frames(s);
  section::CompareStreamOptions o;
  // The nominal stream: the mesh's sections in frames turned 30 degrees and moved in-plane.
  section::NominalSource from_mesh;
  from_mesh.mesh = &mesh;
  section::Stream other = section::nominal_stream(from_mesh, frames, o);
  std::map<int, section::Frame> turned;
  for (const auto& [id, f] : frames) {
    section::Frame g = f;
    const Eigen::AngleAxisd turn(30 * pi / 180, f.n);
    g.u = turn * f.u;
    g.v = turn * f.v;
    g.origin = f.origin + 2 * f.u - 1 * f.v;
    turned[id + 10] = g;
  }
  section::Table ctrl = *other.find("spline_ctrl");
  for (std::size_t r = 0; r < ctrl.rows(); ++r) {
    const int id = static_cast<int>(ctrl.at(r, 0));
    const Eigen::Vector2d p =
        turned.at(id + 10).to_plane(frames.at(id).to_world({ctrl.at(r, 3), ctrl.at(r, 4)}));
    ctrl.values[r * ctrl.columns.size()] = id + 10;
    ctrl.values[r * ctrl.columns.size() + 3] = p.x();
    ctrl.values[r * ctrl.columns.size() + 4] = p.y();
  }
  for (const char* name : {"splines", "spline_knots"}) {
    section::Table t = *other.find(name);
    for (std::size_t r = 0; r < t.rows(); ++r) t.values[r * t.columns.size()] += 10;
    other.put(t);
  }
  other.put(ctrl);
  section::put_frames(other, turned);
  section::NominalSource from_stream;
  from_stream.stream = &other;
  // The nominal points in 3D: the mesh's section vertices.
  const section::Stream sliced =
      section::to_stream(section::slice(mesh, section::planes_at({0, 0, 1}, {16, 32})), "slice");
  section::Table xyz("nominal", {"x", "y", "z"});
  const section::Table& pts = schema::points.get(sliced);
  for (std::size_t r = 0; r < pts.rows(); ++r) {
    if (pts.at(r, 1) != 0) continue;
    const Eigen::Vector3d w =
        frames.at(static_cast<int>(pts.at(r, 0))).to_world({pts.at(r, 3), pts.at(r, 4)});
    xyz.add_row({w.x(), w.y(), w.z()});
  }
  section::NominalSource from_points;
  from_points.points = &xyz;
  for (const auto* source : {&from_stream, &from_points}) {
    section::Stream m = s;
    const section::Stream n = section::nominal_stream(*source, frames, o);
    CHECK(compared_all(n));
    section::compare_stream(m, n, o);
    CHECK(compared_all(m));
    for (const auto& [id, v] : column(m, "fits", "max_before")) CHECK(v < 0.002);
    for (const auto& [id, row] : compared(m, "le_radius")) CHECK(std::abs(row[1]) < 0.002);
  }
}

TEST_CASE("compare stream: verdicts over a dent and a hole, and sections that cannot be compared",
          "[compare]") {
  const Case c = make_case(section::design_family()[0]);
  std::vector<Vector2d> normals;
  const std::vector<Vector2d> all = profile_points(c.truth, 0.05, 0, 1, &normals);
  // Measured: section 0 with a 0.04 dent mid-chord on the suction side and a hole over
  // the LE; section 1 the truth; section 2 no nominal.
  section::Stream s;
  section::Table pts = schema::points.table();
  section::Table nominal("nominal", {"section", "u", "v"});
  for (int id = 0; id < 3; ++id) {
    std::size_t k = 0;
    for (std::size_t i = 0; i < all.size(); ++i) {
      Vector2d p = all[i];
      if (id == 0) {
        if ((p - c.truth.le_point).norm() < 1) continue;
        const double x = (chord_fraction(c.truth, p) - 0.5) * c.truth.chord;
        if (!on_pressure_side(c, p, normals[i], 0, 1) && std::abs(x) < 1)
          p -= 0.02 * (1 + std::cos(pi * x)) * normals[i];
      }
      schema::points.add(pts, {id, 0, k++, p, normals[i], 0.0});
    }
  }
  for (int id : {0, 1})
    for (std::size_t i = 0; i < c.truth.profile.size(); i += 5)
      nominal.add_row({double(id), c.truth.profile[i].x(), c.truth.profile[i].y()});
  s.put(pts);
  section::fit_spline_stream(s);
  section::camber_stream(s);
  section::NominalSource source;
  source.points = &nominal;
  section::CompareStreamOptions o;
  o.compare.fit.freedom = section::FitFreedom::none;
  o.tolerances = tolerances(
      "item,section,low,high\nprofile_suction,,-0.03,0.03\nprofile_pressure,*,-0.03,0.03\nprofile_le,all,-0."
      "03,0.03\n"
      "chord,,-0.05,0.05\nte_radius,,-0.01,0.01\n");
  const std::map<int, section::Frame> frames{{0, {}}, {1, {}}, {2, {}}};
  const section::Stream n = section::nominal_stream(source, frames, o);
  section::compare_stream(s, n, o);
  const auto verdicts = column(s, "verdicts", "verdict");
  CHECK(verdicts.at(0) == 1);  // the dent fails
  CHECK(verdicts.at(1) == 0);
  CHECK(verdicts.at(2) == 2);  // no nominal: not measured
  CHECK(zone_value(s, 0, 4, "verdict") == 1);
  CHECK(zone_value(s, 0, 4, "min") == Approx(-0.04).margin(0.001));
  CHECK(zone_value(s, 0, 3, "verdict") == 0);
  CHECK(zone_value(s, 0, 1, "verdict") == 2);  // the hole over the LE
  CHECK(zone_value(s, 0, 1, "measured") == 0);
  CHECK(compared(s, "chord").at(0)[2] == 2);  // the chord needs the LE
  CHECK(compared(s, "te_radius").at(0)[2] == 0);
  CHECK(compared(s, "chord").at(1)[2] == 0);
  CHECK(compared(s, "chord").at(2)[0] == 0);
  CHECK(section::stream_verdict(s) == 1);
  bool issue = false;
  // The reason is the nominal's, not fitspline's "no points in the stream for this section"
  // (fitspline's restage dropped it).
  for (const auto& i : s.issues)
    issue =
        issue || (i.section == 2 && i.stage == "compare" &&
                  i.message.find("the nominal points have no section on this plane") != std::string::npos);
  CHECK(issue);
  const std::string report = section::compare_report(s);
  CHECK(report.rfind("blade: FAIL", 0) == 0);
  CHECK(report.find("profile_suction") != std::string::npos);
  // The drawings: whiskers and bands on the failed section, the verdicts; the page opens
  // with the blade's.
  const std::string svg = section::plot_svg(s, 0);
  CHECK(svg.find("class=\"whiskers\"") != std::string::npos);
  CHECK(svg.find("class=\"tolerance-band\"") != std::string::npos);
  CHECK(svg.find("FAIL (") != std::string::npos);
  CHECK(svg.find("failed: profile suction side") != std::string::npos);
  CHECK(svg.find("#d62728") != std::string::npos);  // a whisker beyond its tolerance
  const std::string html = section::plot_html(s);
  CHECK(html.find("Blade: FAIL") < html.find("<table class=\"summary\""));
  CHECK(html.find("failing sections: 0") != std::string::npos);
}

namespace {

// Two measured sections of one design (points every 0.03 mm, 5 um of noise, two seeds) through
// fitspline and camber, the exact profile's points as their nominal, compared without a fit.
struct NoisyCase {
  section::Stream measured, nominal;
  section::CompareStreamOptions options;
};

NoisyCase noisy_case() {
  const Case c = make_case(section::design_family()[1]);
  NoisyCase out;
  section::Table pts = schema::points.table();
  section::Table nominal("nominal", {"section", "u", "v"});
  for (int id = 0; id < 2; ++id) {
    std::vector<Vector2d> normals;
    const std::vector<Vector2d> p = profile_points(c.truth, 0.03, 0.005, 11 + id, &normals);
    for (std::size_t i = 0; i < p.size(); ++i) schema::points.add(pts, {id, 0, i, p[i], normals[i], 0.0});
    for (std::size_t i = 0; i < c.truth.profile.size(); i += 5)
      nominal.add_row({double(id), c.truth.profile[i].x(), c.truth.profile[i].y()});
  }
  out.measured.put(pts);
  section::fit_spline_stream(out.measured);
  section::camber_stream(out.measured);
  section::NominalSource source;
  source.points = &nominal;
  out.options.compare.fit.freedom = section::FitFreedom::none;
  out.nominal = section::nominal_stream(source, {{0, {}}, {1, {}}}, out.options);
  return out;
}

// The value of an item's `column` in the compared table of a section.
double compared_column(const section::Stream& s, int section, const std::string& item, const char* name) {
  const auto& items = section::compared_items();
  const double code = static_cast<double>(std::find(items.begin(), items.end(), item) - items.begin());
  const section::Table& t = schema::compared.get(s);
  for (std::size_t r = 0; r < t.rows(); ++r)
    if (t.at(r, 0) == section && t.at(r, t.column("item")) == code) return t.at(r, t.column(name));
  return std::nan("");
}

}  // namespace

TEST_CASE("compare stream: a radius within its uncertainty of a limit is uncertain (guarded rule)",
          "[compare]") {
  const NoisyCase nc = noisy_case();
  const auto sigma = column(nc.measured, "params", "le_radius_sigma");
  const auto nominal_sigma = column(nc.nominal, "params", "le_radius_sigma");
  REQUIRE(column(nc.measured, "params", "flags").at(0) == 0);
  // 5 um of noise on ~60 points of the LE arc: a standard error of a micrometre or two.
  CHECK(sigma.at(0) > 2e-4);
  CHECK(sigma.at(0) < 5e-3);
  CHECK(nominal_sigma.at(0) < 0.1 * sigma.at(0));
  using Rule = section::DecisionRule;
  // compare with le_radius's upper limit `high` on section 0 (the rule, coverage as given).
  const auto run = [&](double high, Rule rule, double coverage = 2) {
    section::Stream s = nc.measured;
    section::CompareStreamOptions o = nc.options;
    o.decision = rule;
    o.coverage = coverage;
    o.tolerances = {{"le_radius", 0, -1, high}, {"chord", -1, -0.05, 0.05}};
    section::compare_stream(s, nc.nominal, o);
    return s;
  };
  const section::Stream loose = run(1, Rule::guarded);
  const double deviation = compared(loose, "le_radius").at(0)[1];
  const double u = compared_column(loose, 0, "le_radius", "uncertainty");
  CHECK(u == Approx(2 * std::hypot(sigma.at(0), nominal_sigma.at(0))).epsilon(1e-12));
  CHECK(compared(loose, "le_radius").at(0)[2] == 0);
  // The chord's standard error camber gives (its end directions' and edge points' noise).
  const double chord_sigma = column(nc.measured, "params", "chord_sigma").at(0),
               chord_nominal = column(nc.nominal, "params", "chord_sigma").at(0);
  CHECK(chord_sigma > 0);
  CHECK(compared_column(loose, 0, "chord", "uncertainty") ==
        Approx(2 * std::hypot(chord_sigma, chord_nominal)).epsilon(1e-12));
  // The limit moved about the deviation: guarded decides only beyond U, simple at the limit.
  const struct {
    double high;
    Rule rule;
    int verdict;
  } cases[] = {
      {deviation + 2 * u, Rule::guarded, 0},   {deviation + 0.5 * u, Rule::guarded, 3},
      {deviation - 0.5 * u, Rule::guarded, 3}, {deviation - 2 * u, Rule::guarded, 1},
      {deviation + 0.5 * u, Rule::simple, 0},  {deviation - 0.5 * u, Rule::simple, 1},
  };
  for (const auto& k : cases) {
    INFO("high = deviation + " << (k.high - deviation) / u << " U, rule " << static_cast<int>(k.rule));
    const section::Stream s = run(k.high, k.rule);
    CHECK(compared(s, "le_radius").at(0)[2] == k.verdict);
    CHECK(column(s, "verdicts", "verdict").at(0) == k.verdict);
    CHECK(column(s, "verdicts", "verdict").at(1) == 0);
    CHECK(section::stream_verdict(s) == k.verdict);
  }
  // A larger coverage factor widens the guard: 1.5 U inside passes at k = 2, not at k = 6.
  CHECK(compared(run(deviation + 1.5 * u, Rule::guarded), "le_radius").at(0)[2] == 0);
  CHECK(compared(run(deviation + 1.5 * u, Rule::guarded, 6), "le_radius").at(0)[2] == 3);
}

TEST_CASE("compare stream: a value camber flagged is uncertain however loose its limits", "[compare]") {
  const NoisyCase nc = noisy_case();
  // Section 1 as if camber had doubted its LE circle and found a hole at its thickest circle:
  // its LE radius and thickness are then uncertain under either rule; its chord (not
  // flagged) still passes.
  section::Stream layered = nc.measured;
  section::Table& params = *layered.find("params");
  const std::size_t cs = params.column("section"), cf = params.column("flags");
  for (std::size_t r = 0; r < params.rows(); ++r)
    if (params.at(r, cs) == 1)
      params.values[r * params.columns.size() + cf] =
          double(section::bit(section::Check::le_radius) | section::bit(section::Check::thickness_measured));
  for (const auto rule : {section::DecisionRule::guarded, section::DecisionRule::simple}) {
    section::Stream s = layered;
    section::CompareStreamOptions o = nc.options;
    o.decision = rule;
    o.tolerances = {{"le_radius", -1, -1, 1}, {"max_thickness", -1, -1, 1}, {"chord", -1, -0.05, 0.05}};
    section::compare_stream(s, nc.nominal, o);
    CHECK(compared(s, "le_radius").at(1)[2] == 3);
    CHECK(compared(s, "max_thickness").at(1)[2] == 3);
    CHECK(compared_column(s, 1, "le_radius", "flags") == section::bit(section::Check::le_radius));
    CHECK(compared(s, "chord").at(1)[2] == 0);
    CHECK(compared(s, "le_radius").at(0)[2] == 0);
    const auto verdicts = column(s, "verdicts", "verdict");
    CHECK(verdicts.at(0) == 0);
    CHECK(verdicts.at(1) == 3);
    CHECK(column(s, "verdicts", "uncertain").at(1) == 2);
    CHECK(section::stream_verdict(s) == 3);
    const std::string report = section::compare_report(s);
    CHECK(report.rfind("blade: UNCERTAIN", 0) == 0);
    CHECK(report.find("section 1: uncertain (1 passed, 0 failed, 0 not measured, 2 uncertain)") !=
          std::string::npos);
    CHECK(report.find("uncertain (flagged: le_radius)") != std::string::npos);
    CHECK(section::plot_svg(s, 1).find("UNCERTAIN (") != std::string::npos);
  }
  // A failure outweighs an uncertain value in the section's verdict.
  section::Stream s = layered;
  section::CompareStreamOptions o = nc.options;
  o.tolerances = {{"le_radius", -1, -1, 1}, {"chord", 1, 0.1, 0.2}};
  section::compare_stream(s, nc.nominal, o);
  CHECK(column(s, "verdicts", "verdict").at(1) == 1);
  CHECK(section::stream_verdict(s) == 1);
  // Bounds far past any blade (the API takes what the tolerance reader refuses) are written
  // out in full: the report once showed the formatter's uninitialised buffer beyond 1e59.
  section::Stream wide = layered;
  o.tolerances = {{"chord", 1, -1e300, 1e300}};
  section::compare_stream(wide, nc.nominal, o);
  const std::string report = section::compare_report(wide);
  // 1e300 has 301 digits before the point.
  CHECK(std::regex_search(report, std::regex(R"(\[-1[0-9]{300}\.0000, 1[0-9]{300}\.0000\])")));
  CHECK(
      std::all_of(report.begin(), report.end(), [](char c) { return c == '\n' || (c >= ' ' && c <= '~'); }));
}

TEST_CASE("pipe: a stage run again replaces its issues and drops what the later stages wrote",
          "[compare][pipe]") {
  const NoisyCase nc = noisy_case();
  const auto stage_issues = [](const section::Stream& s, const std::string& stage) {
    return std::count_if(s.issues.begin(), s.issues.end(), [&](const auto& i) { return i.stage == stage; });
  };
  // A camber warning on section 0 (as a flagged value gets), compared and stacked after.
  section::Stream later = nc.measured;
  later.issues.push_back({0, 0, "camber", "a warning"});
  section::CompareStreamOptions o = nc.options;
  o.tolerances = {{"chord", -1, -0.05, 0.05}};
  section::compare_stream(later, nc.nominal, o);
  REQUIRE(later.find("verdicts"));
  // camber again: its own issues replaced (not added to), compare's tables gone.
  section::Stream again = later;
  section::camber_stream(again);
  CHECK(stage_issues(again, "camber") == stage_issues(nc.measured, "camber"));
  CHECK(!again.find("verdicts"));
  CHECK(!again.find("compared"));
  CHECK(again.find("params"));
  // fitspline again: every section refitted (a camber warning does not hold one back as
  // failed), camber's and compare's tables and issues gone; camber after it measures the same.
  section::Stream refit = later;
  section::fit_spline_stream(refit);
  CHECK(schema::splines.get(refit).rows() == 2);
  CHECK(stage_issues(refit, "camber") == 0);
  for (const char* table : {"params", "camber", "thickness", "sides", "zones", "verdicts"})
    CHECK(!refit.find(table));
  section::camber_stream(refit);
  CHECK(section::format_stream(refit) == section::format_stream(nc.measured));
}

TEST_CASE("compare stream: the tolerance file is read, and refused naming the line", "[compare]") {
  const auto t = tolerances(
      "# "
      "tolerances\nitem,section,low,high,on\nchord,*,-0.1,0.1\nle_radius,3,0.9,1.1,value\nform_le,,,0.02\n");
  REQUIRE(t.size() == 3);
  CHECK(t[0].section == -1);
  CHECK(t[1].section == 3);
  CHECK(t[1].on_value);
  CHECK(!t[2].on_value);
  CHECK(std::isinf(t[2].low));
  CHECK(t[2].high == 0.02);
  CHECK(t[2].where == "tol.csv:5");
  const auto refused = [](const std::string& text, const std::string& what) {
    try {
      tolerances(text);
    } catch (const section::Error& e) {
      INFO(e.what());
      CHECK(std::string(e.what()).find(what) != std::string::npos);
      return;
    }
    FAIL("accepted: " << text);
  };
  refused("item,low,high\nchrod,-1,1\n", "tol.csv:2: unknown item 'chrod'");
  refused("item,low,high\nchord,-1,x\n", "tol.csv:2: high: expected a number");
  refused("item,low,high\nchord,1,-1\n", "tol.csv:2: low is above high");
  refused("item,low,high\nchord,-1e20,1\n", "tol.csv:2: low: -1e20 is beyond +-1e9");  // a typo, not a limit
  refused("item,low,high\nchord,,\n", "tol.csv:2: neither low nor high");
  refused("item,low,high\nchord,-1,1\n\nchord,-2,2\n",
          "tol.csv:4: a second row for 'chord' (the first: tol.csv:2)");
  refused("item,lo,high\n", "tol.csv:1: unknown column 'lo'");
  refused("item,section,low\nchord,-3,1\n", "tol.csv:2: section: expected a section id");
  refused("item,low,high,on\nchord,-1,1,both\n", "on: expected 'deviation' or 'value'");
  refused("# nothing\n", "tol.csv: no header line");
}

TEST_CASE("compare stream: docs/FORMAT.md lists the compared values by their codes", "[compare]") {
  const std::string text = section::read_file(std::string(SECTION_SOURCE_DIR) + "/docs/FORMAT.md");
  std::string line = "Compared values (item): ";
  const auto& items = section::compared_items();
  for (std::size_t k = 0; k < items.size(); ++k) line += (k ? ", " : "") + std::to_string(k) + " " + items[k];
  CHECK(text.find(line + ".\n") != std::string::npos);
}

TEST_CASE("compare_stream: a nominal given as section points is the same curve whichever point starts it",
          "[compare]") {
  // A compressor section's nominal points 0.3 mm apart (its 0.29 mm edges hold a few each),
  // written from the LE, from a third of the way round, and the other way round: fitted from
  // their canonical start, the nominal's params are the same to the bit.
  const section::SectionTruth truth = section::section_truth(section::compressor_blade().at(30), 20000);
  const std::vector<Vector2d> points = section::noisy_profile(truth, 0.3, 0, 1);
  const std::map<int, section::Frame> frames{{0, {}}};
  std::vector<double> first;
  for (const bool reversed : {false, true})
    for (const std::size_t k : {std::size_t(0), points.size() / 3}) {
      std::vector<Vector2d> loop = points;
      if (reversed) std::reverse(loop.begin(), loop.end());
      std::rotate(loop.begin(), loop.begin() + std::ptrdiff_t(k), loop.end());
      section::Table nominal{"points", {"section", "u", "v"}, {}};
      for (const Vector2d& p : loop) nominal.add_row({0, p.x(), p.y()});
      section::NominalSource source;
      source.points = &nominal;
      const section::Stream n = section::nominal_stream(source, frames, {});
      const section::Table& params = n.get("params", "test");
      REQUIRE(params.rows() == 1);
      INFO("start " << k << (reversed ? ", reversed" : ""));
      CHECK(std::abs(params.at(0, params.column("max_thickness")) - truth.max_thickness) < 0.005);
      if (first.empty()) first = params.values;
      CHECK(params.values == first);
    }
}
