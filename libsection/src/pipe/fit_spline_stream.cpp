#include "section/pipe/fit_spline_stream.h"

#include "section/error.h"
#include "section/pipe/schema.h"
#include "section/io/stream.h"
#include "detail/parallel.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace section {

namespace {
using Points = std::vector<Eigen::Vector2d>;
}  // namespace

void fit_spline_stream(Stream& stream, const FitSplineOptions& options) {
  const Table& points = stream.get("points", "slice");
  const std::size_t cs = points.column("section"), cl = points.column("loop"),
                    ci = points.column("index"), cu = points.column("u"), cv = points.column("v");
  using Rows = std::vector<std::pair<double, Eigen::Vector2d>>;
  auto group = [](const Table& t, std::size_t cs, std::size_t cl, std::size_t ci, std::size_t cu,
                  std::size_t cv) {
    std::map<std::pair<int, int>, Rows> loops;
    Rows* loop = nullptr;  // the last row's, which the next row mostly shares
    std::pair<int, int> last;
    for (std::size_t r = 0; r < t.rows(); ++r) {
      const double s = t.at(r, cs), l = t.at(r, cl);
      if (!std::isfinite(s) || !std::isfinite(l))
        throw Error("fit_spline: row " + std::to_string(r + 1) + " of the " + t.name +
                    " table has a non-finite section or loop id");
      const std::pair<int, int> key{static_cast<int>(s), static_cast<int>(l)};
      if (!loop || key != last) {
        loop = &loops[key];
        last = key;
      }
      loop->push_back({t.at(r, ci), Eigen::Vector2d(t.at(r, cu), t.at(r, cv))});
    }
    auto before = [](const auto& x, const auto& y) { return x.first < y.first; };
    for (auto& [key, rows] : loops) {
      // Rows come in index order: left as they are when sorted (finite indices, so the
      // stable sort would keep them too).
      auto finite = [](const auto& x) { return std::isfinite(x.first); };
      if (!std::all_of(rows.begin(), rows.end(), finite) || !std::is_sorted(rows.begin(), rows.end(), before))
        std::stable_sort(rows.begin(), rows.end(), before);
    }
    return loops;
  };
  auto measured = group(points, cs, cl, ci, cu, cv);
  std::map<std::pair<int, int>, Rows> smoothed;
  if (const Table* sm = stream.find("smoothed"))
    smoothed = group(*sm, sm->column("section"), sm->column("loop"), sm->column("index"),
                     sm->column("u"), sm->column("v"));
  const std::map<int, Frame> frame_of = stream.find("frames") ? frames(stream) : std::map<int, Frame>{};

  auto& issues = stream.issues;
  issues.erase(std::remove_if(issues.begin(), issues.end(),
                              [](const SectionIssue& i) { return i.stage == "fitspline"; }),
               issues.end());

  Table splines_table{"splines",
                      {"section", "loop", "degree", "closed", "control_points", "rms", "max", "p95",
                       "iterations", "spacing", "max_gap", "gap_start", "gap_end", "layers", "layers_length"},
                      {}};
  Table knots_table{"spline_knots", {"section", "loop", "index", "knot"}, {}};
  Table ctrl_table{"spline_ctrl", {"section", "loop", "index", "u", "v"}, {}};
  Table gaps_table{"gaps", {"section", "loop", "index", "t_start", "t_end", "length"}, {}};
  Table samples_table{"samples",
                      {"section", "loop", "index", "t", "u", "v", "x", "y", "z", "nu", "nv", "curvature"},
                      {}};
  const bool want_samples = options.samples > 0 || options.sample_spacing > 0;
  // Loops are independent: each fills its own slot, merged in key order afterwards, so the
  // output is the same whatever the thread count.
  struct Slot {
    std::vector<double> splines, knots, ctrl, samples, gaps;
    bool failed = false;
    SectionIssue issue;
  };
  std::vector<std::pair<std::pair<int, int>, const Rows*>> work;
  for (const auto& [key, rows] : measured)
    if (!stream.failed(key.first, key.second)) work.push_back({key, &rows});
  std::vector<Slot> slots(work.size());
  detail::parallel_for(work.size(), options.threads, [&](std::size_t w) {
    const auto key = work[w].first;
    const auto [section, loop] = key;
    const Rows& rows = *work[w].second;
    Slot& slot = slots[w];
    Points q;
    for (const auto& row : rows) q.push_back(row.second);
    Points profile = q;
    if (auto it = smoothed.find(key); it != smoothed.end() && it->second.size() >= 8) {
      profile.clear();
      for (const auto& row : it->second) profile.push_back(row.second);
    }
    try {
      const FitSplineResult r = fit_spline(profile, q, options);
      const BSpline& c = r.spline;
      const double sec = section, lp = loop;
      slot.splines = {sec, lp, double(c.degree), c.closed ? 1.0 : 0.0,
                      double(c.control.size()), r.rms, r.max, r.p95, double(r.iterations),
                      r.spacing, r.max_gap, r.gap_start, r.gap_end, r.layers, r.layers_length};
      for (std::size_t i = 0; i < c.knots.size(); ++i) slot.knots.insert(slot.knots.end(), {sec, lp, double(i), c.knots[i]});
      for (std::size_t i = 0; i < c.control.size(); ++i)
        slot.ctrl.insert(slot.ctrl.end(), {sec, lp, double(i), c.control[i].x(), c.control[i].y()});
      for (std::size_t i = 0; i < r.gaps.size(); ++i)
        slot.gaps.insert(slot.gaps.end(), {sec, lp, double(i), r.gaps[i].start, r.gaps[i].end, r.gaps[i].length});
      if (want_samples) {
        // Even arc-length steps from a dense cumulative length table.
        const std::vector<double> ts = span_samples(c, 32);
        std::vector<double> cum(ts.size() + 1, 0);
        for (std::size_t i = 0; i < ts.size(); ++i)
          cum[i + 1] = cum[i] + arc_length(c, ts[i], i + 1 < ts.size() ? ts[i + 1] : c.t_max());
        const double length = cum.back();
        int count = options.samples;
        if (options.sample_spacing > 0)
          count = std::max(3, static_cast<int>(std::ceil(length / options.sample_spacing)));
        const auto fit = frame_of.find(section);
        const Frame frame = fit == frame_of.end() ? Frame{} : fit->second;
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
          const Eigen::Vector3d x = frame.to_world(p);
          slot.samples.insert(slot.samples.end(), {sec, lp, double(i), t, p.x(), p.y(), x.x(), x.y(), x.z(), nrm.x(),
                                                   nrm.y(), c.curvature(t)});
        }
      }
    } catch (const Error& e) {
      std::string message = e.what();
      if (message.rfind("fit_spline: ", 0) == 0) message = message.substr(12);
      slot = Slot{};
      slot.failed = true;
      slot.issue = {section, loop, "fitspline", message};
    }
  });
  std::vector<SectionIssue> new_issues;
  auto append = [](Table& t, const std::vector<double>& v) { t.values.insert(t.values.end(), v.begin(), v.end()); };
  for (auto& slot : slots) {
    if (slot.failed) {
      new_issues.push_back(std::move(slot.issue));
      continue;
    }
    append(splines_table, slot.splines);
    append(knots_table, slot.knots);
    append(ctrl_table, slot.ctrl);
    append(gaps_table, slot.gaps);
    append(samples_table, slot.samples);
  }
  for (auto& i : new_issues) issues.push_back(std::move(i));
  stream.put(std::move(splines_table));
  stream.put(std::move(knots_table));
  stream.put(std::move(ctrl_table));
  stream.put(std::move(gaps_table));
  if (want_samples) stream.put(std::move(samples_table));
  else stream.erase("samples");
}

