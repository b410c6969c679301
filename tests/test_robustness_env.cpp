// SPDX-License-Identifier: GPL-3.0-or-later
// Hostile environments at the library level (issue 26, docs/ROBUSTNESS.md): geometry far
// from the origin, the resource policy, outputs written whole, streams held to their
// schema, files longer than their headers say. The tool-level cases, with pipes, signals
// and memory caps, are in tests/tools/test_hostile.sh.
#include "section/error.h"
#include "section/extras/generate.h"
#include "section/io/cloud_io.h"
#include "section/io/csv.h"
#include "section/io/file.h"
#include "section/io/limits.h"
#include "section/io/mesh_io.h"
#include "section/io/stream.h"
#include "section/io/stream_reader.h"
#include "section/pipe/camber_stream.h"
#include "section/pipe/fit_spline_stream.h"
#include "section/pipe/schema.h"
#include "section/pipe/slice_stream.h"
#include "section/pipe/smooth_stream.h"
#include "section/pipe/validate.h"
#include "section/slice.h"

#include "thrown.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

using namespace section;

namespace {

std::string temp_path(const std::string& name) {
  const char* dir = std::getenv("TMPDIR");
  return std::string(dir && *dir ? dir : "/tmp") + "/section_env_" + std::to_string(::getpid()) + "_" + name;
}

// The params table of a cloud through slice | smooth | fitspline | camber at `heights`.
Table params_of(const Cloud& cloud, const Eigen::Vector3d& normal, const std::vector<double>& heights) {
  Stream s = to_stream(slice(cloud, planes_at(normal, heights)), "slice");
  smooth_stream(s);
  fit_spline_stream(s);
  camber_stream(s);
  REQUIRE(s.issues.empty());
  return schema::params.get(s);
}

// The largest difference between two params tables, as a length: lengths as they are, 3D
// points less the shift, angles (degrees) over the chord, areas over the perimeter (about
// 2 chords), flags and shapes equal; in-plane points left out (their frame moved).
double worst_difference(const Table& near, const Table& far, double shift, std::string& where) {
  REQUIRE(near.columns == far.columns);
  REQUIRE(near.rows() == far.rows());
  const std::size_t chord = near.column("chord");
  double worst = 0;
  for (std::size_t r = 0; r < near.rows(); ++r)
    for (std::size_t c = 0; c < near.columns.size(); ++c) {
      const std::string& name = near.columns[c];
      const char last = name.back();
      const bool planar = name.size() > 2 && name[name.size() - 2] == '_' && (last == 'u' || last == 'v');
      if (planar || name == "le_arc" || name == "te_arc") continue;  // (arcs: the radii stand for them)
      double d = std::abs(near.at(r, c) - (far.at(r, c) - (name.size() > 2 && name[name.size() - 2] == '_' &&
                                                                   (last == 'x' || last == 'y' || last == 'z')
                                                               ? shift
                                                               : 0)));
      if (name.find("angle") != std::string::npos || name.find("stagger") != std::string::npos)
        d *= near.at(r, chord) * M_PI / 180;
      if (name == "area") d /= 2 * near.at(r, chord);
      if (d > worst) worst = d, where = name + " of section " + std::to_string(r);
    }
  return worst;
}

}  // namespace

TEST_CASE("robustness: a blade 1e6 and 1e9 mm away gets the same parameters to 0.1 um", "[robustness][far]") {
  for (const BladeDesign& blade : {turbine_blade(), compressor_blade()}) {
    ScanOptions scan;
    scan.spacing = 0.15;
    scan.noise = 0.002;
    scan.z_min = 14;
    scan.z_max = 26;
    // On a grid of 2^-23 mm, the spacing of doubles at 1e9: the far cloud is this one moved
    // exactly, and only the stages' arithmetic can tell them apart (not the fit's choices,
    // which a difference in the last bit of a point may turn).
    Cloud cloud = generate_scan(blade, scan).cloud;
    for (auto& p : cloud.points) p = (p * 8388608.0).array().round().matrix() / 8388608.0;
    const Table near = params_of(cloud, Eigen::Vector3d::UnitZ(), {16, 20, 24});
    for (const double shift : {1e6, 1e9}) {
      Cloud far = cloud;
      for (auto& p : far.points) p += Eigen::Vector3d::Constant(shift);
      std::string where;
      const double d = worst_difference(
          near, params_of(far, Eigen::Vector3d::UnitZ(), {shift + 16, shift + 20, shift + 24}), shift, where);
      INFO("shift " << shift << ": " << where);
      CHECK(d < 1e-4);
    }
  }
}

