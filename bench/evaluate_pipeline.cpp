// SPDX-License-Identifier: GPL-3.0-or-later
// evaluate_pipeline: runs slice | smooth | fitspline | camber (through the stream text, as
// the tools do) on generated blades and prints, per section, the fitted curve's distance to
// the exact profile and the camber line and section parameters against section_truth.
// Usage: evaluate_pipeline [--seeds N] [--first-seed S] [--misregistration MM]
//                          [--preset turbine|compressor|both] [--no-camber] [--quiet]
// Legacy positional form: evaluate_pipeline [seeds] [misregistration_mm].
// Columns: rms_um/max_um fitted curve to truth (max only where a measured point lies within
// 0.3 mm along the true profile; gap_um the largest error elsewhere: a bridged hole);
// cam_rms/cam_max camber line to the true camber line (extensions included); d_chord, d_tmax
// in um; d_rle, d_rte in %; d_in, d_out in degrees. The last lines give the worst values and
// the targets. Environment: EVALUATE_STREAMS=PREFIX, EVALUATE_DUMP=preset:seed:section.
#include "section/bspline.h"
#include "section/camber.h"
#include "section/extras/generate.h"
#include "section/extras/score.h"
#include "section/fit_spline.h"
#include "section/io/stream.h"
#include "section/checks.h"
#include "section/pipe/camber_stream.h"
#include "section/pipe/fit_spline_stream.h"
#include "section/pipe/slice_stream.h"
#include "section/pipe/smooth_stream.h"
#include "section/register_views.h"
#include "section/slice.h"
#include "section/smooth.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <map>
#include <optional>
#include <string>

using namespace section;

