// SPDX-License-Identifier: GPL-3.0-or-later
// fit_stability: how much fitspline's result moves when its input moves by far less than
// any measurement can tell (1e-8..1e-6 mm). Reads the streams evaluate_pipeline writes with
// EVALUATE_STREAMS=PREFIX (PREFIX_preset_seed.smooth, the stream fitspline reads), fits
// each one unperturbed and `--trials` times with every smoothed and measured coordinate
// moved at random, and prints per section the fit to the true profile (as evaluate_pipeline
// scores it) of the unperturbed input and its spread over the trials, then the worst.
// Usage: fit_stability --streams PREFIX [--seeds N] [--first-seed S]
//                      [--preset turbine|compressor|both] [--trials T] [--section K]
//                      [--first-iterations N] [--bridge-factor F] [--quiet]
// Trial t of T moves the coordinates by up to 10^(-8 + 2 (t-1)/(T-1)) mm.
#include "section/extras/generate.h"
#include "section/extras/score.h"
#include "section/fit_spline.h"
#include "section/io/stream.h"
#include "section/pipe/fit_spline_stream.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace section;

namespace {

struct Options {
  std::string prefix, preset = "both";
  int seeds = 1, first_seed = 1, trials = 5;
  int section = -1;  // --section K: that section alone
  FitSplineOptions fit;
  bool quiet = false;
};

// Every u and v of the smoothed and measured points moved by up to `amplitude` (uniform).
void perturb(Stream& s, double amplitude, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> d(-amplitude, amplitude);
  for (const char* name : {"smoothed", "points"}) {
    Table* t = s.find(name);
    if (!t) continue;
    t->source = nullptr;
    const std::size_t cu = t->column("u"), cv = t->column("v"), w = t->columns.size();
    for (std::size_t r = 0; r < t->rows(); ++r) {
      t->values[r * w + cu] += d(rng);
      t->values[r * w + cv] += d(rng);
    }
  }
}

// Only the rows of section k in the tables fitspline reads.
void keep_section(Stream& s, int k) {
  for (const char* name : {"smoothed", "points"}) {
    Table* t = s.find(name);
    if (!t) continue;
    t->source = nullptr;
    const std::size_t w = t->columns.size();
    std::vector<double> kept;
    for (std::size_t r = 0; r < t->rows(); ++r)
      if (int(t->at(r, 0)) == k)
        kept.insert(kept.end(), t->values.begin() + r * w, t->values.begin() + (r + 1) * w);
    t->values = std::move(kept);
  }
}

// Fit rms and max (um) of each section of a stream against the truth; NaN where it failed.
std::vector<std::pair<double, double>> scores(Stream s, const BladeDesign& blade, const Table& pts,
                                              const std::vector<double>& zs, FitSplineOptions o) {
  o.threads = 1;
  fit_spline_stream(s, o);
  const auto curves = splines(s);
  std::vector<std::pair<double, double>> out;
  for (std::size_t k = 0; k < zs.size(); ++k) {
    const auto it = curves.find({static_cast<int>(k), 0});
    if (it == curves.end()) {
      out.push_back({NAN, NAN});
      continue;
    }
    std::vector<Eigen::Vector2d> measured;
    for (std::size_t r = 0; r < pts.rows(); ++r)
      if (int(pts.at(r, 0)) == int(k) && int(pts.at(r, 1)) == 0)
        measured.emplace_back(pts.at(r, 3), pts.at(r, 4));
    const FitScore fs = score_fit(it->second, measured, section_truth(blade.at(zs[k])));
    out.push_back({fs.rms * 1e3, fs.max_near * 1e3});
  }
  return out;
}

struct Summary {
  int sections = 0, moved_01 = 0, moved_1 = 0;
  double spread_rms = 0, spread_max = 0, worst_base_max = 0, worst_any_max = 0, worst_base_rms = 0,
         worst_any_rms = 0;
};

void run(const Options& opt) {
  Summary total;
  for (const char* kind : {"turbine", "compressor"}) {
    if (opt.preset != "both" && opt.preset != kind) continue;
    Summary sum;
    const BladeDesign blade = std::string(kind) == "turbine" ? turbine_blade() : compressor_blade();
    std::vector<double> zs;
    for (int k = 1; k <= 9; ++k) zs.push_back(blade.span * k / 10.0);
    for (int seed = opt.first_seed; seed < opt.first_seed + opt.seeds; ++seed) {
      const std::string path = opt.prefix + "_" + kind + "_" + std::to_string(seed) + ".smooth";
      std::ifstream in(path);
      if (!in) throw std::runtime_error("cannot read " + path);
      std::stringstream text;
      text << in.rdbuf();
      const Stream base = parse_stream(text.str(), path);
      const Table& pts = base.get("points", "slice");
      auto fit = [&](Stream s) {
        if (opt.section >= 0) keep_section(s, opt.section);
        return scores(std::move(s), blade, pts, zs, opt.fit);
      };
      std::vector<std::vector<std::pair<double, double>>> trials{fit(base)};
      for (int t = 1; t <= opt.trials; ++t) {
        std::mt19937_64 rng(1000003u * seed + t);
        const double amplitude = std::pow(10.0, -8 + 2.0 * (t - 1) / std::max(opt.trials - 1, 1));
        Stream s = base;
        perturb(s, amplitude, rng);
        trials.push_back(fit(std::move(s)));
      }
      for (std::size_t k = 0; k < zs.size(); ++k) {
        if (opt.section >= 0 && int(k) != opt.section) continue;
        double lo_r = INFINITY, hi_r = -INFINITY, lo_m = INFINITY, hi_m = -INFINITY;
        for (const auto& tr : trials) {
          lo_r = std::min(lo_r, tr[k].first), hi_r = std::max(hi_r, tr[k].first);
          lo_m = std::min(lo_m, tr[k].second), hi_m = std::max(hi_m, tr[k].second);
        }
        const double sr = hi_r - lo_r, sm = hi_m - lo_m;
        ++sum.sections;
        sum.moved_01 += sm > 0.1;
        sum.moved_1 += sm > 1;
        sum.spread_rms = std::max(sum.spread_rms, sr);
        sum.spread_max = std::max(sum.spread_max, sm);
        sum.worst_base_rms = std::max(sum.worst_base_rms, trials[0][k].first);
        sum.worst_base_max = std::max(sum.worst_base_max, trials[0][k].second);
        sum.worst_any_rms = std::max(sum.worst_any_rms, hi_r);
        sum.worst_any_max = std::max(sum.worst_any_max, hi_m);
        if (!opt.quiet || sm > 1) {
          std::printf("%-10s %4d %3zu  rms %6.2f max %6.2f  trials: rms %6.2f..%6.2f max %6.2f..%6.2f", kind,
                      seed, k, trials[0][k].first, trials[0][k].second, lo_r, hi_r, lo_m, hi_m);
          if (sm > 1) {
            std::printf("  [");
            for (const auto& tr : trials) std::printf(" %.2f", tr[k].second);
            std::printf(" ]");
          }
          std::printf("\n");
          std::fflush(stdout);
        }
      }
    }
    std::printf(
        "%-10s %d sections: spread over trials of fit rms %.3f um, max %.3f um; max moved >0.1 um: %d, >1 "
        "um: "
        "%d; worst rms %.2f (any trial %.2f) um, worst max %.2f (any trial %.2f) um\n",
        kind, sum.sections, sum.spread_rms, sum.spread_max, sum.moved_01, sum.moved_1, sum.worst_base_rms,
        sum.worst_any_rms, sum.worst_base_max, sum.worst_any_max);
  }
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--streams" && has_value)
      opt.prefix = argv[++i];
    else if (a == "--seeds" && has_value)
      opt.seeds = std::atoi(argv[++i]);
    else if (a == "--first-seed" && has_value)
      opt.first_seed = std::atoi(argv[++i]);
    else if (a == "--preset" && has_value)
      opt.preset = argv[++i];
    else if (a == "--trials" && has_value)
      opt.trials = std::atoi(argv[++i]);
    else if (a == "--first-iterations" && has_value)
      opt.fit.first_iterations = std::atoi(argv[++i]);
    else if (a == "--bridge-factor" && has_value)
      opt.fit.bridge_factor = std::atof(argv[++i]);
    else if (a == "--section" && has_value)
      opt.section = std::atoi(argv[++i]);
    else if (a == "--quiet")
      opt.quiet = true;
    else {
      std::fprintf(stderr,
                   "usage: fit_stability --streams PREFIX [--seeds N] [--first-seed S] "
                   "[--preset turbine|compressor|both] [--trials T] [--section K] [--first-iterations N] "
                   "[--bridge-factor F] [--quiet]\n");
      return 2;
    }
  }
  if (opt.prefix.empty()) {
    std::fprintf(stderr, "fit_stability: --streams PREFIX is needed\n");
    return 2;
  }
  try {
    run(opt);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fit_stability: error: %s\n", e.what());
    return 1;
  }
}
