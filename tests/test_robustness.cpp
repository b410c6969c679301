// Hostile input to the readers and the pipe parser (docs/ROBUSTNESS.md): each is refused
// with a section::Error naming the file and the problem, never a crash or an allocation
// failure. The tool-level cases are in tests/tools/test_robustness.sh.
#include "section/cloud.h"
#include "section/error.h"
#include "section/mesh.h"
#include "section/pipe.h"

#include <catch2/catch.hpp>

#include <cstdio>
#include <fstream>
#include <string>
#include <unistd.h>

using namespace section;

namespace {

std::string cloud_error(const std::string& bytes, const std::string& name,
                        CloudFormat format = CloudFormat::automatic) {
  CloudReadOptions opt;
  opt.format = format;
  try {
    parse_cloud(bytes, name, opt);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

std::string stream_error(const std::string& text) {
  try {
    parse_stream(text, "s.csv");
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

std::string mesh_error(const std::string& bytes, const std::string& ext) {
  const std::string path = "/tmp/section_robust_" + std::to_string(::getpid()) + "." + ext;
  std::ofstream(path, std::ios::binary) << bytes;
  std::string what = "no error";
  try {
    read_mesh(path);
  } catch (const Error& e) {
    what = e.what();
  }
  std::remove(path.c_str());
  return what;
}

const std::string bom = "\xEF\xBB\xBF";

std::string utf16le(const std::string& ascii) {
  std::string out = "\xFF\xFE";
  for (char c : ascii) out += std::string{c, '\0'};
  return out;
}

}  // namespace

TEST_CASE("robustness: a UTF-8 BOM is skipped, UTF-16 is refused by name", "[robustness]") {
  const Cloud c = parse_cloud(bom + "1 2 3\n4 5 6\n", "b.xyz", {});
  REQUIRE(c.points.size() == 2);
  CHECK(c.points[0].x() == 1.0);
  CHECK_THAT(cloud_error(utf16le("1 2 3\n"), "u.xyz"), Catch::Contains("u.xyz: UTF-16"));
  CHECK_THAT(cloud_error(utf16le("x,y,z\n1,2,3\n").substr(2), "u.csv", CloudFormat::csv),
             Catch::Contains("UTF-16"));  // no BOM: told by the NUL bytes
  CHECK_THAT(cloud_error(std::string("1 2 3\n\0\0\1", 9), "b.xyz"), Catch::Contains("binary data"));

  const std::string s = "# libsection-stream 1\n# table t\na,b\n1,2\n";
  const Stream st = parse_stream(bom + s, "s.csv");
  REQUIRE(st.tables.size() == 1);
  CHECK(st.tables[0].values == std::vector<double>{1, 2});
  CHECK_THAT(stream_error(utf16le(s)), Catch::Contains("s.csv: UTF-16"));
  CHECK(parse_profile(bom + "1 2\n3 4\n", "p.dat").size() == 2);
  CHECK_THROWS_WITH(parse_csv(utf16le("a,b\n1,2\n"), "t.csv"), Catch::Contains("UTF-16"));
}

TEST_CASE("robustness: coordinates beyond 1e15 are refused, not overflowed", "[robustness]") {
  CHECK_THAT(cloud_error("1 2 3\n4 5 6\n1e300 0 0\n", "g.xyz"),
             Catch::Contains("g.xyz: point 3 has a coordinate beyond"));
  CHECK(parse_cloud("1e14 -1e14 0\n", "ok.xyz", {}).points.size() == 1);  // large but usable
  CHECK_THAT(stream_error("# libsection-stream 1\n# table t\na,b\n1,-2e300\n"),
             Catch::Contains("s.csv:4: column 'b' of table 't': value -2e300 is beyond"));
  CHECK_THROWS_WITH(parse_profile("1 2\n1e16 0\n", "p.dat"), Catch::Contains("p.dat:2: coordinate beyond"));
}

TEST_CASE("robustness: long cells and lines give bounded messages", "[robustness]") {
  const std::string nan_payload = "nan(" + std::string(100000, 'a') + ")";
  const std::string what = stream_error("# libsection-stream 1\n# table t\na\n" + nan_payload + "\n");
  CHECK_THAT(what, Catch::Contains("s.csv:4"));
  CHECK(what.size() < 200);
  CHECK_THAT(cloud_error(std::string(1 << 20, '1') + " 2 3\n", "l.xyz"),
             Catch::Contains("l.xyz:1: line longer than"));
}

TEST_CASE("robustness: mesh headers claiming billions of elements are refused before reading",
          "[robustness]") {
  CHECK_THAT(mesh_error("OFF\n4000000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "off"),
             Catch::Contains("declares 4000000000 vertices"));
  CHECK_THAT(mesh_error("OFF\n3 4000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "off"),
             Catch::Contains("declares 4000000000 faces"));
  CHECK_THAT(mesh_error("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                        "property float z\nelement face 3000000000\nproperty list uchar int vertex_indices\n"
                        "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "ply"),
             Catch::Contains("declares 3000000000 face elements"));
  // Honest small files still read.
  const Mesh m = [] {
    const std::string path = "/tmp/section_robust_ok_" + std::to_string(::getpid()) + ".off";
    std::ofstream(path) << "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    Mesh mesh = read_mesh(path);
    std::remove(path.c_str());
    return mesh;
  }();
  CHECK(m.triangles.size() == 1);
  CHECK_THAT(mesh_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99\n", "obj"), Catch::Contains("no faces"));
  CHECK_THAT(mesh_error("OFF\n3 1 0\n1e20 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "off"), Catch::Contains("beyond"));
}
