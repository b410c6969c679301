// SPDX-License-Identifier: GPL-3.0-or-later
// Where a point lies relative to a section's truth (generate.h): locate() and
// camber_distance(), on the polyline index, refined on the exact curve.
#include "generate_index.h"
#include "generate_section.h"
#include "section/error.h"

namespace section {

using namespace detail::gen;
using detail::PolylineIndex;

namespace {

// The profile vertex nearest to p, walking downhill from the nearer end of `segment`: the
// polyline's nearest segment can be off along the curve where the distance is flat (a
// query near a centre of curvature).
std::size_t nearest_vertex(const std::vector<Vector2d>& pts, std::size_t segment, const Vector2d& p) {
  const std::size_t n = pts.size();
  auto vd2 = [&](std::size_t i) { return (pts[i] - p).squaredNorm(); };
  std::size_t v = vd2(segment) <= vd2((segment + 1) % n) ? segment : (segment + 1) % n;
  for (std::size_t steps = 0; steps < n; ++steps) {
    const std::size_t l = (v + n - 1) % n, r = (v + 1) % n;
    if (vd2(l) < vd2(v) && vd2(l) <= vd2(r))
      v = l;
    else if (vd2(r) < vd2(v))
      v = r;
    else
      break;
  }
  return v;
}

// A stretch of one piece, lambda from l0 to l1.
struct Span {
  int piece;
  double l0, l1;
};

// The exact curve from vertex v-1 through v to v+1, piece by piece, parametrised by x in
// [0, size]: span i holds x in [i, i + 1].
struct Spans {
  const Section& sec;
  std::array<Span, 16> span;
  std::size_t size = 0;

  Spans(const PolylineIndex& idx, std::size_t v, std::size_t n) : sec(idx.section) {
    const std::size_t vs[3] = {(v + n - 1) % n, v, (v + 1) % n};
    for (int q = 0; q < 2; ++q) {
      int pa = idx.piece[vs[q]], pb = idx.piece[vs[q + 1]];
      double la = idx.lambda[vs[q]], lb = idx.lambda[vs[q + 1]];
      if (vs[q + 1] == 0) pb = 7, lb = 0;  // closing segment ends at the start of piece 0 = end of piece 6
      if (pb == 7) pb = 6, lb = 1;
      for (int pc = pa; pc <= pb; ++pc) {
        const double a0 = pc == pa ? la : 0.0, a1 = pc == pb ? lb : 1.0;
        if (a1 > a0 && size < span.size()) span[size++] = {pc, a0, a1};
      }
    }
  }
  PieceEval operator()(double x) const {
    const std::size_t i = std::min(size - 1, std::size_t(std::max(0.0, x)));
    const double f = std::clamp(x - double(i), 0.0, 1.0);
    const Span& sp = span[i];
    PieceEval e = piece_eval(sec, sec.pieces[std::size_t(sp.piece)], sp.l0 + f * (sp.l1 - sp.l0));
    e.dp *= sp.l1 - sp.l0;
    return e;
  }
  // s plus the arc length from x = 0 to x.
  double arc_length(double s, double x) const {
    for (std::size_t i = 0; i < size && double(i) < x; ++i) {
      const Span& sp = span[i];
      const double f = std::min(1.0, x - double(i));
      s += gauss5(sp.l0, sp.l0 + f * (sp.l1 - sp.l0), PieceSpeed{sec, sec.pieces[std::size_t(sp.piece)]});
    }
    return s;
  }
};

// Golden section on the squared distance of curve(x) to p over [lo, hi], narrowing the
// bracket (used when its ends do not bracket a minimum of the distance).
template <class C>
void golden_section(const C& curve, const Vector2d& p, double& lo, double& hi) {
  const double g = 0.3819660112501051;
  double x1 = lo + g * (hi - lo), x2 = hi - g * (hi - lo);
  double f1 = (curve(x1).p - p).squaredNorm(), f2 = (curve(x2).p - p).squaredNorm();
  for (int it = 0; it < 60 && hi - lo > 1e-12; ++it) {
    if (f1 <= f2) {
      hi = x2, x2 = x1, f2 = f1, x1 = lo + g * (hi - lo), f1 = (curve(x1).p - p).squaredNorm();
    } else {
      lo = x1, x1 = x2, f1 = f2, x2 = hi - g * (hi - lo), f2 = (curve(x2).p - p).squaredNorm();
    }
  }
}

// The x of the foot of p on the spans: Illinois regula falsi on the slope of the squared
// distance, bracketed by the neighbouring vertices; golden section first when they do not
// bracket a minimum.
double foot(const Spans& curve, const Vector2d& p) {
  auto slope = [&](double x) {  // half the derivative of the squared distance
    const PieceEval e = curve(x);
    return (e.p - p).dot(e.dp);
  };
  double lo = 0, hi = double(curve.size);
  double sl = slope(lo), sh = slope(hi);
  if (!(sl < 0 && sh > 0)) {
    golden_section(curve, p, lo, hi);
    sl = slope(lo), sh = slope(hi);
  }
  double xm = 0.5 * (lo + hi);
  if (!(sl < 0 && sh > 0)) return xm;
  int side = 0;
  for (int it = 0; it < 60 && hi - lo > 1e-14; ++it) {
    const double x = (lo * sh - hi * sl) / (sh - sl);
    const double sx = slope(x);
    if (std::abs(x - xm) < 1e-15) break;
    xm = x;
    if (sx == 0) break;
    if (sx < 0) {
      lo = x, sl = sx;
      if (side == -1) sh *= 0.5;
      side = -1;
    } else {
      hi = x, sh = sx;
      if (side == 1) sl *= 0.5;
      side = 1;
    }
  }
  return xm;
}

}  // namespace

ProfileLocation locate(const SectionTruth& truth, const Eigen::Vector2d& p) {
  const auto& pts = truth.profile;
  if (pts.empty()) throw Error("locate: the section truth has no profile");
  const Nearest nb = nearest(pts, true, truth.profile_index.get(), p);
  ProfileLocation loc;
  loc.distance = std::sqrt(nb.d2);
  const std::size_t n = pts.size();
  if (truth.profile_s.size() != n) return loc;
  const double s0 = truth.profile_s[nb.segment];
  const double s1 = nb.segment + 1 < n ? truth.profile_s[nb.segment + 1] : truth.perimeter;
  loc.s = s0 + nb.t * (s1 - s0);
  const PolylineIndex* idx = truth.profile_index.get();
  if (!indexes(idx, pts, true) || !idx->exact || idx->piece.size() != n || n < 3) return loc;
  // On the true curve between the neighbours of the nearest vertex.
  const std::size_t v = nearest_vertex(pts, nb.segment, p);
  const Spans curve(*idx, v, n);
  if (curve.size == 0) return loc;
  const double xm = foot(curve, p);
  const double dist = (curve(xm).p - p).norm();
  if (!(dist <= 1.001 * loc.distance + 1e-6)) return loc;  // should not happen: keep the polyline answer
  loc.distance = dist;
  // Arc length: from vertex v-1 (exact profile_s) along the spans to the foot.
  const double s_foot = curve.arc_length(truth.profile_s[(v + n - 1) % n], xm);
  loc.s = s_foot >= truth.perimeter ? s_foot - truth.perimeter : s_foot;
  return loc;
}

double camber_distance(const SectionTruth& truth, const Eigen::Vector2d& p) {
  if (truth.camber.empty()) throw Error("camber_distance: the section truth has no camber line");
  return std::sqrt(nearest(truth.camber, false, truth.camber_index.get(), p).d2);
}

}  // namespace section