namespace {

struct Options {
  int seeds = 1, first_seed = 1;
  double misregistration = 0.0;
  double noise = -1, density_min = -1, spacing = -1,
         slab = 0.08;  // scan overrides (< 0: the inspection scan's)
  double twist = 0;    // --twist DEG: extra twist from hub to tip (robustness to drift)
  bool rigid_twist =
      false;  // --rigid-twist: --twist turns the metal angles too (the tip section turned whole)
  double band_spacing = -1;     // --band-spacing MM / --no-band (0); < 0: slice's default
  double band_max = -1;         // --band-max SLABS; < 0: slice's default
  double band_sparse_max = -1;  // --band-sparse-max SLABS; < 0: slice's default
  int holes = -1;
  std::string preset = "both";
  std::string export_dir;  // --export DIR: per-section CSVs for scripts/compare_scipy.py
  bool with_camber = true, quiet = false;
  // --full-scan: scan the whole blade, as a user would, instead of bands around the planes.
  // The bands draw each band's holes within the band (5 per band at the defaults, nearly
  // all crossing the plane), far more holes per section than a whole-blade scan has.
  bool full_scan = false;
  bool register_views_first = false;  // --register (implies --full-scan): register the two views first
  bool fill_gaps = true;              // --no-fill: the slab points alone
  GapFillOptions fill_options;
  std::size_t auto_cells = 0;    // --auto-cells N: the morphology raster budget (0 = the default)
  SmoothOptions smooth_options;  // --smooth-move-tolerance: smooth's stop moved (inputs of fitspline
                                 // a few hundredths of a micrometre apart: fitspline's stability)
  FitSplineOptions fit_options;
  CamberOptions camber_options;
};

const char* const usage =
    "usage: evaluate_pipeline [--seeds N] [--first-seed S] [--misregistration MM] [--noise MM] [--holes N] "
    "[--density-min F] [--spacing MM] [--slab MM] [--twist DEG [--rigid-twist]] [--band-spacing MM] "
    "[--band-max SLABS] "
    "[--band-sparse-max SLABS] [--no-band] [--preset turbine|compressor|both] [--full-scan] [--register] "
    "[--no-fill] [--fill-gap K] [--fill-fraction F] [--fill-reach MM] [--auto-cells N] [--no-camber] "
    "[--quiet] "
    "[--export DIR] [--smooth-move-tolerance SPACINGS]\n"
    "       fit options: [--min-span-points N] [--min-span MM] [--fairness F] [--smoothing-length MM] "
    "[--outlier-floor MM] [--tolerance MM] [--first-iterations N] [--bridge-factor F]; camber: [--edge-arc "
    "DEG] [--edge-core DEG] "
    "[--edge-residual K] "
    "[--edge-noise-residual K] [--edge-circularity K] [--edge-hole R] [--edge-hole-reach R] [--edge-bridge "
    "F] [--edge-prune "
    "DEG] "
    "[--tangent-span FRACTION] [--edge-on-spline] [--edge-point-gap F] [--edge-point-sigma F]\n";

// The flags that set a number, each with the field of `o` it sets.
std::map<std::string, double*> number_flags(Options& o) {
  GapFillOptions& fill = o.fill_options;
  FitSplineOptions& fit = o.fit_options;
  CamberOptions& cam = o.camber_options;
  return {{"--misregistration", &o.misregistration},
          {"--noise", &o.noise},
          {"--density-min", &o.density_min},
          {"--spacing", &o.spacing},
          {"--slab", &o.slab},
          {"--twist", &o.twist},
          {"--band-spacing", &o.band_spacing},
          {"--band-max", &o.band_max},
          {"--band-sparse-max", &o.band_sparse_max},
          {"--fill-gap", &fill.min_gap},
          {"--fill-reach", &fill.reach},
          {"--fill-fraction", &fill.min_gap_fraction},
          {"--smooth-move-tolerance", &o.smooth_options.move_tolerance},
          {"--min-span-points", &fit.min_span_points},
          {"--fairness", &fit.fairness},
          {"--smoothing-length", &fit.smoothing_length},
          {"--outlier-floor", &fit.outlier_floor},
          {"--min-span", &fit.min_span},
          {"--tolerance", &fit.tolerance},
          {"--bridge-factor", &fit.bridge_factor},
          {"--edge-arc", &cam.edge_arc},
          {"--edge-core", &cam.edge_core},
          {"--edge-residual", &cam.edge_residual},
          {"--edge-noise-residual", &cam.edge_noise_residual},
          {"--edge-circularity", &cam.edge_circularity},
          {"--edge-hole", &cam.edge_hole},
          {"--edge-hole-reach", &cam.edge_hole_reach},
          {"--edge-bridge", &cam.edge_bridge},
          {"--edge-prune", &cam.edge_prune},
          {"--tangent-span", &cam.tangent_span},
          {"--edge-point-gap", &cam.edge_point_gap},
          {"--edge-point-sigma", &cam.edge_point_sigma}};
}

// The other flags that take a value.
const std::map<std::string, void (*)(Options&, const char*)> other_values = {
    {"--seeds", [](Options& o, const char* v) { o.seeds = std::atoi(v); }},
    {"--first-seed", [](Options& o, const char* v) { o.first_seed = std::atoi(v); }},
    {"--holes", [](Options& o, const char* v) { o.holes = std::atoi(v); }},
    {"--auto-cells", [](Options& o, const char* v) { o.auto_cells = std::size_t(std::atol(v)); }},
    {"--first-iterations", [](Options& o, const char* v) { o.fit_options.first_iterations = std::atoi(v); }},
    {"--preset", [](Options& o, const char* v) { o.preset = v; }},
    {"--export", [](Options& o, const char* v) { o.export_dir = v; }}};

// The flags without a value.
const std::map<std::string, void (*)(Options&)> switches = {
    {"--rigid-twist", [](Options& o) { o.rigid_twist = true; }},
    {"--no-band", [](Options& o) { o.band_spacing = 0; }},
    {"--no-camber", [](Options& o) { o.with_camber = false; }},
    {"--full-scan", [](Options& o) { o.full_scan = true; }},
    {"--register", [](Options& o) { o.register_views_first = o.full_scan = true; }},
    {"--no-fill", [](Options& o) { o.fill_gaps = false; }},
    {"--edge-on-spline", [](Options& o) { o.camber_options.edge_on_points = false; }},
    {"--quiet", [](Options& o) { o.quiet = true; }}};

// argv to options; an exit code when the program is done (--help: 0, a bad argument: 2).
std::optional<int> parse_args(int argc, char** argv, Options& o) {
  const std::map<std::string, double*> numbers = number_flags(o);
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto digit = [&](std::size_t k) { return std::isdigit(static_cast<unsigned char>(a[k])) != 0; };
    if (numbers.count(a) || other_values.count(a)) {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "evaluate_pipeline: %s needs a value\n", a.c_str());
        return 2;
      }
      const char* v = argv[++i];
      if (const auto n = numbers.find(a); n != numbers.end())
        *n->second = std::atof(v);
      else
        other_values.at(a)(o, v);
    } else if (const auto s = switches.find(a); s != switches.end()) {
      s->second(o);
    } else if (a == "--help" || a == "-h") {
      std::printf("%s", usage);
      return 0;
    } else if (i == 1 && digit(0)) {
      o.seeds = std::atoi(a.c_str());
    } else if (i == 2 && (digit(0) || a[0] == '.')) {
      o.misregistration = std::atof(a.c_str());
    } else {
      std::fprintf(stderr, "evaluate_pipeline: unknown argument '%s'\n", a.c_str());
      return 2;
    }
  }
  return std::nullopt;
}

