// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the plot module: the SVG is well formed, holds every element of what the stream
// carries, and draws it to scale with v up (the drawn curve lies on the true profile).
#include "section/camber.h"
#include "section/error.h"
#include "section/fit_spline.h"
#include "section/extras/generate.h"
#include "section/io/stream.h"
#include "section/pipe/schema.h"
#include "section/pipe/camber_stream.h"
#include "section/extras/plot.h"

#include "plot_fixtures.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <random>
#include <string>
#include <vector>

using Eigen::Vector2d;

namespace {

using namespace plot_test;

// Every element of a full stream is there, with its id or class.
void check_full_elements(const std::string& svg, const std::vector<Element>& es) {
  for (const std::string id : {"s0", "s0-main", "s0-le", "s0-te", "s0-params", "s0-main-scale", "s0-le-clip"})
    CHECK(svg.find("id=\"" + id + "\"") != std::string::npos);
  for (const std::string c : {"points", "curve", "camber", "station", "chord", "le-circle", "te-circle",
                              "le-point", "te-point", "scale-bar", "param-table", "inset-frame"})
    CHECK(!with_class(es, c).empty());
}

// Equal axes, v up: the chord line's px vector is scale * (du, -dv), its length the true
// chord (camber stage accuracy, here ~1 um, plus 0.01 px rounding).
void check_chord(const std::vector<Element>& main_es, const Mapping& m, const section::SectionTruth& truth) {
  const auto chord = with_class(main_es, "chord");
  REQUIRE(chord.size() == 1);
  const Vector2d a(chord[0]->num("x1"), chord[0]->num("y1")), b(chord[0]->num("x2"), chord[0]->num("y2"));
  const Vector2d le = m.world(a), te = m.world(b);
  CHECK((le - truth.le_point).norm() < 0.01);
  CHECK((te - truth.te_point).norm() < 0.01);
  CHECK(std::abs((b - a).norm() / m.s - truth.chord) < 0.005);
  CHECK((b - a).y() * (truth.te_point - truth.le_point).y() <= 0);  // v up = px y down
}

// The LE circle drawn at the true centre and radius, in the main view and in its inset,
// and there wholly inside the inset's frame.
void check_le_circle(const std::string& svg, const std::vector<Element>& main_es, const Mapping& m,
                     const section::SectionTruth& truth) {
  const auto le_circle = with_class(main_es, "le-circle");
  REQUIRE(le_circle.size() == 1);
  const Vector2d c = m.world({le_circle[0]->num("cx"), le_circle[0]->num("cy")});
  CHECK((c - truth.le_center).norm() < 0.01);
  CHECK(std::abs(le_circle[0]->num("r") / m.s - truth.le_radius) < 0.01);
  bool inset_ok = false;
  const auto inset_es = parse(subtree(svg, "s0-le"), &inset_ok);
  REQUIRE(inset_ok);
  const Mapping mi = mapping(by_id(inset_es, "s0-le"));
  CHECK(mi.s > 1.3 * m.s);  // magnified
  const auto inset_circle = with_class(inset_es, "le-circle");
  REQUIRE(inset_circle.size() == 1);
  CHECK(std::abs(inset_circle[0]->num("r") / mi.s - truth.le_radius) < 0.01);
  const auto frames = with_class(inset_es, "view-frame");
  REQUIRE(frames.size() == 1);
  const double fx = frames[0]->num("x"), fy = frames[0]->num("y"), fw = frames[0]->num("width");
  const double cx = inset_circle[0]->num("cx"), cy = inset_circle[0]->num("cy"),
               r = inset_circle[0]->num("r");
  CHECK(cx - r >= fx);
  CHECK(cx + r <= fx + fw);
  CHECK(cy - r >= fy);
  CHECK(cy + r <= fy + fw);
}

// The drawn curve lies on the true profile (fit ~ 1 um, px rounding 0.005 px), and the
// true profile on the drawn curve: thinned to the screen, it departs from it by at most
// 0.2 px between its vertices.
void check_curve(const std::vector<Element>& main_es, const Mapping& m, const section::SectionTruth& truth) {
  const auto curves = with_class(main_es, "curve");
  REQUIRE(curves.size() == 1);
  const auto px = vertices(curves[0]->attr.at("d"));
  REQUIRE(px.size() >= 50);
  double worst = 0;
  for (const auto& p : px) worst = std::max(worst, section::locate(truth, m.world(p)).distance);
  CHECK(worst < 0.005 + 0.01 / m.s);
  double away = 0;  // px, from a true point to the drawn polyline
  for (std::size_t i = 0; i < truth.profile.size(); i += 7) {
    const Vector2d q = m.pixel(truth.profile[i]);
    double nearest = 1e300;
    for (std::size_t k = 0; k < px.size(); ++k) {
      const Vector2d a = px[k], ab = px[(k + 1) % px.size()] - a;
      const double t = ab.squaredNorm() > 0 ? std::clamp((q - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
      nearest = std::min(nearest, (a + t * ab - q).norm());
    }
    away = std::max(away, nearest);
  }
  CHECK(away < 0.2 + 0.01 + 0.005 * m.s);
}

// The scale bar is as long as it says: data-length (1, 2 or 5 times a power of ten) * scale.
void check_scale_bar(const std::string& svg, const Mapping& m) {
  bool bar_ok = false;
  const auto bar = parse(subtree(svg, "s0-main-scale"), &bar_ok);
  const double length = bar.front().num("data-length");
  const double mantissa = length / std::pow(10.0, std::floor(std::log10(length) + 1e-9));
  CHECK((std::abs(mantissa - 1) < 1e-9 || std::abs(mantissa - 2) < 1e-9 || std::abs(mantissa - 5) < 1e-9));
  const auto line = with_class(bar, "scale-bar-line");
  REQUIRE(line.size() == 1);
  CHECK(std::abs(line[0]->num("x2") - line[0]->num("x1") - length * m.s) < 0.02);
}

// Every measured point lies within `reach` px of a drawn dot, no two dots share a cell
// outside the edges, and fewer dots than points are drawn only where they crowd.
void check_dots_cover(const std::vector<Element>& main_es, const Mapping& m, const section::Stream& stream,
                      double reach) {
  const auto drawn = dots(main_es);
  const section::Table& t = *stream.find("points");
  const long cu = t.find_column("u"), cv = t.find_column("v");
  REQUIRE(!drawn.empty());
  double worst = 0;
  for (std::size_t r = 0; r < t.rows(); ++r) {
    const Vector2d p = m.pixel({t.at(r, cu), t.at(r, cv)});
    double nearest = 1e300;
    for (const auto& q : drawn) nearest = std::min(nearest, (q - p).norm());
    worst = std::max(worst, nearest);
  }
  CHECK(worst <= reach);
  CHECK(drawn.size() <= t.rows());
}

}  // namespace

TEST_CASE("plot: a full section is drawn to scale with v up and the curve on the true profile", "[plot]") {
  for (const auto& design : {section::turbine_blade().at(0), section::compressor_blade().at(60)}) {
    const section::SectionTruth truth = section::section_truth(design, 8000);
    const section::Stream stream = full_stream(truth, 800, 300);
    const std::string svg = section::plot_svg(stream, 0);
    bool balanced = false;
    const auto es = parse(svg, &balanced);
    REQUIRE(balanced);
    REQUIRE(svg.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\"", 0) == 0);
    CHECK(all_numbers_finite(svg));
    check_full_elements(svg, es);

    const Mapping m = mapping(by_id(es, "s0-main"));
    bool inner = false;
    const auto main_es = parse(subtree(svg, "s0-main"), &inner);
    REQUIRE(inner);
    // The main view shows every thickness station, and every measured point within a dot's
    // width of a drawn dot (thinned to the screen), the edges' points all drawn.
    CHECK(with_class(main_es, "station").size() == stream.find("thickness")->rows());
    check_dots_cover(main_es, m, stream, 2 * 1.6 * std::sqrt(0.5) + 0.01);

    check_chord(main_es, m, truth);
    check_le_circle(svg, main_es, m, truth);
    check_curve(main_es, m, truth);
    check_scale_bar(svg, m);
    CHECK(svg.find(">chord<") != std::string::npos);  // the parameter table prints the chord
  }
}

TEST_CASE("plot: a value a check flags is drawn red with the checks it failed, never bare", "[plot]") {
  const section::SectionTruth truth = section::section_truth(section::turbine_blade().at(0), 8000);
  section::Stream stream = full_stream(truth, 800, 300);
  const auto count = [](const std::string& svg, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = svg.find(what); at != std::string::npos; at = svg.find(what, at + 1)) ++n;
    return n;
  };
  const std::string clean = section::plot_svg(stream, 0);
  CHECK(count(clean, " flagged\"") == 0);
  // The max thickness flagged by a hole at its circle, and station 3's own circle too.
  section::Table& params = *stream.find("params");
  params.values[params.column("flags")] = double(section::bit(section::Check::thickness_measured));
  params.source.reset();
  section::Table& thickness = *stream.find("thickness");
  REQUIRE(thickness.rows() > 3);
  thickness.values[3 * thickness.columns.size() + thickness.column("flags")] =
      double(section::bit(section::Check::thickness_measured));
  thickness.source.reset();
  const std::string svg = section::plot_svg(stream, 0);
  bool balanced = false;
  const auto es = parse(svg, &balanced);
  REQUIRE(balanced);
  // Two rows of the table (max thickness and its place), each with its check under it.
  CHECK(with_class(es, "param-value").size() == with_class(parse(clean, &balanced), "param-value").size());
  CHECK(count(svg, "class=\"param-value flagged\"") == 2);
  CHECK(count(svg, "fails check thickness_measured") == 2);
  CHECK(count(subtree(svg, "s0-main"), "class=\"station flagged\"") == 1);
  // The drawing's max-thickness dimension red too, the chord's not.
  const std::string main = subtree(svg, "s0-main");
  CHECK(count(main, "class=\"dim-label flagged\"") == 1);
  const std::size_t red = main.find("class=\"dim-label flagged\"");
  REQUIRE(red != std::string::npos);
  const std::size_t group = main.find("dimension dim-max-thickness");
  REQUIRE(group != std::string::npos);
  CHECK(red > group);
  CHECK(red < main.find("</g>", group));
}

