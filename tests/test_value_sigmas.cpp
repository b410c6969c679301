// SPDX-License-Identifier: GPL-3.0-or-later
// The values' standard errors through the points' noise (chord_sigma, max_thickness_sigma,
// inlet_angle_sigma, outlet_angle_sigma) against the errors of generated scans, and the
// *_noise checks they drive.
#include "section/checks.h"
#include "section/extras/generate.h"
#include "section/fit_spline.h"
#include "section/io/stream.h"
#include "section/pipe/camber_stream.h"
#include "section/pipe/slice_stream.h"
#include "section/slice.h"
#include "pipe_stages.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

using section::Check;

namespace {

struct Row {
  double error[4], sigma[4];  // chord, max thickness (mm), inlet, outlet (degrees)
  section::CheckBits flags;
};

// A band scan of `blade` at `heights` through the whole pipe.
section::Stream band_stream(const section::BladeDesign& blade, const std::vector<double>& heights,
                            const section::ScanOptions& so, const section::SliceOptions& slice_options = {}) {
  const section::Cloud cloud = section::scan_bands(blade, heights, so);
  const section::SliceResult r = section::slice(cloud, section::planes_at({0, 0, 1}, heights), slice_options);
  return section::test::after_slice(section::to_stream(r, "test", "mm"));
}

// The params rows of a band scan of `blade` at z = 20 and 40 through the pipe, each with its
// values' errors against the truth.
std::vector<Row> measured_rows(const section::BladeDesign& blade, double noise, unsigned seed,
                               const std::vector<double>& heights = {20.0, 40.0},
                               section::ScanOptions so = {}) {
  so.noise = noise;
  so.seed = seed;
  const section::Stream s = band_stream(blade, heights, so);
  std::vector<Row> out;
  const section::Table* params = s.find("params");
  if (!params) return out;
  for (std::size_t row = 0; row < params->rows(); ++row) {
    const auto at = [&](const char* c) { return params->at(row, std::size_t(params->find_column(c))); };
    const section::SectionTruth t =
        section::section_truth(blade.at(heights[std::size_t(at("section"))]), 4000);
    out.push_back(
        {{at("chord") - t.chord, at("max_thickness") - t.max_thickness, at("inlet_angle") - t.inlet_angle,
          at("outlet_angle") - t.outlet_angle},
         {at("chord_sigma"), at("max_thickness_sigma"), at("inlet_angle_sigma"), at("outlet_angle_sigma")},
         section::CheckBits(at("flags"))});
  }
  return out;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

}  // namespace

TEST_CASE("checks: the values' standard errors match their scatter over scans, and flag a noisy one",
          "[checks]") {
  // 20 um of noise on scans 0.08 mm apart (no holes): the chord's edge points move with
  // the end directions (the turbine's 2 mm LE turns its point by 29 um a degree across its
  // chord) and, at a sharp TE, with its flanks' meeting (a 12-degree wedge: 7 times their
  // error), the thickness with its two contacts. Over 4 blades x 4 seeds x 2 sections, each
  // |error| / sigma is a normal's (median 0.67; 0.62-0.87 here): within 0.35-1.1, none
  // beyond 5, and 3 sigma of the thickness (about 11 um) is over its 5 um tolerance on every
  // row. The sharp TE's outlet angle is left out: its end fit's error there is 2-3 times its
  // sigma, and te_vertex flags it on every row.
  const char* names[] = {"chord", "max thickness", "inlet angle", "outlet angle"};
  std::vector<double> z[4];
  const section::BladeDesign blades[] = {section::turbine_blade(), section::compressor_blade(),
                                         section::thick_root_blade(), section::sharp_te_blade()};
  for (const section::BladeDesign& blade : blades)
    for (unsigned seed = 1; seed <= 4; ++seed) {
      const bool sharp = &blade == &blades[3];
      const std::vector<Row> rows = measured_rows(blade, 0.020, seed);
      REQUIRE(rows.size() == 2);
      for (const Row& r : rows) {
        CHECK((r.flags & section::bit(Check::thickness_noise)) != 0);
        for (int k = 0; k < (sharp ? 3 : 4); ++k) {
          INFO(names[k] << ": error " << r.error[k] << ", sigma " << r.sigma[k] << ", seed " << seed);
          REQUIRE(r.sigma[k] > 0);
          z[k].push_back(std::abs(r.error[k]) / r.sigma[k]);
          CHECK(z[k].back() < 5);
        }
        // A chord off by more than its 10 um tolerance is flagged by its noise.
        if (std::abs(r.error[0]) > 0.010) CHECK((r.flags & section::bit(Check::chord_noise)) != 0);
      }
    }
  for (int k = 0; k < 4; ++k) {
    INFO(names[k] << ": median |error| / sigma " << median(z[k]));
    CHECK(median(z[k]) > 0.35);
    CHECK(median(z[k]) < 1.1);
  }
  // The same scans with 2 um of noise: every value stands within its tolerance.
  for (const auto& blade : {section::turbine_blade(), section::compressor_blade()})
    for (const Row& r : measured_rows(blade, 0.002, 1)) {
      const section::CheckBits noisy = section::bit(Check::chord_noise) |
                                       section::bit(Check::thickness_noise) |
                                       section::bit(Check::inlet_noise) | section::bit(Check::outlet_noise);
      CHECK((r.flags & noisy) == 0);
      CHECK(r.sigma[0] < 0.002);
    }
}

TEST_CASE("checks: an LE taken as the blunter end over an unmeasured edge is a doubtful choice", "[checks]") {
  // A band scan of the compressor (inspection defaults, seed 26) where a hole over the
  // 0.3 mm LE left it bridged to a corner: the 0.25 mm TE was taken as the blunter end, the
  // LE, and every end's value came out swapped (the LE radius 18 % off the true LE's) with
  // only the edge flags, which do not cover it: le_choice now does. Seed 1 keeps its ends
  // and gets no le_choice; on both, an LE radius off by more than 3 % is flagged. The
  // swapped section's LE also lies at the other end from the other 8 sections' LEs, which
  // flags it across the blade as well (flag_swapped_ends).
  const section::BladeDesign blade = section::compressor_blade();
  std::vector<double> zs;
  for (int k = 1; k <= 9; ++k) zs.push_back(blade.span * k / 10.0);
  for (const unsigned seed : {26u, 1u}) {
    section::ScanOptions so = section::inspection_scan();
    so.seed = seed;
    const section::SliceResult r =
        section::slice(section::scan_bands(blade, zs, so), section::planes_at({0, 0, 1}, zs));
    const section::Stream s = section::test::after_slice(section::to_stream(r, "test", "mm"));
    const section::Table& params = s.get("params", "test");
    for (std::size_t row = 0; row < params.rows(); ++row) {
      const auto at = [&](const char* col) { return params.at(row, std::size_t(params.find_column(col))); };
      const std::size_t section = std::size_t(at("section"));
      const section::SectionTruth t = section::section_truth(blade.at(zs[section]), 4000);
      const double off = std::abs(at("le_radius") / t.le_radius - 1);
      const section::CheckBits flags = section::CheckBits(at("flags"));
      INFO("seed " << seed << " section " << section << ": LE radius " << off * 100 << " % off; "
                   << section::check_names_text(flags));
      if (off > 0.03) CHECK(section::checks_flagging(flags, "le_radius") != 0);
      if (seed == 26 && section == 2) CHECK((flags & section::bit(Check::le_choice)) != 0);
      if (seed == 1) CHECK((flags & section::bit(Check::le_choice)) == 0);
    }
    // The blade's other sections have their LEs at the other end: with le_choice taken off
    // every row, flag_swapped_ends sets it on section 2 alone.
    section::Stream unflagged = s;
    section::Table& p = *unflagged.find("params");
    for (std::size_t row = 0; row < p.rows(); ++row) {
      double& cell = p.values[row * p.columns.size() + std::size_t(p.find_column("flags"))];
      cell = double(section::CheckBits(cell) & ~section::bit(Check::le_choice));
    }
    unflagged.issues.clear();
    CHECK(section::flag_swapped_ends({&unflagged}) == (seed == 26 ? 1 : 0));
    for (const section::SectionIssue& i : unflagged.issues) {
      CHECK(i.section == 2);
      CHECK(i.message.find("at the other end from those of 8 of the 9 sections") != std::string::npos);
    }
  }
}

namespace {

struct Chord {
  double error, sigma;
  section::CheckBits flags;
};

// The chord (its error against the truth, its standard error and the row's flags) of the
// compressor's section at `z` sampled every `spacing` mm with `sigma` of noise along the
// normal, but every `nose` mm within 2 LE radii of the LE point, fitted and measured by
// camber_stream.
Chord chord_of(double spacing, double nose, double sigma, unsigned seed, double z) {
  const section::SectionTruth t = section::section_truth(section::compressor_blade().at(z), 40000);
  const std::size_t n = t.profile.size();
  const double step = t.perimeter / double(n);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0, sigma);
  std::vector<Eigen::Vector2d> pts;
  double next = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double s = t.profile_s[i], from_le = std::min(s, t.perimeter - s);
    if (s + 1e-12 < next) continue;
    pts.push_back(t.profile[i] + noise(rng) * t.profile_normal[i]);
    next = s + (from_le < 2 * t.le_radius ? nose : spacing) - 0.5 * step;
  }
  section::Stream stream = section::profile_stream(section::fit_spline(pts, pts).spline);
  section::Table points{"points", {"section", "loop", "index", "u", "v"}, {}};
  for (std::size_t i = 0; i < pts.size(); ++i) points.add_row({0, 0, double(i), pts[i].x(), pts[i].y()});
  stream.put(points);
  section::CamberOptions o;
  o.profile_noise = sigma;  // the fit's rms, which a stream from fitspline carries
  section::camber_stream(stream, o);
  const section::Table& params = *stream.find("params");
  REQUIRE(params.rows() == 1);
  return {params.at(0, params.column("chord")) - t.chord, params.at(0, params.column("chord_sigma")),
          section::CheckBits(params.at(0, params.column("flags")))};
}

}  // namespace

