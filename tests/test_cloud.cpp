// SPDX-License-Identifier: GPL-3.0-or-later
#include "section/cloud.h"
#include "section/error.h"
#include "section/mesh.h"
#include "section/io/cloud_io.h"
#include "section/io/mesh_io.h"

#include "thrown.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <mutex>
#include <random>
#include <unistd.h>
#include <algorithm>

using namespace section;

namespace {

std::string error_of(const std::string& text, const std::string& name, CloudReadOptions opt = {}) {
  return thrown([&] { parse_cloud(text, name, opt); });
}

std::string temp_path(const std::string& ext) {
  static int counter = 0;
  return "/tmp/section_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++) + ext;
}

// The points of `path` read in chunks of `chunk_points`; `chunks` counts the chunks.
std::vector<Eigen::Vector3d> read_in_chunks(const std::string& path, std::size_t chunk_points,
                                            std::size_t& chunks) {
  CloudReadOptions opt;
  opt.chunk_points = chunk_points;
  std::vector<Eigen::Vector3d> got;
  read_cloud_chunks(
      path,
      [&](const Eigen::Vector3d* p, std::size_t n) {
        ++chunks;
        got.insert(got.end(), p, p + n);
      },
      opt);
  return got;
}

template <class T>
void put(std::string& out, T v, bool big) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (big) std::reverse(b, b + sizeof(T));
  out.append(reinterpret_cast<char*>(b), sizeof(T));
}

}  // namespace

TEST_CASE("read_cloud: XYZ with spaces, tabs, commas, extra columns and comments", "[cloud]") {
  const Cloud c =
      parse_cloud("# comment\n1 2 3\n4\t5\t6 7 8\n\n-1.5e-3,2,+3, 9\n// other comment\n", "a.xyz");
  REQUIRE(c.points.size() == 3);
  CHECK(c.points[1] == Eigen::Vector3d(4, 5, 6));
  CHECK(c.points[2] == Eigen::Vector3d(-1.5e-3, 2, 3));
}

TEST_CASE("read_cloud: CSV with a header in any column order", "[cloud]") {
  const Cloud c = parse_cloud("id,Z,y,x\n1,3,2,1\n2,6,5,4\n", "a.csv");
  REQUIRE(c.points.size() == 2);
  CHECK(c.points[0] == Eigen::Vector3d(1, 2, 3));
  CHECK(c.points[1] == Eigen::Vector3d(4, 5, 6));
}

TEST_CASE("read_cloud: bad text names the file and the line", "[cloud]") {
  CHECK_THAT(error_of("1 2 3\n4 5\n", "b.xyz"), Catch::Contains("b.xyz:2") && Catch::Contains("columns"));
  CHECK_THAT(error_of("1 2 3\n4 abc 6\n", "b.xyz"), Catch::Contains("b.xyz:2") && Catch::Contains("'abc'"));
  CHECK_THAT(error_of("1 2 3\n4 nan 6\n", "b.xyz"),
             Catch::Contains("b.xyz:2") && Catch::Contains("non-finite"));
  CHECK_THAT(error_of("1 2 3\n4 inf 6\n", "b.xyz"), Catch::Contains("non-finite"));
  CHECK_THAT(error_of("", "b.xyz"), Catch::Contains("b.xyz") && Catch::Contains("empty"));
  CHECK_THAT(error_of("# only a comment\n", "b.xyz"), Catch::Contains("no points"));
  CHECK_THAT(error_of("a,b,c\n1,2,3\n", "b.csv"), Catch::Contains("b.csv:1") && Catch::Contains("header"));
  CHECK_THAT(error_of("x y z\n1 2 3\n4 5\n", "b.xyz"), Catch::Contains("b.xyz:3"));
  CHECK_THAT(error_of(std::string("1 2 3\n\0\0\0", 9), "b.xyz"), Catch::Contains("binary"));
  CHECK_THAT(error_of("1 2 3\n" + std::string(100000, '1') + "\n", "b.xyz"),
             Catch::Contains("b.xyz:2") && Catch::Contains("longer"));
}

