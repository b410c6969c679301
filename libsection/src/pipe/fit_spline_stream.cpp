// SPDX-License-Identifier: GPL-3.0-or-later
// Stream stage of fitspline: points (and smoothed points) in, splines, holes and samples out.
#include "section/pipe/fit_spline_stream.h"

#include "section/error.h"
#include "section/pipe/schema.h"
#include "section/io/stream.h"
#include "pipe/adapter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace section {

namespace {

using Points = std::vector<Eigen::Vector2d>;

// The slots' tables, in order.
enum : std::size_t { splines_rows, knots_rows, ctrl_rows, gaps_rows, samples_rows, table_count };

// Curve samples at even arc-length steps, from a dense cumulative length table.
void add_samples(int section, int loop, const BSpline& c, const Frame& frame, const FitSplineOptions& options,
                 std::vector<double>& rows) {
  const std::vector<double> ts = span_samples(c, 32);
  std::vector<double> cum(ts.size() + 1, 0);
  for (std::size_t i = 0; i < ts.size(); ++i)
    cum[i + 1] = cum[i] + arc_length(c, ts[i], i + 1 < ts.size() ? ts[i + 1] : c.t_max());
  const double length = cum.back();
  int count = options.samples;
  if (options.sample_spacing > 0) {
    const double wanted = std::ceil(length / options.sample_spacing);
    // Checked before the cast: a tiny spacing overflowed int into 3 samples.
    if (!(wanted <= FitSplineOptions::max_samples)) {
      char text[160];
      std::snprintf(text, sizeof text,
                    "a sample spacing of %.4g gives %.4g samples on a curve %.4g long, more than %d a loop",
                    options.sample_spacing, wanted, length, FitSplineOptions::max_samples);
      throw Error(text);
    }
    count = std::max(3, static_cast<int>(wanted));
  }
  std::size_t seg = 0;
  for (int i = 0; i < count; ++i) {
    const double target = length * i / count;
    while (seg + 1 < ts.size() && cum[seg + 1] <= target) ++seg;
    const double a = ts[seg], b = seg + 1 < ts.size() ? ts[seg + 1] : c.t_max();
    const double frac = cum[seg + 1] > cum[seg] ? (target - cum[seg]) / (cum[seg + 1] - cum[seg]) : 0;
    const double t = a + frac * (b - a);
    const Eigen::Vector2d p = c.point(t);
    const Eigen::Vector2d d1 = c.derivative(t, 1).normalized();
    const Eigen::Vector2d nrm(d1.y(), -d1.x());
    schema::samples.append(rows, {section, loop, i, t, p, frame.to_world(p), nrm, c.curvature(t)});
  }
}

// What fit_spline_stream fits a loop with.
struct FitInput {
  std::map<std::pair<int, int>, pipe::LoopRows> measured, smoothed;
  std::map<int, Frame> frames;
  FitSplineOptions options;
  bool samples = false;
};

// Fits one loop into its slot: the first curve from its smoothed points when it has 8 or
// more, else from the measured ones.
void fit_loop(const std::pair<int, int>& key, const pipe::LoopRows& rows, const FitInput& in,
              pipe::Slot& slot) {
  const auto [section, loop] = key;
  Points q;
  for (const auto& row : rows) q.push_back(row.second);
  Points profile = q;
  if (auto it = in.smoothed.find(key); it != in.smoothed.end() && it->second.size() >= 8) {
    profile.clear();
    for (const auto& row : it->second) profile.push_back(row.second);
  }
  const FitSplineResult r = fit_spline(profile, q, in.options);
  const BSpline& c = r.spline;
  schema::splines.append(slot.rows[splines_rows], {section, loop, r});
  for (std::size_t i = 0; i < c.knots.size(); ++i)
    schema::spline_knots.append(slot.rows[knots_rows], {section, loop, i, c.knots[i]});
  for (std::size_t i = 0; i < c.control.size(); ++i)
    schema::spline_ctrl.append(slot.rows[ctrl_rows], {section, loop, i, c.control[i]});
  for (std::size_t i = 0; i < r.gaps.size(); ++i)
    schema::gaps.append(slot.rows[gaps_rows], {section, loop, i, r.gaps[i]});
  if (in.samples) {
    const auto f = in.frames.find(section);
    add_samples(section, loop, c, f == in.frames.end() ? Frame{} : f->second, in.options,
                slot.rows[samples_rows]);
  }
}

}  // namespace

