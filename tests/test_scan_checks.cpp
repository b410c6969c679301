// SPDX-License-Identifier: GPL-3.0-or-later
// Checks across the sections of a scan: views merged with a misregistration, seen in most
// sections, flag the sections that show one layer too (flag_scan_layers); a section whose
// LE lies at the other end from the blade's is flagged le_choice (flag_swapped_ends).
#include "section/checks.h"
#include "section/extras/generate.h"
#include "section/io/stream.h"
#include "section/pipe/camber_stream.h"
#include "section/pipe/slice_stream.h"
#include "section/slice.h"
#include "pipe_stages.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

using section::Check;

namespace {

// A part of a stream: params rows (section, flags) and loop 0's fits (section, loop, layers).
section::Stream part_of(const std::vector<int>& sections, const std::vector<double>& layers_um,
                        section::CheckBits other = 0) {
  section::Stream s;
  section::Table params("params", {"section", "flags"});
  section::Table fits("splines", {"section", "loop", "layers"});
  for (std::size_t i = 0; i < sections.size(); ++i) {
    const section::CheckBits bits = other | (layers_um[i] > 0 ? section::bit(Check::layers) : 0);
    params.add_row({double(sections[i]), double(bits)});
    fits.add_row({double(sections[i]), 0.0, layers_um[i] * 1e-3});
  }
  s.put(fits);
  s.put(params);
  return s;
}

int flagged(const section::Stream& s) {
  const section::Table& params = *s.find("params");
  int n = 0;
  for (std::size_t r = 0; r < params.rows(); ++r)
    n += (section::CheckBits(params.at(r, 1)) & section::bit(Check::layers)) != 0;
  return n;
}

}  // namespace

TEST_CASE("scan layers: most sections in two layers flag the rest; one in nine does not", "[checks]") {
  {  // 3 of 5 in two layers, over two parts: the other two flagged, with an issue each
    section::Stream a = part_of({0, 1, 2}, {14, 0, 12}), b = part_of({3, 4}, {0, 13});
    CHECK(section::flag_scan_layers({&a, &b}) == 2);
    CHECK(flagged(a) == 3);
    CHECK(flagged(b) == 2);
    REQUIRE(a.issues.size() == 1);
    CHECK(a.issues[0].section == 1);
    CHECK(a.issues[0].message.find("3 of the 5 sections") != std::string::npos);
    CHECK(a.issues[0].message.find("two layers, a median 0.013 mm apart") != std::string::npos);
    CHECK(section::flag_scan_layers({&a, &b}) == 0);  // said once
  }
  {  // noise running high in one section of nine, or two of five: no scan-wide layers
    section::Stream one = part_of({0, 1, 2, 3, 4, 5, 6, 7, 8}, {0, 0, 0, 9, 0, 0, 0, 0, 0});
    section::Stream two = part_of({0, 1, 2, 3, 4}, {0, 9, 0, 8, 0});
    CHECK(section::flag_scan_layers({&one}) == 0);
    CHECK(section::flag_scan_layers({&two}) == 0);
    CHECK(flagged(one) == 1);
    CHECK(flagged(two) == 2);
  }
  {  // a platform's cut (airfoil) is not counted: 2 of the 3 blade sections
    section::Stream s = part_of({0, 1, 2}, {10, 0, 11});
    section::Stream platform = part_of({3, 4}, {0, 0}, section::bit(Check::airfoil));
    CHECK(section::flag_scan_layers({&s, &platform}) == 3);
  }
}

TEST_CASE("scan layers: a misregistered scan's sections all carry layers", "[checks]") {
  // The generated turbine scanned in two views 15 um apart (evaluate_pipeline
  // --misregistration 0.015, seed 1): at z = 36 the views' overlap at the edges showed no
  // second layer, and its max thickness came out 16 um off (5 asked) with no flag covering
  // it. Every section's thickness is off by about the shift; each row now carries `layers`.
  section::ScanOptions so = section::inspection_scan();
  so.seed = 1;
  so.misregistration = 0.015;
  const std::vector<double> heights{6, 12, 18, 24, 30, 36, 42, 48, 54};
  const section::BladeDesign blade = section::turbine_blade();
  const section::Cloud cloud = section::scan_bands(blade, heights, so);
  section::SliceOptions slab;
  slab.slab = 0.08;  // evaluate_pipeline's
  const section::SliceResult r = section::slice(cloud, section::planes_at({0, 0, 1}, heights), slab);
  const section::Stream s = section::test::after_slice(section::to_stream(r, "test", "mm"));
  const section::Table* params = s.find("params");
  REQUIRE(params);
  REQUIRE(params->rows() == heights.size());
  int off = 0;
  for (std::size_t row = 0; row < params->rows(); ++row) {
    const auto at = [&](const char* c) { return params->at(row, std::size_t(params->find_column(c))); };
    const double error =
        at("max_thickness") - section::section_truth(blade.at(heights[row]), 4000).max_thickness;
    INFO("z = " << heights[row] << ": max thickness " << error * 1e3 << " um off");
    CHECK((section::CheckBits(at("flags")) & section::bit(Check::layers)) != 0);
    off += std::abs(error) > 0.005;
  }
  CHECK(off >= 6);  // the shift shows in the thickness
  int scan_wide = 0;
  for (const section::SectionIssue& i : s.issues)
    scan_wide += i.message.find("this one shows a single layer") != std::string::npos;
  CHECK(scan_wide >= 1);  // one section at least is flagged by the others
}

