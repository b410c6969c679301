// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of compare's units: nominals in metres or inches, measured and nominal streams in
// metres compared in mm, and nominals made on frames in another unit.
#include "compare_stream_fixtures.h"
#include "section/extras/generate.h"
#include "section/pipe/compare_stream.h"
#include "section/pipe/schema.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <string>

using namespace compare_stream_test;

TEST_CASE("compare stream: a nominal in metres or inches is converted or said to look so", "[compare]") {
  // A 40 mm section's points in metres: taken as metres from the extent, scaled to mm, the
  // section column left as it is; told mm, left as they are, with a word on their size.
  section::Table points("nominal", {"section", "u", "v"});
  for (int i = 0; i < 8; ++i) points.add_row({3, 0.02 * std::cos(i * 0.785), 0.004 * std::sin(i * 0.785)});
  section::Table metres = points;
  const section::InputUnits in = section::nominal_to_mm(nullptr, &metres, "");
  CHECK(in.mm == 1000);
  CHECK(in.warning.find("taken to be in metres") != std::string::npos);
  CHECK(in.warning.find("--nominal-units") != std::string::npos);
  CHECK(metres.at(0, 0) == 3);
  CHECK(metres.at(0, 1) == Approx(20));
  section::Table as_mm = points;
  CHECK(section::nominal_to_mm(nullptr, &as_mm, "mm").warning.find("0.04 mm: smaller than a blade") !=
        std::string::npos);
  CHECK(as_mm.values == points.values);
  // A mesh 1.6 across looks like inches: read as mm, with a word on it; given in, scaled.
  section::Mesh mesh;
  mesh.vertices = {{0, 0, 0}, {1.6, 0, 0}, {0, 0.3, 1}};
  mesh.triangles = {{0, 1, 2}};
  section::Mesh inches = mesh;
  const section::InputUnits doubtful = section::nominal_to_mm(&inches, nullptr, "");
  CHECK(doubtful.mm == 1);
  CHECK(doubtful.warning.find("looks like inches: give --nominal-units in") != std::string::npos);
  CHECK(section::nominal_to_mm(&inches, nullptr, "in").mm == 25.4);
  CHECK(inches.vertices[1].x() == Approx(1.6 * 25.4));
  CHECK_THROWS(section::nominal_to_mm(&inches, nullptr, "ft"));
}

TEST_CASE("compare stream: a measured stream in metres is compared in mm, on its own frames only",
          "[compare]") {
  const section::Mesh mesh = section::generate_mesh(section::compressor_blade(), 2000, 16);
  const section::Stream s = measured_stream(mesh, {16, 32});
  // The same stream in metres: its lengths scaled by 1/1000 (as read from um) and said in m.
  section::Stream in_m = s;
  in_m.units = "um";
  section::convert_to_mm(in_m);
  in_m.units = "m";
  REQUIRE(section::frames(in_m).at(0).origin.z() == Approx(0.016));
  section::CompareStreamOptions o;
  section::NominalSource source;
  source.mesh = &mesh;
  const section::Stream n = section::nominal_stream(source, section::frames(s), o);
  section::Stream mm = s, m = in_m;
  section::compare_stream(mm, n, o);
  section::compare_stream(m, n, o);
  CHECK(m.units == "mm");
  CHECK(compared_all(m));
  const auto a = compared(mm, "chord"), b = compared(m, "chord");
  REQUIRE(a.size() == 2);
  REQUIRE(b.size() == 2);
  for (const auto& [id, row] : a) {
    CHECK(b.at(id)[0] == Approx(row[0]).epsilon(1e-9));  // the chord in mm, not a thousandth of it
    CHECK(b.at(id)[1] == Approx(row[1]).margin(1e-6));
  }
  // A nominal made on the frames in metres lies on other planes: refused, not compared.
  const section::Stream wrong = section::nominal_stream(source, section::frames(in_m), o);
  section::Stream again = in_m;
  CHECK_THROWS_WITH(section::compare_stream(again, wrong, o),
                    Catch::Contains("other frames than this stream's: section 0's origin lies 15.984 mm"));
  // A nominal stream in metres is read in mm too.
  section::Stream n_m = n;
  n_m.units = "um";
  section::convert_to_mm(n_m);
  n_m.units = "m";
  section::Stream third = s;
  section::compare_stream(third, n_m, o);
  const auto c = compared(third, "chord");
  for (const auto& [id, row] : a) CHECK(c.at(id)[1] == Approx(row[1]).margin(1e-6));
}
