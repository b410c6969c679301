// SPDX-License-Identifier: GPL-3.0-or-later
// The input formats read from files written by other tools (tests/data/formats/, made by
// scripts/make_format_fixtures.py with laspy, pypcd4, pye57, Python's csv module and numpy): each
// gives the points of blade.xyz, exactly or to its format's precision; and bad files are
// refused with a message naming the file and what is wrong.
#include "section/cloud.h"
#include "section/error.h"
#include "section/io/cloud_io.h"

#include "thrown.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>

using namespace section;

namespace {

const std::string dir = std::string(SECTION_TEST_DATA) + "/formats/";

std::string bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string cloud_error(const std::string& bytes, const std::string& name) {
  return thrown([&] { parse_cloud(bytes, name, {}); });
}

// `bytes` with the byte at `at` set to `value`.
std::string with_byte(std::string bytes, std::size_t at, int value) {
  bytes.at(at) = static_cast<char>(value);
  return bytes;
}

}  // namespace

TEST_CASE(
    "formats: PTS, LAS, ascii PCD, E57 (ScaledInteger), semicolon and tab text give blade.xyz's "
    "points exactly",
    "[formats]") {
  const Cloud xyz = read_cloud(dir + "blade.xyz");
  REQUIRE(xyz.points.size() > 4000);
  for (const char* name :
       {"blade.pts", "blade_12_f3.las", "blade_14_f6.las", "blade_ascii.pcd", "blade_scaled.e57",
        "blade_semicolon.csv", "blade_semicolon.txt", "blade_tab.txt"}) {
    INFO(name);
    const Cloud c = read_cloud(dir + name);
    REQUIRE(c.points.size() == xyz.points.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < c.points.size(); ++i) differ += c.points[i] != xyz.points[i];
    CHECK(differ == 0);
  }
}

TEST_CASE("formats: binary float PCD gives the points to float precision, its NaN points dropped",
          "[formats]") {
  const Cloud xyz = read_cloud(dir + "blade.xyz");
  const Cloud c = read_cloud(dir + "blade_binary.pcd");  // 5 NaN points among them
  REQUIRE(c.points.size() == xyz.points.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < c.points.size(); ++i)
    for (int k = 0; k < 3; ++k) differ += c.points[i][k] != double(float(xyz.points[i][k]));
  CHECK(differ == 0);
}

TEST_CASE("formats: semicolon text reads decimal commas, PTS count lines are counted", "[formats]") {
  const Cloud a = parse_cloud("1,5;2,25;-3,0\n4;5;6\n", "a.txt", {});
  REQUIRE(a.points.size() == 2);
  CHECK(a.points[0] == Eigen::Vector3d(1.5, 2.25, -3.0));
  const Cloud b = parse_cloud("x;y;z\n1,5;2;3\n", "b.csv", {});
  CHECK(b.points[0] == Eigen::Vector3d(1.5, 2, 3));
  const Cloud t = parse_cloud("1\t2\t3\n", "t.txt", {});
  CHECK(t.points[0] == Eigen::Vector3d(1, 2, 3));
  const Cloud p = parse_cloud("2\n1 2 3 0 1 2 3\n4 5 6 0 1 2 3\n1\n7 8 9\n", "p.pts", {});
  CHECK(p.points.size() == 3);
  CHECK_THAT(cloud_error("3\n1 2 3\n4 5 6\n", "c.pts"),
             Catch::Contains("c.pts: its PTS count lines declare 3 points, the file holds 2"));
  CHECK_THAT(cloud_error("2\n1 2 3\n4 5\n", "d.pts"),
             Catch::Contains("d.pts:3: expected at least 3 columns"));
  CHECK_THAT(cloud_error("1;2;x\n", "e.txt"), Catch::Contains("e.txt:1: expected a number in column 3"));
}

