// SPDX-License-Identifier: GPL-3.0-or-later
#include "section/bspline.h"
#include "section/io/cad.h"
#include "section/error.h"
#include "section/io/file.h"
#include "section/io/json.h"
#include "thrown.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

using Eigen::Vector2d;
using Eigen::Vector3d;
using section::BSpline;

namespace {

const double pi = std::acos(-1.0);

// A closed curve of `n` random control points around an ellipse, random knot spacing, the
// first knot at `t0`.
BSpline random_closed(int degree, int n, double t0, std::mt19937& rng) {
  std::uniform_real_distribution<double> wiggle(-0.3, 0.3), step(0.2, 2.0);
  BSpline c;
  c.degree = degree;
  c.closed = true;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * pi * i / n;
    c.control.push_back({30 * std::cos(a) + wiggle(rng), 3 * std::sin(a) + wiggle(rng)});
  }
  c.knots.push_back(t0);
  for (int i = 0; i < n; ++i) c.knots.push_back(c.knots.back() + step(rng));
  return c;
}

// The blade-like closed curve of the CAD tests: an ellipse 60 x 6 fitted with 40 control points.
BSpline ellipse_curve() {
  std::vector<Vector2d> p;
  for (int i = 0; i < 400; ++i)
    p.push_back({30 * std::cos(2 * pi * i / 400), 3 * std::sin(2 * pi * i / 400)});
  section::CurveFitOptions o;
  o.control_points = 40;
  return section::fit_curve(p, o);
}

section::CadCurve tilted_curve(int section) {
  section::CadCurve c;
  c.section = section;
  c.frame = section::make_frame({1, 2, 10.0 * section}, {0.1, -0.2, 1});
  c.spline = ellipse_curve();
  return c;
}

// The group code / value pairs of a DXF text.
std::vector<std::pair<int, std::string>> dxf_pairs(const std::string& text) {
  std::vector<std::pair<int, std::string>> out;
  std::istringstream in(text);
  std::string code, value;
  while (std::getline(in, code) && std::getline(in, value)) out.push_back({std::stoi(code), value});
  return out;
}

double iges_real(std::string s) {
  for (char& c : s)
    if (c == 'D') c = 'E';
  return std::stod(s);
}

}  // namespace

TEST_CASE("clamped: a closed curve's clamped form is the same curve over one period", "[bspline][cad]") {
  std::mt19937 rng(7);
  for (int degree = 1; degree <= 5; ++degree) {
    for (double t0 : {0.0, -3.25, 17.5}) {
      const BSpline c = random_closed(degree, 12 + degree, t0, rng);
      const BSpline o = section::clamped(c);
      const int n = static_cast<int>(c.control.size());
      REQUIRE_FALSE(o.closed);
      REQUIRE(o.degree == degree);
      REQUIRE(static_cast<int>(o.control.size()) == n + degree);
      REQUIRE(static_cast<int>(o.knots.size()) == n + 2 * degree + 1);
      for (int i = 0; i <= degree; ++i) {
        REQUIRE(o.knots[i] == c.knots.front());
        REQUIRE(o.knots[o.knots.size() - 1 - i] == c.knots.back());
      }
      REQUIRE((o.control.front() - c.point(t0)).norm() < 1e-12);
      REQUIRE(o.control.front() == o.control.back());
      double worst = 0;
      for (int k = 0; k <= 2000; ++k) {
        const double t = c.t_min() + (c.t_max() - c.t_min()) * k / 2000.0;
        worst = std::max(worst, (o.point(t) - c.point(t)).norm());
      }
      INFO("degree " << degree << " t0 " << t0);
      REQUIRE(worst < 1e-11);  // 30 mm curve: rounding only
    }
  }
  const BSpline open = section::clamped(section::clamped(random_closed(3, 10, 0, rng)));
  REQUIRE(section::clamped(open).knots == open.knots);
  BSpline bad;
  bad.closed = true;
  REQUIRE(thrown([&] { section::clamped(bad); }).find("bspline:") == 0);
}