TEST_CASE("plot: an issue's control characters and stray bytes do not break the SVG", "[plot]") {
  const section::SectionTruth truth = section::section_truth(section::turbine_blade().at(0), 8000);
  section::Stream stream = full_stream(truth, 800, 300);
  stream.issues.push_back({0, -1, "camber", "a bell \x07, a stray \xFF, 20\xC2\xB0"});
  const std::string svg = section::plot_svg(stream, 0);
  // XML 1.0 has no control characters but tab, line feed and return, and is UTF-8 here.
  CHECK(svg.find('\x07') == std::string::npos);
  CHECK(svg.find('\xFF') == std::string::npos);
  CHECK(svg.find("a bell \xEF\xBF\xBD, a stray \xEF\xBF\xBD, 20\xC2\xB0") != std::string::npos);
}

TEST_CASE("plot: a stream that stops after slice draws its points and no more", "[plot]") {
  // Noisy ellipse, a = 15, b = 2, as the slice stage would write it.
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0, 0.005);
  section::Stream stream;
  section::Table pts = table("points", {"section", "loop", "index", "u", "v", "nu", "nv"});
  const int n = 500;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * M_PI * i / n;
    pts.add_row({4, 0, double(i), 15 * std::cos(t) + noise(rng), 2 * std::sin(t) + noise(rng), 0, 0});
  }
  stream.put(pts);
  const std::string svg = section::plot_svg(stream, 4);
  bool balanced = false;
  const auto es = parse(svg, &balanced);
  REQUIRE(balanced);
  CHECK(all_numbers_finite(svg));
  for (const std::string c : {"curve", "camber", "chord", "le-circle", "te-circle", "station"})
    CHECK(with_class(es, c).empty());
  bool inner = false;
  const auto main_es = parse(subtree(svg, "s4-main"), &inner);
  check_dots_cover(main_es, mapping(by_id(es, "s4-main")), stream, 2 * 1.6 * std::sqrt(0.5) + 0.01);
  // Ends found on the principal axis: each ellipse vertex (+-15, 0) lies in one inset.
  for (const Vector2d vertex : {Vector2d(-15, 0), Vector2d(15, 0)}) {
    int inside = 0;
    for (const std::string id : {"s4-le", "s4-te"}) {
      bool ok = false;
      const auto inset = parse(subtree(svg, id), &ok);
      const Vector2d p = mapping(by_id(inset, id)).pixel(vertex);
      const auto frame = with_class(inset, "view-frame");
      REQUIRE(frame.size() == 1);
      const double x = frame[0]->num("x"), y = frame[0]->num("y"), w = frame[0]->num("width");
      inside += p.x() > x && p.x() < x + w && p.y() > y && p.y() < y + w;
    }
    CHECK(inside == 1);
  }
  CHECK(svg.find(">measured points<") != std::string::npos);
  CHECK(with_class(es, "carried").empty());  // no offset column: nothing was carried
}

