// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of what the plot prints for an inspector: dimension lines that measure the true
// chord, maximum thickness and edge radii; the thickness at the stations; sections named
// by their plane; insets that magnify and draw the camber line smooth; text kept within
// the drawing; a page that grows with what is drawn, not with the points.
// (tests/tools/test_plot_layout.sh checks the same drawings' boxes in a browser.)
#include "plot_fixtures.h"
#include "section/extras/plot.h"

#include <catch2/catch.hpp>

#include <random>

using namespace plot_test;

namespace {

bool inside(const std::vector<Vector2d>& loop, const Vector2d& p) {
  bool in = false;
  for (std::size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++)
    if ((loop[i].y() > p.y()) != (loop[j].y() > p.y()) &&
        p.x() <
            loop[j].x() + (loop[i].x() - loop[j].x()) * (p.y() - loop[j].y()) / (loop[i].y() - loop[j].y()))
      in = !in;
  return in;
}

std::vector<Element> parsed(const std::string& svg, const std::string& id) {
  bool ok = false;
  auto es = parse(subtree(svg, id), &ok);
  REQUIRE(ok);
  return es;
}

// The dim-line of dimension group `key` in `es` (elements after the group's opening tag).
std::pair<Vector2d, Vector2d> dim_line(const std::vector<Element>& es, const std::string& key,
                                       double* value) {
  for (std::size_t i = 0; i < es.size(); ++i)
    if (es[i].has_class("dim-" + key)) {
      *value = es[i].num("data-value");
      for (std::size_t k = i + 1; k < es.size(); ++k)
        if (es[k].has_class("dim-line"))
          return {{es[k].num("x1"), es[k].num("y1")}, {es[k].num("x2"), es[k].num("y2")}};
    }
  FAIL("no dimension " << key);
  return {};
}

const std::vector<section::SectionDesign> designs() {
  return {section::turbine_blade().at(0), section::compressor_blade().at(60)};
}

}  // namespace

TEST_CASE("plot: dimension lines measure the true chord, maximum thickness and edge radii", "[plot]") {
  for (const auto& design : designs()) {
    const section::SectionTruth truth = section::section_truth(design, 8000);
    const std::string svg = section::plot_svg(full_stream(truth, 800, 300), 0);
    const auto main_es = parsed(svg, "s0-main");
    const Mapping m = mapping(main_es.front());
    double value = 0;
    // Chord: as long as the true chord, parallel to it, outside the profile.
    const auto [a, b] = dim_line(main_es, "chord", &value);
    CHECK(std::abs(value - truth.chord) < 0.01);
    CHECK(std::abs((b - a).norm() / m.s - truth.chord) < 0.005);
    const Vector2d along = m.world(b) - m.world(a), chord = truth.te_point - truth.le_point;
    CHECK(std::abs(along.normalized().x() * chord.normalized().y() -
                   along.normalized().y() * chord.normalized().x()) < 1e-3);
    CHECK(!inside(truth.profile, m.world(a)));
    CHECK(!inside(truth.profile, m.world(b)));
    // Maximum thickness: across the largest inscribed circle, its ends on the profile.
    const auto [t0, t1] = dim_line(main_es, "max-thickness", &value);
    CHECK(std::abs(value - truth.max_thickness) < 0.01);
    CHECK(std::abs((t1 - t0).norm() / m.s - truth.max_thickness) < 0.005);
    for (const auto& end : {t0, t1}) CHECK(section::locate(truth, m.world(end)).distance < 0.01 + 0.02 / m.s);
    // Edge radii in the insets: from the true centre, as long as the true radius.
    for (const std::string key : {"le", "te"}) {
      const auto inset = parsed(svg, "s0-" + key);
      const Mapping mi = mapping(inset.front());
      const auto [c, r] = dim_line(inset, key + "-radius", &value);
      const double radius = key == "le" ? truth.le_radius : truth.te_radius;
      const Vector2d centre = key == "le" ? truth.le_center : truth.te_center;
      CHECK(std::abs(value - radius) < 0.01);
      CHECK(std::abs((r - c).norm() / mi.s - radius) < 0.01);
      CHECK((mi.world(c) - centre).norm() < 0.01);
    }
  }
}