TEST_CASE("flatten: a polyline within its tolerance of a thin ellipse", "[bspline][cad]") {
  const BSpline c = ellipse_curve();
  std::size_t last = 0;
  for (double tol : {1e-2, 1e-3, 1e-4}) {
    const std::vector<double> ts = section::flatten(c, tol);
    REQUIRE(ts.front() == c.t_min());
    REQUIRE(ts.size() > last);
    last = ts.size();
    double worst = 0;
    for (std::size_t i = 0; i < ts.size(); ++i) {
      const double a = ts[i], b = i + 1 < ts.size() ? ts[i + 1] : c.t_max();
      REQUIRE(b > a);
      const Vector2d pa = c.point(a), pb = c.point(b), d = pb - pa;
      for (int k = 1; k < 16; ++k) {
        const Vector2d q = c.point(a + (b - a) * k / 16.0);
        const double s = std::clamp((q - pa).dot(d) / d.squaredNorm(), 0.0, 1.0);
        worst = std::max(worst, (q - (pa + s * d)).norm());
      }
    }
    INFO("tolerance " << tol << ", " << ts.size() << " points");
    REQUIRE(worst <= tol);
  }
  REQUIRE(thrown([&] { section::flatten(c, 0); }) ==
          "bspline: a polyline's tolerance must be above 0, got 0 mm");
  // A polyline that would outgrow its bound, or a tolerance finer than the coordinates
  // resolve (9e14 mm from the origin they step by 0.125 mm), is refused at once.
  REQUIRE(thrown([&] { section::flatten(c, 1e-4, 100); }) ==
          "bspline: a polyline within 0.0001 mm of the curve needs more than 100 points; a larger tolerance "
          "is needed");
  BSpline far = c;
  for (Vector2d& p : far.control) p.x() -= 9e14;
  REQUIRE(thrown([&] {
            section::flatten(far, 1e-3);
          }).find("is below the resolution of the curve's coordinates") != std::string::npos);
  REQUIRE(section::flatten(far, 100).size() > 4);
  REQUIRE(thrown([&] { section::flatten(c, 1e-300); }).find("a polyline's tolerance of 1e-300 mm is below") !=
          std::string::npos);  // it read "0 mm"
}

TEST_CASE("format_dxf: one SPLINE per curve through its control points in 3D", "[cad]") {
  const std::vector<section::CadCurve> curves = {tilted_curve(0), tilted_curve(3)};
  section::CadOptions o;
  o.polyline_tolerance = 0.001;
  const std::string text = section::format_dxf(curves, o);
  const auto pairs = dxf_pairs(text);
  REQUIRE(pairs.front() == std::make_pair(0, std::string("SECTION")));
  REQUIRE(pairs.back() == std::make_pair(0, std::string("EOF")));
  std::set<std::string> handles;
  unsigned long largest = 0, seed = 0;
  int splines = 0, polylines = 0;
  std::vector<Vector3d> control;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const auto& [code, value] = pairs[i];
    if ((code == 5 || code == 105) && pairs[i - 1].second != "$HANDSEED") {
      REQUIRE(handles.insert(value).second);  // each handle once
      largest = std::max(largest, std::stoul(value, nullptr, 16));
    }
    if (code == 9 && value == "$HANDSEED") seed = std::stoul(pairs[i + 1].second, nullptr, 16);
    if (code == 0 && value == "SPLINE") ++splines;
    if (code == 0 && value == "POLYLINE") ++polylines;
    if (code == 10 && splines == 1 && polylines == 0)
      control.push_back({std::stod(value), std::stod(pairs[i + 1].second), std::stod(pairs[i + 2].second)});
  }
  REQUIRE(splines == 2);
  REQUIRE(polylines == 2);
  REQUIRE(seed > largest);
  const BSpline open = section::clamped(curves[0].spline);
  REQUIRE(control.size() == open.control.size());
  for (std::size_t i = 0; i < control.size(); ++i)
    REQUIRE((control[i] - curves[0].frame.to_world(open.control[i])).norm() < 1e-12);
  REQUIRE(text.find("section_3\n") != std::string::npos);
  o.units = "furlong";
  REQUIRE(thrown([&] { section::format_dxf(curves, o); }) ==
          "cad: unknown length unit 'furlong' (known: mm, cm, m, in, um)");
}