// The worst errors over the sections of a preset (absolute: mm, relative radii, degrees).
struct Worst {
  double rms = 0, rms_near = 0, max = 0, gap = 0, cam_rms = 0, cam_max = 0, chord = 0, tmax = 0, rle = 0,
         rte = 0, in = 0, out = 0;
  int sections = 0, fit_failed = 0, camber_failed = 0;
  // |error| / its standard error (params ..._sigma) of the edge radii, per edge that has one,
  // and of the chord, max thickness, inlet and outlet angles.
  std::vector<double> le_z = {}, te_z = {}, chord_z = {}, tmax_z = {}, in_z = {}, out_z = {};
  void take(const Worst& o) {
    for (double Worst::*m :
         {&Worst::rms, &Worst::rms_near, &Worst::max, &Worst::gap, &Worst::cam_rms, &Worst::cam_max,
          &Worst::chord, &Worst::tmax, &Worst::rle, &Worst::rte, &Worst::in, &Worst::out})
      this->*m = std::max(this->*m, o.*m);
  }
};

// The preset, with --twist: the tip section turned by this much more about its mid-chord.
BladeDesign blade_of(const std::string& kind, const Options& opt) {
  BladeDesign blade = kind == "turbine" ? turbine_blade() : compressor_blade();
  if (opt.twist != 0) {
    blade.tip.stagger += opt.twist;
    // Without --rigid-twist the metal angles stay: the tip's camber changes by the twist too.
    if (opt.rigid_twist) {
      blade.tip.inlet_angle += opt.twist;
      blade.tip.outlet_angle += opt.twist;
    }
    const double a = blade.tip.stagger * M_PI / 180;
    blade.tip.offset = -0.5 * blade.tip.chord * Eigen::Vector2d(std::cos(a), std::sin(a));
  }
  return blade;
}

// The scan of one case: bands around the planes (the same data in the slabs, far fewer
// points) or the whole blade, its views registered first with --register.
Cloud scan_of(const BladeDesign& blade, const char* kind, int seed, const std::vector<double>& zs,
              const Options& opt) {
  ScanOptions so = inspection_scan();
  so.misregistration = opt.misregistration;
  if (opt.noise >= 0) so.noise = opt.noise;
  if (opt.spacing > 0) so.spacing = opt.spacing;
  if (opt.holes >= 0) so.holes = opt.holes;
  if (opt.density_min >= 0) so.density_min = opt.density_min;
  so.seed = static_cast<std::uint64_t>(seed);
  if (!opt.full_scan) return scan_bands(blade, zs, so);
  Scan scan = generate_scan(blade, so);
  if (!opt.register_views_first) return std::move(scan.cloud);
  // --register: the views apart, as a scanner delivers them, registered onto view 0.
  const std::vector<Cloud> views = views_of(scan);
  const RegisterResult reg = register_views(views);
  const auto& r = reg.views[1];
  if (!opt.quiet)
    std::printf(
        "# %s seed %d: view 1 registered: translation %.2f %.2f %.2f um, pairs %zu, rms %.2f -> %.2f um, "
        "%d iterations\n",
        kind, seed, r.transform.translation().x() * 1e3, r.transform.translation().y() * 1e3,
        r.transform.translation().z() * 1e3, r.pairs, r.rms_before * 1e3, r.rms_after * 1e3, r.iterations);
  return merge_views(views, reg);
}