TEST_CASE("read_cloud: PLY ascii and binary, both endians, float and double", "[cloud]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-100, 100);
  std::vector<Eigen::Vector3d> pts(1000);
  for (auto& p : pts) p = {U(rng), U(rng), U(rng)};
  for (const std::string format : {"binary_little_endian", "binary_big_endian", "ascii"}) {
    for (const std::string type : {"float", "double"}) {
      const bool big = format == "binary_big_endian";
      std::string s = "ply\nformat " + format + " 1.0\ncomment test\nelement vertex " +
                      std::to_string(pts.size()) + "\nproperty " + type +
                      " x\nproperty uchar red\nproperty " + type + " y\nproperty " + type +
                      " z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n";
      for (const auto& p : pts) {
        if (format == "ascii") {
          char line[128];
          std::snprintf(
              line, sizeof line, "%.17g 7 %.17g %.17g\n", type == "float" ? double(float(p.x())) : p.x(),
              type == "float" ? double(float(p.y())) : p.y(), type == "float" ? double(float(p.z())) : p.z());
          s += line;
          continue;
        }
        for (int k = 0; k < 3; ++k) {
          if (type == "float")
            put<float>(s, float(p[k]), big);
          else
            put<double>(s, p[k], big);
          if (k == 0) put<unsigned char>(s, 7, big);
        }
      }
      const Cloud c = parse_cloud(s, "c.ply");
      REQUIRE(c.points.size() == pts.size());
      for (std::size_t i = 0; i < pts.size(); ++i) {
        INFO(format << " " << type << " point " << i);
        // float files hold the value to float precision; double files exactly
        const double tol = type == "float" ? 1e-7 * pts[i].norm() : 0.0;
        REQUIRE((c.points[i] - pts[i]).norm() <= tol);
      }
      // Truncation and lying headers are caught, with the file named.
      if (format == "ascii")
        CHECK_THAT(error_of(s.substr(0, s.size() - 40), "t.ply"),
                   Catch::Contains("t.ply:1011") && Catch::Contains("vertex values"));
      else
        CHECK_THAT(error_of(s.substr(0, s.size() - 40), "t.ply"),
                   Catch::Contains("t.ply") && Catch::Contains("truncated"));
    }
  }
  CHECK_THAT(error_of("ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float "
                      "x\nproperty float y\n"
                      "property float z\nend_header\n0000",
                      "huge.ply"),
             Catch::Contains("huge.ply") && Catch::Contains("4000000000"));
  CHECK_THAT(error_of("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n", "h.ply"),
             Catch::Contains("end_header"));
  CHECK_THAT(
      error_of(
          "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
          "end_header\n1 2 3\n1 2 x\n",
          "a.ply"),
      Catch::Contains("a.ply:9"));
}

TEST_CASE("read_cloud: files stream in chunks and write_cloud round-trips", "[cloud]") {
  Cloud c;
  for (int i = 0; i < 5000; ++i) c.points.emplace_back(i * 0.1, -i / 3.0, 1e-7 * i);
  for (const std::string ext : {".xyz", ".ply"}) {
    const std::string path = temp_path(ext);
    write_cloud(path, c);
    std::size_t chunks = 0;
    const std::vector<Eigen::Vector3d> got = read_in_chunks(path, 777, chunks);
    std::remove(path.c_str());
    CHECK(chunks == (5000 + 776) / 777);
    REQUIRE(got == c.points);
  }
  CHECK_THROWS_WITH(read_cloud("/nonexistent/x.xyz"), Catch::Contains("/nonexistent/x.xyz"));
}

TEST_CASE("mean_spacing: a regular grid gives its pitch", "[cloud]") {
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < 100; ++i)
    for (int j = 0; j < 100; ++j) pts.emplace_back(0.08 * i, 0.08 * j, 0);
  CHECK(mean_spacing(pts) == Approx(0.08).epsilon(1e-9));
}

