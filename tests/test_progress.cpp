// SPDX-License-Identifier: GPL-3.0-or-later
// The progress and cancel hook (progress.h, io/progress_io.h): the same results as without
// it, counts that grow to the total, and a cancel that stops the call with Cancelled; the
// section sinks of meshes and surfaces of revolution.
#include "section/extras/generate.h"
#include "section/extras/generate_rotor.h"
#include "section/io/progress_io.h"
#include "section/revolution.h"
#include "section/slice.h"
#include "thrown.h"

#include <catch2/catch.hpp>

#include <cstdio>
#include <string>
#include <unistd.h>
#include <vector>

using namespace section;

namespace {

// A scan of the turbine blade between heights 10 and 40 (mm), about 200 000 points.
const Cloud& scan() {
  static const Cloud cloud = [] {
    ScanOptions o;
    o.spacing = 0.1;
    o.z_min = 10;
    o.z_max = 40;
    return generate_scan(turbine_blade(), o).cloud;
  }();
  return cloud;
}

std::string written(const std::string& ext) {
  const std::string path = "/tmp/section_progress_" + std::to_string(::getpid()) + ext;
  write_cloud(path, scan());
  return path;
}

}  // namespace

TEST_CASE("progress: read_cloud reports the points read and reads the same", "[progress]") {
  for (const std::string ext : {".ply", ".xyz"}) {
    const std::string path = written(ext);
    CloudReadOptions o;
    o.chunk_points = 10000;
    std::vector<ProgressEvent> events;
    const Cloud got = read_cloud(path, o, [&](const ProgressEvent& e) {
      events.push_back(e);
      return true;
    });
    INFO(ext);
    REQUIRE(got.points == read_cloud(path).points);
    REQUIRE(events.size() >= got.points.size() / 10000);
    for (std::size_t i = 1; i < events.size(); ++i) REQUIRE(events[i].done > events[i - 1].done);
    REQUIRE(events.back().done == got.points.size());
    REQUIRE(std::string(events.back().stage) == "read");
    REQUIRE(events.back().total == (ext == ".ply" ? got.points.size() : 0));
    // Cancelled after the third report: the call stops with Cancelled.
    int calls = 0;
    REQUIRE(thrown([&] { read_cloud(path, o, [&](const ProgressEvent&) { return ++calls < 3; }); }) ==
            "read: cancelled");
    REQUIRE(calls == 3);
    std::remove(path.c_str());
  }
}

TEST_CASE("progress: slice_file reports each section in order, and a cancel stops it", "[progress]") {
  const std::string path = written(".ply");
  const PlaneSpec planes{planes_at({0, 0, 1}, {12, 16, 20, 24, 28, 32, 36}), {0, 0, 1}, 0};
  SliceOptions o;
  o.slab = 0.1;
  std::vector<std::size_t> done;
  std::vector<int> ids;
  const SliceResult with = slice_file(
      path, planes, o, {}, [&](const SectionSlice& s) { ids.push_back(s.id); },
      [&](const ProgressEvent& e) {
        REQUIRE(e.total == 7);
        done.push_back(e.done);
        return true;
      });
  REQUIRE(done == std::vector<std::size_t>{1, 2, 3, 4, 5, 6, 7});
  REQUIRE(ids == std::vector<int>{0, 1, 2, 3, 4, 5, 6});
  const SliceResult without = slice_file(path, planes, o);
  REQUIRE(with.sections.size() == without.sections.size());
  for (std::size_t i = 0; i < with.sections.size(); ++i) {
    REQUIRE(with.sections[i].error.empty());
    REQUIRE(with.sections[i].morphology.loops[0].points == without.sections[i].morphology.loops[0].points);
  }
  std::size_t reports = 0;
  REQUIRE(thrown([&] {
            slice_file(path, planes, o, {}, {}, [&](const ProgressEvent&) { return ++reports < 2; });
          }) == "slice: cancelled");
  REQUIRE(reports == 2);
  std::remove(path.c_str());
}

namespace {

// Runs `cut(sink)` with a sink that records each section's id and its loop 0's points, and
// checks them against the result: every section, in order, as the result holds it; then a
// sink that cancels after the first section stops the call there.
template <class Cut>
void sinks_each_section(const Cut& cut, std::size_t sections) {
  std::vector<int> ids;
  std::vector<std::vector<Eigen::Vector2d>> sunk;
  const SliceResult result = cut([&](const SectionSlice& s) {
    ids.push_back(s.id);
    sunk.push_back(s.morphology.loops.empty() ? std::vector<Eigen::Vector2d>{}
                                              : s.morphology.loops[0].points);
  });
  REQUIRE(result.sections.size() == sections);
  REQUIRE(ids.size() == sections);
  for (std::size_t i = 0; i < sections; ++i) {
    REQUIRE(ids[i] == int(i));
    REQUIRE(result.sections[i].error.empty());
    REQUIRE(sunk[i] == result.sections[i].morphology.loops[0].points);
  }
  std::size_t calls = 0;
  REQUIRE(thrown([&] {
            cut([&](const SectionSlice&) {
              if (++calls == 1) throw Cancelled("slice");
            });
          }) == "slice: cancelled");
  REQUIRE(calls == 1);
}

}  // namespace

TEST_CASE("progress: a mesh and surfaces of revolution hand on each section as it is done", "[progress]") {
  const Mesh blade = generate_mesh(turbine_blade(), 400, 20);
  const std::vector<Plane> planes = planes_at({0, 0, 1}, {12, 20, 28});
  sinks_each_section([&](const SectionSink& sink) { return slice(blade, planes, {}, sink); }, 3);
  const RotorDesign rotor = cylinder_rotor();
  std::vector<Revolution> surfaces;
  for (double z : {20.0, 40.5}) surfaces.push_back(rotor.surface(z));
  const Mesh rotor_blade = rotor_mesh(rotor, 400, 61);
  sinks_each_section([&](const SectionSink& sink) { return slice(rotor_blade, surfaces, {}, sink); }, 2);
  // A rotor's sparse rows on their cylinders: the sampling told once, before any section.
  RowsOptions ro;
  ro.rows = 3;
  ro.pitch = 12;
  ro.spacing = 0.05;
  const Cloud rows = rotor_cloud(rotor, generate_rows(rotor.blade, ro));
  surfaces.clear();
  for (double r : row_radii(rows.points, rotor.axis_point, rotor.axis)) {
    surfaces.push_back(cylinder_surface(rotor.axis_point, rotor.axis, r));
    surfaces.back().reference = rotor.reference;
  }
  std::vector<std::string> told;
  sinks_each_section(
      [&](const SectionSink& sink) {
        return slice(
            rows, surfaces, {},
            [&](const SectionSlice& s) {
              told.push_back("section");
              sink(s);
            },
            [&](const Sampling& s) { told.push_back(s.kind == SamplingKind::rows ? "rows" : "other"); });
      },
      3);
  REQUIRE(told.size() >= 4);
  CHECK(told[0] == "rows");
  CHECK(std::vector<std::string>(told.begin() + 1, told.begin() + 4) ==
        std::vector<std::string>(3, "section"));
}