TEST_CASE("formats: blank-separated text with decimal commas reads them as decimal points", "[formats]") {
  // "18,450 -3,589 25,111" (a European export): read as separators, the row was six
  // numbers and the point (18, 450, -3), a scan's garbage that slice cut into a section.
  const Cloud a = parse_cloud("18,450 -3,589 25,111\n18,541\t-3,730\t25,089 128 64 32\n", "a.xyz", {});
  REQUIRE(a.points.size() == 2);
  CHECK(a.points[0] == Eigen::Vector3d(18.450, -3.589, 25.111));
  CHECK(a.points[1] == Eigen::Vector3d(18.541, -3.730, 25.089));
  const Cloud h = parse_cloud("x y z\n1,5 2,25 -3,0\n", "h.txt", {});
  REQUIRE(h.points.size() == 1);
  CHECK(h.points[0] == Eigen::Vector3d(1.5, 2.25, -3.0));
  const Cloud c = parse_cloud("x,y,z\n1,2,3\n", "c.csv", {});
  CHECK(c.points[0] == Eigen::Vector3d(1, 2, 3));
  // Commas as separators stay so: comma-separated rows, with blanks after the commas, or
  // with decimal points.
  CHECK(parse_cloud("1,2,3\n", "p.xyz", {}).points[0] == Eigen::Vector3d(1, 2, 3));
  CHECK(parse_cloud("1, 2, 3\n", "q.xyz", {}).points[0] == Eigen::Vector3d(1, 2, 3));
  CHECK(parse_cloud("1.5,2 3 4\n", "r.xyz", {}).points[0] == Eigen::Vector3d(1.5, 2, 3));
  CHECK(parse_cloud("1 2 3,5\n", "s.xyz", {}).points[0] == Eigen::Vector3d(1, 2, 3));
  // A later row in the other style is refused by line, not read as other numbers.
  CHECK_THAT(cloud_error("1,5 2,5 3,5\n1,5,2,5 3 4\n", "t.xyz"), Catch::Contains("t.xyz:2:"));
}

TEST_CASE("formats: T-Blade3's .dat counts its sections of points", "[formats]") {
  // blade3d.*.dat: `POINTS SECTIONS`, then the sections' x y z rows (its camber lines: rows alone).
  const Cloud c =
      parse_cloud("   3   2\n1 2 3\n4 5 6\n7 8 9\n1 2 4\n4 5 7\n7 8 10\n", "blade3d.Case.dat", {});
  REQUIRE(c.points.size() == 6);
  CHECK(c.points[0] == Eigen::Vector3d(1, 2, 3));
  CHECK(c.points[5] == Eigen::Vector3d(7, 8, 10));
  CHECK(parse_cloud("1 2 3\n4 5 6\n", "meanline.sec1.dat", {}).points.size() == 2);
  CHECK_THAT(
      cloud_error("3 2\n1 2 3\n4 5 6\n7 8 9\n1 2 4\n", "t.dat"),
      Catch::Contains("t.dat: its count line `3 2` (points a section, sections) declares 6 points, the "
                      "file holds 4"));
  // Only the first line counts; two numbers later are a short row, a count of 0 is no count.
  CHECK_THAT(cloud_error("1 2 3\n3 2\n", "u.dat"), Catch::Contains("u.dat:2: expected at least 3 columns"));
  CHECK_THAT(cloud_error("0 2\n1 2 3\n", "v.dat"), Catch::Contains("v.dat:1: expected at least 3 columns"));
  CHECK_THAT(cloud_error("2.5 2\n1 2 3\n", "w.dat"), Catch::Contains("w.dat:1: expected at least 3 columns"));
  CHECK_THAT(cloud_error("3 2\n1 2 3\n", "b.xyz"), Catch::Contains("b.xyz:1: expected at least 3 columns"));
}

TEST_CASE("formats: bad PCD files are refused by name", "[formats]") {
  CHECK_THAT(cloud_error(bytes_of(dir + "compressed.pcd"), "c.pcd"),
             Catch::Contains("c.pcd: PCD DATA binary_compressed is not supported"));
  const std::string bin = bytes_of(dir + "blade_binary.pcd");
  CHECK_THAT(
      cloud_error(bin.substr(0, bin.size() - 10), "t.pcd"),
      Catch::Contains("t.pcd: PCD header declares 4403 points but the file holds only 4402 (truncated"));
  CHECK_THAT(cloud_error(bin + "abcd", "l.pcd"),
             Catch::Contains("4 bytes more than its PCD header declares"));
  const std::string head = "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n";
  const std::string two = "WIDTH 2\nHEIGHT 1\nPOINTS 2\nDATA ascii\n";
  CHECK(parse_cloud(head + two + "1 2 3\nnan nan nan\n", "a.pcd", {}).points.size() == 1);
  CHECK_THAT(cloud_error(head + two + "1 2 3\n4 5\n", "a.pcd"),
             Catch::Contains("a.pcd:11: expected 3 values, found 2"));
  CHECK_THAT(cloud_error(head + two + "1 2 3\n", "a.pcd"), Catch::Contains("ends after 1 of 2 points"));
  CHECK_THAT(cloud_error(head + two + "1 2 3\n1 2 3\n1 2 3\n", "a.pcd"),
             Catch::Contains("a.pcd:12: more points than the PCD header declares (2)"));
  CHECK_THAT(cloud_error(head + two + "1 2 3\n1 inf 3\n", "a.pcd"),
             Catch::Contains("a.pcd: point 2 has an infinite coordinate"));
  CHECK_THAT(cloud_error(head + "WIDTH 3\nHEIGHT 1\nPOINTS 2\nDATA ascii\n", "a.pcd"),
             Catch::Contains("PCD POINTS 2 is not WIDTH x HEIGHT = 3"));
  CHECK_THAT(cloud_error("VERSION 0.7\nFIELDS a b\nSIZE 4 4\nTYPE F F\nWIDTH 1\nPOINTS 1\nDATA ascii\n1 2\n",
                         "n.pcd"),
             Catch::Contains("n.pcd: PCD FIELDS lack x, y or z"));
  CHECK_THAT(cloud_error(head + "WIDTH 1\nDATA xyz\n", "h.pcd"),
             Catch::Contains("h.pcd:7: PCD DATA must be ascii"));
}