TEST_CASE("read_mesh: STL, OBJ, OFF round-trip and bad files are named", "[mesh]") {
  Mesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  for (const std::string ext : {".stl", ".obj", ".off", ".ply"}) {
    const std::string path = temp_path(ext);
    write_mesh(path, m);
    CHECK(is_mesh_file(path));
    const Mesh r = read_mesh(path);
    std::remove(path.c_str());
    CHECK(r.triangles.size() == 4);
    double volume = 0;
    for (const auto& t : r.triangles)
      volume += r.vertices[t[0]].dot(r.vertices[t[1]].cross(r.vertices[t[2]])) / 6;
    CHECK(volume == Approx(1.0 / 6));
  }
  const std::string bad = temp_path(".off");
  std::ofstream(bad) << "OFF\n3 1 0\n0 0 0\n1 0\n";
  CHECK_THROWS_WITH(read_mesh(bad), Catch::Contains(bad));
  std::remove(bad.c_str());
  CHECK_THROWS_WITH(read_mesh("/nonexistent/m.stl"), Catch::Contains("/nonexistent/m.stl"));
}

TEST_CASE("formats: the extension picks the reader, the content when there is none", "[cloud][mesh]") {
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n1 2 3\n";
  CHECK(parse_cloud(ply, "scan").points.at(0) == Eigen::Vector3d(1, 2, 3));        // no extension: by content
  CHECK(parse_cloud("4 5 6\n", "scan").points.at(0) == Eigen::Vector3d(4, 5, 6));  // else XYZ
  CHECK(parse_cloud("7,8,9\n", "SCAN.XYZN").points.at(0) == Eigen::Vector3d(7, 8, 9));
  CHECK(error_of("1 2 3\n", "part.stl") == "read_cloud: part.stl: is a mesh, not a point cloud");
  CHECK(error_of("1 2 3\n", "d.x/scan.fls") ==
        "read_cloud: d.x/scan.fls: unknown point cloud extension '.fls' (use .xyz .asc .txt .pts .csv .ply "
        ".pcd .las .laz .e57 .dat)");
  CHECK(error_of("1 2 3\n", "d.x/scan") == "no error");  // a dot in a directory is no extension
  // A PLY file is a mesh when its header declares faces.
  const std::string mesh = temp_path(".ply"), cloud = temp_path(".ply");
  std::ofstream(mesh)
      << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
         "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
         "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  std::ofstream(cloud) << ply;
  CHECK(is_mesh_file(mesh));
  CHECK(read_mesh(mesh).triangles.size() == 1);
  CHECK_FALSE(is_mesh_file(cloud));
  CHECK_FALSE(is_mesh_file(temp_path(".xyz")));
  CHECK_THROWS_WITH(read_mesh(cloud), Catch::Contains("the mesh has no faces"));
  std::remove(mesh.c_str());
  std::remove(cloud.c_str());
  const std::string xyz = temp_path(".xyz");
  std::ofstream(xyz) << "1 2 3\n";
  CHECK_THROWS_WITH(read_mesh(xyz), Catch::Contains("unknown mesh extension (use .stl .obj .off .ply)"));
  std::remove(xyz.c_str());
}

TEST_CASE("formats: the cloud and mesh readers decode a PLY header alike", "[cloud][mesh]") {
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n";
  const auto both = [&](const std::string& rest) {
    const std::string path = temp_path(".ply");
    std::ofstream(path) << head + rest;
    const std::string cloud = error_of(head + rest, "h.ply"), mesh = thrown([&] { read_mesh(path); });
    std::remove(path.c_str());
    // The same words, placed each in its reader's way: "h.ply:6: ..." and "FILE: line 6: ...".
    const std::string what = cloud.substr(cloud.find(':', cloud.find("h.ply:") + 6) + 2);
    CHECK_THAT(mesh, Catch::EndsWith(": line 6: " + what));
    return what;
  };
  CHECK(both("property flot z\nend_header\n") == "unknown property type 'flot'");
  CHECK(both("property float\nend_header\n") == "bad property line");
  CHECK(both("properly float z\nend_header\n") == "unexpected PLY header line starting 'properly'");
  CHECK(both("element face -1\nend_header\n") == "bad element count '-1'");
}

