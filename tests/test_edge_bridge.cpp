// SPDX-License-Identifier: GPL-3.0-or-later
// A hole shorter than an edge's radius, on its arc: the curve bridging it bends away from
// the chord between its ends, and strays from the blade by a share of that bend, the edge's
// point, inlet angle and chord with it (a 1.6 mm hole on a 2 mm LE radius moved the chord
// 14 um with no flag).
#include "camber_fixtures.h"
#include "section/checks.h"
#include "section/io/stream.h"
#include "section/pipe/camber_stream.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <string>
#include <vector>

using namespace camber_test;

namespace {

// The profile's arc length at each of its points, from its first.
std::vector<double> arc_lengths(const std::vector<Vector2d>& p) {
  std::vector<double> s(p.size(), 0.0);
  for (std::size_t i = 1; i < p.size(); ++i) s[i] = s[i - 1] + (p[i] - p[i - 1]).norm();
  return s;
}

struct Bridged {
  std::string messages;
  section::CheckBits flags = 0;
};

// `truth` sampled every `spacing` with 5 um of noise along its normal, none from `from` to
// `to` LE radii past the LE point along the profile, fitted, and measured by camber_stream
// with `o`.
Bridged measure_with_hole(const SectionTruth& truth, double from, double to, const section::CamberOptions& o,
                          double spacing = 0.02) {
  const std::vector<Vector2d>& p = truth.profile;
  const std::vector<double> s = arc_lengths(p);
  const double perimeter = s.back() + (p.front() - p.back()).norm();
  std::size_t le = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if ((p[i] - truth.le_point).norm() < (p[le] - truth.le_point).norm()) le = i;
  std::mt19937_64 rng(17);
  std::normal_distribution<double> noise(0, 0.005);
  const std::size_t n = p.size(), step = std::size_t(std::round(spacing / (perimeter / double(n))));
  std::vector<Vector2d> pts;
  for (std::size_t i = 0; i < n; i += step) {
    const double along = std::fmod(s[i] - s[le] + perimeter, perimeter);
    const Vector2d t = (p[(i + 1) % n] - p[(i + n - 1) % n]).normalized();
    const Vector2d q = p[i] + noise(rng) * Vector2d(-t.y(), t.x());
    if (along < from * truth.le_radius || along > to * truth.le_radius) pts.push_back(q);
  }
  section::Stream stream = section::profile_stream(section::fit_spline(pts, pts).spline);
  section::Table points{"points", {"section", "loop", "index", "u", "v"}, {}};
  for (std::size_t i = 0; i < pts.size(); ++i) points.add_row({0, 0, double(i), pts[i].x(), pts[i].y()});
  stream.put(points);
  section::camber_stream(stream, o);
  Bridged out;
  for (const auto& issue : stream.issues) out.messages += issue.message + "; ";
  const section::Table& params = *stream.find("params");
  REQUIRE(params.rows() == 1);
  out.flags = section::flags_mask(params.at(0, params.column("flags")));
  return out;
}

// The number before " mm" that follows `lead` in `text`.
double number_after(const std::string& text, const std::string& lead) {
  const std::size_t at = text.find(lead);
  REQUIRE(at != std::string::npos);
  return std::stod(text.substr(at + lead.size()));
}

}  // namespace

TEST_CASE("edge: a short hole on a large edge's arc is flagged by how far its bridge bends", "[edge]") {
  const SectionTruth truth = section::section_truth(section::turbine_blade().at(20), 20000);
  const double r = truth.le_radius;
  REQUIRE(r > 1.5);  // a large LE, where a hole under one radius long bends 0.1 mm
  const char* partly = "leading edge partly not measured: the curve bridging ";
  // 0.8 radii of arc: its sagitta is r (1 - cos 0.4), 0.079 r (0.15 mm); a tenth of it is
  // over 1.5e-4 of the profile's size (about 7 um).
  const section::CamberOptions o;
  const Bridged hole = measure_with_hole(truth, 0.2, 1.0, o);
  INFO(hole.messages);
  CHECK(hole.messages.find(partly) != std::string::npos);
  CHECK((hole.flags & section::bit(section::Check::le_measured)) != 0);
  const double sagitta = r * (1 - std::cos(0.4));
  CHECK(number_after(hole.messages, " bends ") == Approx(sagitta).epsilon(0.2));
  CHECK(number_after(hole.messages, partly) == Approx(0.8 * r).margin(0.1));
  // A tenth of a radius bends 1.25e-3 r (2.5 um): its bridge cannot stray by the accuracy.
  const Bridged gap = measure_with_hole(truth, 0.2, 0.3, o);
  INFO(gap.messages);
  CHECK(gap.messages.find("leading edge partly not measured") == std::string::npos);
  CHECK((gap.flags & section::bit(section::Check::le_measured)) == 0);
  // The rule off: the long hole is under the one radius the hole's length rule asks.
  section::CamberOptions off = o;
  off.edge_bridge = 0;
  const Bridged without = measure_with_hole(truth, 0.2, 1.0, off);
  INFO(without.messages);
  CHECK(without.messages.find("leading edge partly not measured") == std::string::npos);
  CHECK((without.flags & section::bit(section::Check::le_measured)) == 0);
}

TEST_CASE("edge: evenly sparse points are no hole for the bridge's bend", "[edge]") {
  // Points every 1.2 mm (a CMM row's) about a 2 mm LE radius: each stretch between two of
  // them bends its curve 0.09 mm, a tenth of which is over the accuracy (7 um), but the
  // points are as sparse either side: no hole. Counted as holes (hole_spacings 0), each
  // stretch would be one.
  const SectionTruth truth = section::section_truth(section::turbine_blade().at(20), 20000);
  const section::CamberOptions o;
  const Bridged sparse = measure_with_hole(truth, 0, 0, o, 1.2);
  INFO(sparse.messages);
  CHECK(sparse.messages.find("leading edge partly not measured") == std::string::npos);
  section::CamberOptions every = o;
  every.thickness_hole_spacings = 0;
  const Bridged counted = measure_with_hole(truth, 0, 0, every, 1.2);
  INFO(counted.messages);
  CHECK(counted.messages.find("leading edge partly not measured: the curve bridging") != std::string::npos);
}