TEST_CASE("robustness: a stream whose (u, v) lie 1e9 away measures the same", "[robustness][far]") {
  ScanOptions scan;
  scan.spacing = 0.15;
  scan.z_min = 18;
  scan.z_max = 22;
  const Stream sliced =
      to_stream(slice(generate_scan(turbine_blade(), scan).cloud, planes_at({0, 0, 1}, {20})), "slice");
  // Every (u, v) moved by +shift and the frame's origin by -shift along u and v: the same
  // section in 3D, far from the origin of its plane (a stream no slice of ours writes).
  const auto measured = [&](double shift) {
    Stream t = sliced;
    for (const char* name : {"points", "skeleton"}) {
      Table& table = *t.find(name);
      for (std::size_t r = 0; r < table.rows(); ++r)
        for (const char* col : {"u", "v"})
          table.values[r * table.columns.size() + table.column(col)] += shift;
      table.source = nullptr;
    }
    Table& frames = *t.find("frames");
    for (const char* col : {"origin_x", "origin_y"}) frames.values[frames.column(col)] -= shift;
    frames.source = nullptr;
    smooth_stream(t);
    fit_spline_stream(t);
    camber_stream(t);
    REQUIRE(t.issues.empty());
    return schema::params.get(t);
  };
  const Table near = measured(0);
  for (const double shift : {1e6, 1e9}) {
    const Table far = measured(shift);
    std::string where;
    const double d = worst_difference(near, far, 0, where);
    INFO("shift " << shift << ": " << where);
    CHECK(d < 1e-4);
    CHECK(std::abs(far.at(0, far.column("centroid_u")) - shift - near.at(0, near.column("centroid_u"))) <
          1e-4);
  }
}

TEST_CASE("robustness: the memory limit bounds what an input may take", "[robustness][limits]") {
  CHECK(memory_limit() > 0);
  CHECK(max_input_bytes() == memory_limit() / 4);
  const std::string path = temp_path("big.csv");
  write_file(path, std::string(5000, '#') + "\n");
  struct Reset {
    ~Reset() { set_memory_limit(0); }
  } reset;                 // (the limit is the process's: back to the default whatever happens)
  set_memory_limit(4000);  // inputs up to 1000 bytes
  CHECK_THAT(thrown([&] { read_file(path); }),
             Catch::Contains(path + " is larger than 1 kB") && Catch::Contains("--max-memory"));
  CHECK_THAT(thrown([&] { PartReader r(path); }), Catch::Contains("preamble is larger than 1 kB"));
  set_memory_limit(0);
  CHECK(max_input_bytes() > 4000);
  CHECK(read_file(path).size() == 5001);
  std::remove(path.c_str());
  CHECK(format_bytes(512) == "512 bytes");
  CHECK(format_bytes(1.5e9) == "1.5 GB");
}

TEST_CASE("robustness: an output appears whole under its name, never through a planted link",
          "[robustness][output]") {
  const std::string path = temp_path("out.csv"), target = temp_path("target.txt");
  write_file(target, "precious\n");
  ::symlink(target.c_str(), (path + ".partial").c_str());  // where the old writer wrote
  {
    Stream head;
    StreamWriter w(path, head);
    struct stat st {};
    CHECK(::stat(path.c_str(), &st) != 0);  // not there until finished
    w.part("0", Stream{});
    w.finish();
  }
  CHECK(read_file(target) == "precious\n");
  CHECK(read_file(path).substr(read_file(path).size() - 6) == "# end\n");
  {
    StreamWriter unfinished(temp_path("never.csv"), Stream{});
    unfinished.part("0", Stream{});
  }  // (a failure before finish: no file, no temporary file)
  CHECK_THROWS(read_file(temp_path("never.csv")));
  CHECK_THAT(thrown([&] { write_file("/dev/full", std::string(1 << 16, 'x')); }),
             Catch::Contains("write error: No space left on device"));
  for (const auto& p : {path, target, path + ".partial"}) std::remove(p.c_str());
}

