// SPDX-License-Identifier: GPL-3.0-or-later
// slice on rows of points and the slab from the sampling (docs/SAMPLING.md): a plane
// through a sparse row takes it, a plane between rows says which rows lie beside it, and
// each row can be taken as a section as it lies.
#include "section/slice.h"

#include "section/error.h"
#include "detail/parallel.h"
#include "detail/segment.h"
#include "detail/slice_steps.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace section {

namespace {

std::string num(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", x);
  return buf;
}

// How the points of a row lie against a plane (unit normal n through o).
struct Against {
  double low = INFINITY, high = -INFINITY, mean = 0;
};

Against against(const std::vector<Eigen::Vector3d>& points, const PointRow& row, const Eigen::Vector3d& o,
                const Eigen::Vector3d& n) {
  Against a;
  for (std::size_t i : row.points) {
    const double d = n.dot(points[i] - o);
    a.low = std::min(a.low, d), a.high = std::max(a.high, d), a.mean += d;
  }
  a.mean /= double(row.points.size());
  return a;
}

// Why a plane takes no row: the rows beside it (or the nearest, beyond them all).
std::string between(const Sampling& s, const std::vector<double>& mean, double height) {
  int below = -1, above = -1;
  for (std::size_t k = 0; k < s.rows.size(); ++k) {
    if (mean[k] < 0 && (below < 0 || mean[k] > mean[std::size_t(below)])) below = int(k);
    if (mean[k] > 0 && (above < 0 || mean[k] < mean[std::size_t(above)])) above = int(k);
  }
  const std::string rows = s.rows.size() == 1 ? "a single row of points"
                                              : std::to_string(s.rows.size()) + " sparse rows of points " +
                                                    num(s.row_gap) + " apart, each a section's worth";
  const std::string take = "; take the rows as they lie (slice --rows) or a plane through one (";
  const auto at = [&](int k) { return "--at " + num(s.rows[std::size_t(k)].height); };
  const std::string plane = "the plane at height " + num(height);
  if (below >= 0 && above >= 0)
    return plane + " falls between the rows at heights " + num(s.rows[std::size_t(below)].height) + " and " +
           num(s.rows[std::size_t(above)].height) + " (" + rows +
           "): no section is made between rows, too far apart to bridge" + take + at(below) + " or " +
           at(above) + ")";
  const int k = below >= 0 ? below : above;
  return plane + " lies " + (below >= 0 ? "above the highest" : "below the lowest") + " row, at height " +
         num(s.rows[std::size_t(k)].height) + " (" + rows + ")" + take + at(k) + ")";
}

// The options for rows: a row is all there is (no band, no fill).
SliceOptions as_they_lie(const SliceOptions& options) {
  SliceOptions o = options;
  o.band_spacing = 0;
  o.fill_gaps = false;
  return o;
}

// The nearest point to p on the closed curve through `curve`'s points: on the circle through
// the nearest vertex and its two neighbours (exact on a circular arc such as a round edge,
// where the chords would cut the corner), or on the nearest chord where they are in line.
Eigen::Vector2d nearest_on(const std::vector<Eigen::Vector2d>& curve, const Eigen::Vector2d& p) {
  const std::size_t m = curve.size();
  std::size_t k = 0;
  for (std::size_t j = 1; j < m; ++j)
    if ((curve[j] - p).squaredNorm() < (curve[k] - p).squaredNorm()) k = j;
  const Eigen::Vector2d &a = curve[(k + m - 1) % m], &b = curve[k], &c = curve[(k + 1) % m];
  const Eigen::Vector2d ab = b - a, ac = c - a;
  const double d = 2 * (ab.x() * ac.y() - ab.y() * ac.x());
  if (d != 0) {
    const Eigen::Vector2d o = a + Eigen::Vector2d(ac.y() * ab.squaredNorm() - ab.y() * ac.squaredNorm(),
                                                  ab.x() * ac.squaredNorm() - ac.x() * ab.squaredNorm()) /
                                      d;
    const double r = (b - o).norm(), q = (p - o).norm();
    if (q > 0 && r < 100 * (ab.norm() + ac.norm())) return o + r / q * (p - o);
  }
  const detail::SegmentFoot f1 = detail::segment_foot(a, b, p), f2 = detail::segment_foot(b, c, p);
  return f1.d2 < f2.d2 ? Eigen::Vector2d(a + f1.t * ab) : Eigen::Vector2d(b + f2.t * (c - b));
}

// The points of `from` each carried the fraction w of the way to its nearest point on the
// closed curve through `curve`, appended to `out`.
void carry_toward(const std::vector<Eigen::Vector2d>& from, const std::vector<Eigen::Vector2d>& curve,
                  double w, std::vector<Eigen::Vector2d>& out) {
  for (const Eigen::Vector2d& p : from) out.push_back(p + w * (nearest_on(curve, p) - p));
}

// The section between the lines below and above a plane (their points' mean heights off
// it `below` < 0 <= `above`): each line's points in the plane, carried toward the other's
// curve by the other's share of the height.
std::vector<Eigen::Vector2d> between_lines(const std::vector<Eigen::Vector3d>& points, const PointRow& low,
                                           const PointRow& high, double below, double above,
                                           const Frame& frame, const MorphologyOptions& morphology) {
  std::vector<Eigen::Vector2d> a, b, out;
  for (std::size_t i : low.points) a.push_back(frame.to_plane(points[i]));
  for (std::size_t i : high.points) b.push_back(frame.to_plane(points[i]));
  const double w = -below / (above - below);
  carry_toward(a, detail::order_row(b, morphology).loops.at(0).points, w, out);
  carry_toward(b, detail::order_row(a, morphology).loops.at(0).points, 1 - w, out);
  return out;
}

// Each point of line `from` followed to its nearest point on line `to`'s curve (both
// taken in the frame f of their mean plane, `to` at its mean height in it), cut where that
// step crosses the plane: the crossings, in the plane's frame, appended to `out`.
void step_across(const std::vector<Eigen::Vector3d>& points, const PointRow& from, const PointRow& to,
                 const Frame& f, const Frame& plane, const MorphologyOptions& morphology,
                 std::vector<Eigen::Vector2d>& out) {
  std::vector<Eigen::Vector2d> in_f;
  double h = 0;
  for (std::size_t i : to.points) in_f.push_back(f.to_plane(points[i])), h += f.height(points[i]);
  h /= double(to.points.size());
  const std::vector<Eigen::Vector2d> curve = detail::order_row(in_f, morphology).loops.at(0).points;
  for (std::size_t i : from.points) {
    const Eigen::Vector3d& p = points[i];
    const Eigen::Vector3d q = f.to_world(nearest_on(curve, f.to_plane(p))) + h * f.n;
    const double sp = plane.height(p), sq = plane.height(q);
    if ((sp <= 0 && sq > 0) || (sp >= 0 && sq < 0))
      out.push_back(plane.to_plane(p + sp / (sp - sq) * (q - p)));
  }
}

// The section where a plane tilted to the lines of points crosses them: between every two
// neighbouring lines whose points lie on both sides of it (and no farther apart than 2.5
// times the lines' spacing), each line's points stepped toward the other's curve and cut
// where the step crosses the plane (step_across).
std::vector<Eigen::Vector2d> across_lines(const std::vector<Eigen::Vector3d>& points, const Sampling& s,
                                          const Frame& plane, const MorphologyOptions& morphology) {
  // Part of the section beyond the lines (the plane below part of the lowest, above part
  // of the highest) would be left out: a partial profile posing as the section.
  const bool below = against(points, s.rows.front(), plane.origin, plane.n).high > 0;
  if (below || against(points, s.rows.back(), plane.origin, plane.n).low < 0)
    throw Error("the plane at height " + num(plane.n.dot(plane.origin)) +
                " leaves the lines of points: part of its section lies beyond the " +
                (below ? "lowest" : "highest") + " line");
  std::vector<Eigen::Vector2d> out;
  for (std::size_t k = 0; k + 1 < s.rows.size(); ++k) {
    const PointRow &a = s.rows[k], &b = s.rows[k + 1];
    const Against ha = against(points, a, plane.origin, plane.n),
                  hb = against(points, b, plane.origin, plane.n);
    if (std::min(ha.low, hb.low) > 0 || std::max(ha.high, hb.high) < 0) continue;
    if (b.height - a.height > 2.5 * s.row_gap)
      throw Error("the plane at height " + num(plane.n.dot(plane.origin)) + " crosses a gap of " +
                  num(b.height - a.height) + " between the lines at heights " + num(a.height) + " and " +
                  num(b.height) + " (" + num(s.row_gap) + " apart elsewhere)");
    const Frame f = make_frame(a.origin, (a.normal + b.normal).normalized());
    step_across(points, a, b, f, plane, morphology, out);
    step_across(points, b, a, f, plane, morphology, out);
  }
  return out;
}

}  // namespace

