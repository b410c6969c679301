// SPDX-License-Identifier: GPL-3.0-or-later
// Sections are processed in parallel; results are stored by index, so every stage's output
// must be byte-identical whatever the thread count.
#include "section/camber.h"
#include "section/cloud.h"
#include "section/error.h"
#include "section/fit_spline.h"
#include "section/extras/generate.h"
#include "section/io/stream.h"
#include "section/io/cloud_io.h"
#include "section/io/slice_file.h"
#include "section/pipe/slice_stream.h"
#include "section/pipe/smooth_stream.h"
#include "section/pipe/fit_spline_stream.h"
#include "section/pipe/camber_stream.h"
#include "section/slice.h"
#include "section/smooth.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <string>
#include <unistd.h>
#include <vector>

namespace {

// A band 3 mm high of a generated scan from z_min up (0.12 mm spacing, 5 um noise).
section::Scan band_scan(const section::BladeDesign& blade, double z_min, unsigned seed) {
  section::ScanOptions so;
  so.spacing = 0.12;
  so.noise = 0.005;
  so.z_min = z_min;
  so.z_max = z_min + 3;
  so.seed = seed;
  return section::generate_scan(blade, so);
}

// A thin band of a generated turbine scan (z in [11, 14] mm), sliced by 3 planes; section
// 3 at z = 40 misses the band and must fail alone.
section::Stream sliced(int threads) {
  const section::Scan scan = band_scan(section::turbine_blade(), 11, 7);
  section::SliceOptions opt;
  opt.threads = threads;
  const auto planes = section::planes_at({0, 0, 1}, {11.5, 12.5, 13.5, 40});
  return section::to_stream(section::slice(scan.cloud, planes, opt), "slice test");
}

struct Run {
  std::string slice, smooth, fit, camber;
};

Run pipeline(int threads) {
  Run run;
  section::Stream s = sliced(threads);
  run.slice = section::format_stream(s);
  section::SmoothOptions so;
  so.threads = threads;
  section::smooth_stream(s, so);
  run.smooth = section::format_stream(s);
  section::FitSplineOptions fo;
  fo.threads = threads;
  fo.samples = 50;
  section::fit_spline_stream(s, fo);
  run.fit = section::format_stream(s);
  section::CamberOptions co;
  co.threads = threads;
  section::camber_stream(s, co);
  run.camber = section::format_stream(s);
  return run;
}

}  // namespace

TEST_CASE("parallel: every stage writes the same stream with 1 and 2 threads", "[parallel]") {
  const Run one = pipeline(1);
  const Run two = pipeline(2);
  CHECK(one.slice == two.slice);
  CHECK(one.smooth == two.smooth);
  CHECK(one.fit == two.fit);
  CHECK(one.camber == two.camber);
  // The run did real work: three measured sections and one failed section all the way down.
  const section::Stream s = section::parse_stream(two.camber, "camber");
  REQUIRE(s.find("params") != nullptr);
  CHECK(s.find("params")->rows() == 3);
  int slice_issues = 0;
  for (const auto& i : s.issues)
    if (i.stage == "slice" && i.section == 3) ++slice_issues;
  CHECK(slice_issues == 1);
}

TEST_CASE("parallel: a failing loop is reported in order among good ones", "[parallel]") {
  // Loops 0 and 2 are circles of radius 2 and 3 mm; loop 1 (section 1) has too few points.
  section::Table points{"points", {"section", "loop", "index", "u", "v", "nu", "nv"}, {}};
  const double pi = 3.14159265358979323846;
  for (int sec : {0, 1, 2}) {
    const int n = sec == 1 ? 4 : 300;
    const double r = 2 + 0.5 * sec;
    for (int i = 0; i < n; ++i) {
      const double t = 2 * pi * i / n;
      points.add_row(
          {double(sec), 0.0, double(i), r * std::cos(t), r * std::sin(t), std::cos(t), std::sin(t)});
    }
  }
  for (int threads : {1, 2, 3}) {
    section::Stream s;
    s.put(points);
    section::SmoothOptions so;
    so.threads = threads;
    section::smooth_stream(s, so);
    REQUIRE(s.issues.size() == 1);
    CHECK(s.issues[0].section == 1);
    CHECK(s.issues[0].stage == "smooth");
    const section::Table& stats = *s.find("smooth_stats");
    REQUIRE(stats.rows() == 2);
    CHECK(stats.at(0, 0) == 0);
    CHECK(stats.at(1, 0) == 2);
  }
}

