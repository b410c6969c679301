// evaluate_pipeline: runs slice | smooth | fitspline | camber (through the stream text, as
// the tools do) on generated blades and prints, per section, the fitted curve's distance to
// the exact profile and the camber line and section parameters against section_truth.
// Usage: evaluate_pipeline [--seeds N] [--first-seed S] [--misregistration MM]
//                          [--preset turbine|compressor|both] [--no-camber] [--quiet]
// Legacy positional form: evaluate_pipeline [seeds] [misregistration_mm].
// Columns: rms_um/max_um fitted curve to truth (max only where a measured point lies within
// 0.3 mm along the true profile; gap_um the largest error elsewhere: a bridged hole); cam_rms/cam_max camber line
// to the true camber line (extensions included); d_chord, d_tmax in um; d_rle, d_rte in %;
// d_in, d_out in degrees. The last lines give the worst values and the targets.
#include "section/bspline.h"
#include "section/camber.h"
#include "section/fit_spline.h"
#include "section/extras/generate.h"
#include "section/io/stream.h"
#include "section/pipe/slice_stream.h"
#include "section/pipe/smooth_stream.h"
#include "section/pipe/fit_spline_stream.h"
#include "section/pipe/camber_stream.h"
#include "section/register_views.h"
#include "section/extras/score.h"
#include "section/slice.h"
#include "section/smooth.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <exception>
#include <map>
#include <string>

using namespace section;

namespace {

struct Worst {
  double rms = 0, rms_near = 0, max = 0, gap = 0, cam_rms = 0, cam_max = 0, chord = 0, tmax = 0, rle = 0, rte = 0,
         in = 0, out = 0;
  int sections = 0, fit_failed = 0, camber_failed = 0;
  void take(const Worst& o) {
    rms = std::max(rms, o.rms);
    rms_near = std::max(rms_near, o.rms_near);
    max = std::max(max, o.max);
    gap = std::max(gap, o.gap);
    cam_rms = std::max(cam_rms, o.cam_rms);
    cam_max = std::max(cam_max, o.cam_max);
    chord = std::max(chord, o.chord);
    tmax = std::max(tmax, o.tmax);
    rle = std::max(rle, o.rle);
    rte = std::max(rte, o.rte);
    in = std::max(in, o.in);
    out = std::max(out, o.out);
  }
};

}  // namespace

