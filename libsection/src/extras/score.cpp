// SPDX-License-Identifier: GPL-3.0-or-later
#include "section/extras/score.h"

#include "section/error.h"
#include "section/io/stream.h"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <string>

namespace section {

double wrap_degrees(double a) {
  a = std::fmod(a, 360.0);
  if (a > 180) a -= 360;
  if (a <= -180) a += 360;
  return a;
}

FitScore score_fit(const BSpline& curve, const std::vector<Eigen::Vector2d>& measured,
                   const SectionTruth& truth, const FitScoreOptions& options) {
  std::vector<double> measured_s;
  for (const auto& m : measured) measured_s.push_back(locate(truth, m).s);
  std::sort(measured_s.begin(), measured_s.end());
  const double per = truth.perimeter;
  auto near_data = [&](double s) {
    if (measured_s.empty()) return false;
    const auto it = std::lower_bound(measured_s.begin(), measured_s.end(), s);
    const double after = it == measured_s.end() ? measured_s.front() + per : *it;
    const double before = it == measured_s.begin() ? measured_s.back() - per : *(it - 1);
    return std::min(after - s, s - before) <= options.near;
  };
  FitScore score;
  double sum = 0, sum_near = 0;
  int count_near = 0;
  const auto samples = sample(curve, std::max(options.samples, 1));
  for (const auto& p : samples) {
    const ProfileLocation l = locate(truth, p);
    const double d = l.distance;
    sum += d * d;
    if (near_data(l.s)) {
      sum_near += d * d;
      ++count_near;
      if (d > score.max_near) score.max_near = d, score.where_max = l.s;
    } else if (d > score.gap) {
      score.gap = d, score.where_gap = l.s;
    }
  }
  score.rms = samples.empty() ? 0 : std::sqrt(sum / samples.size());
  score.rms_near = count_near ? std::sqrt(sum_near / count_near) : 0;
  return score;
}

CamberScore score_camber(const Stream& stream, int section, const SectionTruth& truth) {
  const Table& cam = stream.get("camber", "camber");
  const Table& par = stream.get("params", "camber");
  long row = -1;
  for (std::size_t r = 0; r < par.rows(); ++r)
    if (static_cast<int>(par.at(r, 0)) == section) row = static_cast<long>(r);
  if (row < 0) throw Error("score: the params table has no row for section " + std::to_string(section));
  auto v = [&](const char* c) { return par.at(static_cast<std::size_t>(row), par.column(c)); };
  CamberScore s;
  double sum = 0;
  int n = 0;
  const std::size_t cu = cam.column("u"), cv = cam.column("v");
  for (std::size_t r = 0; r < cam.rows(); ++r) {
    if (static_cast<int>(cam.at(r, 0)) != section) continue;
    const double d = camber_distance(truth, {cam.at(r, cu), cam.at(r, cv)});
    sum += d * d;
    s.camber_max = std::max(s.camber_max, d);
    ++n;
  }
  s.camber_rms = n ? std::sqrt(sum / n) : 0;
  s.chord = v("chord") - truth.chord;
  s.max_thickness = v("max_thickness") - truth.max_thickness;
  s.le_radius = v("le_radius") / truth.le_radius - 1;
  s.te_radius = v("te_radius") / truth.te_radius - 1;
  // A stream from before the standard errors has none (0).
  auto sigma = [&](const char* c) {
    const long k = par.find_column(c);
    return k < 0 ? 0.0 : par.at(static_cast<std::size_t>(row), static_cast<std::size_t>(k));
  };
  s.le_radius_sigma = sigma("le_radius_sigma");
  s.te_radius_sigma = sigma("te_radius_sigma");
  s.chord_sigma = sigma("chord_sigma");
  s.max_thickness_sigma = sigma("max_thickness_sigma");
  s.inlet_angle_sigma = sigma("inlet_angle_sigma");
  s.outlet_angle_sigma = sigma("outlet_angle_sigma");
  s.inlet_angle = wrap_degrees(v("inlet_angle") - truth.inlet_angle);
  s.outlet_angle = wrap_degrees(v("outlet_angle") - truth.outlet_angle);
  s.le_point = (Eigen::Vector2d(v("le_u"), v("le_v")) - truth.le_point).norm();
  s.te_point = (Eigen::Vector2d(v("te_u"), v("te_v")) - truth.te_point).norm();
  return s;
}

Calibration calibration(std::vector<double> ratios) {
  Calibration c;
  if (ratios.empty()) return c;
  std::sort(ratios.begin(), ratios.end());
  const std::size_t n = ratios.size();
  const auto at = [&](double q) { return ratios[static_cast<std::size_t>(q * double(n - 1))]; };
  const auto beyond = [&](double k) {
    return double(ratios.end() - std::upper_bound(ratios.begin(), ratios.end(), k)) / double(n);
  };
  c.count = n;
  c.median = at(0.5);
  c.p90 = at(0.9);
  c.p99 = at(0.99);
  c.beyond2 = beyond(2);
  c.beyond3 = beyond(3);
  return c;
}

std::string calibration_text(const std::vector<double>& ratios) {
  const Calibration c = calibration(ratios);
  char buf[128];
  std::snprintf(buf, sizeof buf, "median %.2f, 90 %% %.2f, 99 %% %.2f, %.1f %% beyond 3 (%zu)", c.median,
                c.p90, c.p99, 100 * c.beyond3, c.count);
  return buf;
}

}  // namespace section