TEST_CASE("robustness: a stream is held to its schema", "[robustness][stream]") {
  const std::string head = "# libsection-stream 1\n";
  const auto refused = [&](const std::string& body) {
    return thrown([&] { validate_stream(parse_stream(head + body, "s.csv"), "s.csv"); });
  };
  CHECK_THAT(refused("# table params\nsection,chord\n0,1\n0,2\n"),
             Catch::Contains("table 'params' has two rows (data rows 1 and 2) for section 0"));
  CHECK_THAT(refused("# table points\nsection,loop,index,u,v\n0,0,1,0,0\n0,0,0,0,0\n0,0,1,1,1\n"),
             Catch::Contains("section 0 loop 0 index 1"));
  CHECK_THAT(refused("# table loops\nsection,loop,points\n0,0,-5\n"),
             Catch::Contains("column 'points' is -5, a count must be a whole number of 0 or more"));
  CHECK_THAT(refused("# table splines\nsection,loop,degree,closed\n0,0,3,2\n"),
             Catch::Contains("column 'closed' is 2, a flag must be 0 or 1"));
  CHECK_THAT(refused("# table params\nsection,flags\n0,-5\n"),
             Catch::Contains("column 'flags' is -5, check bits must be a whole number from 0 to 2^42 - 1"));
  // Bit 41 is a check's (outlet_noise); no check has bit 42.
  CHECK_NOTHROW(validate_stream(
      parse_stream(head + "# table params\nsection,flags\n0,2199023255552\n", "s.csv"), "s.csv"));
  CHECK_THAT(refused("# table params\nsection,flags\n0,4398046511104\n"),
             Catch::Contains("column 'flags' is 4398046511104"));
  CHECK_THAT(refused("# table params\nsection,flags\n0,2.5\n"), Catch::Contains("column 'flags' is 2.5"));
  CHECK_THAT(refused("# table params\nsection,le_radius_sigma\n0,-0.001\n"),
             Catch::Contains("column 'le_radius_sigma' is -0.001, a standard error must not be negative"));
  // Params no section can have: blade, compare, plot and tocad showed them as measured.
  CHECK_THAT(refused("# table params\nsection,chord\n0,40\n1,-5\n"),
             Catch::Contains("data row 2 (section 1): column 'chord' is -5, it cannot be negative"));
  CHECK_THAT(
      refused("# table params\nsection,max_thickness_pos\n0,5\n"),
      Catch::Contains("column 'max_thickness_pos' is 5, a place along the camber line lies in [0, 1]"));
  CHECK(refused("# table params\nsection,chord,le_radius,max_thickness_pos,stagger\n0,40,0,1,-55\n") ==
        "no error");  // 0 radius (a sharp edge), a position at the TE, a negative angle
  // Compare's zones and compared values: one row per zone or item of a section.
  CHECK(refused("# table zones\nsection,zone\n0,0\n0,1\n# table compared\nsection,item\n0,0\n0,1\n") ==
        "no error");
  CHECK_THAT(refused("# table compared\nsection,item\n0,4\n0,4\n"), Catch::Contains("section 0 item 4"));
  CHECK_THAT(refused("# table points\nsection,loop,index,u,v\n0,-1,0,0,0\n"), Catch::Contains("negative id"));
  CHECK_THAT(refused("# table points\nsection,loop,index,u,u\n0,0,0,0,0\n"),
             Catch::Contains("column 'u' appears twice"));
  CHECK_THAT(refused("# part 2\n# table frames\nsection,z\n3,0\n# end\n"),
             Catch::Contains("section 3 in the part of section 2"));
  CHECK_THAT(refused("# part x\n# end\n"), Catch::Contains("part label 'x' is not a section id"));
  CHECK_THAT(refused("# part 2\n# issue section=3 loop=-1 stage=slice message=m\n# end\n"),
             Catch::Contains("an issue of section 3 in the part of section 2"));
  // Tables the schema does not know keep rows as they come.
  CHECK(refused("# table mine\nsection,value\n0,1\n0,2\n") == "no error");
  CHECK_THAT(thrown([&] { parse_planes("origin_x,origin_x\n0,0\n", "p.csv"); }),
             Catch::Contains("p.csv:1: column 'origin_x' appears twice"));
  // A profile's columns by the names its header gives them.
  const auto yx = parse_profile("y,x\n1,10\n2,20\n", "p.dat");
  CHECK(yx == std::vector<Eigen::Vector2d>{{10, 1}, {20, 2}});
}