int main(int argc, char** argv) {
  int seeds = 1, first_seed = 1;
  double misregistration = 0.0;
  double noise = -1, density_min = -1, slab = 0.08;  // scan overrides (< 0: the inspection scan's)
  double twist = 0;          // --twist DEG: extra twist from hub to tip (robustness to drift)
  bool rigid_twist = false;  // --rigid-twist: --twist turns the metal angles too (the tip section turned whole)
  double band_spacing = -1;  // --band-spacing MM / --no-band (0); < 0: slice's default
  double band_max = -1;      // --band-max SLABS; < 0: slice's default
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
  bool fill_gaps = true;  // --no-fill: the slab points alone
  GapFillOptions fill_options;
  std::size_t auto_cells = 0;  // --auto-cells N: the morphology raster budget (0 = the default)
  FitSplineOptions fit_options;
  CamberOptions camber_options;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "evaluate_pipeline: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--seeds") seeds = std::atoi(value());
    else if (a == "--first-seed") first_seed = std::atoi(value());
    else if (a == "--misregistration") misregistration = std::atof(value());
    else if (a == "--noise") noise = std::atof(value());
    else if (a == "--holes") holes = std::atoi(value());
    else if (a == "--density-min") density_min = std::atof(value());
    else if (a == "--slab") slab = std::atof(value());
    else if (a == "--twist") twist = std::atof(value());
    else if (a == "--rigid-twist") rigid_twist = true;
    else if (a == "--band-spacing") band_spacing = std::atof(value());
    else if (a == "--no-band") band_spacing = 0;
    else if (a == "--band-max") band_max = std::atof(value());
    else if (a == "--band-sparse-max") band_sparse_max = std::atof(value());
    else if (a == "--preset") preset = value();
    else if (a == "--no-camber") with_camber = false;
    else if (a == "--full-scan") full_scan = true;
    else if (a == "--register") register_views_first = full_scan = true;
    else if (a == "--no-fill") fill_gaps = false;
    else if (a == "--fill-gap") fill_options.min_gap = std::atof(value());
    else if (a == "--fill-reach") fill_options.reach = std::atof(value());
    else if (a == "--fill-fraction") fill_options.min_gap_fraction = std::atof(value());
    else if (a == "--auto-cells") auto_cells = std::size_t(std::atol(value()));
    else if (a == "--export") export_dir = value();
    else if (a == "--min-span-points") fit_options.min_span_points = std::atof(value());
    else if (a == "--fairness") fit_options.fairness = std::atof(value());
    else if (a == "--smoothing-length") fit_options.smoothing_length = std::atof(value());
    else if (a == "--outlier-floor") fit_options.outlier_floor = std::atof(value());
    else if (a == "--min-span") fit_options.min_span = std::atof(value());
    else if (a == "--tolerance") fit_options.tolerance = std::atof(value());
    else if (a == "--edge-arc") camber_options.edge_arc = std::atof(value());
    else if (a == "--edge-core") camber_options.edge_core = std::atof(value());
    else if (a == "--edge-residual") camber_options.edge_residual = std::atof(value());
    else if (a == "--edge-noise-residual") camber_options.edge_noise_residual = std::atof(value());
    else if (a == "--edge-circularity") camber_options.edge_circularity = std::atof(value());
    else if (a == "--edge-hole") camber_options.edge_hole = std::atof(value());
    else if (a == "--edge-hole-reach") camber_options.edge_hole_reach = std::atof(value());
    else if (a == "--edge-prune") camber_options.edge_prune = std::atof(value());
    else if (a == "--tangent-span") camber_options.tangent_span = std::atof(value());
    else if (a == "--edge-on-spline") camber_options.edge_on_points = false;
    else if (a == "--edge-point-gap") camber_options.edge_point_gap = std::atof(value());
    else if (a == "--edge-point-sigma") camber_options.edge_point_sigma = std::atof(value());
    else if (a == "--quiet") quiet = true;
    else if (a == "--help" || a == "-h") {
      std::printf("usage: evaluate_pipeline [--seeds N] [--first-seed S] [--misregistration MM] [--noise MM] [--holes N] [--density-min F] [--slab MM] [--twist DEG [--rigid-twist]] [--band-spacing MM] [--band-max SLABS] [--band-sparse-max SLABS] [--no-band] "
                  "[--preset turbine|compressor|both] [--full-scan] [--register] [--no-fill] [--fill-gap K] [--fill-fraction F] [--fill-reach MM] [--auto-cells N] [--no-camber] [--quiet] [--export DIR]\n"
                  "       fit options: [--min-span-points N] [--min-span MM] [--fairness F] [--smoothing-length MM] [--outlier-floor MM] [--tolerance MM]; camber: [--edge-arc DEG] [--edge-core DEG] [--edge-residual K] [--edge-noise-residual K] [--edge-circularity K] [--edge-hole R] [--edge-hole-reach R] "
                  "[--edge-prune DEG] [--tangent-span FRACTION] [--edge-on-spline] [--edge-point-gap F] [--edge-point-sigma F]\n");
      return 0;
    } else if (i == 1 && std::isdigit(static_cast<unsigned char>(a[0]))) seeds = std::atoi(a.c_str());
    else if (i == 2 && (std::isdigit(static_cast<unsigned char>(a[0])) || a[0] == '.'))
      misregistration = std::atof(a.c_str());
    else {
      std::fprintf(stderr, "evaluate_pipeline: unknown argument '%s'\n", a.c_str());
      return 2;
    }
  }
  try {
    std::printf("%-10s %4s %3s %5s %7s %7s %7s %7s %7s %7s %7s %6s %6s %6s %6s %6s\n", "blade", "seed",
                "sec", "z", "rms_um", "max_um", "gap_um", "camrms", "cammax", "dchord", "dtmax", "drle%",
                "drte%", "d_in", "d_out", "ms");
    std::map<std::string, Worst> worst;
    for (const char* kind : {"turbine", "compressor"}) {
      if (preset != "both" && preset != kind) continue;
      Worst& W = worst[kind];
      BladeDesign blade = std::string(kind) == "turbine" ? turbine_blade() : compressor_blade();
      if (twist != 0) {
        // --twist: the tip section turned by this much more about its mid-chord.
        blade.tip.stagger += twist;
        // Without --rigid-twist the metal angles stay: the tip's camber changes by the twist too.
        if (rigid_twist) {
          blade.tip.inlet_angle += twist;
          blade.tip.outlet_angle += twist;
        }
        const double a = blade.tip.stagger * M_PI / 180;
        blade.tip.offset = -0.5 * blade.tip.chord * Eigen::Vector2d(std::cos(a), std::sin(a));
      }
      for (int seed = first_seed; seed < first_seed + seeds; ++seed) {
        std::vector<double> zs;
        for (int k = 1; k <= 9; ++k) zs.push_back(blade.span * k / 10.0);
        ScanOptions so = inspection_scan();
        so.misregistration = misregistration;
        if (noise >= 0) so.noise = noise;
        if (holes >= 0) so.holes = holes;
        if (density_min >= 0) so.density_min = density_min;
        so.seed = static_cast<std::uint64_t>(seed);
        // Scan only bands around the planes: the same data in the slabs, far fewer points.
        Cloud cloud;
        if (full_scan) {
          Scan scan = generate_scan(blade, so);
          if (register_views_first) {
            // --register: the views apart, as a scanner delivers them, registered onto view 0.
            const std::vector<Cloud> views = views_of(scan);
            const RegisterResult reg = register_views(views);
            const auto& r = reg.views[1];
            if (!quiet)
              std::printf("# %s seed %d: view 1 registered: translation %.2f %.2f %.2f um, pairs %zu, rms %.2f -> %.2f um, %d iterations\n",
                          kind, seed, r.transform.translation().x() * 1e3, r.transform.translation().y() * 1e3,
                          r.transform.translation().z() * 1e3, r.pairs, r.rms_before * 1e3, r.rms_after * 1e3, r.iterations);
            cloud = merge_views(views, reg);
          } else {
            cloud = std::move(scan.cloud);
          }
        } else {
          cloud = scan_bands(blade, zs, so);
        }
        const auto t0 = std::chrono::steady_clock::now();
        SliceOptions sopt;
        sopt.slab = slab;
        sopt.fill_gaps = fill_gaps;
        sopt.fill = fill_options;
        if (auto_cells > 0) sopt.morphology.auto_cells = auto_cells;
        if (band_spacing >= 0) sopt.band_spacing = band_spacing;
        if (band_max >= 0) sopt.band_max = band_max;
        if (band_sparse_max >= 0) sopt.band_sparse_max = band_sparse_max;
        Stream stream = parse_stream(format_stream(to_stream(slice(cloud, planes_at({0, 0, 1}, zs), sopt), "slice")), "slice");
        smooth_stream(stream);
        stream = parse_stream(format_stream(stream), "smooth");
        // EVALUATE_STREAMS=PREFIX writes each blade's stream as fitspline reads it
        // (PREFIX_preset_seed.smooth), to rerun the tools on one case.
        if (const char* prefix = std::getenv("EVALUATE_STREAMS"))
          std::ofstream(std::string(prefix) + "_" + kind + "_" + std::to_string(seed) + ".smooth") << format_stream(stream);
        fit_spline_stream(stream, fit_options);
        stream = parse_stream(format_stream(stream), "fitspline");
        double camber_ms = NAN;
        if (with_camber) {
          const auto c0 = std::chrono::steady_clock::now();
          camber_stream(stream, camber_options);
          camber_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - c0).count() / zs.size();
          stream = parse_stream(format_stream(stream), "camber");
        }
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() / zs.size();
        const auto curves = splines(stream);
        const Table& pts = stream.get("points", "slice");
        const Table* cam = stream.find("camber");
        const Table* par = stream.find("params");
        for (std::size_t k = 0; k < zs.size(); ++k) {
          const int id = static_cast<int>(k);
          ++W.sections;
          const auto it = curves.find({id, 0});
          if (it == curves.end()) {
            ++W.fit_failed;
            std::string why;
            for (const auto& is : stream.issues)
              if (is.section == id) why += is.stage + ": " + is.message + "; ";
            std::printf("%-10s %4d %3d %5.1f   FIT FAILED %s\n", kind, seed, id, zs[k], why.c_str());
            continue;
          }
          std::vector<Eigen::Vector2d> measured;
          for (std::size_t r = 0; r < pts.rows(); ++r)
            if (int(pts.at(r, 0)) == id && int(pts.at(r, 1)) == 0) measured.emplace_back(pts.at(r, 3), pts.at(r, 4));
          const SectionTruth truth = section_truth(blade.at(zs[k]));
          Worst e;
          // For --export: our camber scores (NaN without a camber result).
          double cam_rms = NAN, cam_max = NAN, le_point_err = NAN, te_point_err = NAN, rle_signed = NAN,
                 rte_signed = NAN;
          const FitScore fs = score_fit(it->second, measured, truth);
          e.rms = fs.rms;
          e.rms_near = fs.rms_near;
          e.max = fs.max_near;
          e.gap = fs.gap;
          const double where_max = fs.where_max, where_gap = fs.where_gap;
          std::string line;
          char buf[256];
          std::snprintf(buf, sizeof buf, "%-10s %4d %3d %5.1f %7.2f %7.2f %7.2f", kind, seed, id, zs[k], e.rms * 1e3,
                        e.max * 1e3, e.gap * 1e3);
          line = buf;
          if (with_camber) {
            long row = -1;
            for (std::size_t r = 0; par && r < par->rows(); ++r)
              if (int(par->at(r, 0)) == id) row = static_cast<long>(r);
            if (row < 0) {
              ++W.camber_failed;
              std::string why;
              for (const auto& is : stream.issues)
                if (is.section == id) why += is.stage + ": " + is.message + "; ";
              line += "   CAMBER FAILED " + why;
            } else {
              const CamberScore cs = score_camber(stream, id, truth);
              e.cam_rms = cs.camber_rms;
              e.cam_max = cs.camber_max;
              cam_rms = e.cam_rms, cam_max = e.cam_max;
              le_point_err = cs.le_point;
              te_point_err = cs.te_point;
              rle_signed = cs.le_radius;
              rte_signed = cs.te_radius;
              e.chord = std::abs(cs.chord);
              e.tmax = std::abs(cs.max_thickness);
              e.rle = std::abs(cs.le_radius);
              e.rte = std::abs(cs.te_radius);
              e.in = std::abs(cs.inlet_angle);
              e.out = std::abs(cs.outlet_angle);
              std::snprintf(buf, sizeof buf, " %7.2f %7.2f %7.2f %7.2f %6.2f %6.2f %6.3f %6.3f", e.cam_rms * 1e3,
                            e.cam_max * 1e3, cs.chord * 1e3, cs.max_thickness * 1e3, e.rle * 100, e.rte * 100,
                            cs.inlet_angle, cs.outlet_angle);
              line += buf;
            }
          }
          W.take(e);
          // --export: the slab points with their true arc length, the dense true profile and
          // our scores, so that another fitter can be run on the same data.
          if (!export_dir.empty()) {
            char name[512];
            std::snprintf(name, sizeof name, "%s/%s_%d_%d_points.csv", export_dir.c_str(), kind, seed, id);
            if (FILE* f = std::fopen(name, "w")) {
              std::fprintf(f, "u,v,true_s\n");
              for (const auto& m : measured) std::fprintf(f, "%.9g,%.9g,%.9g\n", m.x(), m.y(), locate(truth, m).s);
              std::fclose(f);
            }
            std::snprintf(name, sizeof name, "%s/%s_%d_%d_truth.csv", export_dir.c_str(), kind, seed, id);
            if (FILE* f = std::fopen(name, "w")) {
              std::fprintf(f, "u,v\n");
              for (std::size_t i = 0; i < truth.profile.size(); i += 2)
                std::fprintf(f, "%.9g,%.9g\n", truth.profile[i].x(), truth.profile[i].y());
              std::fclose(f);
            }
            // Our fitted curve, densely sampled.
            std::snprintf(name, sizeof name, "%s/%s_%d_%d_fit.csv", export_dir.c_str(), kind, seed, id);
            if (FILE* f = std::fopen(name, "w")) {
              std::fprintf(f, "u,v\n");
              const BSpline& c = it->second;
              const int n = 20000;
              for (int i = 0; i < n; ++i) {
                const Eigen::Vector2d p = c.point(c.t_min() + (c.t_max() - c.t_min()) * i / n);
                std::fprintf(f, "%.9g,%.9g\n", p.x(), p.y());
              }
              std::fclose(f);
            }
            // The true camber line (extensions included) and edges, for the camber comparison.
            std::snprintf(name, sizeof name, "%s/%s_%d_%d_camber.csv", export_dir.c_str(), kind, seed, id);
            if (FILE* f = std::fopen(name, "w")) {
              std::fprintf(f, "u,v\n");
              for (const auto& c : truth.camber) std::fprintf(f, "%.9g,%.9g\n", c.x(), c.y());
              std::fclose(f);
            }
            std::snprintf(name, sizeof name, "%s/%s_%d_%d_edges.csv", export_dir.c_str(), kind, seed, id);
            if (FILE* f = std::fopen(name, "w")) {
              std::fprintf(f, "le_u,le_v,te_u,te_v,le_center_u,le_center_v,le_radius,te_center_u,te_center_v,te_radius\n");
              std::fprintf(f, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", truth.le_point.x(),
                           truth.le_point.y(), truth.te_point.x(), truth.te_point.y(), truth.le_center.x(),
                           truth.le_center.y(), truth.le_radius, truth.te_center.x(), truth.te_center.y(),
                           truth.te_radius);
              std::fclose(f);
            }
            std::snprintf(name, sizeof name, "%s/scores.csv", export_dir.c_str());
            FILE* probe = std::fopen(name, "r");
            const bool fresh = !probe;
            if (probe) std::fclose(probe);
            if (FILE* f = std::fopen(name, "a")) {
              if (fresh)
                std::fprintf(f, "blade,seed,section,rms_um,max_um,gap_um,ms_per_section,cam_rms_um,cam_max_um,"
                                "le_radius_err_pct,te_radius_err_pct,le_point_um,te_point_um,camber_ms\n");
              std::fprintf(f, "%s,%d,%d,%.4f,%.4f,%.4f,%.1f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.2f\n", kind, seed, id,
                           e.rms * 1e3, e.max * 1e3, e.gap * 1e3, ms, cam_rms * 1e3, cam_max * 1e3, rle_signed * 100,
                           rte_signed * 100, le_point_err * 1e3, te_point_err * 1e3, camber_ms);
              std::fclose(f);
            }
          }
          // EVALUATE_DUMP=preset:seed:section writes the measured points and the fitted curve
          // with their signed truth distances, for a closer look at one case.
          if (const char* dump = std::getenv("EVALUATE_DUMP")) {
            char want[64];
            std::snprintf(want, sizeof want, "%s:%d:%d", kind, seed, id);
            if (std::string(dump) == want) {
              FILE* f = std::fopen("evaluate_dump.csv", "w");
              std::fprintf(f, "kind,u,v,s,d\n");
              auto put = [&](const char* what, const Eigen::Vector2d& p) {
                const ProfileLocation l = locate(truth, p);
                std::fprintf(f, "%s,%.6f,%.6f,%.6f,%.6f\n", what, p.x(), p.y(), l.s, l.distance);
              };
              for (const auto& m : measured) put("m", m);
              for (const auto& c : sample(it->second, 5000)) put("c", c);
              if (const Table* sm = stream.find("smoothed"))
                for (std::size_t r = 0; r < sm->rows(); ++r)
                  if (int(sm->at(r, 0)) == id) put("s", {sm->at(r, sm->column("u")), sm->at(r, sm->column("v"))});
              std::fprintf(f, "te,%.6f,%.6f,%.6f,0\n", truth.te_point.x(), truth.te_point.y(), truth.te_s);
              std::fclose(f);
            }
          }
          // Where the largest errors are: arc length from the LE point, and from the TE point.
          auto at = [&](double s) {
            const double P = truth.perimeter;
            const double le = std::min(s, P - s), te = std::abs(s - truth.te_s);
            char w[48];
            std::snprintf(w, sizeof w, le < te ? "LE%+.1f" : "TE%+.1f", le < te ? (s > P / 2 ? s - P : s) : s - truth.te_s);
            return std::string(w);
          };
          std::snprintf(buf, sizeof buf, " %6.0f  max@%s gap@%s rms_near %.2f", ms, at(where_max).c_str(),
                        at(where_gap).c_str(), e.rms_near * 1e3);
          line += buf;
          // Two layers of points found by fitspline (views merged with a misregistration).
          if (const Table* sp = stream.find("splines")) {
            const std::size_t cl = sp->column("layers"), cll = sp->column("layers_length");
            for (std::size_t r = 0; r < sp->rows(); ++r)
              if (int(sp->at(r, 0)) == id && int(sp->at(r, 1)) == 0 && sp->at(r, cl) > 0) {
                std::snprintf(buf, sizeof buf, " layers %.1f/%.2f", sp->at(r, cl) * 1e3, sp->at(r, cll));
                line += buf;
              }
          }
          // Edges camber flagged as not measured (a hole or too few points on the edge).
          for (const auto& is : stream.issues)
            if (is.section == id && is.stage == "camber") {
              if (is.message.find("leading edge not measured") != std::string::npos) line += " LE-unmeasured";
              if (is.message.find("trailing edge not measured") != std::string::npos) line += " TE-unmeasured";
              if (is.message.find("leading edge partly not measured") != std::string::npos) line += " LE-partly";
              if (is.message.find("trailing edge partly not measured") != std::string::npos) line += " TE-partly";
            }
          if (!quiet) std::printf("%s\n", line.c_str());
        }
      }
    }
    const bool misreg = misregistration > 0;
    for (const auto& [kind, W] : worst) {
      std::printf("worst %-10s (%d sections, %d fit failed, %d camber failed): fit rms %.2f um (%.2f um where "
                  "measured), max %.2f um (measured within 0.3 mm along the profile), hole bridging %.2f um\n",
                  kind.c_str(), W.sections, W.fit_failed, W.camber_failed, W.rms * 1e3, W.rms_near * 1e3,
                  W.max * 1e3, W.gap * 1e3);
      if (with_camber)
        std::printf("      %-10s camber rms %.2f um, max %.2f um; chord %.2f um, max thickness %.2f um, "
                    "LE radius %.2f%%, TE radius %.2f%%, inlet %.3f deg, outlet %.3f deg\n",
                    kind.c_str(), W.cam_rms * 1e3, W.cam_max * 1e3, W.chord * 1e3, W.tmax * 1e3, W.rle * 100,
                    W.rte * 100, W.in, W.out);
    }
    std::printf("targets: fit rms <= %s um, max <= %s um; camber rms <= 3 um, max <= 15 um, chord 10 um, "
                "max thickness 5 um, LE radius 3%%, TE radius 10%%, angles 0.5 deg\n",
                misreg ? "10" : "3", misreg ? "25" : "15");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "evaluate_pipeline: error: %s\n", e.what());
    return 1;
  }
}