TEST_CASE("formats: bad LAS files and LAZ are refused by name", "[formats]") {
  const std::string las = bytes_of(dir + "blade_14_f6.las");
  CHECK_THAT(cloud_error(las.substr(0, las.size() - 100), "t.las"),
             Catch::Contains("t.las: LAS header declares 4398 points but the file holds only"));
  std::string laz = las;
  laz[104] = static_cast<char>(laz[104] | 0x80);  // what LASzip marks a compressed file with
  CHECK_THAT(cloud_error(laz, "c.laz"),
             Catch::Contains("c.laz: LAZ file without its LASzip VLR (corrupt file?)"));
  // An item version LASzip's version-2 decoders do not read (version 1: LASzip 1.x) is refused.
  std::string v1 = bytes_of(dir + "blade_12_f3.laz");
  const std::size_t vlr = v1.find("laszip encoded");
  REQUIRE(vlr != std::string::npos);
  v1[vlr - 2 + 54 + 38] = 1;  // the first item's version
  CHECK_THAT(cloud_error(v1, "v1.laz"),
             Catch::Contains("v1.laz: LAZ item version 1 is not supported (2 is): decompress it to LAS first "
                             "(laszip -i v1.laz -o FILE.las; pdal translate"));
  std::string short_record = las;
  short_record[105] = 20;  // a record shorter than format 6's 30 bytes
  short_record[106] = 0;
  CHECK_THAT(cloud_error(short_record, "r.las"),
             Catch::Contains("point record length 20 is shorter than format 6"));
  std::string v2 = las;
  v2[24] = 2;
  CHECK_THAT(cloud_error(v2, "v.las"), Catch::Contains("v.las: LAS version 2.4 is not supported"));
  CHECK_THAT(cloud_error(las.substr(0, 100), "h.las"),
             Catch::Contains("h.las: LAS header ends after 100 bytes"));
  std::string zero = las;
  std::memset(&zero[131], 0, 8);  // x scale 0
  CHECK_THAT(cloud_error(zero, "z.las"),
             Catch::Contains("LAS x scale factor or offset is zero or not finite"));
}

TEST_CASE("formats: a truncated or corrupt LAZ file is refused or read, never crashes", "[formats][laz]") {
  // blade_12_f3.laz (lazrs): point format 3 with 4 extra bytes, 5 chunks of up to 1000 points.
  const std::string laz = bytes_of(dir + "blade_12_f3.laz");
  const std::string f6 = bytes_of(dir + "blade_14_f6.laz");  // layered, one chunk
  CHECK_THAT(cloud_error(f6.substr(0, f6.size() - 3000), "t6.laz"),
             Catch::Contains("t6.laz: LAZ file ends inside its points (truncated file?)"));
  for (std::size_t at = 400; at < f6.size(); at += 1111) {
    INFO(at);
    const std::string e = cloud_error(with_byte(f6, at, f6[at] ^ 0x5A), "b6.laz");
    CHECK((e == "no error" || e.find("b6.laz: ") != std::string::npos));
  }
  CHECK_THAT(cloud_error(laz.substr(0, 40000), "t.laz"),
             Catch::Contains("t.laz: LAZ file ends inside its points (truncated file?)"));
  std::uint32_t count = 0;
  std::memcpy(&count, laz.data() + 107, 4);
  REQUIRE(count == 4398);
  std::string more = laz;
  count = 44000;
  std::memcpy(&more[107], &count, 4);
  CHECK_THAT(
      cloud_error(more, "m.laz"),
      Catch::Contains("m.laz: LAZ chunk table lists 5 chunks, its header's points make 44 (corrupt file?)"));
  for (std::size_t cut = 100; cut < laz.size(); cut += 1777)
    CHECK_THAT(cloud_error(laz.substr(0, cut), "t.laz"), Catch::Contains("t.laz: "));
  // A flipped byte in the compressed points decodes to other points or is refused; nothing else.
  for (std::size_t at = 500; at < laz.size(); at += 1231) {
    INFO(at);
    const std::string e = cloud_error(with_byte(laz, at, laz[at] ^ 0x5A), "b.laz");
    CHECK((e == "no error" || e.find("b.laz: ") != std::string::npos));
  }
}