TEST_CASE("parallel: XYZ text parsed by several threads keeps points and line numbers", "[parallel]") {
  // 300000 lines (~8 MB) so the block is split; comments and blank lines shift line numbers.
  std::string text = "# scan\n\n";
  for (int i = 0; i < 300000; ++i) {
    text += std::to_string(i) + " " + std::to_string(i % 977) + ".25 " + std::to_string(-i) + "e-3\n";
    if (i % 50000 == 7) text += "# comment\n\n";
  }
  section::CloudReadOptions one, two;
  one.threads = 1;
  two.threads = 2;
  const section::Cloud a = section::parse_cloud(text, "big.xyz", one);
  const section::Cloud b = section::parse_cloud(text, "big.xyz", two);
  REQUIRE(a.points.size() == 300000);
  REQUIRE(b.points.size() == 300000);
  CHECK(a.points == b.points);
  CHECK(b.points[123456] == Eigen::Vector3d(123456, 123456 % 977 + 0.25, -123.456));

  // A bad cell deep in the file and a later one: the first is reported, with its line.
  std::size_t pos = 0;
  int line = 1;
  while (line < 250000) pos = text.find('\n', pos) + 1, ++line;
  std::string bad = text;
  bad.replace(pos, 1, "x");
  std::size_t pos2 = pos;
  for (int k = 0; k < 30000; ++k) pos2 = bad.find('\n', pos2) + 1;
  bad.replace(pos2, 1, "y");
  for (const auto& opt : {one, two}) {
    try {
      section::parse_cloud(bad, "big.xyz", opt);
      FAIL("no error");
    } catch (const section::Error& e) {
      CHECK(std::string(e.what()).find("big.xyz:250000: expected a number in column 1") != std::string::npos);
    }
  }
}

TEST_CASE("slice: a cloud in memory hands each section on as it is done, in plane order, the sampling first",
          "[parallel][slice]") {
  // (The slice tool writes each to the pipe from there, for standard input and views.)
  const section::Scan scan = band_scan(section::turbine_blade(), 11, 7);
  const auto planes = section::planes_at({0, 0, 1}, {11.5, 12.5, 13.5, 40});
  for (int threads : {1, 2}) {
    section::SliceOptions opt;
    opt.threads = threads;
    std::vector<std::string> told;
    section::SliceResult sunk;
    const section::SliceResult r = section::slice(
        scan.cloud, planes, opt,
        [&](const section::SectionSlice& s) {
          told.push_back("section " + std::to_string(s.id));
          sunk.sections.push_back(s);
        },
        [&](const section::Sampling& s) { told.push_back(section::sampling_kind_name(s.kind)); });
    CHECK(told == std::vector<std::string>{"dense", "section 0", "section 1", "section 2", "section 3"});
    sunk.slab = r.slab;
    sunk.sampling = r.sampling;
    sunk.points = r.points;
    CHECK(section::format_stream(section::to_stream(sunk, "t")) ==
          section::format_stream(section::to_stream(r, "t")));
    CHECK_FALSE(r.sections[3].error.empty());  // the plane off the band fails, handed on in its place
  }
}