TEST_CASE("checks: an edge point on the curve through too few points is as uncertain as their circle",
          "[checks]") {
  // A 0.3 mm LE: points 0.02 mm apart put about 45 on its arc, the circle is refitted on
  // them, and the chord's standard error is the noise's through the end directions and
  // edge points. Every 0.2 mm, 4-5 lie on it: too few to refit the circle on, the edge point
  // is on the fitted curve through them, as uncertain as a circle they would fit, and the
  // chord with it: 5.1 um off, where the noise alone gave it a standard error of under 1 um.
  const Chord dense = chord_of(0.02, 0.02, 0.002, 3, 30), sparse = chord_of(0.02, 0.2, 0.002, 3, 30);
  INFO("chord error " << dense.error << " +- " << dense.sigma << ", sparse nose " << sparse.error << " +- "
                      << sparse.sigma);
  CHECK(std::abs(dense.error) < 0.002);
  CHECK(dense.sigma < 0.002);
  CHECK((dense.flags & section::bit(Check::chord_noise)) == 0);
  CHECK(std::abs(sparse.error) > 0.004);
  CHECK(std::abs(sparse.error) < 2 * sparse.sigma);
  CHECK((sparse.flags & section::bit(Check::chord_noise)) != 0);
}

TEST_CASE("checks: an edge point moves with the circle or the curve it rests on, and the chord with it",
          "[checks]") {
  // A compressor's band scans 0.12 mm apart with 5 um of noise, holes and uneven density
  // (inspection_scan's): its 0.29 mm LE and 0.23 mm TE hold 8-15 points. An edge circle
  // refitted on them moves by several um (its radius's standard error up to 7 um), and
  // where none is refitted the curve's arc through them strays from a circle by as much;
  // the edge point moves with either. Counting the noise alone along the end directions,
  // the chord of seed 19 at z 12 was 10.45 um off with a standard error of 1.8 um and no
  // flag (5.8 of them). Over 48 sections, those flagged by no check but the *_noise ones
  // have each |error| / sigma below 3.5, a normal's median, and every chord off by more
  // than its 10 um tolerance is flagged.
  section::ScanOptions so = section::inspection_scan();
  so.spacing = 0.12;
  const section::CheckBits noise_checks =
      section::bit(Check::chord_noise) | section::bit(Check::thickness_noise) |
      section::bit(Check::inlet_noise) | section::bit(Check::outlet_noise);
  std::vector<double> z;
  for (unsigned seed = 13; seed <= 24; ++seed)
    for (const Row& r :
         measured_rows(section::compressor_blade(), 0.005, seed, {12.0, 24.0, 36.0, 48.0}, so)) {
      INFO("seed " << seed << ": chord error " << r.error[0] << ", sigma " << r.sigma[0] << ", flags "
                   << r.flags);
      if (std::abs(r.error[0]) > 0.010) CHECK(section::checks_flagging(r.flags, "chord") != 0);
      if (r.flags & ~noise_checks) continue;  // another check covers the values
      REQUIRE(r.sigma[0] > 0);
      z.push_back(std::abs(r.error[0]) / r.sigma[0]);
      CHECK(z.back() < 3.5);
    }
  REQUIRE(z.size() >= 20);
  INFO("median |error| / sigma " << median(z) << " over " << z.size());
  CHECK(median(z) > 0.35);
  CHECK(median(z) < 1.1);
}