TEST_CASE("plot: points the gap fill carried are ringed and counted", "[plot]") {
  section::Stream stream;
  section::Table pts = table("points", {"section", "loop", "index", "u", "v", "nu", "nv", "offset"});
  const int n = 400;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * M_PI * i / n;
    pts.add_row({2, 0, double(i), 15 * std::cos(t), 2 * std::sin(t), 0, 0, i % 50 == 0 ? 0.3 : 0.0});
  }
  stream.put(pts);
  const std::string svg = section::plot_svg(stream, 2);
  bool balanced = false;
  const auto es = parse(svg, &balanced);
  REQUIRE(balanced);
  bool inner = false;
  const auto main_es = parse(subtree(svg, "s2-main"), &inner);
  std::size_t rings = 0;
  bool in_carried = false;
  for (const auto& e : main_es) {
    if (e.tag == "g") in_carried = e.attr.count("class") && e.attr.at("class") == "carried";
    rings += in_carried && e.tag == "circle";
  }
  CHECK(rings == 8);
  CHECK(svg.find("8 carried onto the plane") != std::string::npos);
  CHECK(svg.find(">points carried onto the plane (gap fill)<") != std::string::npos);
}

TEST_CASE("plot: the curve falls back on the samples, then the smoothed points", "[plot]") {
  const section::SectionTruth truth = section::section_truth(section::SectionDesign{}, 4000);
  section::Stream stream = full_stream(truth, 400, 100);
  CHECK(section::plot_svg(stream, 0).find("data-source=\"spline\"") != std::string::npos);
  section::Table samples = table("samples", {"section", "loop", "index", "u", "v"});
  section::Table smoothed = table("smoothed", {"section", "loop", "index", "u", "v"});
  for (std::size_t i = 0; i < truth.profile.size(); i += 10) {
    samples.add_row({0, 0, double(i), truth.profile[i].x(), truth.profile[i].y()});
    smoothed.add_row({0, 0, double(i), truth.profile[i].x(), truth.profile[i].y()});
  }
  for (const char* t : {"splines", "spline_knots", "spline_ctrl"}) stream.erase(t);
  stream.put(smoothed);
  CHECK(section::plot_svg(stream, 0).find("data-source=\"smoothed\"") != std::string::npos);
  stream.put(samples);
  const std::string svg = section::plot_svg(stream, 0);
  CHECK(svg.find("data-source=\"samples\"") != std::string::npos);
  // Camber tables stay drawn without the spline tables.
  bool balanced = false;
  const auto es = parse(svg, &balanced);
  CHECK(balanced);
  CHECK(with_class(es, "camber").size() == 4);  // main view, both insets, the legend
}

