// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the airfoil check (section/checks.h): a plane through a blade's platform, root
// block or a fixture measures a plate or a box, which no check of its edges doubts; such a
// section is flagged in every value and kept out of the blade's jumps. Airfoils of every
// shape, thick, thin, round, sharp or cut off at the TE, are not flagged.
#include "section/checks.h"

#include "camber_fixtures.h"
#include "pipe_stages.h"
#include "section/pipe/camber_stream.h"
#include "section/pipe/schema.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <tuple>
#include <vector>

using namespace camber_test;
using section::bit;
using section::Check;

namespace {

// A box `length` x `width` about the origin, its corners rounded to `corner`, points about
// every 0.05 along it.
std::vector<Vector2d> box(double length, double width, double corner) {
  std::vector<Vector2d> pts;
  const double hx = length / 2 - corner, hy = width / 2 - corner;
  const auto line = [&](const Vector2d& a, const Vector2d& b) {
    const int n = std::max(1, int((b - a).norm() / 0.05));
    for (int i = 0; i < n; ++i) pts.push_back(a + (b - a) * (double(i) / n));
  };
  const auto arc = [&](const Vector2d& c, double a0) {
    for (int i = 0, n = int(corner * M_PI / 2 / 0.05); i < n; ++i)
      pts.push_back(c + corner * Vector2d(std::cos(a0 + M_PI / 2 * i / n), std::sin(a0 + M_PI / 2 * i / n)));
  };
  line({-hx, -width / 2}, {hx, -width / 2});
  arc({hx, -hy}, -M_PI / 2);
  line({length / 2, -hy}, {length / 2, hy});
  arc({hx, hy}, 0);
  line({hx, width / 2}, {-hx, width / 2});
  arc({-hx, hy}, M_PI / 2);
  line({-length / 2, hy}, {-length / 2, -hy});
  arc({-hx, -hy}, M_PI);
  return pts;
}

section::CheckBits flags_of(const section::Table& params) {
  return section::flags_mask(params.at(0, std::size_t(params.find_column("flags"))));
}

}  // namespace

TEST_CASE("checks: a platform's box and a block cut by the plane are flagged airfoil", "[checks]") {
  // A plane through a blade's platform measured a 58 x 36 mm box as a blade (chord 57.9,
  // max thickness 35.6, both edges blunt faces) with no check failing. Boxes with square
  // and rounded corners: thicker than half the chord, or flat faces as wide as the box is
  // thick at both ends. Every value is flagged.
  for (const auto& [length, width, corner] : {std::tuple{58.0, 35.6, 0.0}, std::tuple{80.0, 30.0, 0.0},
                                              std::tuple{80.0, 30.0, 3.0}, std::tuple{100.0, 20.0, 2.0}}) {
    const section::Table params = section::test::profile_params(box(length, width, corner));
    const section::CheckBits flags = flags_of(params);
    INFO("box " << length << " x " << width << ", corners " << corner << ": "
                << section::check_names_text(flags));
    CHECK((flags & bit(Check::airfoil)) != 0);
    for (const char* column : {"chord", "max_thickness", "area", "le_radius", "stagger", "thickness"})
      CHECK(section::checks_flagging(flags, column) & bit(Check::airfoil));
  }
}

TEST_CASE("checks: airfoils thick and thin, round, sharp or cut off at the TE are not flagged airfoil",
          "[checks]") {
  // Five designs (thin and thick, 20-115 degrees of turning, edge radii 0.15-2.5 mm), each
  // whole and with its TE cut off 1 mm back (a flat face, a fraction of the thickness), and
  // NACA 0012 with its sharp TE.
  int faces = 0;
  for (const SectionDesign& design : designs()) {
    const SectionTruth truth = section::section_truth(design, 20000);
    Vector2d cut;
    double width = 0;
    for (const auto& pts : {truth.profile, cut_trailing_edge(truth, 1.0, cut, width)}) {
      const Checked c = measure(dense_spline(pts), 0);
      INFO("design chord " << design.chord << ", TE face " << c.camber.te.face << ": "
                           << section::check_names_text(c.check.flags));
      CHECK((c.check.flags & bit(Check::airfoil)) == 0);
      if (c.camber.te.face > 0) ++faces;
    }
  }
  CHECK(faces >= 3);  // the cut-off TEs measured as faces
  const Checked naca = measure(dense_spline(naca0012()), 0);
  CHECK((naca.check.flags & bit(Check::airfoil)) == 0);
}

TEST_CASE("checks: a section that is no airfoil is no neighbour of the blade's in the jumps", "[checks]") {
  // A platform's section below four blade sections: as their neighbour its 35.6 mm thickness
  // flagged the max thickness of the sections beside it (the limit is 5 % of each one's own).
  section::Stream stream;
  section::Table t = section::schema::params.table();
  for (int k = 0; k < 5; ++k) {
    section::SectionParams p;
    p.chord = k == 0 ? 60 : 41 - 0.1 * k;
    p.max_thickness = k == 0 ? 35.6 : 8 - 0.02 * k;
    p.le_radius = k == 0 ? 0 : 2, p.te_radius = k == 0 ? 0 : 0.5;
    p.stagger = k == 0 ? -17 : -8, p.inlet_angle = k == 0 ? 0 : 45, p.outlet_angle = k == 0 ? -45 : -65;
    p.camber_angle = p.inlet_angle - p.outlet_angle;
    const section::CamberResult c;
    const Eigen::Vector3d at(0, 0, k == 0 ? -3 : 3.0 * k);
    section::schema::params.add(t, {k, p, c, at, at, at, 0, 0, k == 0 ? bit(Check::airfoil) : 0});
  }
  stream.put(t);
  section::check_blade_stream({&stream});
  const section::Table& params = *stream.find("params");
  for (std::size_t r = 0; r < params.rows(); ++r)
    CHECK(params.at(r, params.column("flags")) == (r == 0 ? bit(Check::airfoil) : 0));
  CHECK(stream.issues.empty());
}