// One blade and seed through the pipe, and what the sections' scores need of it.
struct Case {
  const char* kind;
  int seed;
  const BladeDesign& blade;
  const std::vector<double>& zs;
  Stream stream;
  double ms = 0;           // per section, the whole pipe
  double camber_ms = NAN;  // per section, camber alone
};

// slice | smooth | fitspline | camber, each stage's stream through its text.
void run_pipe(Case& c, const Cloud& cloud, const Options& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  SliceOptions sopt;
  sopt.slab = opt.slab;
  sopt.fill_gaps = opt.fill_gaps;
  sopt.fill = opt.fill_options;
  if (opt.auto_cells > 0) sopt.morphology.auto_cells = opt.auto_cells;
  if (opt.band_spacing >= 0) sopt.band_spacing = opt.band_spacing;
  if (opt.band_max >= 0) sopt.band_max = opt.band_max;
  if (opt.band_sparse_max >= 0) sopt.band_sparse_max = opt.band_sparse_max;
  const auto& zs = c.zs;
  Stream stream =
      parse_stream(format_stream(to_stream(slice(cloud, planes_at({0, 0, 1}, zs), sopt), "slice")), "slice");
  smooth_stream(stream, opt.smooth_options);
  stream = parse_stream(format_stream(stream), "smooth");
  // EVALUATE_STREAMS=PREFIX writes each blade's stream as fitspline reads it
  // (PREFIX_preset_seed.smooth), to rerun the tools on one case.
  if (const char* prefix = std::getenv("EVALUATE_STREAMS"))
    std::ofstream(std::string(prefix) + "_" + c.kind + "_" + std::to_string(c.seed) + ".smooth")
        << format_stream(stream);
  fit_spline_stream(stream, opt.fit_options);
  stream = parse_stream(format_stream(stream), "fitspline");
  if (opt.with_camber) {
    const auto c0 = std::chrono::steady_clock::now();
    camber_stream(stream, opt.camber_options);  // with the check across the sections
    c.camber_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - c0).count() / zs.size();
    stream = parse_stream(format_stream(stream), "camber");
  }
  c.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() / zs.size();
  c.stream = std::move(stream);
}

// "stage: message; " for each issue of section `id`.
std::string issues_of(const Stream& stream, int id) {
  std::string why;
  for (const auto& is : stream.issues)
    if (is.section == id) why += is.stage + ": " + is.message + "; ";
  return why;
}

// One section's errors; the signed ones for --export (NaN without a camber result).
struct SectionScore {
  Worst e;
  double where_max = 0, where_gap = 0;
  double cam_rms = NAN, cam_max = NAN, le_point_err = NAN, te_point_err = NAN, rle_signed = NAN,
         rte_signed = NAN;
  double sigmas[4] = {0, 0, 0, 0};  // camber's chord, max thickness, inlet, outlet standard errors
};