TEST_CASE("plot: unknown sections and bad options are plot errors", "[plot]") {
  section::Stream stream;
  section::Table pts = table("points", {"section", "loop", "index", "u", "v"});
  for (int i = 0; i < 20; ++i) pts.add_row({2, 0, double(i), std::cos(i * 0.314), std::sin(i * 0.314)});
  stream.put(pts);
  CHECK_THROWS_WITH(section::plot_svg(stream, 7),
                    Catch::Contains("plot: section 7 is not in the stream (sections: 2)"));
  section::PlotOptions o;
  o.width = 10;
  CHECK_THROWS_WITH(section::plot_svg(stream, 2, o), Catch::StartsWith("plot: width"));
  CHECK_THROWS_WITH(section::plot_html(section::Stream{}),
                    Catch::StartsWith("plot: the stream holds no section"));
  CHECK(section::plot_sections(stream) == std::vector<int>{2});
}

TEST_CASE("plot: the HTML page holds every section once, issues escaped", "[plot]") {
  const section::SectionTruth truth = section::section_truth(section::SectionDesign{}, 4000);
  section::Stream stream = full_stream(truth, 400, 100);
  stream.history.push_back("slice <blade>.ply");
  stream.issues.push_back({3, -1, "slice", "no points in the slab & no <loop>"});
  const std::string html = section::plot_html(stream);
  CHECK(html.rfind("<!DOCTYPE html>", 0) == 0);
  bool balanced = false;
  // <meta> and <br>-like void elements would unbalance the reader: drop the head.
  const std::size_t body_end = html.find("</body>");
  REQUIRE(body_end != std::string::npos);
  const std::string body = html.substr(html.find("<body>"), body_end + 7 - html.find("<body>"));
  parse(body, &balanced);
  CHECK(balanced);
  for (const std::string id : {"s0", "s3"}) {
    const std::string key = "id=\"" + id + "\"";
    const std::size_t first = html.find(key);
    REQUIRE(first != std::string::npos);
    CHECK(html.find(key, first + 1) == std::string::npos);
  }
  CHECK(html.find("no points in the slab &amp; no &lt;loop&gt;") != std::string::npos);
  CHECK(html.find("slice &lt;blade&gt;.ply") != std::string::npos);
  CHECK(html.find("nothing to draw") != std::string::npos);  // section 3 has only its issue
  CHECK(all_numbers_finite(html));
}