std::map<std::pair<int, int>, std::vector<FitSplineResult::Gap>> gaps(const Stream& stream) {
  std::map<std::pair<int, int>, std::vector<FitSplineResult::Gap>> out;
  const Table* g = stream.find("gaps");
  if (!g) return out;
  const std::size_t cs = g->column("section"), cl = g->column("loop"), ci = g->column("index"),
                    ca = g->column("t_start"), cb = g->column("t_end"), cn = g->column("length");
  std::map<std::pair<int, int>, std::vector<std::pair<double, FitSplineResult::Gap>>> rows;
  for (std::size_t r = 0; r < g->rows(); ++r)
    rows[{static_cast<int>(g->at(r, cs)), static_cast<int>(g->at(r, cl))}].push_back(
        {g->at(r, ci), {g->at(r, ca), g->at(r, cb), g->at(r, cn)}});
  for (auto& [key, list] : rows) {
    std::stable_sort(list.begin(), list.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    for (const auto& entry : list) out[key].push_back(entry.second);
  }
  return out;
}

std::map<std::pair<int, int>, BSpline> splines(const Stream& stream) {
  const Table& s = stream.get("splines", "fitspline");
  const Table& k = stream.get("spline_knots", "fitspline");
  const Table& c = stream.get("spline_ctrl", "fitspline");
  std::map<std::pair<int, int>, BSpline> out;
  const std::size_t ss = s.column("section"), sl = s.column("loop"), sd = s.column("degree"),
                    sc = s.column("closed");
  for (std::size_t r = 0; r < s.rows(); ++r) {
    BSpline b;
    b.degree = static_cast<int>(s.at(r, sd));
    b.closed = s.at(r, sc) != 0;
    out[{static_cast<int>(s.at(r, ss)), static_cast<int>(s.at(r, sl))}] = b;
  }
  auto rows_of = [&](const Table& t, auto&& add) {
    const std::size_t ts = t.column("section"), tl = t.column("loop"), ti = t.column("index");
    std::map<std::pair<int, int>, std::vector<std::pair<double, std::size_t>>> by;
    for (std::size_t r = 0; r < t.rows(); ++r)
      by[{static_cast<int>(t.at(r, ts)), static_cast<int>(t.at(r, tl))}].push_back({t.at(r, ti), r});
    for (auto& [key, rows] : by) {
      auto it = out.find(key);
      if (it == out.end())
        throw Error("fit_spline: table '" + t.name + "' has rows for section " +
                    std::to_string(key.first) + " loop " + std::to_string(key.second) +
                    " that the splines table lacks");
      std::sort(rows.begin(), rows.end());
      for (const auto& row : rows) add(it->second, row.second);
    }
  };
  const std::size_t kk = k.column("knot");
  rows_of(k, [&](BSpline& b, std::size_t r) { b.knots.push_back(k.at(r, kk)); });
  const std::size_t cu = c.column("u"), cv = c.column("v");
  rows_of(c, [&](BSpline& b, std::size_t r) { b.control.emplace_back(c.at(r, cu), c.at(r, cv)); });
  for (const auto& [key, b] : out) {
    const std::size_t expect = b.closed ? b.control.size() + 1 : b.control.size() + b.degree + 1;
    if (b.control.size() < static_cast<std::size_t>(b.degree + 1) || b.knots.size() != expect)
      throw Error("fit_spline: the spline of section " + std::to_string(key.first) + " loop " +
                  std::to_string(key.second) + " has " + std::to_string(b.control.size()) +
                  " control points and " + std::to_string(b.knots.size()) + " knots, which do not match");
  }
  return out;
}

}  // namespace section