// The camber columns of a section's line, or CAMBER FAILED with its issues.
std::string camber_columns(const Case& c, int id, const SectionTruth& truth, SectionScore& s, Worst& W) {
  const Table* par = c.stream.find("params");
  long row = -1;
  for (std::size_t r = 0; par && r < par->rows(); ++r)
    if (int(par->at(r, 0)) == id) row = static_cast<long>(r);
  if (row < 0) {
    ++W.camber_failed;
    return "   CAMBER FAILED " + issues_of(c.stream, id);
  }
  const CamberScore cs = score_camber(c.stream, id, truth);
  Worst& e = s.e;
  e.cam_rms = cs.camber_rms;
  e.cam_max = cs.camber_max;
  s.cam_rms = e.cam_rms, s.cam_max = e.cam_max;
  s.le_point_err = cs.le_point;
  s.te_point_err = cs.te_point;
  s.rle_signed = cs.le_radius;
  s.rte_signed = cs.te_radius;
  e.chord = std::abs(cs.chord);
  e.tmax = std::abs(cs.max_thickness);
  e.rle = std::abs(cs.le_radius);
  e.rte = std::abs(cs.te_radius);
  if (cs.le_radius_sigma > 0) W.le_z.push_back(e.rle * truth.le_radius / cs.le_radius_sigma);
  if (cs.te_radius_sigma > 0) W.te_z.push_back(e.rte * truth.te_radius / cs.te_radius_sigma);
  e.in = std::abs(cs.inlet_angle);
  e.out = std::abs(cs.outlet_angle);
  const double sigma[] = {cs.chord_sigma, cs.max_thickness_sigma, cs.inlet_angle_sigma,
                          cs.outlet_angle_sigma};
  const double error[] = {e.chord, e.tmax, e.in, e.out};
  std::vector<double>* zs[] = {&W.chord_z, &W.tmax_z, &W.in_z, &W.out_z};
  for (int k = 0; k < 4; ++k)
    if ((s.sigmas[k] = sigma[k]) > 0) zs[k]->push_back(error[k] / sigma[k]);
  char buf[256];
  std::snprintf(buf, sizeof buf, " %7.2f %7.2f %7.2f %7.2f %6.2f %6.2f %6.3f %6.3f", e.cam_rms * 1e3,
                e.cam_max * 1e3, cs.chord * 1e3, cs.max_thickness * 1e3, e.rle * 100, e.rte * 100,
                cs.inlet_angle, cs.outlet_angle);
  return buf;
}

// DIR/<kind>_<seed>_<section>_<what>.csv opened for writing, its header line written; null
// when it cannot be opened.
FILE* export_file(const Options& opt, const Case& c, int id, const char* what, const char* header) {
  char name[512];
  std::snprintf(name, sizeof name, "%s/%s_%d_%d_%s.csv", opt.export_dir.c_str(), c.kind, c.seed, id, what);
  FILE* f = std::fopen(name, "w");
  if (f) std::fprintf(f, "%s\n", header);
  return f;
}

// --export: the slab points with their true arc length, the dense true profile, our fitted
// curve, the true camber line and edges, so that another fitter can be run on the same data.
void export_section(const Options& opt, const Case& c, int id, const std::vector<Eigen::Vector2d>& measured,
                    const SectionTruth& truth, const BSpline& curve) {
  if (FILE* f = export_file(opt, c, id, "points", "u,v,true_s")) {
    for (const auto& m : measured) std::fprintf(f, "%.9g,%.9g,%.9g\n", m.x(), m.y(), locate(truth, m).s);
    std::fclose(f);
  }
  if (FILE* f = export_file(opt, c, id, "truth", "u,v")) {
    for (std::size_t i = 0; i < truth.profile.size(); i += 2)
      std::fprintf(f, "%.9g,%.9g\n", truth.profile[i].x(), truth.profile[i].y());
    std::fclose(f);
  }
  if (FILE* f = export_file(opt, c, id, "fit", "u,v")) {
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector2d p = curve.point(curve.t_min() + (curve.t_max() - curve.t_min()) * i / n);
      std::fprintf(f, "%.9g,%.9g\n", p.x(), p.y());
    }
    std::fclose(f);
  }
  if (FILE* f = export_file(opt, c, id, "camber", "u,v")) {
    for (const auto& q : truth.camber) std::fprintf(f, "%.9g,%.9g\n", q.x(), q.y());
    std::fclose(f);
  }
  if (FILE* f = export_file(
          opt, c, id, "edges",
          "le_u,le_v,te_u,te_v,le_center_u,le_center_v,le_radius,te_center_u,te_center_v,te_radius")) {
    std::fprintf(f, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", truth.le_point.x(),
                 truth.le_point.y(), truth.te_point.x(), truth.te_point.y(), truth.le_center.x(),
                 truth.le_center.y(), truth.le_radius, truth.te_center.x(), truth.te_center.y(),
                 truth.te_radius);
    std::fclose(f);
  }
}

