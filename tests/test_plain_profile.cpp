// SPDX-License-Identifier: GPL-3.0-or-later
// A plain profile (an airfoil file, a CMM section) measured whichever point it starts at and
// whichever way it runs (canonical_loop, plain_profile_stream), and its values flagged where
// the same points fitted from the other end give others (flag_start_dependence).
#include "section/checks.h"
#include "section/extras/generate.h"
#include "section/fit_spline.h"
#include "section/io/stream.h"
#include "section/pipe/camber_stream.h"
#include "section/pipe/plain_profile.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <future>
#include <string>
#include <vector>

namespace {

using Points = std::vector<Eigen::Vector2d>;

// The loop started at point k, and run the other way when `reversed`.
Points restarted(Points loop, std::size_t k, bool reversed) {
  if (reversed) std::reverse(loop.begin(), loop.end());
  std::rotate(loop.begin(), loop.begin() + std::ptrdiff_t(k % loop.size()), loop.end());
  return loop;
}

// Equal to the bit, an empty value (NaN) matching an empty one.
bool same(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](double x, double y) {
           return x == y || (std::isnan(x) && std::isnan(y));
         });
}

double signed_area(const Points& p) {
  double a = 0;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++)
    a += p[j].x() * p[i].y() - p[i].x() * p[j].y();
  return a / 2;
}

// Sections whose edges hold few points (0.2-0.4 mm apart, edge radii 0.3-0.5 mm), 2 um of
// noise: before canonical_loop, the start of such points moved a turbine chord by up to
// 0.18 mm and its outlet angle by 8 deg (bladegen --rows, scripts/probe_profile_start.py).
struct Case {
  std::string name;
  section::SectionDesign design;
  double spacing;
};

std::vector<Case> cases() {
  return {{"turbine z 50, 0.4 mm", section::turbine_blade().at(50), 0.4},
          {"compressor z 8, 0.2 mm", section::compressor_blade().at(8), 0.2},
          {"compressor z 36, 0.2 mm", section::compressor_blade().at(36), 0.2}};
}

}  // namespace

TEST_CASE("canonical_loop: one order whatever the start and direction, from an edge's tip", "[fit_spline]") {
  for (const Case& c : cases()) {
    INFO(c.name);
    const section::SectionTruth truth = section::section_truth(c.design, 20000);
    const Points points = section::noisy_profile(truth, c.spacing, 0.002, 11);
    const Points canonical = section::canonical_loop(points);
    REQUIRE(canonical.size() == points.size());
    CHECK(signed_area(canonical) > 0);
    // It starts at an edge's tip: the point farthest from the centroid lies on an edge arc.
    const Eigen::Vector2d& start = canonical.front();
    CHECK(std::min((start - truth.le_center).norm() - truth.le_radius,
                   (start - truth.te_center).norm() - truth.te_radius) < 0.01);
    for (bool reversed : {false, true})
      for (std::size_t k : {std::size_t(0), std::size_t(1), points.size() / 3, points.size() - 2}) {
        INFO("start " << k << (reversed ? ", reversed" : ""));
        CHECK(section::canonical_loop(restarted(points, k, reversed)) == canonical);
      }
  }
  CHECK(section::canonical_loop({{0, 0}, {1, 0}}).size() == 2);
}

TEST_CASE("plain_profile_stream: the same parameters whatever point the profile starts at", "[camber]") {
  for (const Case& c : cases()) {
    INFO(c.name);
    const section::SectionTruth truth = section::section_truth(c.design, 20000);
    const Points points = section::noisy_profile(truth, c.spacing, 0.002, 11);
    std::vector<double> first;
    for (bool reversed : {false, true})
      for (std::size_t k : {std::size_t(0), points.size() / 4, points.size() / 2}) {
        INFO("start " << k << (reversed ? ", reversed" : ""));
        section::Stream s = section::plain_profile_stream(restarted(points, k, reversed));
        section::camber_stream(s);
        const section::Table& params = s.get("params", "test");
        REQUIRE(params.rows() == 1);
        std::vector<double> row;
        for (std::size_t j = 0; j < params.columns.size(); ++j) row.push_back(params.at(0, j));
        if (first.empty()) first = row;
        CHECK(same(row, first));
        // The values themselves: the thickness, which no edge shapes, to the 5 um target.
        CHECK(std::abs(params.at(0, params.column("max_thickness")) - truth.max_thickness) < 0.005);
      }
  }
}

namespace {

// camber_stream on plain_profile_stream, then flag_start_dependence: the checks it set.
section::CheckBits measured_with_start_check(const Points& points, section::Stream& s) {
  s = section::plain_profile_stream(points);
  section::camber_stream(s);
  return section::flag_start_dependence(s, points);
}

}  // namespace