TEST_CASE("formats: LAS takes its record length and offset from the header", "[formats]") {
  // blade_14_f6.las: format 6 with 4 extra bytes a record (34, not 30) and offsets (10, -5, 30).
  const std::string las = bytes_of(dir + "blade_14_f6.las");
  std::uint16_t record = 0;
  std::memcpy(&record, las.data() + 105, 2);
  CHECK(record == 34);
  double offset = 0;
  std::memcpy(&offset, las.data() + 163, 8);
  CHECK(offset == -5);
}

TEST_CASE("formats: E57 scans with poses, double, float, scaled and spherical, give blade.xyz's points",
          "[formats][e57]") {
  // blade_scans.e57 (pye57): the points in four scans, each in its own frame and posed back
  // into the file's: doubles with 5 invalid points among them, floats, ScaledInteger (1e-6),
  // spherical (range, azimuth, elevation). Read: merged in file order, invalid points dropped.
  const Cloud xyz = read_cloud(dir + "blade.xyz");
  const Cloud c = read_cloud(dir + "blade_scans.e57");
  REQUIRE(c.points.size() == xyz.points.size());
  const std::size_t quarter = (xyz.points.size() + 3) / 4;
  double worst[4] = {0, 0, 0, 0};
  for (std::size_t i = 0; i < c.points.size(); ++i) {
    double& w = worst[std::min<std::size_t>(i / quarter, 3)];
    w = std::max(w, (c.points[i] - xyz.points[i]).norm());
  }
  CHECK(worst[0] < 1e-9);  // double
  CHECK(worst[1] < 1e-5);  // float: coordinates up to ~70 mm in the scan's frame, ulp 8e-6 mm
  CHECK(worst[2] < 2e-6);  // 1e-6 mm steps
  CHECK(worst[3] < 1e-9);  // double range and angles
  // Standard input: by its first bytes.
  const std::string bytes = bytes_of(dir + "blade_scans.e57");
  CHECK(parse_cloud(bytes, "-", {}).points.size() == xyz.points.size());
}

TEST_CASE("formats: bad E57 files are refused by name and place", "[formats][e57]") {
  CHECK_THAT(cloud_error(bytes_of(dir + "codec.e57"), "c.e57"),
             Catch::Contains("c.e57: E57 scan 1 ('tiny'): its points use the codec 'zLibCodec', which is not "
                             "supported (only bitPackCodec is)"));
  CHECK_THAT(cloud_error(bytes_of(dir + "no_z.e57"), "z.e57"),
             Catch::Contains("z.e57: E57 scan 1 ('tiny'): its points have neither cartesianX, Y and Z"));
  CHECK_THAT(cloud_error(bytes_of(dir + "packet.e57"), "p.e57"),
             Catch::Contains("p.e57: E57 scan 1 ('tiny')'s data packet at byte 80 holds 7 bytestreams, its "
                             "prototype 3 fields"));
  const std::string e57 = bytes_of(dir + "blade_scans.e57");
  CHECK_THAT(
      cloud_error(e57.substr(0, 50000), "t.e57"),
      Catch::Contains("t.e57: E57 header declares 82944 bytes but the file holds only 50000 (truncated"));
  CHECK_THAT(cloud_error(with_byte(e57, 5000, e57[5000] ^ 4), "f.e57"),
             Catch::Contains("f.e57: E57 page 4 (bytes 4096 to 5119) fails its CRC-32C checksum (corrupt"));
  CHECK_THAT(cloud_error(with_byte(e57, 8, 2), "v.e57"),
             Catch::Contains("v.e57: E57 version 2.0 is not supported"));
  CHECK_THAT(cloud_error(e57.substr(0, 20), "h.e57"),
             Catch::Contains("h.e57: E57 header ends after 20 bytes"));
}

TEST_CASE("formats: a truncated or corrupt E57 file is refused, never crashes", "[formats][e57]") {
  const std::string e57 = bytes_of(dir + "blade_scans.e57");
  for (std::size_t cut = 8; cut < e57.size(); cut += 997)
    CHECK_THAT(cloud_error(e57.substr(0, cut), "t.e57"), Catch::Contains("t.e57: E57 "));
  for (std::size_t at = 0; at < e57.size(); at += 1231) {
    INFO(at);
    CHECK_THAT(cloud_error(with_byte(e57, at, e57[at] ^ 0x5A), "b.e57"), Catch::Contains("b.e57: E57 "));
  }
}