// --export: the section's scores appended to DIR/scores.csv (its header when new).
void export_scores(const Options& opt, const Case& c, int id, const SectionScore& s) {
  char name[512];
  std::snprintf(name, sizeof name, "%s/scores.csv", opt.export_dir.c_str());
  FILE* probe = std::fopen(name, "r");
  const bool fresh = !probe;
  if (probe) std::fclose(probe);
  FILE* f = std::fopen(name, "a");
  if (!f) return;
  if (fresh)
    std::fprintf(f,
                 "blade,seed,section,rms_um,max_um,gap_um,ms_per_section,cam_rms_um,cam_max_um,"
                 "le_radius_err_pct,te_radius_err_pct,le_point_um,te_point_um,camber_ms\n");
  const Worst& e = s.e;
  std::fprintf(f, "%s,%d,%d,%.4f,%.4f,%.4f,%.1f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.2f\n", c.kind, c.seed, id,
               e.rms * 1e3, e.max * 1e3, e.gap * 1e3, c.ms, s.cam_rms * 1e3, s.cam_max * 1e3,
               s.rle_signed * 100, s.rte_signed * 100, s.le_point_err * 1e3, s.te_point_err * 1e3,
               c.camber_ms);
  std::fclose(f);
}

// EVALUATE_DUMP=preset:seed:section writes the measured points and the fitted curve with
// their signed truth distances to evaluate_dump.csv, for a closer look at one case.
void dump_section(const Case& c, int id, const std::vector<Eigen::Vector2d>& measured,
                  const SectionTruth& truth, const BSpline& curve) {
  const char* dump = std::getenv("EVALUATE_DUMP");
  if (!dump) return;
  char want[64];
  std::snprintf(want, sizeof want, "%s:%d:%d", c.kind, c.seed, id);
  if (std::string(dump) != want) return;
  FILE* f = std::fopen("evaluate_dump.csv", "w");
  std::fprintf(f, "kind,u,v,s,d\n");
  auto put = [&](const char* what, const Eigen::Vector2d& p) {
    const ProfileLocation l = locate(truth, p);
    std::fprintf(f, "%s,%.6f,%.6f,%.6f,%.6f\n", what, p.x(), p.y(), l.s, l.distance);
  };
  for (const auto& m : measured) put("m", m);
  for (const auto& q : sample(curve, 5000)) put("c", q);
  if (const Table* sm = c.stream.find("smoothed"))
    for (std::size_t r = 0; r < sm->rows(); ++r)
      if (int(sm->at(r, 0)) == id) put("s", {sm->at(r, sm->column("u")), sm->at(r, sm->column("v"))});
  std::fprintf(f, "te,%.6f,%.6f,%.6f,0\n", truth.te_point.x(), truth.te_point.y(), truth.te_s);
  std::fclose(f);
}

