// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the tools' command lines without the binaries (tools/args/): a flag maps to its
// option, a bad value is refused as bad usage (exit code 2), --help answers with exit 0.
#if __has_include("args/slice_args.h")  // the tools are built (SECTION_BUILD_TOOLS)
#include "args/blade_args.h"
#include "args/bladegen_args.h"
#include "args/camber_args.h"
#include "args/compare_args.h"
#include "args/fitspline_args.h"
#include "args/plot_args.h"
#include "args/slice_args.h"
#include "args/smooth_args.h"

#include <catch2/catch.hpp>

#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace section::tool;

// A command line parsed into `Args`: the exit code (-1 = run) and what was printed.
template <class Args>
struct Parsed {
  Args args;
  int code = 0;
  std::string out, err;
};

template <class Args>
Parsed<Args> parsed(std::vector<std::string> words) {
  words.insert(words.begin(), Args::name);
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  Parsed<Args> p;
  std::ostringstream out, err;
  p.code = parse(static_cast<int>(argv.size()), argv.data(), p.args, out, err);
  p.out = out.str();
  p.err = err.str();
  return p;
}

}  // namespace

TEST_CASE("tool options: slice reads its planes, slab and input", "[tools]") {
  const auto p = parsed<SliceArgs>({"blade.ply", "--normal", "1,0,0", "--at", "2,4", "--slab", "0.1",
                                    "--no-fill", "--band-spacing", "0", "--units", "in", "-o", "out.csv"});
  REQUIRE(p.code == -1);
  CHECK(p.args.common.input == "blade.ply");
  CHECK(p.args.common.output == "out.csv");
  CHECK(p.args.normal == std::vector<double>{1, 0, 0});
  CHECK(p.args.at == std::vector<double>{2, 4});
  CHECK(p.args.options.slab == 0.1);
  CHECK(!p.args.options.fill_gaps);
  CHECK(p.args.options.band_spacing == 0);
  CHECK(p.args.units == "in");
  CHECK(parsed<SliceArgs>({"blade.ply", "--count", "7", "--view", "b.ply"}).args.views ==
        std::vector<std::string>{"b.ply"});
}

TEST_CASE("tool options: bad usage is refused with exit code 2 and names the flag", "[tools]") {
  // No planes: each row of points a section (slice decides from the points), as --rows.
  const auto no_planes = parsed<SliceArgs>({"blade.ply"});
  CHECK(no_planes.code == -1);
  CHECK(no_planes.args.by_rows());
  CHECK(parsed<SliceArgs>({"blade.ply", "--rows"}).args.rows);
  CHECK(parsed<SliceArgs>({"blade.ply", "--rows", "--at", "1"}).code == 2);
  CHECK(parsed<SliceArgs>({"blade.ply", "--rows", "--count", "3"}).code == 2);
  CHECK(parsed<SliceArgs>({"blade.ply", "--count", "0"}).code == 2);
  CHECK(parsed<SliceArgs>({"blade.ply", "--at", "1", "--normal", "1,2"}).code == 2);
  CHECK(parsed<SliceArgs>({"blade.ply", "--at", "1", "--count", "3"}).code == 2);
  CHECK(parsed<SmoothArgs>({"--solver", "lu"}).code == 2);
  CHECK(parsed<SmoothArgs>({"--b", "0"}).code == 2);
  CHECK(parsed<FitsplineArgs>({"--samples", "10", "--spacing", "1"}).code == 2);
  const auto stations = parsed<CamberArgs>({"--stations", "0.5,2"});
  CHECK(stations.code == 2);
  CHECK(stations.err.find("stations must lie between 0 and 1") != std::string::npos);
  CHECK(parsed<CamberArgs>({"--stations", "0,0.5"}).code == 2);  // an edge point: the whole section failed
  CHECK(parsed<CamberArgs>({"--le-direction", "0,0"}).code == 2);
  CHECK(parsed<CompareArgs>({"--nominal", "n.stl", "--le-direction", "0,0,0"}).code == 2);
  CHECK(parsed<CompareArgs>({"--nominal", "n.stl", "--freedom", "along", "--direction", "0,0"}).code == 2);
  CHECK(parsed<CompareArgs>({"--nominal", "n.stl", "--center", "0,0"}).code == -1);  // a point may be 0
  CHECK(parsed<CamberArgs>({"--edge", "square"}).code == 2);
  CHECK(parsed<PlotArgs>({"--section", "1", "--html"}).code == 2);
  const auto inset = parsed<PlotArgs>({"--inset", "10"});  // was exit 1 naming inset_size
  CHECK(inset.code == 2);
  CHECK(inset.err.find("--inset: 0 (none) or 80 to") != std::string::npos);
  CHECK(parsed<PlotArgs>({"--inset", "10", "--no-insets"}).code == -1);
  CHECK(parsed<PlotArgs>({"--inset", "300", "--width", "500"}).code == 2);
  CHECK(parsed<PlotArgs>({"--width", "500"}).args.options.inset_size == 230);  // the default inset narrowed
  CHECK(parsed<BladegenArgs>({"--points"}).code == 2);                         // no -o
  CHECK(parsed<BladegenArgs>({"--truth", "t.csv"}).code == 2);                 // no --at
}