TEST_CASE("format_dxf: a tolerance that is not a number, or polylines too long in all, are refused",
          "[cad]") {
  const std::vector<section::CadCurve> two = {tilted_curve(0), tilted_curve(3)};
  section::CadOptions o;
  for (double t : {std::nan(""), -0.001, HUGE_VAL}) {
    o.polyline_tolerance = t;
    CHECK(thrown([&] {
            section::format_dxf(two, o);
          }).find("polyline tolerance must be 0 (none) or a length") !=
          std::string::npos);  // a NaN wrote splines only, as if 0 were asked
  }
  // Each curve's polyline within its own limit, all of them beyond the file's.
  o.polyline_tolerance = 1e-6;
  const std::size_t each = section::flatten(two[0].spline, o.polyline_tolerance).size();
  o.max_polyline_vertices = 20 * each + each / 2;
  std::vector<section::CadCurve> many(21, tilted_curve(0));
  for (std::size_t k = 0; k < many.size(); ++k) many[k].section = static_cast<int>(k);
  const std::string message = thrown([&] { section::format_dxf(many, o); });
  CHECK(message.find("dxf: the polyline of section " + std::to_string(many.size() - 1)) != std::string::npos);
  CHECK(message.find("within 1e-06 mm of the curve needs more than " + std::to_string(each / 2)) !=
        std::string::npos);
  CHECK(message.find("may hold " + std::to_string(o.max_polyline_vertices) + " vertices in all") !=
        std::string::npos);
  CHECK(section::CadOptions{}.max_polyline_vertices == 2000000);
  many.pop_back();
  CHECK(section::format_dxf(many, o).find("SEQEND") != std::string::npos);  // within the limit
}

