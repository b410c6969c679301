// SPDX-License-Identifier: GPL-3.0-or-later
// camber_stream's cavities and their walls (docs/CAMBER.md, "Hollow blades").
#include "pipe/camber_walls.h"

#include "fit_spline_steps.h"

#include "detail/coverage.h"
#include "detail/local_origin.h"
#include "pipe/camber_issues.h"
#include "section/error.h"
#include "section/pipe/schema.h"
#include "section/units.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

namespace section::pipe {

std::vector<SectionCavity> cavities_of(int section, const BSpline& local, const Eigen::Vector2d& origin,
                                       const std::map<std::pair<int, int>, BSpline>& curves,
                                       const std::map<int, std::map<int, double>>& listed, int loops) {
  std::vector<SectionCavity> out;
  if (loops <= 1) return out;
  const auto found = listed.find(section);
  const std::map<int, double> none;
  const std::map<int, double>& areas = found != listed.end() ? found->second : none;
  const auto refuse = [&](const std::string& why) {
    throw Error("camber: section " + std::to_string(section) + " has " + std::to_string(loops) + " loops; " +
                why + other_loops(curves, section, areas));
  };
  const std::string beside =
      "camber measures a profile and the cavities inside it (a hollow blade's), not loops beside it or "
      "crossing it";
  for (const auto& listed_loop : areas)
    if (listed_loop.first != 0 && !curves.count({section, listed_loop.first})) refuse(beside);
  for (auto it = curves.lower_bound({section, 1}); it != curves.end() && it->first.first == section; ++it) {
    SectionCavity c{it->first.second, it->second, {}};
    c.curve.control = detail::moved(it->second.control, origin);
    c.cavity = measure_cavity(local, c.curve);
    if (c.cavity.place != LoopPlace::inside) refuse(beside);
    out.push_back(std::move(c));
  }
  for (const SectionCavity& a : out)
    for (const SectionCavity& b : out)
      if (&a != &b && measure_cavity(a.curve, b.curve, {256}).place != LoopPlace::outside)
        refuse("loop " + std::to_string(b.loop) + " lies within loop " + std::to_string(a.loop) +
               ", a cavity: camber measures a profile and the cavities inside it, not loops within those");
  return out;
}

namespace {

// The measured points' coverage of a cavity's two curves, about its walls.
struct WallCoverage {
  const ProfileCoverage& outer;
  const ProfileCoverage& inner;
  const detail::PiecewiseCurve& cavity;
  const CamberOptions& opt;
  double chord;

