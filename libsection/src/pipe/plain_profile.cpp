// SPDX-License-Identifier: GPL-3.0-or-later
#include "section/pipe/plain_profile.h"

#include "pipe/camber_issues.h"
#include "section/error.h"
#include "section/pipe/camber_stream.h"
#include "section/pipe/schema.h"
#include "section/units.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <system_error>
#include <thread>
#include <utility>

namespace section {

Stream plain_profile_stream(const std::vector<Eigen::Vector2d>& points, const FitSplineOptions& options) {
  const std::vector<Eigen::Vector2d> loop = canonical_loop(points);
  const FitSplineResult fit = fit_spline(loop, loop, options);
  return profile_stream(fit.spline, fit.rms, loop);
}

namespace {

// The canonical loop restarted at its point farthest from its start: the other end of a
// blade section (a tie goes to the first in the canonical order, itself the same from any start).
std::vector<Eigen::Vector2d> from_other_end(const std::vector<Eigen::Vector2d>& points) {
  std::vector<Eigen::Vector2d> loop = canonical_loop(points);
  std::size_t far = 0;
  double most = -1;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const double d = (loop[i] - loop.front()).squaredNorm();
    if (d > most) most = d, far = i;
  }
  std::rotate(loop.begin(), loop.begin() + std::ptrdiff_t(far), loop.end());
  return loop;
}

// One edge's values in a params row.
struct EdgeValues {
  Eigen::Vector2d point;
  double radius = 0, angle = 0;
};

EdgeValues edge_of(const Table& t, bool le) {
  const auto at = [&](const char* name) { return t.at(0, t.column(name)); };
  return le ? EdgeValues{{at("le_u"), at("le_v")}, at("le_radius"), at("inlet_angle")}
            : EdgeValues{{at("te_u"), at("te_v")}, at("te_radius"), at("outlet_angle")};
}

// What moved at one edge from this fit to the other, beyond its limit ("" when nothing).
std::string moved(const EdgeValues& a, const EdgeValues& b, double point_limit, double radius_tolerance,
                  bool angles, const char* angle_name) {
  std::string out;
  char text[160];
  const double shift = (a.point - b.point).norm();
  if (!(shift <= point_limit)) {
    out += "its point " + format_length(shift) + " away";
  }
  const bool round_a = a.radius > 0, round_b = b.radius > 0;
  if (round_a != round_b ||
      !(std::abs(a.radius - b.radius) <= radius_tolerance * std::max(a.radius, b.radius))) {
    std::snprintf(text, sizeof text, "%sits radius %.4g mm (%.4g here)", out.empty() ? "" : ", ", b.radius,
                  a.radius);
    out += text;
  }
  if (angles && !(std::abs(a.angle - b.angle) <= 0.5)) {
    std::snprintf(text, sizeof text, "%sits %s %.3g deg (%.3g here)", out.empty() ? "" : ", ", angle_name,
                  b.angle, a.angle);
    out += text;
  }
  return out;
}

// The params row of a stream that measured one section with a chord; null otherwise.
const Table* measured_params(const Stream& stream) {
  const Table* params = stream.find(schema::params.name);
  if (!params || params->rows() != 1 || std::isnan(params->at(0, params->column("chord")))) return nullptr;
  return params;
}

}  // namespace

Stream other_end_stream(const std::vector<Eigen::Vector2d>& points, const CamberOptions& options,
                        const FitSplineOptions& fit) {
  try {
    const std::vector<Eigen::Vector2d> loop = from_other_end(points);
    const FitSplineResult f = fit_spline(loop, loop, fit);
    Stream other = profile_stream(f.spline, f.rms, loop);
    CamberOptions one = options;
    one.across_sections = false;
    camber_stream(other, one);
    return other;
  } catch (const Error&) {
    return {};
  }
}

std::future<Stream> other_end_stream_async(std::vector<Eigen::Vector2d> points, const CamberOptions& options,
                                           const FitSplineOptions& fit) {
  const int threads = options.threads;
  auto make = [points = std::move(points), options, fit] { return other_end_stream(points, options, fit); };
  if (threads == 1 || (threads == 0 && std::thread::hardware_concurrency() <= 1))
    return std::async(std::launch::deferred, std::move(make));
  try {
    return std::async(std::launch::async, make);
  } catch (const std::system_error&) {  // no thread (a low `ulimit -v`): made when read
    return std::async(std::launch::deferred, std::move(make));
  }
}

CheckBits flag_start_dependence(Stream& stream, const std::vector<Eigen::Vector2d>& points,
                                const CamberOptions& options, const FitSplineOptions& fit) {
  if (!measured_params(stream)) return 0;  // nothing to compare: the other end is not fitted
  return flag_start_dependence(stream, other_end_stream(points, options, fit));
}

CheckBits flag_start_dependence(Stream& stream, const Stream& other) {
  const Table* params = measured_params(stream);
  const Table* again = measured_params(other);
  if (!params || !again) return 0;
  const CheckOptions limits;
  const double point_limit = limits.accuracy * params->at(0, params->column("caliper_chord"));
  EdgeValues here[2] = {edge_of(*params, true), edge_of(*again, true)};
  EdgeValues there[2] = {edge_of(*params, false), edge_of(*again, false)};
  // The other fit may take the other end for the LE (a near tie): its edges are matched by
  // place, and their angles, measured the other way along the chord, are not compared.
  const bool swapped = (here[0].point - there[1].point).norm() + (there[0].point - here[1].point).norm() <
                       (here[0].point - here[1].point).norm() + (there[0].point - there[1].point).norm();
  if (swapped) std::swap(here[1], there[1]);
  CheckBits set = 0;
  for (const bool le : {true, false}) {
    const EdgeValues* e = le ? here : there;
    const std::string what =
        moved(e[0], e[1], point_limit, le ? limits.le_radius_tolerance : limits.te_radius_tolerance, !swapped,
              le ? "inlet angle" : "outlet angle");
    const Check check = le ? Check::le_start : Check::te_start;
    if (what.empty() || (flags_mask(params->at(0, params->column("flags"))) & bit(check))) continue;
    set |= bit(check);
    pipe::flag_every_row(
        stream, check,
        std::string(le ? "leading" : "trailing") + " edge fails check " + check_name(check) +
            ": the same points fitted from the profile's other end put " + what +
            ": they do not fix the curve between them at this edge, and its values depend on "
            "where the profile starts; measure more points there");
  }
  return set;
}

}  // namespace section