namespace detail {

Sampling sample_all(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& normal,
                    const SamplingOptions& options, SpacingSearch& search) {
  Sampling s = sampling_of(points, normal, options, search);
  if (s.kind == SamplingKind::rows && points.size() > s.points) {
    SamplingOptions all = options;
    all.max_points = points.size();
    s = sampling_of(points, normal, all, search);
  }
  return s;
}

double sampled_slab(const std::vector<Eigen::Vector3d>& points, const Sampling& sampling,
                    const SpacingSearch& search) {
  double slab = sampling.kind == SamplingKind::lines ? sampling.slab : 0;
  if (sampling.kind == SamplingKind::dense) {
    // mean_spacing's random subset scales its spacing by the density, which copies inflate.
    slab = 100 * sampling.duplicates > sampling.measured ? sampling.spacing : mean_spacing(points, search);
    if (!(slab > 0)) slab = sampling.spacing;
  }
  if (!(slab > 0))
    throw Error("slice: cannot estimate the point spacing (fewer than two distinct points); give --slab");
  return slab;
}

void slice_through_rows(const std::vector<Eigen::Vector3d>& points, const std::vector<Plane>& planes,
                        const SliceOptions& options, SliceResult& result, const SectionFn& sink) {
  const Sampling& s = result.sampling;
  std::vector<std::vector<Eigen::Vector2d>> slabs(planes.size());
  result.sections.assign(planes.size(), SectionSlice{});
  for (std::size_t p = 0; p < planes.size(); ++p) {
    const Eigen::Vector3d n = planes[p].normal.normalized();
    const Frame frame = make_frame(planes[p].origin, planes[p].normal);
    SectionSlice& section = result.sections[p];
    std::vector<double> mean(s.rows.size());
    int taken = -1;
    Against best;
    for (std::size_t k = 0; k < s.rows.size(); ++k) {
      const Against a = against(points, s.rows[k], planes[p].origin, n);
      mean[k] = a.mean;
      const bool through = a.low <= s.spacing && a.high >= -s.spacing;
      if (through && (taken < 0 || std::abs(a.mean) < std::abs(best.mean))) taken = int(k), best = a;
    }
    if (taken < 0) {
      section.error = between(s, mean, n.dot(planes[p].origin));
      continue;
    }
    const PointRow& row = s.rows[std::size_t(taken)];
    section.row = taken;
    section.row_height = row.height;
    section.row_spread = std::max(std::abs(best.low), std::abs(best.high));
    if (section.row_spread > options.sampling.flatness * row.size) {
      section.error = "the plane crosses the row at height " + num(row.height) +
                      " at an angle: its points lie " + num(best.low) + " to " + num(best.high) +
                      " off the plane, more than " + num(100 * options.sampling.flatness) +
                      " % of its size " + num(row.size) + "; take the rows as they lie (slice --rows)";
      continue;
    }
    for (std::size_t i : row.points) slabs[p].push_back(frame.to_plane(points[i]));
  }
  order_slabs(slabs, {}, planes, s.spacing, as_they_lie(options), result, sink, order_row);
}

void slice_between_lines(const std::vector<Eigen::Vector3d>& points, const std::vector<Plane>& planes,
                         const SliceOptions& options, SliceResult& result, const SectionFn& sink) {
  const Sampling& s = result.sampling;
  std::vector<std::vector<Eigen::Vector2d>> slabs(planes.size());
  result.sections.assign(planes.size(), SectionSlice{});
  detail::parallel_for(planes.size(), options.threads, [&](std::size_t p) {
    const Eigen::Vector3d n = planes[p].normal.normalized();
    const Frame frame = make_frame(planes[p].origin, planes[p].normal);
    int below = -1, above = -1;
    std::vector<double> mean(s.rows.size());
    for (std::size_t k = 0; k < s.rows.size(); ++k) {
      mean[k] = against(points, s.rows[k], planes[p].origin, n).mean;
      if (mean[k] <= 0 && (below < 0 || mean[k] > mean[std::size_t(below)])) below = int(k);
      if (mean[k] > 0 && (above < 0 || mean[k] < mean[std::size_t(above)])) above = int(k);
    }
    SectionSlice& section = result.sections[p];
    if (below < 0 || above < 0) {
      section.error =
          "the plane at height " + num(n.dot(planes[p].origin)) + " lies beyond the lines of points";
      return;
    }
    // A plane tilted to the lines (their points spread in height off it over a tenth of
    // their spacing) is cut where it crosses them, not between the two beside it.
    const Against lo = against(points, s.rows[std::size_t(below)], planes[p].origin, n),
                  hi = against(points, s.rows[std::size_t(above)], planes[p].origin, n);
    if (std::max(lo.high - lo.low, hi.high - hi.low) > 0.1 * s.row_gap) {
      try {
        slabs[p] = across_lines(points, s, frame, options.morphology);
      } catch (const Error& e) {
        section.error = e.what();
      }
      return;
    }
    const double gap = mean[std::size_t(above)] - mean[std::size_t(below)];
    if (gap > 2.5 * s.row_gap) {
      section.error = "the plane at height " + num(n.dot(planes[p].origin)) + " falls in a gap of " +
                      num(gap) + " between the lines of points beside it (" + num(s.row_gap) +
                      " apart elsewhere)";
      return;
    }
    try {
      slabs[p] = between_lines(points, s.rows[std::size_t(below)], s.rows[std::size_t(above)],
                               mean[std::size_t(below)], mean[std::size_t(above)], frame, options.morphology);
    } catch (const Error& e) {
      section.error = std::string("the lines beside the plane: ") + e.what();
    }
  });
  order_slabs(slabs, {}, planes, s.slab, as_they_lie(options), result, sink, order_row);
}

void rows_as_sections(const std::vector<Eigen::Vector3d>& points, const SliceOptions& options,
                      SliceResult& result, const SectionFn& sink) {
  const Sampling& s = result.sampling;
  std::vector<Plane> planes;
  std::vector<std::vector<Eigen::Vector2d>> slabs(s.rows.size());
  result.sections.assign(s.rows.size(), SectionSlice{});
  for (std::size_t k = 0; k < s.rows.size(); ++k) {
    const PointRow& row = s.rows[k];
    planes.push_back({row.origin, row.normal});
    SectionSlice& section = result.sections[k];
    section.row = int(k);
    section.row_height = row.height;
    section.row_spread = row.spread;
    if (!row.planar) {
      section.error = "the row at height " + num(row.height) + " is not planar: its points lie up to " +
                      num(row.spread) + " from its best plane, more than " +
                      num(100 * options.sampling.flatness) + " % of its size " + num(row.size) +
                      " (a row on a curved surface, such as one at constant radius, is no plane section)";
      continue;
    }
    const Frame frame = make_frame(row.origin, row.normal);
    for (std::size_t i : row.points) slabs[k].push_back(frame.to_plane(points[i]));
  }
  order_slabs(slabs, {}, planes, s.spacing, as_they_lie(options), result, sink, order_row);
}

}  // namespace detail

