// SPDX-License-Identifier: GPL-3.0-or-later
#include "section/error.h"
#include "section/pipe/schema.h"
#include "section/units.h"

#include <catch2/catch.hpp>

#include <string>

using namespace section;

TEST_CASE("units: millimetres per unit", "[units]") {
  CHECK(mm_per_unit("mm") == 1);
  CHECK(mm_per_unit("m") == 1000);
  CHECK(mm_per_unit("cm") == 10);
  CHECK(mm_per_unit("um") == 0.001);
  CHECK(mm_per_unit("in") == 25.4);
  try {
    mm_per_unit("furlong");
    FAIL("an unknown unit is refused");
  } catch (const Error& e) {
    CHECK(std::string(e.what()) == "units: unknown length unit 'furlong' (known: mm, m, cm, um, in)");
  }
}

TEST_CASE("units: the likely unit of a blade from its extent", "[units]") {
  CHECK(guess_unit(0.2).unit == "m");
  CHECK(guess_unit(0.2).doubtful);
  CHECK(guess_unit(0.999).unit == "m");
  CHECK(guess_unit(1).unit == "in");
  CHECK(guess_unit(2.8).unit == "in");  // a 70 mm blade in inches
  CHECK(guess_unit(2.8).doubtful);
  CHECK_FALSE(guess_unit(10).doubtful);
  CHECK(guess_unit(45).unit == "mm");
  CHECK_FALSE(guess_unit(10000).doubtful);
  CHECK(guess_unit(20000).unit == "um");
  CHECK_FALSE(guess_unit(0).doubtful);  // unknown extent: mm, no warning
}

TEST_CASE("units: an input's unit, given or guessed", "[units]") {
  const InputUnits given = input_units("in", 0.5);
  CHECK(given.mm == 25.4);
  CHECK(given.warning.empty());  // a unit given is not second-guessed ...
  // ... unless it makes the input larger or smaller than any blade (a scan in mm said to be in
  // m, one in m said to be in um): converted as given, with a warning naming the option.
  const InputUnits huge = input_units("m", 41.6, "--nominal-units");
  CHECK(huge.mm == 1000);
  CHECK(huge.warning ==
        "the input is 41.6 m across, 4.16e+04 mm: larger than a blade (1 mm to 10 m); check "
        "--nominal-units");
  CHECK(input_units("um", 60).warning.find("0.06 mm: smaller than a blade") != std::string::npos);
  CHECK(input_units("m", 0.06).warning.empty());
  const InputUnits metres = input_units("", 0.21);
  CHECK(metres.unit == "m");
  CHECK(metres.mm == 1000);
  CHECK(metres.warning.find("taken to be in metres") != std::string::npos);
  const InputUnits micro = input_units("", 35000);
  CHECK(micro.mm == 1);  // kept as mm: said, not converted, and doubtful
  CHECK(micro.doubtful);
  CHECK(micro.warning.find("--units um") != std::string::npos);
  const InputUnits inches = input_units("", 2.8);
  CHECK((inches.mm == 1 && inches.doubtful));
  CHECK(inches.warning.find("--units in") != std::string::npos);
  CHECK(inches.note.rfind("units_doubtful in", 0) == 0);
  CHECK_FALSE(input_units("mm", 2.8).doubtful);  // a small blade in mm, said so
  const InputUnits mm = input_units("", 40);
  CHECK((mm.mm == 1 && mm.warning.empty() && mm.note.empty()));
  CHECK_THROWS_AS(input_units("yard", 40), Error);
}

TEST_CASE("units: a stream in metres converted to mm by its columns' units", "[units]") {
  Stream s;
  s.units = "m";
  Table points = schema::points.table();
  points.add_row({0, 0, 3, 0.010, -0.002, 0.6, 0.8, 0.0005});
  s.put(points);
  Table stats = schema::smooth_stats.table();
  std::vector<double> row(stats.columns.size(), 2.0);
  stats.add_row(row);
  s.put(stats);
  Table knots = schema::spline_knots.table();
  knots.add_row({0, 0, 1, 0.25});
  s.put(knots);
  convert_to_mm(s);
  CHECK(s.units == "mm");
  const Table& p = *s.find("points");
  CHECK(p.at(0, p.column("index")) == 3);                      // an id
  CHECK(p.at(0, p.column("u")) == Approx(10).epsilon(1e-15));  // a length
  CHECK(p.at(0, p.column("nu")) == 0.6);                       // a unit vector's component
  CHECK(p.at(0, p.column("offset")) == Approx(0.5));
  const Table& st = *s.find("smooth_stats");
  CHECK(st.at(0, st.column("energy_before")) == Approx(2e6));  // a squared length
  CHECK(st.at(0, st.column("points")) == 2);                   // a count
  CHECK(s.find("spline_knots")->at(0, 3) == 0.25);             // a curve parameter
  Stream unknown;
  unknown.units = "furlong";
  CHECK_THROWS_AS(convert_to_mm(unknown), Error);
}

TEST_CASE("units: numbers in messages get three digits and their unit", "[units]") {
  CHECK(format_length(0.025885718878794383) == "0.0259 mm");  // issue 24's example
  CHECK(format_length(17.269) == "17.3 mm");
  CHECK(format_length(1234.7) == "1235 mm");   // no exponent
  CHECK(format_length(0.5) == "0.5 mm");       // no trailing zeros
  CHECK(format_length(0.00001234) == "0 mm");  // 0.1 um is the finest length shown
  CHECK(format_length(0.00012) == "0.0001 mm");
  CHECK(format_length(-0.0123456) == "-0.0123 mm");
  CHECK(format_length(0) == "0 mm");
  CHECK(format_length(-1e300) == "-1e+300 mm");  // the first 63 digits of 301 before
  CHECK(format_angle(0.178123) == "0.178 deg");
  CHECK(format_angle(-72.8081) == "-72.8 deg");
  CHECK(format_angle(0.0001) == "0 deg");
  CHECK(format_share(0.05) == "5%");
  CHECK(format_share(0.025886) == "2.59%");
  CHECK(format_share(0.4512) == "45.1%");
}