void fit_spline_stream(Stream& stream, const FitSplineOptions& options) {
  FitInput in;
  in.measured = pipe::loop_rows(schema::points.get(stream), "fit_spline");
  if (const Table* sm = schema::smoothed.find(stream)) in.smoothed = pipe::loop_rows(*sm, "fit_spline");
  if (schema::frames.find(stream)) in.frames = frames(stream);
  in.options = options;
  in.samples = options.samples > 0 || options.sample_spacing > 0;
  pipe::restage(stream, "fitspline");
  std::vector<Table> tables = {schema::splines.table(), schema::spline_knots.table(),
                               schema::spline_ctrl.table(), schema::gaps.table(), schema::samples.table()};
  std::vector<std::pair<std::pair<int, int>, const pipe::LoopRows*>> work;
  std::set<int> present;
  for (const auto& [key, rows] : in.measured) {
    present.insert(key.first);
    if (!stream.failed(key.first, key.second)) work.push_back({key, &rows});
  }
  pipe::vanished_sections(stream, present, "fitspline", "points");
  std::vector<Table*> out;
  for (auto& t : tables) out.push_back(&t);
  pipe::run_slots(
      work.size(), options.threads, out, stream.issues, "fit_spline",
      [&](std::size_t w, pipe::Slot& slot) { fit_loop(work[w].first, *work[w].second, in, slot); },
      [&](std::size_t w, const std::string& message) {
        return SectionIssue{work[w].first.first, work[w].first.second, "fitspline", message};
      });
  for (std::size_t k = 0; k < samples_rows; ++k) stream.put(std::move(tables[k]));
  if (in.samples)
    stream.put(std::move(tables[samples_rows]));
  else
    stream.erase(schema::samples.name);
}

std::map<std::pair<int, int>, std::vector<FitSplineResult::Gap>> gaps(const Stream& stream) {
  std::map<std::pair<int, int>, std::vector<FitSplineResult::Gap>> out;
  const Table* g = schema::gaps.find(stream);
  if (!g) return out;
  namespace col = schema::col;
  const std::size_t cs = g->column(col::section), cl = g->column(col::loop), ci = g->column(col::index),
                    ca = g->column(col::t_start), cb = g->column(col::t_end), cn = g->column(col::length);
  std::map<std::pair<int, int>, std::vector<std::pair<double, FitSplineResult::Gap>>> rows;
  for (std::size_t r = 0; r < g->rows(); ++r)
    rows[{static_cast<int>(g->at(r, cs)), static_cast<int>(g->at(r, cl))}].push_back(
        {g->at(r, ci), {g->at(r, ca), g->at(r, cb), g->at(r, cn)}});
  for (auto& [key, list] : rows) {
    std::stable_sort(list.begin(), list.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
    for (const auto& entry : list) out[key].push_back(entry.second);
  }
  return out;
}

std::map<std::pair<int, int>, BSpline> splines(const Stream& stream) {
  namespace col = schema::col;
  const Table& s = schema::splines.get(stream);
  const Table& k = schema::spline_knots.get(stream);
  const Table& c = schema::spline_ctrl.get(stream);
  std::map<std::pair<int, int>, BSpline> out;
  const std::size_t ss = s.column(col::section), sl = s.column(col::loop), sd = s.column(col::degree),
                    sc = s.column(col::closed);
  for (std::size_t r = 0; r < s.rows(); ++r) {
    BSpline b;
    b.degree = static_cast<int>(s.at(r, sd));
    b.closed = s.at(r, sc) != 0;
    out[{static_cast<int>(s.at(r, ss)), static_cast<int>(s.at(r, sl))}] = b;
  }
  auto rows_of = [&](const Table& t, auto&& add) {
    const std::size_t ts = t.column(col::section), tl = t.column(col::loop), ti = t.column(col::index);
    std::map<std::pair<int, int>, std::vector<std::pair<double, std::size_t>>> by;
    for (std::size_t r = 0; r < t.rows(); ++r)
      by[{static_cast<int>(t.at(r, ts)), static_cast<int>(t.at(r, tl))}].push_back({t.at(r, ti), r});
    for (auto& [key, rows] : by) {
      auto it = out.find(key);
      if (it == out.end())
        throw Error("fit_spline: table '" + t.name + "' has rows for section " + std::to_string(key.first) +
                    " loop " + std::to_string(key.second) + " that the splines table lacks");
      std::sort(rows.begin(), rows.end());
      for (const auto& row : rows) add(it->second, row.second);
    }
  };
  const std::size_t kk = k.column(col::knot);
  rows_of(k, [&](BSpline& b, std::size_t r) { b.knots.push_back(k.at(r, kk)); });
  const std::size_t cu = c.column(col::u), cv = c.column(col::v);
  rows_of(c, [&](BSpline& b, std::size_t r) { b.control.emplace_back(c.at(r, cu), c.at(r, cv)); });
  for (const auto& [key, b] : out) {
    const std::size_t expect = b.closed ? b.control.size() + 1 : b.control.size() + b.degree + 1;
    if (b.control.size() < static_cast<std::size_t>(b.degree + 1) || b.knots.size() != expect)
      throw Error("fit_spline: the spline of section " + std::to_string(key.first) + " loop " +
                  std::to_string(key.second) + " has " + std::to_string(b.control.size()) +
                  " control points and " + std::to_string(b.knots.size()) + " knots, which do not match");
    try {
      check_spline(b);
    } catch (const Error& e) {
      throw Error("fit_spline: the spline of section " + std::to_string(key.first) + " loop " +
                  std::to_string(key.second) + " is not a curve: " + e.what());
    }
  }
  return out;
}

}  // namespace section
