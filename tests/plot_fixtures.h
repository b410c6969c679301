// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Fixtures of the plot tests (test_plot, test_plot_layout): a tiny SVG reader (elements,
// subtrees by id, path vertices, the px mapping of a view) and a full stream of one
// generated section.
#include "section/camber.h"
#include "section/extras/generate.h"
#include "section/fit_spline.h"
#include "section/io/stream.h"
#include "section/pipe/camber_stream.h"
#include "section/pipe/schema.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

namespace plot_test {

using Eigen::Vector2d;

// ------------------------------------------------------------------ a tiny SVG reader

struct Element {
  std::string tag;
  std::map<std::string, std::string> attr;
  double num(const std::string& name) const {
    const auto it = attr.find(name);
    REQUIRE(it != attr.end());
    char* end = nullptr;
    const double v = std::strtod(it->second.c_str(), &end);
    REQUIRE(end != it->second.c_str());
    return v;
  }
  bool has_class(const std::string& c) const {
    const auto it = attr.find("class");
    if (it == attr.end()) return false;
    return (" " + it->second + " ").find(" " + c + " ") != std::string::npos;
  }
};

// Opening tags in document order; checks on the way that tags nest properly.
inline std::vector<Element> parse(const std::string& text, bool* balanced) {
  std::vector<Element> out;
  std::vector<std::string> open;
  *balanced = true;
  std::size_t pos = 0;
  while ((pos = text.find('<', pos)) != std::string::npos) {
    const std::size_t end = text.find('>', pos);
    REQUIRE(end != std::string::npos);
    const std::string tag = text.substr(pos + 1, end - pos - 1);
    pos = end + 1;
    if (tag.empty() || tag[0] == '!' || tag[0] == '?') continue;
    if (tag[0] == '/') {
      if (open.empty() || open.back() != tag.substr(1)) *balanced = false;
      if (!open.empty()) open.pop_back();
      continue;
    }
    Element e;
    const bool self_closing = tag.back() == '/';
    const std::size_t name_end = tag.find_first_of(" /");
    e.tag = tag.substr(0, name_end);
    // name="value" pairs (no std::regex: it recurses per character on long path data).
    std::size_t q = name_end;
    while (q != std::string::npos && (q = tag.find('=', q)) != std::string::npos) {
      std::size_t n0 = tag.rfind(' ', q);
      const std::size_t v0 = q + 2, v1 = tag.find('"', v0);
      REQUIRE(tag[q + 1] == '"');
      REQUIRE(v1 != std::string::npos);
      e.attr[tag.substr(n0 + 1, q - n0 - 1)] = tag.substr(v0, v1 - v0);
      q = v1 + 1;
    }
    if (!self_closing) open.push_back(e.tag);
    out.push_back(std::move(e));
  }
  if (!open.empty()) *balanced = false;
  return out;
}

// Elements between the opening of the element with id `id` and its closing: found by
// nesting depth on the raw text.
inline std::string subtree(const std::string& svg, const std::string& id) {
  const std::size_t start = svg.find("id=\"" + id + "\"");
  REQUIRE(start != std::string::npos);
  const std::size_t open = svg.rfind('<', start);
  int depth = 0;
  std::size_t pos = open;
  while ((pos = svg.find('<', pos)) != std::string::npos) {
    const std::size_t end = svg.find('>', pos);
    if (svg[pos + 1] == '/')
      --depth;
    else if (svg[end - 1] != '/')
      ++depth;
    pos = end + 1;
    if (depth == 0) return svg.substr(open, pos - open);
  }
  FAIL("unterminated element " << id);
  return {};
}

inline std::vector<const Element*> with_class(const std::vector<Element>& es, const std::string& c) {
  std::vector<const Element*> out;
  for (const auto& e : es)
    if (e.has_class(c)) out.push_back(&e);
  return out;
}

// Vertices of a path's d attribute ("M x y L x y ... Z").
inline std::vector<Vector2d> vertices(const std::string& d) {
  std::vector<Vector2d> out;
  std::vector<double> numbers;
  const char* p = d.c_str();
  while (*p) {
    if (*p == '-' || (*p >= '0' && *p <= '9') || *p == '.') {
      char* end = nullptr;
      numbers.push_back(std::strtod(p, &end));
      p = end;
    } else {
      ++p;
    }
  }
  REQUIRE(numbers.size() % 2 == 0);
  for (std::size_t i = 0; i + 1 < numbers.size(); i += 2) out.emplace_back(numbers[i], numbers[i + 1]);
  return out;
}

// The px mapping of a view group: x = s u + tx, y = -s v + ty.
struct Mapping {
  double s, tx, ty;
  Vector2d world(const Vector2d& p) const { return {(p.x() - tx) / s, (ty - p.y()) / s}; }
  Vector2d pixel(const Vector2d& w) const { return {s * w.x() + tx, -s * w.y() + ty}; }
};

inline Mapping mapping(const Element& group) {
  return {group.num("data-scale"), group.num("data-tx"), group.num("data-ty")};
}

inline const Element& by_id(const std::vector<Element>& es, const std::string& id) {
  for (const auto& e : es) {
    const auto it = e.attr.find("id");
    if (it != e.attr.end() && it->second == id) return e;
  }
  FAIL("no element with id " << id);
  return es.front();
}

// ------------------------------------------------------------------ streams

inline section::Table table(const std::string& name, std::vector<std::string> columns) {
  section::Table t;
  t.name = name;
  t.columns = std::move(columns);
  return t;
}

// A full stream of one section (id `id`, frame at height z): measured points on the exact
// profile, the spline fitted to them, and the camber stage's tables.
inline section::Stream full_stream(const section::SectionTruth& truth, int points, int control_points) {
  std::vector<Vector2d> measured;
  const std::size_t step = truth.profile.size() / points;
  for (std::size_t i = 0; i < truth.profile.size(); i += step) measured.push_back(truth.profile[i]);
  section::FitSplineOptions fo;
  fo.control_points = control_points;
  section::Stream stream = section::profile_stream(section::fit_spline(measured, measured, fo).spline);
  section::camber_stream(stream);
  section::Table pts = table("points", {"section", "loop", "index", "u", "v", "nu", "nv"});
  for (std::size_t i = 0; i < measured.size(); ++i)
    pts.add_row({0, 0, double(i), measured[i].x(), measured[i].y(), 0, 0});
  stream.put(pts);
  section::put_frames(stream, {{0, section::make_frame({0, 0, 12}, {0, 0, 1})}});
  return stream;
}

inline bool all_numbers_finite(const std::string& svg) {
  return svg.find("nan") == std::string::npos && svg.find("inf\"") == std::string::npos &&
         svg.find("NaN") == std::string::npos;
}

// The px centres of the measured points' dots: "M x yh0" then "m dx dyh0" subpaths of
// class "points".
inline std::vector<Vector2d> dots(const std::vector<Element>& es) {
  std::vector<Vector2d> out;
  for (const auto& e : es) {
    if (e.tag != "path" || !e.has_class("points")) continue;
    const std::string& d = e.attr.at("d");
    Vector2d at(0, 0);
    for (std::size_t m = d.find_first_of("Mm"); m != std::string::npos; m = d.find_first_of("Mm", m + 1)) {
      char* end = nullptr;
      const double x = std::strtod(d.c_str() + m + 1, &end);
      const double y = std::strtod(end, &end);
      REQUIRE(std::string(end, 2) == "h0");
      at = d[m] == 'M' ? Vector2d(x, y) : Vector2d(at + Vector2d(x, y));
      out.push_back(at);
    }
  }
  return out;
}

}  // namespace plot_test