TEST_CASE("tool options: an empty value is refused, not read as the option left out or as 0", "[tools]") {
  // What an unset shell variable gives: `compare --tolerances "$TOL"` judged nothing, exit 0.
  const auto tolerances = parsed<CompareArgs>({"--nominal", "n.stl", "--tolerances", ""});
  CHECK(tolerances.code == 2);
  CHECK(tolerances.err.find("--tolerances: an empty value") != std::string::npos);
  CHECK(parsed<CompareArgs>({"--nominal", "n.stl", "--report", ""}).code == 2);
  CHECK(parsed<SliceArgs>({"blade.ply", "--at", ""}).code == 2);  // sliced at 0
  CHECK(parsed<PlotArgs>({"--section", ""}).code == 2);           // section 0
  CHECK(parsed<CamberArgs>({"--params", ""}).code == 2);
  CHECK(parsed<BladeArgs>({"--lines", " "}).code == 2);
  CHECK(parsed<FitsplineArgs>({"-o", ""}).code == 2);
  CHECK(parsed<SmoothArgs>({"--report", "r.csv"}).code == -1);
}

TEST_CASE("tool options: fitspline's samples are bounded", "[tools]") {
  CHECK(parsed<FitsplineArgs>({"--samples", "1000000"}).code == -1);
  CHECK(parsed<FitsplineArgs>({"--samples", "1000001"}).code == 2);  // 4.7 GB at 10 million
}

TEST_CASE("tool options: --help answers with exit code 0 without the required flags", "[tools]") {
  const auto help = parsed<SliceArgs>({"--help"});
  CHECK(help.code == 0);
  CHECK(help.out.find("--normal") != std::string::npos);
  CHECK(help.out.rfind(SliceArgs::description, 0) == 0);
  CHECK(parsed<BladegenArgs>({"--help"}).code == 0);
  CHECK(parsed<CamberArgs>({"--version"}).out.find("camber (libsection)") == 0);
}

TEST_CASE("tool options: smooth, fitspline and camber read their flags into the stage options", "[tools]") {
  const auto smooth = parsed<SmoothArgs>(
      {"--solver", "gauss-seidel", "--length", "0.5", "--report", "r.csv", "--move-tolerance", "0"});
  REQUIRE(smooth.code == -1);
  CHECK(smooth.args.options.move_tolerance == 0);
  CHECK(smooth.args.options.solver == section::SmoothSolver::gauss_seidel);
  CHECK(smooth.args.options.smoothing_length == 0.5);
  CHECK(smooth.args.report == "r.csv");
  CHECK(smooth.args.common.input == "-");

  const auto fit = parsed<FitsplineArgs>(
      {"in.csv", "--samples", "40", "--threads", "2", "--first-iterations", "12", "--bridge-factor", "4"});
  REQUIRE(fit.code == -1);
  CHECK(fit.args.options.samples == 40);
  CHECK(fit.args.options.threads == 2);
  CHECK(fit.args.options.first_iterations == 12);
  CHECK(fit.args.options.bridge_factor == 4);
  CHECK(parsed<FitsplineArgs>({"--first-iterations", "-1"}).code != -1);
  CHECK(parsed<FitsplineArgs>({"--bridge-factor", "-2"}).code != -1);

  const auto camber = parsed<CamberArgs>(
      {"--stations", "0.25, +0.5", "--le-direction", "0,0,-1", "--edge", "auto", "--edge-on-spline"});
  REQUIRE(camber.code == -1);
  CHECK(camber.args.options.stations == std::vector<double>{0.25, 0.5});
  CHECK(camber.args.options.le_direction_3d == Eigen::Vector3d(0, 0, -1));
  CHECK(camber.args.options.le_direction == Eigen::Vector2d(0, 0));
  CHECK(camber.args.options.edge == section::EdgeModel::automatic);
  CHECK(!camber.args.options.edge_on_points);
  CHECK(parsed<CamberArgs>({"--le-direction", "1,0"}).args.options.le_direction == Eigen::Vector2d(1, 0));
}

TEST_CASE("tool options: plot takes HTML from the output's name unless a section is asked for", "[tools]") {
  CHECK(parsed<PlotArgs>({"-o", "page.html"}).args.html);
  const auto one = parsed<PlotArgs>({"-o", "page.html", "--section", "3", "--no-insets"});
  REQUIRE(one.code == -1);
  CHECK(!one.args.html);
  CHECK(one.args.one);
  CHECK(one.args.only == 3);
  CHECK(one.args.options.inset_size == 0);
  CHECK(!parsed<PlotArgs>({"-o", "dir"}).args.one);
}