TEST_CASE("flag_start_dependence: an edge the points do not fix is flagged, a well measured one not",
          "[camber]") {
  using section::Check;
  // Points 0.05 mm apart: either end's fit gives the same edges.
  for (const auto& design : {section::turbine_blade().at(30), section::compressor_blade().at(30)}) {
    const section::SectionTruth truth = section::section_truth(design, 20000);
    section::Stream s;
    CHECK(measured_with_start_check(section::noisy_profile(truth, 0.05, 0.002, 11), s) == 0);
    const section::Table& params = s.get("params", "test");
    CHECK((section::flags_mask(params.at(0, params.column("flags"))) &
           (bit(Check::le_start) | bit(Check::te_start))) == 0);
  }
  // A turbine TE of 0.45 mm radius with points 0.4 mm apart: fitted from the other end its
  // point moves 0.27 mm and its outlet angle 9 deg. Flagged, in the row, every thickness
  // station and an issue; a second run adds nothing.
  const section::SectionTruth truth = section::section_truth(section::turbine_blade().at(50), 20000);
  const Points points = section::noisy_profile(truth, 0.4, 0.002, 11);
  section::Stream s;
  CHECK(measured_with_start_check(points, s) == bit(Check::te_start));
  const section::Table& params = s.get("params", "test");
  CHECK((section::flags_mask(params.at(0, params.column("flags"))) & bit(Check::te_start)) != 0);
  const section::Table& stations = s.get("thickness", "test");
  for (std::size_t r = 0; r < stations.rows(); ++r)
    CHECK((section::flags_mask(stations.at(r, stations.column("flags"))) & bit(Check::te_start)) != 0);
  const auto said = [&] {
    return std::count_if(s.issues.begin(), s.issues.end(), [](const section::SectionIssue& i) {
      return i.message.find("check te_start") != std::string::npos;
    });
  };
  CHECK(said() == 1);
  CHECK(section::flag_start_dependence(s, points) == 0);
  CHECK(said() == 1);
  // The other end fitted and measured on a thread of its own (or, with one thread, when
  // read) flags the same, with the same words.
  for (const int threads : {0, 1, 2}) {
    section::CamberOptions options;
    options.threads = threads;
    std::future<section::Stream> other = section::other_end_stream_async(points, options);
    section::Stream again = section::plain_profile_stream(points);
    section::camber_stream(again);
    CHECK(section::flag_start_dependence(again, other.get()) == bit(Check::te_start));
    REQUIRE(again.issues.size() == s.issues.size());
    for (std::size_t k = 0; k < s.issues.size(); ++k) CHECK(again.issues[k].message == s.issues[k].message);
  }
  // An other end that measured nothing flags nothing.
  section::Stream unflagged = section::plain_profile_stream(points);
  section::camber_stream(unflagged);
  CHECK(section::flag_start_dependence(unflagged, section::Stream{}) == 0);
  CHECK(section::checks_flagging(bit(Check::te_start), "chord") != 0);
  CHECK(section::checks_flagging(bit(Check::te_start), "max_thickness") == 0);
}

TEST_CASE(
    "plain profile: an edge radius resting on the curve through a few points is flagged where the curve "
    "strays",
    "[camber]") {
  // A CMM's compressor rows, points 0.2 mm apart with 2 um of noise (bladegen --kind
  // compressor --rows 4 --row-pitch 14 --first-row 8 --spacing 0.2 --noise 0.002): the
  // 0.29 mm LE holds 4 of them. The row at z 36 of seed 7 measured its LE radius 3.85 %
  // small, unflagged: the spread allowed the noise (2 um) alone, while the curve's edge arc
  // strays 3.2 um from its circle. Every radius off its tolerance is flagged.
  const section::BladeDesign blade = section::compressor_blade();
  for (std::uint64_t seed : {7u, 8u, 9u}) {
    section::RowsOptions o;
    o.rows = 4, o.pitch = 14, o.first = 8, o.spacing = 0.2, o.noise = 0.002, o.seed = seed;
    const section::Cloud rows = section::generate_rows(blade, o);
    for (double z : {8.0, 22.0, 36.0, 50.0}) {
      Points row;
      for (const auto& p : rows.points)
        if (std::abs(p.z() - z) < 1e-9) row.push_back(p.head<2>());
      REQUIRE(row.size() > 100);
      const section::SectionTruth truth = section::section_truth(blade.at(z), 20000);
      section::Stream s;
      measured_with_start_check(row, s);
      const section::Table& params = s.get("params", "test");
      const section::CheckBits flags = section::flags_mask(params.at(0, params.column("flags")));
      INFO("seed " << seed << " z " << z << ", " << row.size() << " points, flags "
                   << section::check_names_text(flags));
      const double le = params.at(0, params.column("le_radius")),
                   te = params.at(0, params.column("te_radius"));
      if (std::abs(le - truth.le_radius) > 0.03 * truth.le_radius)
        CHECK(section::checks_flagging(flags, "le_radius") != 0);
      if (std::abs(te - truth.te_radius) > 0.10 * truth.te_radius)
        CHECK(section::checks_flagging(flags, "te_radius") != 0);
    }
  }
}