TEST_CASE("write_dxf: format_dxf's file, written a curve at a time; a curve refused leaves no file",
          "[cad]") {
  const std::string path = std::string(std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp") +
                           "/libsection_write_dxf_test_" + std::to_string(::getpid()) + ".dxf";
  std::vector<section::CadCurve> curves = {tilted_curve(0), tilted_curve(3), tilted_curve(5)};
  section::CadOptions o;
  o.polyline_tolerance = 0.001;
  section::write_dxf(path, curves, o);
  CHECK(section::read_file(path) == section::format_dxf(curves, o));  // $HANDSEED counted ahead
  o.polyline_tolerance = 0;
  section::write_dxf(path, curves, o);
  CHECK(section::read_file(path) == section::format_dxf(curves, o));
  std::remove(path.c_str());
  // The last curve's number that is not finite, or its polyline past the file's limit, is
  // refused before the first byte (the curves before it were written by then), named by
  // the input when given.
  o.source = "blade.csv";
  curves.back().spline.control[2].y() = std::nan("");
  CHECK(thrown([&] { section::write_dxf(path, curves, o); }) ==
        "blade.csv: bspline: control point 2 is not finite");
  CHECK_THROWS_AS(section::read_file(path), section::Error);
  curves.back() = tilted_curve(5);
  curves.back().frame.n.z() = std::nan("");  // written as the SPLINE's extrusion only
  CHECK(thrown([&] { section::write_dxf(path, curves, o); }) ==
        "blade.csv: cad: a curve has a number that is not finite (nan)");
  CHECK_THROWS_AS(section::read_file(path), section::Error);
  curves.back() = tilted_curve(5);
  o.polyline_tolerance = 1e-6;
  o.max_polyline_vertices = 2 * section::flatten(curves[0].spline, 1e-6).size() + 10;
  CHECK(thrown([&] {
          section::write_dxf(path, curves, o);
        }).find("blade.csv: dxf: the polyline of section 5") == 0);
  CHECK_THROWS_AS(section::read_file(path), section::Error);
}

TEST_CASE("format_iges: 80-column records whose entity 126 reads back as the curve", "[cad]") {
  const std::vector<section::CadCurve> curves = {tilted_curve(0), tilted_curve(1)};
  const std::string text = section::format_iges(curves, {});
  std::istringstream in(text);
  std::string line, params;
  std::map<char, int> count;
  std::vector<std::string> entries;
  while (std::getline(in, line)) {
    REQUIRE(line.size() == 80);
    const char letter = line[72];
    REQUIRE(std::stoi(line.substr(73)) == ++count[letter]);  // numbered 1, 2, ... in each section
    if (letter == 'D') entries.push_back(line);
    if (letter == 'P' && std::stoi(line.substr(64, 8)) == 1) params += line.substr(0, 64);
  }
  REQUIRE(count['S'] == 1);  // no source given: one start line
  REQUIRE(count['T'] == 1);
  REQUIRE(entries.size() == 4);
  REQUIRE(entries[0].substr(0, 8) == "     126");
  // The first curve's parameters: 126, K, M, 4 flags, knots, weights, control points, V0, V1, normal.
  std::vector<std::string> p;
  std::string token;
  for (char c : params) {
    if (c == ',' || c == ';') {
      p.push_back(token.substr(token.find_first_not_of(' ')));
      token.clear();
    } else {
      token += c;
    }
  }
  const BSpline open = section::clamped(curves[0].spline);
  const int k = std::stoi(p[1]), m = std::stoi(p[2]);
  REQUIRE(k + 1 == static_cast<int>(open.control.size()));
  REQUIRE(m == 3);
  REQUIRE(p[3] == "1");  // planar
  REQUIRE(p[4] == "1");  // closed
  const std::size_t knots = 7, weights = knots + k + m + 2, points = weights + k + 1;
  for (int i = 0; i < k + m + 2; ++i) REQUIRE(iges_real(p[knots + i]) == open.knots[i]);
  for (int i = 0; i <= k; ++i) {
    REQUIRE(iges_real(p[weights + i]) == 1.0);
    const Vector3d q(iges_real(p[points + 3 * i]), iges_real(p[points + 3 * i + 1]),
                     iges_real(p[points + 3 * i + 2]));
    REQUIRE(q == curves[0].frame.to_world(open.control[i]));
  }
  REQUIRE(p.size() == points + 3 * (k + 1) + 5);
}

TEST_CASE("format_json: tables by section, rows as objects or columns", "[cad][json]") {
  section::Stream s;
  s.history = {"camber --params p.csv"};
  s.issues.push_back({2, -1, "camber", "a \"quoted\"\tmessage"});
  section::Table params("params", {"section", "chord", "le_radius"});
  params.add_row({0, 41.25, std::nan("")});
  params.add_row({1, 40.5, 0.125});
  section::Table thickness("thickness", {"section", "index", "fraction", "thickness"});
  thickness.add_row({0, 0, 0.1, 1.5});
  thickness.add_row({0, 1, 0.2, 2.25});
  const std::string json = section::format_json(s, {&params, &thickness});
  REQUIRE(json.find("\"history\": [\"camber --params p.csv\"]") != std::string::npos);
  REQUIRE(json.find("\"message\": \"a \\\"quoted\\\"\\u0009message\"") != std::string::npos);
  // Bytes that are not UTF-8 (a stray 0xFF, a cut sequence) made the file unreadable as JSON:
  // each is U+FFFD; well-formed text (a degree sign) is kept.
  section::Stream odd = s;
  odd.issues = {{2, -1, "camber", "bad \xFF byte, cut \xE2\x82, 20\xC2\xB0"}};
  const std::string odd_json = section::format_json(odd, {&params});
  CHECK(odd_json.find("bad \xEF\xBF\xBD byte, cut \xEF\xBF\xBD\xEF\xBF\xBD, 20\xC2\xB0") !=
        std::string::npos);
  REQUIRE(
      json.find(
          "{\"section\": 0,\n     \"params\": {\"chord\": 41.25, \"le_radius\": null},\n"
          "     \"thickness\": {\"index\": [0, 1], \"fraction\": [0.1, 0.2], \"thickness\": [1.5, 2.25]}}") !=
      std::string::npos);
  REQUIRE(json.find("{\"section\": 1,\n     \"params\": {\"chord\": 40.5, \"le_radius\": 0.125}}") !=
          std::string::npos);
  params.add_row({1, 3, 4});
  REQUIRE(thrown([&] { section::format_json(s, {&params}); }) ==
          "json: table 'params' has 2 rows for section 1, one was expected");
  // Rows keyed by a zone or a compared item (compare's tables): an array of row objects.
  section::Table zones("zones", {"section", "zone", "max"});
  zones.add_row({3, 0, 0.5});
  zones.add_row({3, 1, 0.25});
  REQUIRE(section::format_json(s, {&zones})
              .find("\"zones\": [{\"zone\": 0, \"max\": 0.5}, {\"zone\": 1, \"max\": 0.25}]") !=
          std::string::npos);
}
