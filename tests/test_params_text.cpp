// SPDX-License-Identifier: GPL-3.0-or-later
// The params table as text for people (io/params_text.h): widths, digits, words, units.
#include "section/io/params_text.h"

#include "section/checks.h"
#include "section/extras/generate.h"
#include "section/io/stream.h"
#include "section/pipe/slice_stream.h"
#include "section/slice.h"
#include "pipe_stages.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

namespace {

using section::Stream;
using section::Table;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// The number printed after `label` on the first line at or after `from` that holds it.
double number_after(const std::vector<std::string>& lines, std::size_t from, const std::string& label) {
  for (std::size_t k = from; k < lines.size(); ++k) {
    const auto at = lines[k].find("  " + label + " ");
    if (at != std::string::npos) return std::stod(lines[k].substr(at + label.size() + 2));
  }
  return NAN;
}

std::size_t line_starting(const std::vector<std::string>& lines, const std::string& head) {
  for (std::size_t k = 0; k < lines.size(); ++k)
    if (lines[k].rfind(head, 0) == 0) return k;
  return lines.size();
}

}  // namespace

TEST_CASE("params text: a generated blade's sections fit 120 columns, at the planes' heights, rounded",
          "[params_text]") {
  const section::BladeDesign blade = section::turbine_blade();
  const std::vector<double> zs = {0.3 * blade.span, 0.6 * blade.span};
  section::ScanOptions so = section::inspection_scan();
  so.seed = 3;
  const section::Cloud cloud = section::scan_bands(blade, zs, so);
  section::SliceOptions sopt;
  sopt.slab = 0.08;
  const Stream stream = section::test::after_slice(
      section::to_stream(section::slice(cloud, section::planes_at({0, 0, 1}, zs), sopt), "slice"));
  const std::string text = section::format_params_text(stream);
  const auto lines = lines_of(text);
  for (const auto& line : lines) {
    INFO(line);
    CHECK(line.size() <= 120);
  }
  const Table& params = stream.get("params", "camber");
  REQUIRE(params.rows() == zs.size());
  for (std::size_t k = 0; k < zs.size(); ++k) {
    const int s = int(params.at(k, params.column("section")));
    const std::size_t head = line_starting(lines, "section " + std::to_string(s) + " ");
    REQUIRE(head < lines.size());
    INFO(lines[head]);
    // The plane offset along +z is the height the section was cut at.
    char plane[64];
    std::snprintf(plane, sizeof plane, "plane %.4f mm along n (0.000, 0.000, 1.000)", zs[k]);
    CHECK(lines[head].find(plane) != std::string::npos);
    // Lengths to 0.1 um, angles to 0.001 deg: the printed value is the table's, rounded.
    for (const char* c : {"chord", "max_thickness", "le_radius", "te_radius", "caliper_chord"}) {
      std::string label = c;
      for (auto& ch : label) ch = ch == '_' ? ' ' : ch;
      if (label == "le radius") label = "LE radius";
      if (label == "te radius") label = "TE radius";
      INFO(label);
      CHECK(std::abs(number_after(lines, head, label) - params.at(k, params.column(c))) <= 0.5e-4 + 1e-12);
    }
    for (const char* c : {"stagger", "inlet_angle", "outlet_angle", "camber_angle"}) {
      std::string label = c;
      for (auto& ch : label) ch = ch == '_' ? ' ' : ch;
      INFO(label);
      CHECK(std::abs(number_after(lines, head, label) - params.at(k, params.column(c))) <= 0.5e-3 + 1e-12);
    }
  }
  // The turbine blade's edges are round, in words.
  CHECK(text.find("mm round") != std::string::npos);
  CHECK(text.find("lengths in mm") != std::string::npos);
}

TEST_CASE("params text: codes in words, other units in mm, issues shortened, a failed section listed",
          "[params_text]") {
  Stream stream;
  stream.units = "m";
  const section::CheckBits flags =
      section::bit(section::Check::le_circle) | section::bit(section::Check::jump_chord);
  stream.put(Table("params",
                   {"section", "chord", "max_thickness", "le_radius", "le_shape", "te_shape", "pressure_side",
                    "stagger", "flags", "chord_sigma", "inlet_angle_sigma", "te_radius_sigma"},
                   {4, 0.0412312475748, 0.003, 0.0001, 0, 2, -1, NAN, double(flags), 2.5e-6, 0.0312, 0}));
  stream.issues.push_back({4, 0, "camber", std::string(300, 'x')});
  stream.issues.push_back({7, 0, "fitspline", "too few points"});
  const std::string text = section::format_params_text(stream);
  const auto lines = lines_of(text);
  for (const auto& line : lines) CHECK(line.size() <= 120);
  CHECK(number_after(lines, 0, "chord") == Approx(41.2312).margin(1e-9));  // m -> mm, 4 decimals
  // The values a failed check flags marked: the chord (jump_chord), the LE radius (le_circle).
  CHECK(text.find("41.2312 mm!") != std::string::npos);
  CHECK(text.find("0.1000 mm round!") != std::string::npos);
  CHECK(text.find("3.0000 mm") != std::string::npos);  // the max thickness, not flagged
  CHECK(text.find("mm sharp") != std::string::npos);
  CHECK(text.find("right") != std::string::npos);
  CHECK(text.find("le_circle, jump_chord") != std::string::npos);
  CHECK(text.find("xxx...") != std::string::npos);
  const std::size_t failed = line_starting(lines, "section 7");
  REQUIRE(failed < lines.size());
  CHECK(lines[failed].find("(no params)") != std::string::npos);
  CHECK(text.find("fitspline: too few points") != std::string::npos);
  // The standard errors known (over 0) in their units, m -> mm; an unknown one (0) left out.
  const std::size_t sigmas = line_starting(lines, "  std. error");
  REQUIRE(sigmas < lines.size());
  CHECK(lines[sigmas].find("chord 0.0025 mm, inlet angle 0.031 deg") != std::string::npos);
  CHECK(text.find("TE radius 0") == std::string::npos);
  // A column the table lacks, and a value that is not finite, print as "-".
  CHECK(lines[line_starting(lines, "  stagger")].find(" - ") != std::string::npos);
}