TEST_CASE("plot: each station's thickness is printed beside it, outside the profile", "[plot]") {
  const section::SectionTruth truth = section::section_truth(designs().front(), 8000);
  const section::Stream stream = full_stream(truth, 800, 300);
  const std::string svg = section::plot_svg(stream, 0);
  const auto main_es = parsed(svg, "s0-main");
  const Mapping m = mapping(main_es.front());
  const section::Table& t = *stream.find("thickness");
  const long ct = t.find_column("thickness");
  std::size_t labels = 0;
  for (std::size_t i = 0; i < main_es.size(); ++i) {
    if (!main_es[i].has_class("station-label")) continue;
    ++labels;
    const double value = main_es[i].num("data-value");
    bool known = false;
    for (std::size_t r = 0; r < t.rows(); ++r) known |= std::abs(t.at(r, ct) - value) < 1e-6;
    CHECK(known);
    const Element& text = main_es[i + 1];
    REQUIRE(text.tag == "text");
    CHECK(!inside(truth.profile, m.world({text.num("x"), text.num("y")})));
  }
  CHECK(labels >= t.rows() / 2);
}

TEST_CASE("plot: an edge circle far too large still leaves the edge magnified in its inset", "[plot]") {
  const section::SectionTruth truth = section::section_truth(designs().front(), 8000);
  section::Stream stream = full_stream(truth, 800, 300);
  section::Table& params = *stream.find("params");
  params.values[params.find_column("le_radius")] = 10 * truth.chord;  // a wrong fit
  const std::string svg = section::plot_svg(stream, 0);
  CHECK(all_numbers_finite(svg));
  const Mapping m = mapping(parsed(svg, "s0-main").front());
  const auto inset = parsed(svg, "s0-le");
  const Mapping mi = mapping(inset.front());
  CHECK(mi.s >= 2 * m.s);
  const auto frame = with_class(inset, "view-frame");
  REQUIRE(frame.size() == 1);
  const Vector2d le = mi.pixel(truth.le_point);
  const double x = frame[0]->num("x"), y = frame[0]->num("y"), w = frame[0]->num("width");
  CHECK((le.x() > x && le.x() < x + w && le.y() > y && le.y() < y + w));
  CHECK(svg.find("dim-le-radius") == std::string::npos);  // a circle that does not fit gets no radius line
}

TEST_CASE("plot: the camber line in an inset follows the true camber line", "[plot]") {
  for (const auto& design : designs()) {
    const section::SectionTruth truth = section::section_truth(design, 8000);
    const std::string svg = section::plot_svg(full_stream(truth, 800, 300), 0);
    for (const std::string id : {"s0-le", "s0-te"}) {
      const auto inset = parsed(svg, id);
      const Mapping mi = mapping(inset.front());
      const auto frame = with_class(inset, "view-frame");
      const double x = frame[0]->num("x"), y = frame[0]->num("y"), w = frame[0]->num("width");
      const auto camber = with_class(inset, "camber");
      REQUIRE(camber.size() == 1);
      const auto v = vertices(camber[0]->attr.at("d"));
      double worst = 0;  // px, from the drawn line (vertices and segment midpoints) to the true one
      for (std::size_t i = 0; i + 1 < v.size(); ++i)
        for (const double f : {0.0, 0.25, 0.5, 0.75}) {
          const Vector2d p = v[i] + f * (v[i + 1] - v[i]);
          if (p.x() < x || p.x() > x + w || p.y() < y || p.y() > y + w) continue;
          const Vector2d q = mi.world(p);
          if ((q - truth.le_point).norm() < 1e-9) continue;
          worst = std::max(worst, section::camber_distance(truth, q) * mi.s);
        }
      CHECK(worst < 1.0 + 0.003 * mi.s);  // the camber stage within 3 um, the drawing within 1 px
    }
  }
}