namespace {

// The sampling of all of a cloud's points: a row is a section only with all its points.
Sampling all_points_sampling(const Cloud& cloud, const Eigen::Vector3d& normal, const SliceOptions& options) {
  if (cloud.points.empty()) throw Error("slice: the cloud has no points");
  SamplingOptions all = options.sampling;
  all.max_points = std::max(all.max_points, cloud.points.size());
  return sampling_of(cloud.points, normal, all);
}

// slice_rows on `sampling`, each section handed to `sink` as it is done (the sampling to
// `on_sampling` first, with slab 0).
SliceResult rows_sliced(const Cloud& cloud, const Sampling& sampling, const SliceOptions& options,
                        const SectionSink& sink, const SamplingSink& on_sampling) {
  if (sampling.points < cloud.points.size())
    throw Error("slice: the rows were found on the first " + std::to_string(sampling.points) + " of " +
                std::to_string(cloud.points.size()) + " points only");
  if (sampling.points > cloud.points.size())  // another cloud's: its rows index past this one
    throw Error("slice: the rows were found on " + std::to_string(sampling.points) +
                " points, the cloud has " + std::to_string(cloud.points.size()));
  if (sampling.rows.empty())
    throw Error("slice: the points are not rows of points, each a section's worth, but " +
                sampling.describe() + ": give section planes (--at, --count or --planes)");
  if (on_sampling && options.slab == 0) on_sampling(sampling);
  SliceResult result;
  result.points = cloud.points.size();
  result.sampling = sampling;
  detail::rows_as_sections(cloud.points, options, result, sink);
  return result;
}

}  // namespace