TEST_CASE("read_cloud: every row layout reads the same numbers, odd rows are refused with their line",
          "[cloud]") {
  // The reader has a fast path for plain rows; each layout below must give the numbers
  // themselves whatever path reads it.
  const std::vector<std::string> rows = {
      "1.5 -2 3e-3",        "1.5\t-2\t3e-3",     "  1.5 -2 3e-3  ",  "1.5,-2,3e-3",       "1.5, -2, 3e-3",
      "1.5 , -2 , 3e-3",    "+1.5 -2 +3e-3",     "1.5 -2 3e-3 7 8",  "1.5,-2,3e-3,",      "1.5 -2 3e-3\r",
      "1.5 -2 3e-3 # note", "\t1.5 -2 3e-3\t\r", "1.5E0 -2.0 0.003", "1.5,-2,3e-3,extra", ".15e1 -2. 3E-3"};
  std::mt19937 rng(5);
  std::string text;
  std::vector<std::size_t> kind;
  for (int i = 0; i < 3000; ++i) {
    kind.push_back(rng() % rows.size());
    text += rows[kind.back()] + "\n";
    if (rng() % 50 == 0) text += "# comment\n\n";
  }
  for (int threads : {1, 2}) {
    CloudReadOptions opt;
    opt.threads = threads;
    const Cloud c = parse_cloud(text, "rows.xyz", opt);
    REQUIRE(c.points.size() == kind.size());
    for (std::size_t i = 0; i < kind.size(); ++i) {
      INFO("row '" << rows[kind[i]] << "'");
      REQUIRE(c.points[i] == Eigen::Vector3d(1.5, -2, 3e-3));
    }
  }
  // Rows the fast path must not take: the general reader words the error, with the line.
  const std::string head = "1 2 3\n4 5 6\n";
  CHECK_THAT(error_of(head + "1 2 3x\n", "r.xyz"), Catch::Contains("r.xyz:3") && Catch::Contains("'3x'"));
  CHECK_THAT(error_of(head + "1\r2 3\n", "r.xyz"), Catch::Contains("r.xyz:3") && Catch::Contains("columns"));
  CHECK_THAT(error_of(head + "1,,2,3\n", "r.xyz"), Catch::Contains("r.xyz:3") && Catch::Contains("column 2"));
  CHECK_THAT(error_of(head + "1 2 inf\n", "r.xyz"),
             Catch::Contains("r.xyz:3") && Catch::Contains("non-finite"));
  CHECK_THAT(error_of(head + "1 2 -nan\n", "r.xyz"),
             Catch::Contains("r.xyz:3") && Catch::Contains("non-finite"));
  CHECK_THAT(error_of(head + "++1 2 3\n", "r.xyz"), Catch::Contains("r.xyz:3") && Catch::Contains("'++1'"));
  CHECK_THAT(error_of(head + "0x10 2 3\n", "r.xyz"), Catch::Contains("r.xyz:3") && Catch::Contains("'0x10'"));
  CHECK_THAT(error_of(head + "1 2\n", "r.xyz"), Catch::Contains("r.xyz:3") && Catch::Contains("columns"));
  // No final newline: the last row still counts.
  CHECK(parse_cloud(head + "7 8 9", "r.xyz").points.back() == Eigen::Vector3d(7, 8, 9));
}