TEST_CASE("plot: long issues and frames are wrapped within the drawing", "[plot]") {
  const section::SectionTruth truth = section::section_truth(designs().front(), 4000);
  section::Stream stream = full_stream(truth, 400, 100);
  std::string words;
  for (int i = 0; i < 80; ++i) words += "word" + std::to_string(i) + " ";
  stream.issues.push_back(
      {0, 0, "camber",
       words + "and_a_token_far_longer_than_any_line_of_the_drawing_" + std::string(200, 'x')});
  const std::string svg = section::plot_svg(stream, 0);
  bool ok = false;
  const auto es = parse(svg, &ok);
  REQUIRE(ok);
  const double W = es.front().num("width"), H = es.front().num("height");
  std::size_t lines = 0;
  for (const auto* e : with_class(es, "issue")) {
    ++lines;
    CHECK(e->num("y") < H);
  }
  CHECK(lines >= 5);
  // Every line of text fits the width at 0.62 em a glyph (the browser test measures).
  std::size_t pos = 0;
  while ((pos = svg.find("<text", pos)) != std::string::npos) {
    const std::size_t open = svg.find('>', pos), close = svg.find("</text>", open);
    const std::string tag = svg.substr(pos, open - pos), text = svg.substr(open + 1, close - open - 1);
    pos = close;
    if (tag.find("rotate(") != std::string::npos || tag.find("text-anchor") != std::string::npos ||
        tag.find("param-value") != std::string::npos)  // anchored at their right end, x <= W - margin
      continue;
    const std::size_t x0 = tag.find(" x=\"") + 4;
    const double x = std::stod(tag.substr(x0)), font = tag.find("title") != std::string::npos ? 17 : 13;
    std::size_t glyphs = 0;
    for (unsigned char c : text) glyphs += (c & 0xC0) != 0x80;
    INFO(tag << ">" << text);
    CHECK(x + 0.62 * font * static_cast<double>(glyphs) <= W + 0.5);
  }
}

TEST_CASE("plot: sections are named by their plane", "[plot]") {
  const section::SectionTruth truth = section::section_truth(section::SectionDesign{}, 4000);
  section::Stream stream = full_stream(truth, 400, 100);  // the plane z = 12
  CHECK(section::plot_svg(stream, 0).find(">z = 12 mm") != std::string::npos);
  CHECK(section::plot_html(stream).find(">z = 12 mm</a>") != std::string::npos);
  section::put_frames(stream, {{0, section::make_frame({3, 0, 4}, {0.6, 0, 0.8})}});
  CHECK(section::plot_svg(stream, 0).find(">h = 5 mm along (0.6, 0, 0.8)") != std::string::npos);
}

TEST_CASE("plot: the page grows with what is drawn, not with the points, and pans and zooms by itself",
          "[plot]") {
  const section::SectionTruth truth = section::section_truth(designs().front(), 40000);
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0, 0.003);
  std::vector<std::size_t> sizes;
  for (const int n : {2000, 40000}) {
    section::Stream stream = full_stream(truth, 400, 100);
    section::Table pts = table("points", {"section", "loop", "index", "u", "v", "nu", "nv"});
    const double step = double(truth.profile.size()) / n;
    for (int i = 0; i < n; ++i) {
      const std::size_t k = static_cast<std::size_t>(i * step);
      const Vector2d p = truth.profile[k] + noise(rng) * truth.profile_normal[k];
      pts.add_row({0, 0, double(i), p.x(), p.y(), 0, 0});
    }
    stream.put(pts);
    const std::string html = section::plot_html(stream);
    sizes.push_back(html.size());
    if (n == 40000) {
      // Every measured point still lies within a dot's width of a drawn one.
      const auto main_es = parsed(html, "s0-main");
      const Mapping m = mapping(main_es.front());
      const auto drawn = dots(main_es);
      CHECK(drawn.size() < 5000);
      for (std::size_t r = 0; r < pts.rows(); r += 97) {
        const Vector2d p = m.pixel({pts.at(r, 3), pts.at(r, 4)});
        double nearest = 1e300;
        for (const auto& q : drawn) nearest = std::min(nearest, (q - p).norm());
        CHECK(nearest <= 2.27);
      }
      CHECK(html.find("<script>") != std::string::npos);
      CHECK(html.find("'wheel'") != std::string::npos);
      for (const char* fetch : {"<script src", "<link", "href=\"http", "url(http", "import("})
        CHECK(html.find(fetch) == std::string::npos);
    }
  }
  INFO("HTML bytes with 2000 and 40000 points: " << sizes[0] << ", " << sizes[1]);
  CHECK(double(sizes[1]) < 1.6 * double(sizes[0]));
}
