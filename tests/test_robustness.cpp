// SPDX-License-Identifier: GPL-3.0-or-later
// Hostile input to the readers and the pipe parser (docs/ROBUSTNESS.md): each is refused
// with a section::Error naming the file and the problem, never a crash or an allocation
// failure. The tool-level cases are in tests/tools/test_robustness.sh.
#include "section/cloud.h"
#include "section/error.h"
#include "section/mesh.h"
#include "section/io/stream.h"
#include "section/io/csv.h"
#include "section/io/cloud_io.h"
#include "section/io/mesh_io.h"

#include "thrown.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <utility>
#include <vector>
#include <unistd.h>

using namespace section;

namespace {

std::string cloud_error(const std::string& bytes, const std::string& name,
                        CloudFormat format = CloudFormat::automatic) {
  CloudReadOptions opt;
  opt.format = format;
  return thrown([&] { parse_cloud(bytes, name, opt); });
}

std::string stream_error(const std::string& text) {
  return thrown([&] { parse_stream(text, "s.csv"); });
}

std::string mesh_error(const std::string& bytes, const std::string& ext) {
  const std::string path = "/tmp/section_robust_" + std::to_string(::getpid()) + "." + ext;
  std::ofstream(path, std::ios::binary) << bytes;
  const std::string what = thrown([&] { read_mesh(path); });
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
                        "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
                        "ply"),
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
  CHECK_THAT(mesh_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99\n", "obj"),
             Catch::Contains("line 4: the face refers to vertex 99"));
  CHECK_THAT(mesh_error("OFF\n3 1 0\n1e20 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "off"), Catch::Contains("beyond"));
}

namespace {

// Reads `bytes` as a mesh file with extension `ext`.
Mesh mesh_of(const std::string& bytes, const std::string& ext) {
  const std::string path = "/tmp/section_robust_mesh_" + std::to_string(::getpid()) + "." + ext;
  std::ofstream(path, std::ios::binary) << bytes;
  Mesh m;
  try {
    m = read_mesh(path);
  } catch (...) {
    std::remove(path.c_str());
    throw;
  }
  std::remove(path.c_str());
  return m;
}

// Total area and area-weighted normal of the triangles: a fan of the right polygons gives
// the known values exactly.
double area(const Mesh& m) {
  double a = 0;
  for (const auto& t : m.triangles)
    a += 0.5 * (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]).norm();
  return a;
}

// A unit square (a quad) and a triangle of area 0.5 standing on its edge y = 0: area 1.5.
const char* square_and_triangle_vertices[] = {"0 0 0", "1 0 0", "1 1 0", "0 1 0", "0 0 1"};

std::string binary_ply(bool big_endian) {
  std::string s = std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") +
                  " 1.0\nelement vertex 5\nproperty double x\nproperty float y\nproperty short z\n"
                  "property uchar red\nelement face 2\nproperty list uchar int vertex_indices\n"
                  "property ushort flags\nend_header\n";
  const auto put = [&](const void* p, std::size_t n) {
    std::string b(static_cast<const char*>(p), n);
    if (big_endian) std::reverse(b.begin(), b.end());  // the test host is little endian
    s += b;
  };
  const double xs[] = {0, 1, 1, 0, 0};
  const float ys[] = {0, 0, 1, 1, 0};
  const short zs[] = {0, 0, 0, 0, 1};
  for (int i = 0; i < 5; ++i) {
    put(&xs[i], 8);
    put(&ys[i], 4);
    put(&zs[i], 2);
    s += '\x7f';
  }
  const std::vector<std::vector<int>> faces = {{0, 1, 2, 3}, {0, 1, 4}};
  for (const auto& f : faces) {
    s += static_cast<char>(f.size());
    for (int i : f) put(&i, 4);
    const unsigned short flags = 7;
    put(&flags, 2);
  }
  return s;
}

}  // namespace

TEST_CASE("read_mesh: OFF, OBJ and PLY in the forms other writers use", "[robustness][mesh]") {
  std::string off = "# comment\nCOFF 5 2 0\n";
  for (const char* v : square_and_triangle_vertices) off += std::string(v) + " 255 0 0 255  # colour\n";
  off += "\n4 0 1 2 3 0.5 0.5 0.5\n3 0 1 4\n";
  std::string obj = "mtllib x.mtl\no part\n";
  for (const char* v : square_and_triangle_vertices) obj += "v " + std::string(v) + "\n";
  obj += "vt 0 0\nvn 0 0 1\ng top\ns off\nf 1/1/1 2/1/1 3//1 4\nf -5 -4 -1\n";
  std::string ply =
      "ply\r\nformat ascii 1.0\r\ncomment made by hand\r\nelement vertex 5\r\nproperty float x\r\n"
      "property float y\r\nproperty float z\r\nproperty float nx\r\nelement face 2\r\n"
      "property list uchar uint vertex_indices\r\nelement edge 1\r\nproperty int vertex1\r\n"
      "property int vertex2\r\nend_header\r\n";
  for (const char* v : square_and_triangle_vertices) ply += std::string(v) + " 0\r\n";
  ply += "4 0 1 2 3\r\n3 0 1 4\r\n0 1\r\n";
  for (const auto& [bytes, ext] : std::vector<std::pair<std::string, std::string>>{
           {off, "off"}, {obj, "obj"}, {ply, "ply"}, {binary_ply(false), "ply"}, {binary_ply(true), "ply"}}) {
    CAPTURE(ext, bytes.substr(0, 40));
    const Mesh m = mesh_of(bytes, ext);
    CHECK(m.vertices.size() == 5);
    CHECK(m.triangles.size() == 3);
    CHECK(area(m) == Approx(1.5).epsilon(1e-12));
    CHECK(m.vertices[4].isApprox(Eigen::Vector3d(0, 0, 1)));
  }
  // 4OFF: homogeneous coordinates are divided out.
  const Mesh h = mesh_of("4OFF\n3 1 0\n0 0 0 2\n2 0 0 2\n0 4 0 2\n3 0 1 2\n", "off");
  CHECK(area(h) == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("read_mesh: a garbled OFF, OBJ or PLY body is refused with its line", "[robustness][mesh]") {
  const std::string off = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n";
  CHECK_THAT(mesh_error("OFF\n2 1\n\x10 0 0\n", "off"),
             Catch::Contains("line 3: vertex 0: expected a number, found '\\x10'"));
  CHECK_THAT(mesh_error("OFF\v2 1 \x10" + std::string(1, '\0') + "0\n", "off"),
             Catch::Contains("binary data in a text file"));  // the fuzzer's hang
  CHECK_THAT(mesh_error(off + "-3 0 1 2\n", "off"),
             Catch::Contains("line 6: face 0 has a negative vertex count -3"));
  CHECK_THAT(mesh_error(off + "4 0 1 2\n", "off"), Catch::Contains("line 6: face 0 announces 4 vertices"));
  CHECK_THAT(mesh_error(off + "3 0 1 3\n", "off"), Catch::Contains("line 6: face 0 has the vertex index 3"));
  CHECK_THAT(mesh_error(off + "3 0 1 x\x01\n", "off"), Catch::Contains("found 'x\\x01'"));
  CHECK_THAT(mesh_error(off, "off"), Catch::Contains("line 5: the file ends after 0 of 1 faces"));
  CHECK_THAT(mesh_error("OFF\n3 1 0\n0 0 0\n1 zero 0\n", "off"),
             Catch::Contains("line 4: vertex 1: expected a number, found 'zero'"));
  CHECK_THAT(mesh_error("OFF BINARY\n" + std::string(12, '\0'), "off"),
             Catch::Contains("binary OFF is not supported"));
  CHECK_THAT(mesh_error("nOFF 4 3 1 0\n", "off"), Catch::Contains("only 3 is supported"));
  CHECK_THAT(mesh_error("XOFF 3 1 0\n", "off"), Catch::Contains("malformed OFF header"));

  CHECK_THAT(mesh_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 /2\n", "obj"),
             Catch::Contains("line 4: expected a vertex index, found '/2'"));
  CHECK_THAT(mesh_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n", "obj"),
             Catch::Contains("line 4: the face refers to vertex 0"));
  CHECK_THAT(mesh_error("v 0 0 0\nv 1 0 0\nf 1 2\n", "obj"),
             Catch::Contains("line 3: a face needs at least 3 vertices"));
  CHECK_THAT(mesh_error("v 0 0\n", "obj"), Catch::Contains("line 1: a vertex needs x, y and z"));
  CHECK_THAT(mesh_error("v 0 0 nan\n", "obj"), Catch::Contains("line 1: non-finite coordinate 'nan'"));

  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\n";
  CHECK_THAT(mesh_error(ply + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "ply"),
             Catch::Contains("line 9: unexpected PLY header line starting '0'"));  // OpenMesh hung
  CHECK_THAT(mesh_error(ply + "end_header\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n", "ply"),
             Catch::Contains("line 11: vertex 1: fewer values than the header declares"));
  CHECK_THAT(mesh_error(ply + "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 7\n", "ply"),
             Catch::Contains("line 13: face 0: more values than the header declares"));
  CHECK_THAT(mesh_error(ply + "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n", "ply"),
             Catch::Contains("face 0 has the vertex index 5 (the mesh has 3 vertices"));
  CHECK_THAT(mesh_error(ply + "0", "ply"), Catch::Contains("truncated PLY header (no end_header)"));
  CHECK_THAT(mesh_error(ply + "end_header\n0 0 0\n1 0 0\n0 1 0\n", "ply"),
             Catch::Contains("the file ends after 0 of 1 face elements"));
  CHECK_THAT(mesh_error(ply + "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n", "ply"),
             Catch::Contains("line 13: face 0: expected an integer, found '1.5'"));
  std::string binary = binary_ply(false);
  CHECK_THAT(mesh_error(binary.substr(0, binary.size() - 3), "ply"),
             Catch::Contains("the file ends inside face 1"));
  binary[binary.find("end_header\n") + 11 + 5 * 15] = '\xff';  // the first face's count: 255
  CHECK_THAT(mesh_error(binary, "ply"), Catch::Contains("the file ends inside face 0"));
}

TEST_CASE("read_mesh: STL, ascii and binary, shares the corners of its triangles", "[robustness][mesh]") {
  // The unit square as two triangles: 4 distinct corners, area 1.
  const float tri[2][3][3] = {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}, {{0, 0, 0}, {1, 1, 0}, {-0.0f, 1, 0}}};
  std::string ascii = "solid square\r\n";
  for (const auto& t : tri) {
    ascii += "  FACET NORMAL 0 0 1\r\n    outer loop\r\n";
    for (const auto& c : t)
      ascii += "      vertex " + std::to_string(c[0]) + " " + std::to_string(c[1]) + " " +
               std::to_string(c[2]) + "\r\n";
    ascii += "    endloop\r\n  endfacet\r\nendsolid square\r\nsolid second\r\n";
  }
  ascii += "endsolid second\r\n";
  std::string binary = "solid written by a CAD program";  // binary headers may start with "solid"
  binary.resize(80, ' ');
  const std::uint32_t n = 2;
  binary.append(reinterpret_cast<const char*>(&n), 4);
  for (const auto& t : tri) {
    const float normal[3] = {0, 0, 1};
    binary.append(reinterpret_cast<const char*>(normal), 12);
    binary.append(reinterpret_cast<const char*>(t), 36);
    binary.append(2, '\0');
  }
  for (const std::string& bytes : {ascii, binary}) {
    const Mesh m = mesh_of(bytes, "stl");
    CHECK(m.vertices.size() == 4);  // -0 and 0 are one corner
    CHECK(m.triangles.size() == 2);
    CHECK(area(m) == Approx(1.0).epsilon(1e-12));
  }
  CHECK_THAT(mesh_error(binary.substr(0, 120), "stl"),
             Catch::Contains("declares 2 triangles (184 bytes) but the file has only 120"));
  CHECK_THAT(mesh_error(ascii.substr(0, 72), "stl"), Catch::Contains("line 4: the file ends inside a facet"));
  CHECK_THAT(mesh_error("solid x\nfacet normal 0 0 1\nouter loop\nvertex 1 zero 0\n", "stl"),
             Catch::Contains("line 4: expected a number, found 'zero'"));
  CHECK_THAT(mesh_error("facet normal 0 0 1\n", "stl"), Catch::Contains("neither an ascii STL"));
}