// The end of a section's line: where the largest errors are (arc length from the LE point,
// or from the TE point), the layers fitspline found, the edges camber flagged.
std::string where_columns(const Case& c, int id, const SectionTruth& truth, const SectionScore& s) {
  auto at = [&](double where) {
    const double P = truth.perimeter;
    const double le = std::min(where, P - where), te = std::abs(where - truth.te_s);
    char w[48];
    std::snprintf(w, sizeof w, le < te ? "LE%+.1f" : "TE%+.1f",
                  le < te ? (where > P / 2 ? where - P : where) : where - truth.te_s);
    return std::string(w);
  };
  char buf[256];
  std::snprintf(buf, sizeof buf, " %6.0f  max@%s gap@%s rms_near %.2f", c.ms, at(s.where_max).c_str(),
                at(s.where_gap).c_str(), s.e.rms_near * 1e3);
  std::string line = buf;
  if (s.sigmas[0] > 0) {  // the standard errors camber gave (um, um, deg, deg)
    std::snprintf(buf, sizeof buf, " sigma %.2f %.2f %.3f %.3f", s.sigmas[0] * 1e3, s.sigmas[1] * 1e3,
                  s.sigmas[2], s.sigmas[3]);
    line += buf;
  }
  // Two layers of points found by fitspline (views merged with a misregistration).
  if (const Table* sp = c.stream.find("splines")) {
    const std::size_t cl = sp->column("layers"), cll = sp->column("layers_length");
    for (std::size_t r = 0; r < sp->rows(); ++r)
      if (int(sp->at(r, 0)) == id && int(sp->at(r, 1)) == 0 && sp->at(r, cl) > 0) {
        std::snprintf(buf, sizeof buf, " layers %.1f/%.2f", sp->at(r, cl) * 1e3, sp->at(r, cll));
        line += buf;
      }
  }
  // The checks the section's params failed (the params table's flags, section/checks.h).
  if (const Table* par = c.stream.find("params"))
    for (std::size_t r = 0; r < par->rows(); ++r)
      if (int(par->at(r, 0)) == id && par->at(r, par->column("flags")) != 0) {
        line += " flags";
        const auto flags = section::flags_mask(par->at(r, par->column("flags")));
        for (const auto& k : check_names)
          if (flags & bit(k.check)) line += std::string(":") + k.name;
      }
  // Edges camber flagged as not measured (a hole or too few points on the edge).
  for (const auto& is : c.stream.issues)
    if (is.section == id && is.stage == "camber") {
      if (is.message.find("leading edge not measured") != std::string::npos) line += " LE-unmeasured";
      if (is.message.find("trailing edge not measured") != std::string::npos) line += " TE-unmeasured";
      if (is.message.find("leading edge partly not measured") != std::string::npos) line += " LE-partly";
      if (is.message.find("trailing edge partly not measured") != std::string::npos) line += " TE-partly";
    }
  return line;
}

// Scores section k of a case against its truth, prints its line and takes its errors into W.
void evaluate_section(const Case& c, std::size_t k, const std::map<std::pair<int, int>, BSpline>& curves,
                      const Table& pts, const Options& opt, Worst& W) {
  const int id = static_cast<int>(k);
  ++W.sections;
  const auto it = curves.find({id, 0});
  if (it == curves.end()) {
    ++W.fit_failed;
    std::printf("%-10s %4d %3d %5.1f   FIT FAILED %s\n", c.kind, c.seed, id, c.zs[k],
                issues_of(c.stream, id).c_str());
    return;
  }
  std::vector<Eigen::Vector2d> measured;
  for (std::size_t r = 0; r < pts.rows(); ++r)
    if (int(pts.at(r, 0)) == id && int(pts.at(r, 1)) == 0) measured.emplace_back(pts.at(r, 3), pts.at(r, 4));
  const SectionTruth truth = section_truth(c.blade.at(c.zs[k]));
  SectionScore s;
  const FitScore fs = score_fit(it->second, measured, truth);
  s.e.rms = fs.rms;
  s.e.rms_near = fs.rms_near;
  s.e.max = fs.max_near;
  s.e.gap = fs.gap;
  s.where_max = fs.where_max, s.where_gap = fs.where_gap;
  char buf[256];
  std::snprintf(buf, sizeof buf, "%-10s %4d %3d %5.1f %7.2f %7.2f %7.2f", c.kind, c.seed, id, c.zs[k],
                s.e.rms * 1e3, s.e.max * 1e3, s.e.gap * 1e3);
  std::string line = buf;
  if (opt.with_camber) line += camber_columns(c, id, truth, s, W);
  W.take(s.e);
  if (!opt.export_dir.empty()) {
    export_section(opt, c, id, measured, truth, it->second);
    export_scores(opt, c, id, s);
  }
  dump_section(c, id, measured, truth, it->second);
  line += where_columns(c, id, truth, s);
  if (!opt.quiet) std::printf("%s\n", line.c_str());
}

