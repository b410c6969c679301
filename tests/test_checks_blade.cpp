// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the blade check (check_blade, check_blade_stream in section/checks.h): a value
// that jumps from its neighbours across a blade's sections is flagged, and the right values
// beside it are not.
#include "section/checks.h"

#include "section/params.h"
#include "section/pipe/camber_stream.h"
#include "section/pipe/schema.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

using section::Check;

namespace {

// `count` sections 7.5 mm apart whose values fall linearly with height.
std::vector<section::BladeSection> linear_blade(int count) {
  std::vector<section::BladeSection> blade;
  for (int k = 0; k < count; ++k) {
    section::BladeSection s;
    s.height = 7.5 * k;
    const double z = s.height / 60;
    s.params.chord = 40 - 2 * z;
    s.params.max_thickness = 8 - 1 * z;
    s.params.stagger = -10 - 4 * z;
    s.params.inlet_angle = 45 - 5 * z;
    s.params.outlet_angle = -65 - 3 * z;
    s.params.camber_angle = s.params.inlet_angle - s.params.outlet_angle;
    s.params.le_radius = 2 - 0.2 * z;
    s.params.te_radius = 0.5 - 0.05 * z;
    blade.push_back(s);
  }
  return blade;
}

// The sections check_blade flags for `check`.
std::vector<std::size_t> jumps_of(const std::vector<section::BladeSection>& blade, Check check) {
  std::vector<std::size_t> at;
  for (const auto& j : section::check_blade(blade))
    if (j.check == check) at.push_back(j.index);
  return at;
}

}  // namespace

TEST_CASE("checks: blade: a section that jumps from its neighbours is flagged with the jump", "[checks]") {
  // Nine sections 7.5 mm apart: smooth trends (chord, twist, turning) with small noise.
  std::vector<section::BladeSection> blade;
  for (int k = 0; k < 9; ++k) {
    section::BladeSection s;
    s.height = 7.5 * k;
    const double z = s.height / 60;
    s.params.chord = 40 - 2 * z + 0.01 * std::sin(7.0 * k);
    s.params.max_thickness = 8 - 1 * z * z;
    s.params.stagger = -10 - 4 * z + 0.1 * std::cos(5.0 * k);
    s.params.inlet_angle = 45 - 5 * z;
    s.params.outlet_angle = -65 - 3 * z * z;
    s.params.camber_angle = s.params.inlet_angle - s.params.outlet_angle;
    s.params.le_radius = 2 - 0.2 * z;
    s.params.te_radius = 0.5 - 0.05 * z;
    blade.push_back(s);
  }
  CHECK(section::check_blade(blade).empty());
  // Stagger flipping by 175 degrees (-63 / 112 on a sparse rotor) at section 4, a chord
  // 60 % short at section 7.
  std::vector<section::BladeSection> bad = blade;
  bad[4].params.stagger += 175;
  bad[7].params.chord *= 0.4;
  const std::vector<section::Jump> jumps = section::check_blade(bad);
  REQUIRE(jumps.size() == 2);
  CHECK(jumps[0].index == 4);
  CHECK(jumps[0].check == Check::jump_stagger);
  CHECK(std::abs(std::abs(jumps[0].value - jumps[0].expected) - 175) < 1);
  CHECK(jumps[1].index == 7);
  CHECK(jumps[1].check == Check::jump_chord);
  // Camber angles 5.6, 17.1, 16.8, 3.8 over four sections (the blade's fall smoothly from
  // 17.9 to 9.3): the ends that depart from their neighbours are flagged.
  std::vector<section::BladeSection> four(4);
  const double camber[] = {5.6, 17.1, 16.8, 3.8};
  for (int k = 0; k < 4; ++k) {
    four[k].height = 15 * k;
    four[k].params = blade[k].params;
    four[k].params.camber_angle = camber[k];
  }
  int flagged = 0;
  for (const auto& j : section::check_blade(four)) flagged += j.check == Check::jump_camber;
  CHECK(flagged >= 2);
  // Fewer than three sections: nothing to compare.
  CHECK(section::check_blade({bad[0], bad[4]}).empty());
}

