// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of compare's units: nominals in metres or inches, measured and nominal streams in
// metres compared in mm, nominals made on frames in another unit, and the nominal's file.
#include "compare_stream_fixtures.h"
#include "section/extras/generate.h"
#include "section/io/file.h"
#include "section/io/mesh_io.h"
#include "section/pipe/nominal_file.h"
#include "section/pipe/compare_stream.h"
#include "section/pipe/schema.h"

#include <catch2/catch.hpp>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
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

namespace {

std::string temp_file(const std::string& name, const std::string& text) {
  const std::string path = std::string(std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp") +
                           "/libsection_nominal_" + std::to_string(::getpid()) + "_" + name;
  section::write_file(path, text);
  return path;
}

}  // namespace

TEST_CASE("read_nominal: a mesh by its extension, a stream by its first line, else points", "[compare]") {
  // Points 40 mm across written in metres: read as points, taken as metres, in mm.
  const std::string points =
      temp_file("points.csv", "section,u,v\n3,0.02,0\n3,0,0.004\n3,-0.02,0\n3,0,-0.004\n");
  const section::NominalFile p = section::read_nominal(points);
  CHECK(p.kind == section::NominalFile::Kind::points);
  CHECK(p.source().points == &p.points);
  CHECK(p.source().mesh == nullptr);
  CHECK(p.units.mm == 1000);
  CHECK(p.points.at(0, 1) == Approx(20));
  CHECK(section::read_nominal(points, "mm").points.at(0, 1) == 0.02);
  // A stream in metres: in mm, and no unit may be given for it.
  section::Stream s;
  s.units = "m";
  section::Table frames("frames", {"section", "origin_x", "origin_y", "origin_z", "u_x", "u_y", "u_z", "v_x",
                                   "v_y", "v_z", "n_x", "n_y", "n_z"});
  frames.add_row({0, 0, 0, 0.016, 1, 0, 0, 0, 1, 0, 0, 0, 1});
  s.put(frames);
  const std::string stream = temp_file("stream.csv", section::format_stream(s));
  const section::NominalFile n = section::read_nominal(stream);
  CHECK(n.kind == section::NominalFile::Kind::stream);
  CHECK(n.stream.units == "mm");
  CHECK(section::frames(n.stream).at(0).origin.z() == Approx(16));
  CHECK_THROWS_WITH(section::read_nominal(stream, "m"),
                    Catch::Contains(stream + ": --nominal-units: a stream says its own unit"));
  // A mesh by its extension, whatever the case; a file that is none of them names itself.
  section::Mesh mesh;
  mesh.vertices = {{0, 0, 0}, {40, 0, 0}, {0, 8, 1}, {0, 0, 2}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}};
  const std::string stl = temp_file("mesh.STL", "");
  section::write_mesh(stl, mesh);
  const section::NominalFile m = section::read_nominal(stl);
  CHECK(m.kind == section::NominalFile::Kind::mesh);
  CHECK(m.mesh.vertices.size() == 4);
  CHECK(m.units.mm == 1);
  const std::string bad = temp_file("bad.csv", "section,u,v\n3,nan,0\n");
  CHECK_THROWS_WITH(section::read_nominal(bad), Catch::Contains(bad));
  for (const std::string& f : {points, stream, stl, bad}) std::remove(f.c_str());
}
