// SPDX-License-Identifier: GPL-3.0-or-later
// bench_compare: compare's best fit on generated sections moved by known rigid motions, its
// time per section, and the files engeom's alignment runs on (scripts/compare_engeom.sh).
#include "common/tool.h"

#include "section/compare.h"
#include "section/error.h"
#include "section/extras/generate.h"
#include "section/fit_spline.h"
#include "section/io/csv.h"
#include "section/io/file.h"

#include <algorithm>
#include <ctime>
#include <functional>
#include <map>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

namespace {

const char* const description =
    "bench_compare: the best fit of measured sections onto their nominal, against known moves.\n\n"
    "Each of the generator's five designs (section_truth, exact) is the nominal; the measured\n"
    "section is its profile every --spacing with --noise along the normal, moved by a rigid\n"
    "motion of up to 0.1 deg and 50 um. --export DIR writes, per case, the nominal polyline\n"
    "(20000 exact points), its edge points, the measured points, the true motion and our fit\n"
    "(least squares and minimum zone on the nominal prepared once, least squares preparing it in\n"
    "each call; the CPU time per section: the median of 5 runs, one thread). --score DIR reads\n"
    "DIR/engeom.csv (and DIR/python.csv when present; case, method, angle, tx, ty, ms) and prints,\n"
    "for ours and theirs:\n"
    "how far the fit leaves the true move (the largest distance between a noise-free point\n"
    "moved and fitted back and where it was, um), the rms and largest exact distance of the\n"
    "fitted points to the true profile (um), and the CPU time per section (ms).\n\n"
    "Example: bench_compare --export /tmp/cmp && python3 scripts/peers/compare_peer.py /tmp/cmp &&\n"
    "         bench_compare --score /tmp/cmp";

constexpr double pi = 3.14159265358979323846;

struct Case {
  std::string name;
  section::SectionTruth truth;
  std::vector<Eigen::Vector2d> clean, measured;
  double angle = 0;
  Eigen::Vector2d shift{0, 0};
};

Eigen::Vector2d moved(const Eigen::Vector2d& p, double degrees, const Eigen::Vector2d& shift) {
  const double a = degrees * pi / 180;
  return Eigen::Vector2d(std::cos(a) * p.x() - std::sin(a) * p.y(),
                         std::sin(a) * p.x() + std::cos(a) * p.y()) +
         shift;
}

std::vector<Case> cases(int seeds, double spacing, double noise) {
  std::vector<Case> out;
  const auto designs = section::design_family();
  for (std::size_t d = 0; d < designs.size(); ++d)
    for (int s = 1; s <= seeds; ++s) {
      Case c;
      c.name = "d" + std::to_string(d) + "_s" + std::to_string(s);
      c.truth = section::section_truth(designs[d], 20000);
      std::mt19937_64 rng(1000 * d + s);
      std::normal_distribution<double> n(0, 1);
      std::uniform_real_distribution<double> u(-1, 1);
      c.angle = 0.1 * u(rng);
      c.shift = 0.05 * Eigen::Vector2d(u(rng), u(rng));
      const int count = static_cast<int>(c.truth.perimeter / spacing);
      for (int i = 0; i < count; ++i) {
        const std::size_t j = static_cast<std::size_t>(i) * c.truth.profile.size() / count;
        c.clean.push_back(moved(c.truth.profile[j], c.angle, c.shift));
        c.measured.push_back(
            moved(c.truth.profile[j] + noise * n(rng) * c.truth.profile_normal[j], c.angle, c.shift));
      }
      out.push_back(std::move(c));
    }
  return out;
}

// The nominal as the pipe makes it of a mesh section: fit_spline on the polyline.
section::NominalSection nominal_of(const section::SectionTruth& t) {
  section::NominalSection n;
  n.curve = section::fit_spline(t.profile, t.profile).spline;
  n.le_point = t.le_point;
  n.te_point = t.te_point;
  n.pressure_side = t.inlet_angle > t.outlet_angle ? -1 : 1;
  return n;
}

// CPU ms of f (one thread; wall time on a shared machine would measure the neighbours):
// the median of 5 runs.
double median_ms(const std::function<void()>& f) {
  std::vector<double> ms;
  for (int k = 0; k < 5; ++k) {
    const std::clock_t t0 = std::clock();
    f();
    ms.push_back(1e3 * double(std::clock() - t0) / CLOCKS_PER_SEC);
  }
  std::nth_element(ms.begin(), ms.begin() + 2, ms.end());
  return ms[2];
}

std::string points_csv(const std::vector<Eigen::Vector2d>& p) {
  std::string out = "x,y\n";
  for (const auto& q : p) out += section::format_number(q.x()) + "," + section::format_number(q.y()) + "\n";
  return out;
}

void export_cases(const std::string& dir, int seeds, double spacing, double noise) {
  std::filesystem::create_directories(dir);
  std::string ours = "case,method,angle,tx,ty,ms\n";
  for (const Case& c : cases(seeds, spacing, noise)) {
    section::write_file(dir + "/" + c.name + "_nominal.csv", points_csv(c.truth.profile));
    section::write_file(dir + "/" + c.name + "_points.csv", points_csv(c.measured));
    const section::NominalSection n = nominal_of(c.truth);
    section::write_file(
        dir + "/" + c.name + "_edges.csv",
        "le_u,le_v,te_u,te_v,pressure_side\n" + section::format_number(n.le_point.x()) + "," +
            section::format_number(n.le_point.y()) + "," + section::format_number(n.te_point.x()) + "," +
            section::format_number(n.te_point.y()) + "," + std::to_string(n.pressure_side) + "\n");
    // ours_*: the nominal prepared once (prepare_nominal), as for blade after blade of one
    // design; ours_ls_once: prepared in each call (compare_section on the NominalSection).
    const section::PreparedNominal prepared = section::prepare_nominal(n);
    for (const char* method : {"ours_ls", "ours_mz", "ours_ls_once"}) {
      section::CompareOptions o;
      o.fit.method = method == std::string("ours_mz") ? section::FitMethod::minimum_zone
                                                      : section::FitMethod::least_squares;
      section::SectionComparison r;
      const double ms = method == std::string("ours_ls_once")
                            ? median_ms([&] { r = section::compare_section(n, c.measured, o); })
                            : median_ms([&] { r = section::compare_section(prepared, c.measured, o); });
      ours += c.name + "," + method + "," + section::format_number(r.fit.motion.angle) + "," +
              section::format_number(r.fit.motion.translation.x()) + "," +
              section::format_number(r.fit.motion.translation.y()) + "," + section::format_number(ms) + "\n";
    }
    std::printf("%s: %zu points\n", c.name.c_str(), c.measured.size());
    std::fflush(stdout);
  }
  section::write_file(dir + "/ours.csv", ours);
}

// Signed exact distance to the true profile.
double deviation(const section::SectionTruth& t, const Eigen::Vector2d& p) {
  const section::ProfileLocation l = section::locate(t, p);
  const auto it = std::lower_bound(t.profile_s.begin(), t.profile_s.end(), l.s);
  const std::size_t j = it == t.profile_s.end() ? 0 : static_cast<std::size_t>(it - t.profile_s.begin());
  return (p - t.profile[j]).dot(t.profile_normal[j]) >= 0 ? l.distance : -l.distance;
}

void score(const std::string& dir, int seeds, double spacing, double noise) {
  const std::vector<Case> all = cases(seeds, spacing, noise);
  std::map<std::string, const Case*> by_name;
  for (const Case& c : all) by_name[c.name] = &c;
  std::printf("%-8s %-10s %10s %10s %10s %9s\n", "case", "method", "move_um", "rms_um", "max_um", "ms");
  std::map<std::string, std::vector<double>> ms, move, rms, mx;
  for (const char* file : {"ours.csv", "engeom.csv", "python.csv"}) {
    const std::string path = dir + "/" + file;
    if (file == std::string("python.csv") && !std::filesystem::exists(path)) continue;  // python_speed.sh's
    const std::string text = section::read_file(path);
    std::size_t pos = text.find('\n') + 1;
    while (pos < text.size()) {
      const std::size_t end = text.find('\n', pos);
      std::vector<std::string> f;
      std::string line = text.substr(pos, end - pos), cell;
      pos = end == std::string::npos ? text.size() : end + 1;
      for (std::size_t a = 0, b; a <= line.size(); a = b + 1) {
        b = std::min(line.find(',', a), line.size());
        f.push_back(line.substr(a, b - a));
      }
      if (f.size() < 6 || !by_name.count(f[0])) continue;
      const Case& c = *by_name.at(f[0]);
      const double angle = std::stod(f[2]), t = std::stod(f[5]);
      const Eigen::Vector2d shift(std::stod(f[3]), std::stod(f[4]));
      double worst = 0, sum = 0, largest = 0;
      for (std::size_t i = 0; i < c.clean.size(); ++i) {
        const Eigen::Vector2d q = moved(c.clean[i], angle, shift);
        const Eigen::Vector2d origin = moved(c.clean[i] - c.shift, -c.angle, {0, 0});
        worst = std::max(worst, (q - origin).norm());
        const double d = deviation(c.truth, moved(c.measured[i], angle, shift));
        sum += d * d;
        largest = std::max(largest, std::abs(d));
      }
      const double r = std::sqrt(sum / c.clean.size());
      std::printf("%-8s %-10s %10.3f %10.3f %10.3f %9.3f\n", f[0].c_str(), f[1].c_str(), 1e3 * worst, 1e3 * r,
                  1e3 * largest, t);
      ms[f[1]].push_back(t);
      move[f[1]].push_back(1e3 * worst);
      rms[f[1]].push_back(1e3 * r);
      mx[f[1]].push_back(1e3 * largest);
    }
  }
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
  };
  auto worst = [](const std::vector<double>& v) {
    return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end());
  };
  std::printf("\nmedian / worst over %zu cases\n%-12s %16s %16s %16s %16s\n", all.size(), "method", "move_um",
              "rms_um", "max_um", "ms");
  for (const auto& [m, v] : ms)
    std::printf("%-12s %7.3f / %6.3f %7.3f / %6.3f %7.3f / %6.3f %7.3f / %6.3f\n", m.c_str(), median(move[m]),
                worst(move[m]), median(rms[m]), worst(rms[m]), median(mx[m]), worst(mx[m]), median(v),
                worst(v));
}

}  // namespace

int main(int argc, char** argv) {
  std::string export_dir, score_dir;
  int seeds = 3;
  double spacing = 0.025, noise = 0.005;
  return section::tool::run_tool(
      "bench_compare", description, argc, argv,
      [&](CLI::App& app) {
        app.add_option("--export", export_dir, "Write the cases and our fits to DIR");
        app.add_option("--score", score_dir, "Score ours.csv and engeom.csv of DIR");
        app.add_option("--seeds", seeds, "Cases per design")->capture_default_str();
        app.add_option("--spacing", spacing, "Measured point spacing (mm)")->capture_default_str();
        app.add_option("--noise", noise, "Noise sigma along the normal (mm)")->capture_default_str();
      },
      [&] {
        if (!export_dir.empty()) export_cases(export_dir, seeds, spacing, noise);
        if (!score_dir.empty()) score(score_dir, seeds, spacing, noise);
        if (export_dir.empty() && score_dir.empty()) throw section::Error("give --export DIR or --score DIR");
      });
}
