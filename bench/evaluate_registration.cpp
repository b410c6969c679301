// SPDX-License-Identifier: GPL-3.0-or-later
// evaluate_registration: how often register_views moves a view right, refuses it, or
// moves it wrong with no word, over views set apart by known motions. Each case: the
// inspection scan of 10 mm of span around z = 30 (tests/test_register_views.cpp's
// two_views), its second view moved by a misalignment along a direction in the section
// plane (the second view optionally 6 times as noisy), registered at a reach; the error is
// the largest in-plane distance of a point of the view from where it was. Prints one line
// per case and the counts: right (error under 10 um), refused (and why), wrong; a motion
// kept but said to be unconfirmed (ViewRegistration::caution) is counted apart.
// Usage: evaluate_registration [--seeds 40,41,44] [--reaches 0,0.3,0.5,1]
//                              [--misalignments 0.012,0.1,0.2,0.25,0.3,0.33,0.375,0.45]
//                              [--noisy-seed 44] [--reach-check F] [--whole-span] [--quiet]
// The defaults are the 1 024 registrations of docs/REGISTRATION.md ("Found again at a second
// reach" and "Near the reach"): both presets, four directions, the noisy view on seed 44
// only. --whole-span scans the whole blade (60 mm of span) instead of 10 mm.
#include "section/error.h"
#include "section/extras/generate.h"
#include "section/register_views.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using namespace section;

namespace {

std::vector<double> numbers(const char* text) {
  std::vector<double> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) out.push_back(std::stod(item));
  return out;
}

struct Options {
  std::vector<double> seeds{40, 41, 44}, reaches{0, 0.3, 0.5, 1},
      misalignments{0.012, 0.1, 0.2, 0.25, 0.3, 0.33, 0.375, 0.45};
  double noisy_seed = 44;
  double reach_check = RegisterOptions{}.reach_check;
  bool whole_span = false;
  bool quiet = false;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const char* a = argv[i];
    const bool has_value = i + 1 < argc;
    if (!std::strcmp(a, "--quiet")) {
      o.quiet = true;
    } else if (!std::strcmp(a, "--whole-span")) {
      o.whole_span = true;
    } else if (has_value && !std::strcmp(a, "--seeds")) {
      o.seeds = numbers(argv[++i]);
    } else if (has_value && !std::strcmp(a, "--reaches")) {
      o.reaches = numbers(argv[++i]);
    } else if (has_value && !std::strcmp(a, "--misalignments")) {
      o.misalignments = numbers(argv[++i]);
    } else if (has_value && !std::strcmp(a, "--noisy-seed")) {
      o.noisy_seed = std::stod(argv[++i]);
    } else if (has_value && !std::strcmp(a, "--reach-check")) {
      o.reach_check = std::stod(argv[++i]);
    } else {
      throw Error(std::string("evaluate_registration: unknown or incomplete option ") + a +
                  " (--seeds, --reaches, --misalignments: comma-separated; --noisy-seed, --reach-check, "
                  "--whole-span, --quiet)");
    }
  }
  return o;
}

// The scan's two views (10 mm of span around z = 30, or the whole blade), the second 30 um
// noisy instead of 5 when `noisy`.
std::vector<Cloud> two_views(const BladeDesign& blade, std::uint64_t seed, bool noisy, bool whole_span) {
  ScanOptions so = inspection_scan();
  so.seed = seed;
  if (!whole_span) {
    so.z_min = 25;
    so.z_max = 35;
  }
  std::vector<Cloud> views = views_of(generate_scan(blade, so));
  if (noisy) {
    so.noise = 0.03;
    views[1] = views_of(generate_scan(blade, so))[1];
  }
  return views;
}

}  // namespace

int main(int argc, char** argv) try {
  const Options opt = parse(argc, argv);
  const Eigen::Vector3d directions[] = {{0.615, -0.79, 0}, {1, -0.75, 0}, {0.2, 1, 0}, {1, 0.3, 0}};
  std::map<std::string, int> counts;
  double worst_wrong = 0, worst_right = 0;
  for (const bool turbine : {false, true}) {
    const BladeDesign blade = turbine ? turbine_blade() : compressor_blade();
    for (const double seed : opt.seeds) {
      for (const bool noisy : {false, true}) {
        if (noisy && seed != opt.noisy_seed) continue;
        const std::vector<Cloud> base = two_views(blade, std::uint64_t(seed), noisy, opt.whole_span);
        for (const double mm : opt.misalignments) {
          for (const Eigen::Vector3d& d : directions) {
            const Eigen::Vector3d move = d.normalized() * mm;
            std::vector<Cloud> views = base;
            for (auto& p : views[1].points) p += move;
            for (const double reach : opt.reaches) {
              RegisterOptions ro;
              ro.reach = reach;
              ro.reach_check = opt.reach_check;
              std::string outcome;
              double error = 0;
              try {
                const ViewRegistration r = register_views(views, ro).views[1];
                for (const auto& p : base[1].points)
                  error = std::max(error, ((r.transform * (p + move)) - p).head<2>().norm());
                const bool right = error < 0.01;
                outcome = std::string(right ? "right" : "wrong") + (r.caution.empty() ? "" : ", unconfirmed");
                if (r.caution.empty()) {  // the worst said nothing of
                  double& worst = right ? worst_right : worst_wrong;
                  worst = std::max(worst, error);
                }
              } catch (const Error& e) {
                const std::string what = e.what();
                outcome = what.find("depends on the reach") != std::string::npos
                              ? "refused: depends on the reach"
                          : what.find("no motion leaves it") != std::string::npos
                              ? "refused: unconfirmed at twice the reach"
                          : what.find("left off the reference surface") != std::string::npos
                              ? "refused: off the surface"
                              : "refused: other";
              }
              ++counts[outcome];
              if (!opt.quiet) {
                std::printf("%-10s seed %2.0f%s misalignment %.3f mm along (%.3g, %.3g) reach %.3g mm: %s",
                            turbine ? "turbine" : "compressor", seed, noisy ? " noisy" : "", mm, d.x(), d.y(),
                            reach, outcome.c_str());
                if (outcome.rfind("refused", 0) != 0) std::printf(" (%.3f um)", error * 1000);
                std::printf("\n");
              }
              std::fflush(stdout);
            }
          }
        }
      }
    }
  }
  int total = 0;
  for (const auto& [k, n] : counts) total += n;
  std::printf("%d registrations (reach_check %g):", total, opt.reach_check);
  for (const auto& [k, n] : counts) std::printf(" %s %d;", k.c_str(), n);
  std::printf(" worst right %.1f um, worst wrong %.1f um (of those not said unconfirmed)\n",
              worst_right * 1000, worst_wrong * 1000);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "%s\n", e.what());
  return 1;
}