TEST_CASE("read_cloud: a text file larger than one read window keeps every row and line number", "[cloud]") {
  // ~20 MB: more than one 16 MiB window, so rows straddle a window boundary.
  std::string text;
  text.reserve(21 << 20);
  const int n = 600000;
  char line[96];
  for (int i = 0; i < n; ++i) {
    std::snprintf(line, sizeof line, "%.17g %.17g %.17g\n", i * 1e-3, -i * 7e-4, 0.5 + i * 1e-9);
    text += line;
  }
  const std::string path = temp_path(".xyz");
  std::ofstream(path, std::ios::binary) << text;
  std::size_t count = 0;
  bool in_order = true;
  read_cloud_chunks(path, [&](const Eigen::Vector3d* p, std::size_t m) {
    for (std::size_t k = 0; k < m; ++k, ++count) in_order = in_order && p[k].x() == double(count) * 1e-3;
  });
  CHECK(count == std::size_t(n));
  CHECK(in_order);
  // A bad row past the first window is named by its line.
  text.replace(text.rfind('\n', text.size() - 2) + 1, 1, "z");
  std::ofstream(path, std::ios::binary) << text;
  CHECK_THROWS_WITH(read_cloud(path), Catch::Contains(path + ":" + std::to_string(n) + ":"));
  std::remove(path.c_str());
}

TEST_CASE("read_cloud: packed double PLY, aligned or not, in chunks, with its errors", "[cloud]") {
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < 5000; ++i) pts.emplace_back(i * 0.25, -i / 3.0, std::sin(i));
  // The comment shifts the vertex data: aligned and unaligned to 8 bytes.
  for (const std::string comment : {"", "x", "xy", "xyz", "xyzw"}) {
    const std::string header = "ply\nformat binary_little_endian 1.0\ncomment " + comment +
                               "\nelement vertex " + std::to_string(pts.size()) +
                               "\nproperty double x\nproperty double y\nproperty double z\nend_header\n";
    std::string body(reinterpret_cast<const char*>(pts.data()), pts.size() * 24);
    const std::string path = temp_path(".ply");
    std::ofstream(path, std::ios::binary) << header << body;
    std::size_t chunks = 0;
    const std::vector<Eigen::Vector3d> got = read_in_chunks(path, 999, chunks);
    INFO("header of " << header.size() << " bytes");
    CHECK(chunks == (pts.size() + 998) / 999);
    CHECK(got == pts);
    // A NaN at vertex 3210 and a value beyond 1e15 at vertex 4321 (index, 0-based).
    std::string bad = body;
    const double nan = std::numeric_limits<double>::quiet_NaN(), huge = 1e16;
    std::memcpy(&bad[3210 * 24 + 8], &nan, 8);
    CHECK_THAT(error_of(header + bad, "n.ply"), Catch::Contains("n.ply: vertex 3210 has a non-finite"));
    bad = body;
    std::memcpy(&bad[4321 * 24 + 16], &huge, 8);
    CHECK_THAT(error_of(header + bad, "h.ply"), Catch::Contains("h.ply: point 4322 has a coordinate beyond"));
    CHECK_THAT(error_of(header + body.substr(0, 24 * 4000 + 5), "t.ply"),
               Catch::Contains("t.ply") && Catch::Contains("truncated"));
    std::remove(path.c_str());
  }
}