TEST_CASE("checks: an edge circle not refitted for a gap among its points still has their spread",
          "[checks]") {
  // The compressor's band scans 0.12 mm apart (inspection_scan's noise, holes and density):
  // at z 54, seed 35, its 0.19 mm TE holds 8 measured points with an angular gap over a
  // quarter of the arc, so the circle is not refitted on them and its radius rests on the
  // curve between them, 14 % small (10 % asked). The circle fitted on those points was
  // never made, its spread was taken as unknown (0) and nothing flagged the radius; it is
  // 14 um, twice that over the tolerance's 19 um.
  section::ScanOptions so = section::inspection_scan();
  so.spacing = 0.12;
  so.noise = 0.005;
  so.seed = 35;
  const std::vector<double> heights = {6, 12, 18, 24, 30, 36, 42, 48, 54};
  const section::BladeDesign blade = section::compressor_blade();
  section::SliceOptions slab;
  slab.slab = 0.08;  // evaluate_pipeline's, where this case was found
  const section::Stream s = band_stream(blade, heights, so, slab);
  const section::Table* params = s.find("params");
  REQUIRE(params);
  int off = 0;
  for (std::size_t row = 0; row < params->rows(); ++row) {
    const auto at = [&](const char* c) { return params->at(row, std::size_t(params->find_column(c))); };
    const double z = heights[std::size_t(at("section"))];
    const section::SectionTruth t = section::section_truth(blade.at(z), 4000);
    const double error = at("te_radius") / t.te_radius - 1;
    const section::CheckBits flags = section::flags_mask(at("flags"));
    INFO("z " << z << ": TE radius " << at("te_radius") << " against " << t.te_radius << " (" << 100 * error
              << " %), flags " << section::check_names_text(flags));
    if (std::abs(error) <= 0.10) continue;
    ++off;
    CHECK(section::checks_flagging(flags, "te_radius") != 0);
  }
  CHECK(off >= 1);  // the case this test is about is still measured so
}