SliceResult slice_rows(const Cloud& cloud, const Eigen::Vector3d& normal, const SliceOptions& options) {
  return rows_sliced(cloud, all_points_sampling(cloud, normal, options), options, {}, {});
}

SliceResult slice_rows(const Cloud& cloud, const Sampling& sampling, const SliceOptions& options) {
  return rows_sliced(cloud, sampling, options, {}, {});
}

SliceResult slice_by_rows(const Cloud& cloud, const Eigen::Vector3d& normal, const SliceOptions& options,
                          bool any_lines, const SectionSink& sink, const SamplingSink& on_sampling) {
  const Sampling sampling = all_points_sampling(cloud, normal, options);
  if (!(sampling.spacing > 0) || cloud.points.size() < 8)
    throw Error("no section planes given, and " + std::to_string(cloud.points.size()) + " points" +
                (sampling.spacing > 0 ? "" : ", all equal,") +
                " make no row (a section needs 8 distinct points or more)");
  if (!any_lines && sampling.kind != SamplingKind::rows)
    throw Error("no section planes given, and the points are not sparse rows (each a section's worth) but " +
                sampling.describe() + ": give planes (--at, --count or --planes)" +
                (sampling.rows.empty() ? std::string()
                                       : ", or --rows to take each of its " +
                                             std::to_string(sampling.rows.size()) + " lines as a section"));
  // A scan settled dense on a first look has no rows (and was looked at in part only).
  if (sampling.rows.empty())
    throw Error("--rows: the points hold no rows or lines to take as sections, they are " +
                sampling.describe() + ": give planes (--at, --count or --planes)");
  return rows_sliced(cloud, sampling, options, sink, on_sampling);
}

}  // namespace section