TEST_CASE("slice_file: one pass over a PLY file when the planes guessed from a first look hold, two when not",
          "[parallel][slice]") {
  section::ScanOptions so;
  so.spacing = 0.2;
  so.noise = 0.005;
  so.seed = 5;
  section::Scan scan = section::generate_scan(section::turbine_blade(), so);
  const std::string path = "/tmp/libsection_test_one_pass_" + std::to_string(::getpid()) + ".ply";
  section::CloudReadOptions small_chunks;
  small_chunks.chunk_points = 10007;  // many chunks, boundaries anywhere
  // The same sections as the held cloud sliced with the planes and slab found.
  const auto same_as_held = [&](const section::Cloud& cloud, const section::PlaneSpec& spec, int passes) {
    section::write_cloud(path, cloud);
    const section::SliceResult r = section::slice_file(path, spec, {}, small_chunks);
    CHECK(r.file_passes == passes);
    section::SliceOptions held;
    held.slab = r.slab;
    std::vector<section::Plane> planes;
    for (const auto& s : r.sections) planes.push_back({s.frame.origin, s.frame.n});
    for (const auto& s : r.sections) CHECK(s.error.empty());
    CHECK(section::format_stream(section::to_stream(r, "t")) ==
          section::format_stream(section::to_stream(section::slice(cloud, planes, held), "t")));
    return r;
  };
  SECTION("planes spread over the extent: the first look finds it, and keeps the band's points") {
    const section::SliceResult r = same_as_held(scan.cloud, section::PlaneSpec{{}, {0, 0, 1}, 3}, 1);
    for (const auto& sec : r.sections) CHECK(sec.band_points > sec.slab_points);  // no read for them
  }
  SECTION("explicit planes, the slab estimated") {
    same_as_held(scan.cloud, section::PlaneSpec{section::planes_at({0, 0, 1}, {15, 30, 45}), {0, 0, 1}, 0},
                 1);
  }
  SECTION("holes in the scan: the points beside the planes, read again for the gaps") {
    so.holes = 40;
    so.spacing = 0.1;
    const section::Scan holed = section::generate_scan(section::turbine_blade(), so);
    const section::SliceResult r = same_as_held(holed.cloud, section::PlaneSpec{{}, {0, 0, 1}, 6}, 2);
    int filled = 0;
    for (const auto& sec : r.sections) filled += sec.fill.gaps_filled;
    CHECK(filled > 0);
  }
  SECTION("a lone point above the blade, which the first look misses: the file is read again") {
    auto& p = scan.cloud.points;
    p.insert(p.begin() + std::ptrdiff_t(p.size() / 2 + 1), Eigen::Vector3d(10, 0, 62));
    same_as_held(scan.cloud, section::PlaneSpec{{}, {0, 0, 1}, 3}, 2);
  }
  SECTION("a lone point far above the blade, a stray: the planes are the blade's, read once") {
    section::write_cloud(path, scan.cloud);
    const section::SliceResult clean =
        section::slice_file(path, section::PlaneSpec{{}, {0, 0, 1}, 3}, {}, small_chunks);
    auto& p = scan.cloud.points;
    p.insert(p.begin() + std::ptrdiff_t(p.size() / 2 + 1), Eigen::Vector3d(10, 0, 70));
    const section::SliceResult r = same_as_held(scan.cloud, section::PlaneSpec{{}, {0, 0, 1}, 3}, 1);
    CHECK(r.extent.strays == 1);
    CHECK(r.extent.highest == 70);
    for (std::size_t k = 0; k < r.sections.size(); ++k)
      CHECK(r.sections[k].frame.origin == clean.sections[k].frame.origin);
  }
  SECTION("XYZ text: no first look, two passes") {
    const std::string xyz = path + ".xyz";
    section::write_cloud(xyz, scan.cloud);
    CHECK(section::slice_file(xyz, section::PlaneSpec{{}, {0, 0, 1}, 3}, {}).file_passes == 2);
    std::remove(xyz.c_str());
  }
  std::remove(path.c_str());
}

TEST_CASE("slice_file: streaming the file gives the same sections as slicing the held cloud",
          "[parallel][slice]") {
  const section::Scan scan = band_scan(section::compressor_blade(), 20, 11);
  const std::string path = "/tmp/libsection_test_slice_file_" + std::to_string(::getpid()) + ".ply";
  section::write_cloud(path, scan.cloud);
  section::CloudReadOptions small_chunks;
  small_chunks.chunk_points = 10007;  // many chunks, boundaries anywhere
  section::SliceOptions opt;
  opt.slab = 0.12;
  // --count: two passes; planes from the extent, as planes_across on the held cloud.
  const auto planes = section::planes_across(scan.cloud.points, {0, 0, 1}, 3);
  const auto held = section::to_stream(section::slice(scan.cloud, planes, opt), "t");
  const auto streamed = section::to_stream(
      section::slice_file(path, section::PlaneSpec{{}, {0, 0, 1}, 3}, opt, small_chunks), "t");
  CHECK(section::format_stream(held) == section::format_stream(streamed));
  // Explicit planes, one pass.
  const auto one_pass =
      section::to_stream(section::slice_file(path, section::PlaneSpec{planes, {0, 0, 1}, 0}, opt), "t");
  CHECK(section::format_stream(held) == section::format_stream(one_pass));
  // Default slab: estimated from a random sample, within 15% of the held cloud's estimate.
  opt.slab = 0;
  const auto r = section::slice_file(path, section::PlaneSpec{planes, {0, 0, 1}, 0}, opt);
  const double full = section::mean_spacing(scan.cloud.points);
  CHECK(std::abs(r.slab - full) <= 0.15 * full);
  for (const auto& s : r.sections) CHECK(s.error.empty());
  std::remove(path.c_str());
}
