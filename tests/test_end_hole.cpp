// SPDX-License-Identifier: GPL-3.0-or-later
// A hole in the measured points near an edge, beyond the edge's own arc: the fit's bridge
// over it strays from the blade, and the inscribed circles touching it would carry that into
// the end direction's fit (the inlet angle, and the LE point and chord it places); they
// count less there, nothing over a long hole (CamberOptions::end_hole).
#include "camber_fixtures.h"
#include "detail/coverage.h"
#include "section/checks.h"
#include "section/io/stream.h"
#include "section/pipe/camber_stream.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <algorithm>
#include <vector>

using namespace camber_test;

namespace {

// Inlet angle (deg) and chord (mm) against the truth's.
struct Measured {
  double inlet = 0, chord = 0;
};

// `truth` sampled every `spacing`, none from `from` to `to` mm past the LE point along the
// profile (counterclockwise), fitted, and measured by camber_stream with `o`.
Measured measure(const SectionTruth& truth, double from, double to, const section::CamberOptions& o,
                 double spacing = 0.04) {
  const std::vector<Vector2d>& p = truth.profile;
  const std::size_t n = p.size();
  const std::size_t step = std::size_t(std::round(spacing / (truth.perimeter / double(n))));
  std::vector<Vector2d> pts;
  for (std::size_t i = 0; i < n; i += step) {
    const double along = truth.profile_s[i];  // from the LE point
    if (along >= from && along <= to) continue;
    pts.push_back(p[i]);
  }
  section::Stream stream = section::profile_stream(section::fit_spline(pts, pts).spline);
  section::Table points{"points", {"section", "loop", "index", "u", "v"}, {}};
  for (std::size_t i = 0; i < pts.size(); ++i) points.add_row({0, 0, double(i), pts[i].x(), pts[i].y()});
  stream.put(points);
  section::camber_stream(stream, o);
  const section::Table& params = *stream.find("params");
  REQUIRE(params.rows() == 1);
  return {params.at(0, params.column("inlet_angle")) - truth.inlet_angle,
          params.at(0, params.column("chord")) - truth.chord};
}

}  // namespace

TEST_CASE("camber: circles on the bridge over a hole near an edge count not in its end fit", "[camber]") {
  // Holes 2-3 mm long beginning 2-4 mm past a turbine LE of radius 1.85-2 mm, on either
  // side: beyond the edge's arc, within the end fit's span (15 % of the axis, about 6 mm).
  // The exact profile's points every 0.04 mm; without the hole, inlet angle and chord are
  // off by +0.028 deg and -1 um (the fit's own). With every circle counted fully, the holes
  // moved them by up to 0.21 deg and 5.9 um; weighed, by under 0.018 deg and 0.5 um.
  section::CamberOptions every;
  every.end_hole = 0;
  const section::CamberOptions o;
  double worst_inlet = 0, worst_chord = 0, every_inlet = 0, every_chord = 0;
  for (int z : {10, 40}) {
    const SectionTruth truth = section::section_truth(section::turbine_blade().at(z), 20000);
    REQUIRE(truth.le_radius > 1.8);
    const Measured whole = measure(truth, -1, -1, o), whole_every = measure(truth, -1, -1, every);
    // No hole: every circle counts fully.
    CHECK(whole.inlet == whole_every.inlet);
    CHECK(whole.chord == whole_every.chord);
    for (double from : {2.0, 3.0, 4.0})
      for (double length : {2.0, 3.0})
        for (bool suction : {true, false}) {
          const double a = suction ? from : truth.perimeter - from - length;
          const Measured m = measure(truth, a, a + length, o), e = measure(truth, a, a + length, every);
          worst_inlet = std::max(worst_inlet, std::abs(m.inlet - whole.inlet));
          worst_chord = std::max(worst_chord, std::abs(m.chord - whole.chord));
          every_inlet = std::max(every_inlet, std::abs(e.inlet - whole.inlet));
          every_chord = std::max(every_chord, std::abs(e.chord - whole.chord));
        }
  }
  CHECK(worst_inlet < 0.03);
  CHECK(worst_chord < 0.001);
  // The same holes with every circle counted fully: the bridge tilts the end direction.
  CHECK(every_inlet > 0.15);
  CHECK(every_chord > 0.004);
}

TEST_CASE("camber: evenly sparse points leave every circle in the end fits", "[camber]") {
  // Points every 1.2 mm (a CMM row's): every stretch between two is as long as the next,
  // no hole.
  const SectionTruth truth = section::section_truth(section::turbine_blade().at(20), 20000);
  section::CamberOptions every;
  every.end_hole = 0;
  const Measured m = measure(truth, -1, -1, {}, 1.2), e = measure(truth, -1, -1, every, 1.2);
  CHECK(m.inlet == e.inlet);
  CHECK(m.chord == e.chord);
}

TEST_CASE("camber: a circle's end-fit weight is continuous in the hole and the contact's place", "[camber]") {
  using section::detail::ContactCoverage;
  using section::detail::end_fit_weight;
  const double limit = 0.4, spacings = 4;
  // Points 0.03 mm apart beside the hole: the length rule (0.4 mm) is the longer one.
  const auto weight = [&](double hole, double inside) {
    ContactCoverage c;
    c.hole = hole, c.inside = inside, c.spacing = 0.03;
    return end_fit_weight(c, limit, spacings);
  };
  CHECK(weight(2.0, 0) == 1);      // the contact outside the hole
  CHECK(weight(0.39, 0.19) == 1);  // a hole under the limit
  CHECK(weight(0.8, 0.4) == 0);    // twice the limit, the contact in its middle
  CHECK(weight(0.6, 0.3) == Approx(0.5));
  CHECK(weight(2.0, 0.1) == Approx(0.5));  // half a tenth of the hole from its end
  // Sparse points (0.3 mm apart): a gap is a hole from 2 x 4 spacings (2.4 mm) on.
  ContactCoverage sparse;
  sparse.hole = 2.3, sparse.inside = 1.0, sparse.spacing = 0.3;
  CHECK(end_fit_weight(sparse, limit, spacings) == 1);
  // No jump: a step of 1 um in the hole's length or the contact's place moves the weight
  // by at most 1 um over the ramp's width.
  double worst = 0;
  for (double hole = 0.3; hole < 1.0; hole += 0.001)
    worst = std::max(worst, std::abs(weight(hole + 0.001, hole / 2) - weight(hole, hole / 2)));
  CHECK(worst <= 0.001 / limit + 1e-12);
  worst = 0;
  for (double inside = 0; inside < 0.2; inside += 0.001)
    worst = std::max(worst, std::abs(weight(1.0, inside + 0.001) - weight(1.0, inside)));
  CHECK(worst <= 0.001 / 0.1 + 1e-12);
}