namespace {

// A part of params rows (section, flags, LE and TE in 3D) and a thickness table of two
// stations a section: chords 40 mm long, turned by `twist_deg` about z (the span), a
// negative length an LE at the other end.
section::Stream blade_part(const std::vector<double>& twist_deg, const std::vector<double>& length,
                           section::CheckBits other = 0) {
  section::Stream s;
  section::Table params("params", {"section", "flags", "le_x", "le_y", "le_z", "te_x", "te_y", "te_z"});
  section::Table thickness("thickness", {"section", "station", "flags"});
  for (std::size_t i = 0; i < twist_deg.size(); ++i) {
    const double a = twist_deg[i] * M_PI / 180, z = 10.0 * double(i);
    const double dx = 0.5 * length[i] * std::cos(a), dy = 0.5 * length[i] * std::sin(a);
    params.add_row({double(i), double(other), -dx, -dy, z, dx, dy, z});
    for (const double station : {0.25, 0.75}) thickness.add_row({double(i), station, 0.0});
  }
  s.put(params);
  s.put(thickness);
  return s;
}

std::vector<int> le_choice_rows(const section::Stream& s, const char* table) {
  const section::Table& t = *s.find(table);
  std::vector<int> out;
  for (std::size_t r = 0; r < t.rows(); ++r)
    if (section::CheckBits(t.at(r, std::size_t(t.find_column("flags")))) & section::bit(Check::le_choice))
      out.push_back(int(t.at(r, 0)));
  return out;
}

}  // namespace

TEST_CASE("swapped ends: a section whose LE lies at the other end from the blade's is flagged", "[checks]") {
  {  // 5 sections twisted 60 deg along the span, the fourth with its ends swapped
    section::Stream s = blade_part({0, 15, 30, 45, 60}, {40, 40, 40, -40, 40});
    CHECK(section::flag_swapped_ends({&s}) == 1);
    CHECK(le_choice_rows(s, "params") == std::vector<int>{3});
    CHECK(le_choice_rows(s, "thickness") == std::vector<int>{3, 3});
    REQUIRE(s.issues.size() == 1);
    CHECK(s.issues[0].section == 3);
    CHECK(s.issues[0].message.find("from those of 4 of the 5 sections") != std::string::npos);
    CHECK(section::flag_swapped_ends({&s}) == 0);  // said once
  }
  {  // a propeller twisted 100 deg, none swapped; over two parts, one swapped at the tip
    section::Stream twisted = blade_part({-50, -25, 0, 25, 50}, {40, 40, 40, 40, 40});
    CHECK(section::flag_swapped_ends({&twisted}) == 0);
    section::Stream a = blade_part({-50, -25, 0}, {40, 40, 40}), b = blade_part({25, 50}, {40, -40});
    CHECK(section::flag_swapped_ends({&a, &b}) == 1);
    CHECK(le_choice_rows(a, "params").empty());
    CHECK(le_choice_rows(b, "params") == std::vector<int>{1});
  }
  {  // no clear majority (2 of 5, 1 of 2): nothing; a platform's cut is not counted
    section::Stream two_of_five = blade_part({0, 5, 10, 15, 20}, {40, -40, 40, -40, 40});
    section::Stream one_of_two = blade_part({0, 5}, {40, -40});
    CHECK(section::flag_swapped_ends({&two_of_five}) == 0);
    CHECK(section::flag_swapped_ends({&one_of_two}) == 0);
    section::Stream blade = blade_part({0, 5}, {40, 40});
    section::Stream platform = blade_part({0}, {-40}, section::bit(Check::airfoil));
    CHECK(section::flag_swapped_ends({&blade, &platform}) == 0);
  }
}