  // The longest hole under a wall's thin stretch, on either curve (0: none), and on which.
  double hole_under(const std::vector<std::pair<double, double>>& thin, double wall,
                    const char*& side) const {
    const double limit = std::min(opt.thickness_hole * chord, wall);
    double hole = 0;
    Eigen::Vector2d last(std::numeric_limits<double>::infinity(), 0);
    for (const auto& [tc, tp] : thin) {
      // Every quarter of the shortest hole that counts: a hole begins within half of it.
      const Eigen::Vector2d at = cavity.point(cavity.locate(tc));
      if ((at - last).norm() < limit / 4) continue;
      last = at;
      const ContactCoverage on[2] = {outer.about(tp, 3 * limit, limit / 2),
                                     inner.about(tc, 3 * limit, limit / 2)};
      for (int k = 0; k < 2; ++k)
        if (on[k].hole > hole && unmeasured(on[k], limit, opt.thickness_hole_spacings))
          hole = on[k].hole, side = k == 0 ? "profile" : "cavity";
    }
    return hole;
  }
};

// A cavity's walls' standard error through the points' noise (WallNoise; 0 when unknown):
// the cavity's share its curve's control points over its `measured` points.
double wall_sigma(const WallNoise& nz, const BSpline& cavity, std::size_t measured) {
  if (!(nz.sigma > 0)) return 0;
  const double share = measured > 0 ? std::min(1.0, double(cavity.control.size()) / double(measured)) : 1.0;
  return nz.sigma * std::sqrt(nz.profile_share + share);
}

// The centroid's standard error through the points' noise (WallNoise; 0 when unknown or no
// point measured the cavity), along its least sure direction. Each of the `measured` points
// moves the boundary normal to itself by its noise over its share L / measured of the
// length, and the centroid by (x - c) times that area over the area; summed, the
// covariance is noise^2 (L / measured) times the integral of (x - c)(x - c)' ds over the
// area squared. A fit of the points passes a smooth functional like this one on whole, so
// the cavity's control points do not enter (unlike a wall's, where one place counts).
double centroid_standard_error(const WallNoise& nz, const detail::PiecewiseCurve& pc, const Cavity& c,
                               std::size_t measured) {
  if (!(nz.sigma > 0) || measured == 0 || !(c.area > 0)) return 0;
  // 512 chords around the closed curve (the last point is the first again).
  const std::vector<Eigen::Vector2d> p = pc.points(pc.t_min(), pc.t_max(), 513);
  Eigen::Matrix2d second = Eigen::Matrix2d::Zero();
  double length = 0;
  for (std::size_t k = 1; k < p.size(); ++k) {
    const double ds = (p[k] - p[k - 1]).norm();
    const Eigen::Vector2d mid = 0.5 * (p[k] + p[k - 1]) - c.centroid;
    second += ds * mid * mid.transpose();
    length += ds;
  }
  const Eigen::Matrix2d covariance =
      nz.sigma * nz.sigma * (length / double(measured)) * second / (c.area * c.area);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(covariance, Eigen::EigenvaluesOnly);
  return std::sqrt(std::max(eigen.eigenvalues()(1), 0.0));
}

// `count` parameters of the closed curve `pc` evenly along it by length from its first
// (from 2048 chords), and those lengths.
struct AlongCurve {
  std::vector<double> t, s;
};
AlongCurve evenly_along(const detail::PiecewiseCurve& pc, int count) {
  constexpr int fine = 2048;
  const std::vector<Eigen::Vector2d> p = pc.points(pc.t_min(), pc.t_max(), fine + 1);
  std::vector<double> at(p.size(), 0.0);
  for (std::size_t k = 1; k < p.size(); ++k) at[k] = at[k - 1] + (p[k] - p[k - 1]).norm();
  const double t0 = pc.t_min(), period = pc.t_max() - t0;
  AlongCurve out;
  for (int j = 0; j < count; ++j) {
    const double s = at.back() * j / count;
    const std::size_t k = std::size_t(std::upper_bound(at.begin(), at.end(), s) - at.begin()) - 1;
    const double f = at[k + 1] > at[k] ? (s - at[k]) / (at[k + 1] - at[k]) : 0.0;
    out.t.push_back(t0 + period * (double(k) + f) / fine);
    out.s.push_back(s);
  }
  return out;
}

// Cavity c's wall map: in.options.wall_stations stations evenly along it, each with its least
// distance to the profile (its foot there), the side of that foot and the wall's `flags`,
// wall_measured added where a hole lies at the station or its foot.
void add_wall_map(const WallsInput& in, const SectionCavity& c, const WallCoverage& coverage, CheckBits flags,
                  std::vector<double>& rows) {
  const int count = in.options.wall_stations;
  if (count <= 0) return;
  const AlongCurve along = evenly_along(coverage.cavity, count);
  fit::Points stations;
  detail::PiecewiseCurve::Cursor cursor;
  for (double t : along.t) stations.push_back(coverage.cavity.point(coverage.cavity.locate(t, cursor)));
  const fit::Feet feet = fit::foot_points(in.curve, in.profile, stations, nullptr);
  for (std::size_t j = 0; j < stations.size(); ++j) {
    const Eigen::Vector2d foot = in.profile.point(in.profile.locate(feet.t[j]));
    const double wall = (stations[j] - foot).norm();
    const bool forward = in.profile.forward(in.le_t, feet.t[j]) <= in.profile.forward(in.le_t, in.te_t);
    CheckBits at = flags;
    const char* where = "";
    if (coverage.hole_under({{along.t[j], feet.t[j]}}, wall, where) > 0) at |= bit(Check::wall_measured);
    const Eigen::Vector2d station = stations[j] + in.origin, nearest = foot + in.origin;
    schema::wall_map.append(
        rows, {in.section, c.loop, j, along.s[j], station, in.frame.to_world(station), wall, nearest,
               in.frame.to_world(nearest), forward == in.forward_is_pressure ? 0 : 1, at});
  }
}

}  // namespace

void add_walls(const WallsInput& in, const std::vector<SectionCavity>& cavities, std::vector<double>& rows,
               std::vector<double>& map_rows, std::vector<SectionIssue>& issues) {
  if (cavities.empty()) return;
  const CamberOptions& opt = in.options;
  const double chord = in.chord;
  const int section = in.section;
  // The coverage's step: 3 % of the shortest hole that counts, but not below 3e-5 of the
  // chord (a wall of a micrometre would ask for billions of samples).
  double finest = opt.thickness_hole * chord;
  for (const SectionCavity& c : cavities) finest = std::min(finest, c.cavity.wall);
  const double h = 0.03 * std::max(finest, 1e-3 * chord);
  const ProfileCoverage outer(in.profile, in.measured, h);
  for (const SectionCavity& c : cavities) {
    const auto points = in.loop_points.find({section, c.loop});
    const ProfileCoverage inner(detail::PiecewiseCurve(c.curve),
                                points != in.loop_points.end() ? detail::moved(points->second, in.origin)
                                                               : std::vector<Eigen::Vector2d>{},
                                h);
    const detail::PiecewiseCurve cavity(c.curve);
    const WallCoverage coverage{outer, inner, cavity, opt, chord};
    const std::string name = "cavity (loop " + std::to_string(c.loop) + "): ";
    const auto hole_issue = [&](const std::string& wall, double value, double hole, const char* side) {
      issues.push_back({section, c.loop, "camber",
                        name + wall + ", thinnest " + format_length(value) + ", runs over " +
                            format_length(hole) + " of the " + side +
                            " without a measured point where it is thin; the fits' bridge over that hole may "
                            "hide a thinner wall (check wall_measured)"});
    };
    const char* side = "";
    const double hole = coverage.hole_under(c.cavity.thin, c.cavity.wall, side);
    CheckBits flags = in.section_flags;
    const WallNoise& nz = in.noise;
    const double sigma =
        wall_sigma(nz, c.curve, points != in.loop_points.end() ? points->second.size() : std::size_t(0));
    if (sigma > 0 && 2 * sigma > nz.limit && !(flags & bit(Check::noise))) {
      flags |= bit(Check::noise);
      issues.push_back(
          {section, c.loop, "camber",
           name + "its thinnest wall, " + format_length(c.cavity.wall) + ", has a standard error of " +
               format_length(sigma) +
               " through the points' noise over the profile's and the cavity's fits: twice that is "
               "more than the accuracy allows (" +
               format_length(nz.limit) + "; check noise)"});
    }
    // The sides' walls: flagged as the thinnest (the same noise), each by its own holes.
    const CheckBits side_flags = flags;
    if (hole > 0) {
      flags |= bit(Check::wall_measured);
      hole_issue("its wall", c.cavity.wall, hole, side);
    }
    std::array<CavityWall, 2> walls = side_walls(in.curve, c.curve, in.le_t, in.te_t);
    if (!in.forward_is_pressure) std::swap(walls[0], walls[1]);
    add_wall_map(in, c, coverage, side_flags, map_rows);
    CheckBits wall_flags[2] = {side_flags, side_flags};
    for (int k = 0; k < 2; ++k) {
      const char* where = "";
      const double side_hole = coverage.hole_under(walls[k].thin, walls[k].wall, where);
      if (side_hole > 0) {
        wall_flags[k] |= bit(Check::wall_measured);
        hole_issue(k == 0 ? "its wall to the pressure side" : "its wall to the suction side", walls[k].wall,
                   side_hole, where);
      }
      walls[k].profile_point += in.origin, walls[k].cavity_point += in.origin;
    }
    const double centroid_sigma = centroid_standard_error(
        nz, cavity, c.cavity, points != in.loop_points.end() ? points->second.size() : 0);
    Cavity at = c.cavity;
    at.profile_point += in.origin, at.cavity_point += in.origin, at.centroid += in.origin;
    schema::walls.append(rows, {section, c.loop, at, sigma, in.frame.to_world(at.profile_point),
                                in.frame.to_world(at.cavity_point), flags, walls[0], walls[1], wall_flags[0],
                                wall_flags[1], in.frame.to_world(at.centroid), centroid_sigma});
  }
}

}  // namespace section::pipe