TEST_CASE("robustness: files longer than their headers say are refused", "[robustness][length]") {
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty double x\n"
      "property double y\nproperty double z\nend_header\n";
  const double xyz[9] = {1, 2, 3, 4, 5, 6, 7, 8, 9};
  ply.append(reinterpret_cast<const char*>(xyz), sizeof xyz);  // 3 vertices, 2 declared
  CHECK_THAT(thrown([&] { parse_cloud(ply, "b.ply"); }),
             Catch::Contains("b.ply: the file holds 24 bytes more than its PLY header declares"));
  const std::string ascii =
      "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n1 2 3\n4 5 6\n7 8 9\n";
  CHECK_THAT(thrown([&] { parse_cloud(ascii, "a.ply"); }),
             Catch::Contains("a.ply:10: more lines than the PLY header declares (2 vertices)"));
  CHECK(parse_cloud(ascii.substr(0, ascii.size() - 6), "a.ply").points.size() == 2);
  // A binary STL whose count is half its triangles.
  std::string stl(80, '\0');
  const std::uint32_t count = 1;
  stl.append(reinterpret_cast<const char*>(&count), 4);
  for (int t = 0; t < 2; ++t) {
    const float tri[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, float(t)};
    stl.append(reinterpret_cast<const char*>(tri), sizeof tri);
    stl.append(2, '\0');
  }
  const std::string path = temp_path("half.stl");
  write_file(path, stl);
  CHECK_THAT(thrown([&] { read_mesh(path); }), Catch::Contains("room for 2 triangles"));
  std::remove(path.c_str());
}

TEST_CASE("robustness: a mesh with no extension is told by its content", "[robustness][mesh]") {
  const std::string named = temp_path("m.off"), bare = temp_path("mesh");
  write_file(named, "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
  write_file(bare, read_file(named));
  CHECK(is_mesh_file(bare));
  CHECK(read_mesh(bare).triangles == read_mesh(named).triangles);
  write_file(bare, "1 2 3\n4 5 6\n");
  CHECK(!is_mesh_file(bare));
  for (const auto& p : {named, bare}) std::remove(p.c_str());
}

#if __has_include("common/tool.h")  // the tools are built (SECTION_BUILD_TOOLS)
#include "common/tool.h"

#include <sstream>

TEST_CASE("robustness: the tools' command line refuses NaN, 0,0,0 and clobbering", "[robustness][tools]") {
  using namespace section::tool;
  CHECK(byte_size("100000") == 100000);
  CHECK(byte_size("512M") == 512000000);
  CHECK(byte_size("1.5GB") == 1500000000);
  CHECK(byte_size("8g") == 8000000000ULL);
  for (const char* bad : {"", "0", "-1G", "nan", "1Q", "1GiB", "inf"}) CHECK(byte_size(bad) == 0);
  CHECK(tidy_message("slice", "slice: the slab width must be finite") == "the slab width must be finite");
  CHECK(tidy_message("slice", "<stdin>: slice: cannot estimate") == "<stdin>: cannot estimate");
  CHECK(tidy_message("slice", "read_cloud: x.xyz:3: bad") == "read_cloud: x.xyz:3: bad");
  // A numeric option given NaN or infinity is bad usage, named.
  const auto usage = [](std::vector<std::string> words) {
    words.insert(words.begin(), "tool");
    std::vector<char*> argv;
    for (auto& w : words) argv.push_back(w.data());
    double x = 0;
    std::vector<double> list;
    std::ostringstream out, err;
    const int code = parse_args(
        "tool", "", int(argv.size()), argv.data(),
        [&](CLI::App& app) {
          app.add_option("--x", x)->check(CLI::NonNegativeNumber);
          app.add_option("--list", list)->delimiter(',');
        },
        out, err);
    return std::to_string(code) + " " + err.str();
  };
  CHECK_THAT(usage({"--x", "nan"}),
             Catch::StartsWith("2 ") && Catch::Contains("--x: must be a finite number"));
  CHECK_THAT(usage({"--list", "1,inf"}), Catch::Contains("--list: must be a finite number, got 'inf'"));
  CHECK_THAT(usage({"--x", "-1"}), Catch::Contains("Value -1 is below 0\n"));
  CHECK_THAT(usage({"--x", "inf"}),
             Catch::StartsWith("2 ") && Catch::Contains("--x: must be a finite number, got 'inf'\n"));
  CHECK_THAT(usage({"--x", "-inf"}), Catch::Contains("--x: must be a finite number, got '-inf'\n"));
  CHECK(usage({"--x", "2", "--list", "1,2"}) == "-1 ");
}
#endif