TEST_CASE("checks: blade: a value its own section's checks flag goes first", "[checks]") {
  // Nine sections 7.5 mm apart, the last cut past the blade's tip: its LE radius 72 mm.
  // Its limit is a quarter of its own value, so as the neighbour of section 7 it made that
  // section's right radius jump first (and, once 7 was left out, section 6's): the value
  // whose leaving out leaves the others in line goes first, and they are clean.
  std::vector<section::BladeSection> blade = linear_blade(9);
  blade[8].params.le_radius = 72;
  CHECK(jumps_of(blade, Check::jump_le_radius) == std::vector<std::size_t>{8});
  // So with its own check's flag, and a flag on a value that does not jump changes nothing.
  blade[8].flags = section::bit(Check::le_radius);
  blade[3].flags = section::bit(Check::le_radius);
  CHECK(jumps_of(blade, Check::jump_le_radius) == std::vector<std::size_t>{8});
  // Three sections, the middle one off: all three depart (the ends from lines through it),
  // and leaving out any leaves too few to compare; the one its own checks flag goes first,
  // and two are left.
  std::vector<section::BladeSection> three(blade.begin() + 5, blade.begin() + 8);
  three[1].params.le_radius = 72;
  three[1].flags = section::bit(Check::le_radius);
  const auto jumps = section::check_blade(three);
  REQUIRE(jumps.size() == 1);
  CHECK(jumps[0].index == 1);
  // A TE radius 1.8 times too large at the blade's other end, bridged over a hole and
  // flagged so: within a quarter of its own value of its neighbours' line, it is no jump,
  // but as their neighbour it makes the right radii of sections 1 and 2 jump; left out,
  // none does.
  std::vector<section::BladeSection> hub = linear_blade(9);
  hub[0].params.te_radius = 0.9;
  CHECK(jumps_of(hub, Check::jump_te_radius) == std::vector<std::size_t>{1, 2});
  hub[0].flags = section::bit(Check::te_radius);
  CHECK(jumps_of(hub, Check::jump_te_radius).empty());
}

TEST_CASE("checks: blade: an end plane far from the others is not measured against an extrapolation",
          "[checks]") {
  // Nine sections 7.5 mm apart whose trends fall with height, and a tenth plane 1e14 mm
  // up (a stream's origin edited): the line through its neighbours gave it an LE radius of
  // -4.6e11 mm and a jump of as much. Each value at the far plane continues the trend of its
  // neighbours over one spacing, so none departs.
  std::vector<section::BladeSection> blade = linear_blade(10);
  blade[9].height = 1e14;  // its values those of 67.5 mm
  CHECK(section::check_blade(blade).empty());
  // A far plane's LE radius doubled is still a jump, against a value its neighbours give.
  blade[9].params.le_radius *= 2;
  const std::vector<section::Jump> jumps = section::check_blade(blade);
  REQUIRE(jumps.size() == 1);
  CHECK(jumps[0].index == 9);
  CHECK(jumps[0].check == Check::jump_le_radius);
  CHECK(jumps[0].expected > 1.5);
  CHECK(jumps[0].expected < 2);
  // Radii falling fast toward the tip are never expected below zero.
  for (int k = 0; k < 10; ++k) {
    blade[k].height = 7.5 * k;
    blade[k].params.te_radius = k < 9 ? 0.5 - 0.055 * k : 0.02;
  }
  for (const auto& j : section::check_blade(blade))
    if (j.check == Check::jump_te_radius) CHECK(j.expected >= 0);
}

TEST_CASE("checks: the stream's params rows carry the blade check's flags and issues", "[checks]") {
  // Five sections' params rows (centroids 10 apart along z), the third with a chord 30 % short.
  section::Stream stream;
  section::Table t = section::schema::params.table();
  for (int k = 0; k < 5; ++k) {
    section::SectionParams p;
    p.chord = k == 2 ? 28 : 40;
    p.max_thickness = 4;
    p.le_radius = 1, p.te_radius = 0.3;
    p.stagger = 30, p.inlet_angle = 50, p.outlet_angle = 10, p.camber_angle = 40;
    const section::CamberResult c;
    const Eigen::Vector3d at(0, 0, 10.0 * k);
    section::schema::params.add(t, {k, p, c, at, at, at, 0, 0, 0});
  }
  stream.put(t);
  section::check_blade_stream({&stream});
  const section::Table& params = *stream.find("params");
  for (std::size_t r = 0; r < params.rows(); ++r)
    CHECK(params.at(r, params.column("flags")) == (r == 2 ? section::bit(Check::jump_chord) : 0));
  REQUIRE(stream.issues.size() == 1);
  CHECK(stream.issues[0].section == 2);
  CHECK(stream.issues[0].message.find("chord 28 fails check jump_chord: it jumps by -12") !=
        std::string::npos);
}