TEST_CASE("tool options: bladegen reads the scanner and the truth heights", "[tools]") {
  const auto p = parsed<BladegenArgs>({"--kind", "compressor", "--points", "--noise", "0.01", "-o", "b.ply",
                                       "--truth", "t.csv", "--at", "5,10"});
  REQUIRE(p.code == -1);
  CHECK(p.args.kind == "compressor");
  CHECK(p.args.points);
  CHECK(p.args.scan.noise == 0.01);
  CHECK(p.args.at == std::vector<double>{5, 10});
}

TEST_CASE("tool options: compare reads its fit, freedom and zones into the stage options", "[tools]") {
  const auto p = parsed<CompareArgs>({"m.csv", "--nominal", "n.stl", "--fit", "weighted", "--weights",
                                      "le=5,te=2.5", "--freedom", "along", "--direction", "1,1",
                                      "--edge-zone", "0.1", "--keep-outliers"});
  REQUIRE(p.code == -1);
  const section::CompareOptions& o = p.args.options.compare;
  CHECK(o.fit.method == section::FitMethod::weighted);
  CHECK(o.fit.freedom == section::FitFreedom::translation_along);
  CHECK(o.fit.direction == Eigen::Vector2d(1, 1));
  CHECK(o.fit.weights[1] == 5);
  CHECK(o.fit.weights[2] == 2.5);
  CHECK(o.fit.weights[3] == 1);
  CHECK(o.edge_zone == 0.1);
  CHECK(o.outlier_distance < 0);
  const auto whole = parsed<CompareArgs>(
      {"--nominal", "n.stl", "--whole-blade", "--freedom", "rotation", "--center", "1,2,3"});
  REQUIRE(whole.code == -1);
  CHECK(whole.args.options.whole);
  CHECK(whole.args.options.compare.fit.center_3d == Eigen::Vector3d(1, 2, 3));
  CHECK(parsed<CompareArgs>({"m.csv"}).code == 2);  // --nominal is required
  CHECK(parsed<CompareArgs>({"--nominal", "n.stl", "--center", "1,2,3"}).code == 2);
  CHECK(parsed<CompareArgs>({"--nominal", "n.stl", "--weights", "middle=2"}).code == 2);
  CHECK(parsed<CompareArgs>({"--help"}).out.find("Exit status") != std::string::npos);
  // The decision rule: guarded with two standard errors unless told.
  CHECK(p.args.options.decision == section::DecisionRule::guarded);
  CHECK(p.args.options.coverage == 2);
  const auto simple =
      parsed<CompareArgs>({"--nominal", "n.stl", "--decision-rule", "simple", "--coverage-factor", "3"});
  REQUIRE(simple.code == -1);
  CHECK(simple.args.options.decision == section::DecisionRule::simple);
  CHECK(simple.args.options.coverage == 3);
}
#endif

TEST_CASE("tool options: blade reads its reference, axis and format, bladegen its stacking law", "[tools]") {
  const auto p = parsed<BladeArgs>({"c.txt", "--reference", "2", "--axis", "0,0,-100,1,0,0", "--format",
                                    "csv", "--plot", "b.svg", "--samples", "11"});
  REQUIRE(p.code == -1);
  CHECK(p.args.common.input == "c.txt");
  CHECK(p.args.options.reference == 2);
  CHECK(p.args.options.rotor);
  CHECK(p.args.options.axis_point == Eigen::Vector3d(0, 0, -100));
  CHECK(p.args.options.axis_direction == Eigen::Vector3d(1, 0, 0));
  CHECK(p.args.options.samples == 11);
  CHECK(p.args.plot_file == "b.svg");
  CHECK(!parsed<BladeArgs>({}).args.options.rotor);
  CHECK(parsed<BladeArgs>({"--axis", "0,0,0,1,0"}).code == 2);
  CHECK(parsed<BladeArgs>({"--axis", "0,0,0,0,0,0"}).code == 2);
  CHECK(parsed<BladeArgs>({"--format", "xml"}).code == 2);
  CHECK(parsed<BladeArgs>({"--help"}).code == 0);
  const auto g =
      parsed<BladegenArgs>({"--points", "-o", "b.ply", "--lean", "1.5", "--sweep", "-0.5", "--bow", "0.2"});
  REQUIRE(g.code == -1);
  const section::BladeDesign b = g.args.blade();
  CHECK(b.stacking.lean == 1.5);
  CHECK(b.stacking.sweep == -0.5);
  CHECK(b.stacking.bow == 0.2);
}