TEST_CASE("read_cloud: a packed double PLY file is read in parts by the threads, in order, with its errors",
          "[cloud]") {
  // 40000 points in one chunk: two parts of 20000 read side by side by two threads.
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < 40000; ++i) pts.emplace_back(i * 0.25, -i / 3.0, std::cos(i));
  const std::string header = "ply\nformat binary_little_endian 1.0\nelement vertex " +
                             std::to_string(pts.size()) +
                             "\nproperty double x\nproperty double y\nproperty double z\nend_header\n";
  const std::string body(reinterpret_cast<const char*>(pts.data()), pts.size() * 24);
  const std::string path = temp_path(".ply");
  const auto read_with = [&](const std::string& bytes, int threads, std::size_t chunk) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << header << bytes;
    CloudReadOptions opt;
    opt.chunk_points = chunk;
    opt.threads = threads;
    std::vector<Eigen::Vector3d> got;
    read_cloud_chunks(
        path, [&](const Eigen::Vector3d* p, std::size_t n) { got.insert(got.end(), p, p + n); }, opt);
    return got;
  };
  for (int threads : {1, 2, 3})
    for (std::size_t chunk : {std::size_t(40000), std::size_t(33333), std::size_t(1) << 20}) {
      INFO("threads " << threads << " chunk " << chunk);
      CHECK(read_with(body, threads, chunk) == pts);
    }
  // Bad vertices in both parts: the first in the file is the one named, whatever the threads.
  std::string bad = body;
  const double nan = std::numeric_limits<double>::quiet_NaN(), huge = 1e16;
  std::memcpy(&bad[30001 * 24 + 8], &nan, 8);
  std::memcpy(&bad[25000 * 24 + 16], &huge, 8);
  for (int threads : {1, 2}) {
    std::string message;
    try {
      read_with(bad, threads, 40000);
    } catch (const section::Error& e) {
      message = e.what();
    }
    CHECK_THAT(message, Catch::Contains(path + ": point 25001 has a coordinate beyond"));
  }
  std::memcpy(&bad[25000 * 24 + 16], &pts[25000].z(), 8);
  CHECK_THROWS_WITH(read_with(bad, 2, 40000), Catch::Contains(path + ": vertex 30001 has a non-finite"));
  // A file cut short is refused before any point is handed on.
  std::size_t handed = 0;
  std::ofstream(path, std::ios::binary | std::ios::trunc) << header << body.substr(0, 24 * 30000 + 7);
  CHECK_THROWS_WITH(read_cloud_chunks(path, [&](const Eigen::Vector3d*, std::size_t n) { handed += n; }),
                    Catch::Contains("truncated"));
  CHECK(handed == 0);
  std::remove(path.c_str());
}

TEST_CASE("read_cloud_chunks_parallel: chunks not wanted are passed over, the others in order", "[cloud]") {
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < 10000; ++i) pts.emplace_back(i * 0.5, std::sin(i), -i / 7.0);
  // A packed double PLY (read side by side, the chunks not wanted not read) and a float PLY
  // (read in turn): the same chunks either way.
  const std::string packed = temp_path(".ply"), floats = temp_path(".ply");
  write_cloud(packed, Cloud{pts});
  std::string body;
  for (const auto& p : pts)
    for (int c = 0; c < 3; ++c) {
      const float f = static_cast<float>(p[c]);
      body.append(reinterpret_cast<const char*>(&f), 4);
    }
  std::ofstream(floats, std::ios::binary)
      << "ply\nformat binary_little_endian 1.0\nelement vertex " << pts.size()
      << "\nproperty float x\nproperty float y\nproperty float z\nend_header\n"
      << body;
  for (const std::string& path : {packed, floats})
    for (int threads : {1, 2}) {
      INFO(path << " threads " << threads);
      CloudReadOptions opt;
      opt.chunk_points = 999;
      opt.threads = threads;
      std::mutex mutex;
      std::vector<std::size_t> worked, merged;
      std::vector<double> xs;
      const std::size_t total = read_cloud_chunks_parallel(
          path,
          [&](std::size_t k, const Eigen::Vector3d*, std::size_t, int) {
            std::lock_guard<std::mutex> lock(mutex);
            worked.push_back(k);
          },
          [&](std::size_t k, const Eigen::Vector3d* p, std::size_t n) {
            merged.push_back(k);
            for (std::size_t i = 0; i < n; ++i) xs.push_back(p[i].x());
          },
          opt, [](std::size_t k) { return k % 3 == 1; });
      CHECK(total == pts.size());
      std::sort(worked.begin(), worked.end());
      const std::vector<std::size_t> wanted{1, 4, 7, 10};
      CHECK(worked == wanted);
      CHECK(merged == wanted);
      REQUIRE(xs.size() == 3 * 999 + 10);  // the last chunk holds 10 points
      CHECK(xs.front() == pts[999].x());
      CHECK(xs[999] == pts[4 * 999].x());
      CHECK(xs.back() == pts[9999].x());
    }
  std::remove(packed.c_str());
  std::remove(floats.c_str());
}