// How the edge radii's errors compare with their standard errors (LE / TE).
std::string calibration_line(const std::vector<double>& le_z, const std::vector<double>& te_z) {
  const Calibration le = calibration(le_z), te = calibration(te_z);
  char buf[320];
  std::snprintf(
      buf, sizeof buf,
      "radius |error| / standard error (LE / TE, %zu / %zu edges): median %.2f / %.2f, 90 %% %.2f / "
      "%.2f, 99 %% %.2f / %.2f, beyond 2 sigma %.1f / %.1f %%, beyond 3 sigma %.1f / %.1f %%",
      le.count, te.count, le.median, te.median, le.p90, te.p90, le.p99, te.p99, 100 * le.beyond2,
      100 * te.beyond2, 100 * le.beyond3, 100 * te.beyond3);
  return buf;
}

void print_worst(const std::map<std::string, Worst>& worst, const Options& opt) {
  const bool misreg = opt.misregistration > 0;
  for (const auto& [kind, W] : worst) {
    std::printf(
        "worst %-10s (%d sections, %d fit failed, %d camber failed): fit rms %.2f um (%.2f um where "
        "measured), max %.2f um (measured within 0.3 mm along the profile), hole bridging %.2f um\n",
        kind.c_str(), W.sections, W.fit_failed, W.camber_failed, W.rms * 1e3, W.rms_near * 1e3, W.max * 1e3,
        W.gap * 1e3);
    if (opt.with_camber)
      std::printf(
          "      %-10s camber rms %.2f um, max %.2f um; chord %.2f um, max thickness %.2f um, "
          "LE radius %.2f%%, TE radius %.2f%%, inlet %.3f deg, outlet %.3f deg\n",
          kind.c_str(), W.cam_rms * 1e3, W.cam_max * 1e3, W.chord * 1e3, W.tmax * 1e3, W.rle * 100,
          W.rte * 100, W.in, W.out);
    if (opt.with_camber && !W.le_z.empty() && !W.te_z.empty())
      std::printf("      %-10s %s\n", kind.c_str(), calibration_line(W.le_z, W.te_z).c_str());
    if (opt.with_camber && !W.chord_z.empty())
      std::printf(
          "      %-10s value |error| / standard error: chord %s; max thickness %s; inlet %s; outlet %s\n",
          kind.c_str(), calibration_text(W.chord_z).c_str(), calibration_text(W.tmax_z).c_str(),
          calibration_text(W.in_z).c_str(), calibration_text(W.out_z).c_str());
  }
  std::printf(
      "targets: fit rms <= %s um, max <= %s um; camber rms <= 3 um, max <= 15 um, chord 10 um, "
      "max thickness 5 um, LE radius 3%%, TE radius 10%%, angles 0.5 deg\n",
      misreg ? "10" : "3", misreg ? "25" : "15");
}

void evaluate(const Options& opt) {
  std::printf("%-10s %4s %3s %5s %7s %7s %7s %7s %7s %7s %7s %6s %6s %6s %6s %6s\n", "blade", "seed", "sec",
              "z", "rms_um", "max_um", "gap_um", "camrms", "cammax", "dchord", "dtmax", "drle%", "drte%",
              "d_in", "d_out", "ms");
  std::map<std::string, Worst> worst;
  for (const char* kind : {"turbine", "compressor"}) {
    if (opt.preset != "both" && opt.preset != kind) continue;
    Worst& W = worst[kind];
    const BladeDesign blade = blade_of(kind, opt);
    for (int seed = opt.first_seed; seed < opt.first_seed + opt.seeds; ++seed) {
      std::vector<double> zs;
      for (int k = 1; k <= 9; ++k) zs.push_back(blade.span * k / 10.0);
      const Cloud cloud = scan_of(blade, kind, seed, zs, opt);
      Case c{kind, seed, blade, zs};
      run_pipe(c, cloud, opt);
      const auto curves = splines(c.stream);
      const Table& pts = c.stream.get("points", "slice");
      for (std::size_t k = 0; k < zs.size(); ++k) evaluate_section(c, k, curves, pts, opt, W);
    }
  }
  print_worst(worst, opt);
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  if (const auto code = parse_args(argc, argv, opt)) return *code;
  try {
    evaluate(opt);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "evaluate_pipeline: error: %s\n", e.what());
    return 1;
  }
}
