// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The generator's exact section (generate.h), internal to section_extras: the envelope of
// circles r(s) on a cubic Bezier camber c(s), closed by the end circles' arcs, held as 7
// pieces counterclockwise from the LE point. Everything is evaluated analytically (c, c',
// c'', r, r', r''), so lengths come from Gauss-Legendre quadrature of exact derivatives and
// points are placed at exact arc lengths by Newton inversion. See docs/GENERATOR.md.
#include "section/extras/generate.h"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace section::detail::gen {

using Eigen::Vector2d;

constexpr double pi = 3.14159265358979323846;
constexpr double deg = pi / 180;

inline Vector2d dir(double degrees) {
  return {std::cos(degrees * deg), std::sin(degrees * deg)};
}
inline Vector2d rot90(const Vector2d& v) {
  return {-v.y(), v.x()};
}
inline double cross(const Vector2d& a, const Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// A number for messages: 6 significant digits.
std::string num(double v);

// 10-point Gauss-Legendre on [-1, 1] (positive half; symmetric).
inline constexpr double gl_x[5] = {0.1488743389816312, 0.4333953941292472, 0.6794095682990244,
                                   0.8650633666889845, 0.9739065285171717};
inline constexpr double gl_w[5] = {0.2955242247147529, 0.2692667193099963, 0.2190863625159820,
                                   0.1494513491505806, 0.0666713443086881};

// 5-point rule, for the short steps between neighbouring samples.
inline constexpr double gl5_x[3] = {0.0, 0.5384693101056831, 0.9061798459386640};
inline constexpr double gl5_w[3] = {0.5688888888888889, 0.4786286704993665, 0.2369268850561891};

template <class F>
double gauss5(double a, double b, const F& f) {
  const double m = 0.5 * (a + b), h = 0.5 * (b - a);
  double sum = gl5_w[0] * f(m);
  for (int i = 1; i < 3; ++i) sum += gl5_w[i] * (f(m - h * gl5_x[i]) + f(m + h * gl5_x[i]));
  return sum * h;
}

template <class F>
double gauss(double a, double b, const F& f) {
  const double m = 0.5 * (a + b), h = 0.5 * (b - a);
  double sum = 0;
  for (int i = 0; i < 5; ++i) sum += gl_w[i] * (f(m - h * gl_x[i]) + f(m + h * gl_x[i]));
  return sum * h;
}

/// Newton for the parameter at arc length `target`, integrating the speed from a known
/// (lam0, a0) that lies within the same panel (so the 5-point rule is exact enough).
template <class F>
double advance(const F& speed, double lam0, double a0, double target, double lo, double hi) {
  double lam = lam0 + (target - a0) / speed(lam0);
  for (int it = 0; it < 12; ++it) {
    lam = std::clamp(lam, lo, hi);
    const double step = (a0 + gauss5(lam0, lam, speed) - target) / speed(lam);
    lam -= step;
    if (std::abs(step) < 1e-15) break;
  }
  return lam;
}

/// The parameter in [0, 1] at increasing arc lengths along a curve whose cumulative lengths
/// over `panels` equal parameter panels are cum[0..panels]. Each step integrates on from the
/// previous answer while it stays in the same panel, else from the panel's start.
template <class F>
struct ArcWalker {
  const double* cum;
  int panels;
  F speed;
  int panel = -1;
  double lam_prev = 0, a_prev = 0;

  double operator()(double a) {
    int k = int(std::upper_bound(cum, cum + panels + 1, a) - cum) - 1;
    k = std::clamp(k, 0, panels - 1);
    const double l0 = double(k) / panels, l1 = double(k + 1) / panels;
    if (k != panel || a < a_prev) {
      panel = k;
      lam_prev = l0;
      a_prev = cum[k];
    }
    const double lam = advance(speed, lam_prev, a_prev, a, l0 - 1e-3, l1 + 1e-3);
    lam_prev = lam;
    a_prev = a;
    return std::clamp(lam, 0.0, 1.0);
  }
};

// ---------------------------------------------------------------------------------------
// Section geometry: camber Bezier + two-branch thickness law.

struct Geometry {
  std::array<Vector2d, 4> b;      // Bezier control points of c(s)
  double rl = 1, rt = 1;          // r(0), r(1)
  double R = 1, sm = 0.5;         // max r and its s
  double beta_l = 0, beta_r = 0;  // shape parameters of the two thickness branches
};

/// r(s) and its derivatives on a branch (0: s <= sm, 1: s >= sm); each branch is a
/// polynomial, so evaluating it slightly outside its range is harmless.
void thickness(const Geometry& g, double s, int branch, double& r, double& r1, double& r2);
/// c(s) and its first two derivatives.
void camber_eval(const Geometry& g, double s, Vector2d& c, Vector2d& d1, Vector2d& d2);
Geometry make_geometry(const SectionDesign& d);

/// A point of the envelope side `sign` (+1: left of c, -1: right of c) at s.
struct SideEval {
  Vector2d p, dp, u;      // point, d/ds, outward unit normal
  double rho = 0, w = 0;  // r'/|c'|; signed speed along the counterclockwise direction
};
SideEval side_eval(const Geometry& g, double s, int sign, int branch);

/// Throws section::Error unless the design gives a valid envelope whose medial axis is c(s).
void check_design(const SectionDesign& d, const std::string& who);

// ---------------------------------------------------------------------------------------
// The closed profile as 7 pieces, counterclockwise from the LE point.

struct Piece {
  enum Kind { arc, side } kind = arc;
  double t0 = 0, t1 = 0;     // angle range (arc, radians) or s range (side)
  int sign = 0, branch = 0;  // side only
  Vector2d center{0, 0};     // arc only
  double radius = 0;         // arc only
};

struct Section {
  Geometry g;
  std::array<Piece, 7> pieces;
};

Section make_section(const SectionDesign& d);

struct PieceEval {
  Vector2d p, dp, normal;  // point, d/dlambda, outward unit normal
};
/// The point of piece `pc` at lambda in [0, 1].
PieceEval piece_eval(const Section& sec, const Piece& pc, double lambda);

/// |dp/dlambda| along one piece: what its arc lengths integrate.
struct PieceSpeed {
  const Section& sec;
  const Piece& pc;
  double operator()(double l) const { return piece_eval(sec, pc, l).dp.norm(); }
};

// Arc-length inversion within one piece: panels with cumulative lengths, Newton inside.
struct PieceLength {
  static constexpr int panels = 24;
  std::array<double, panels + 1> cum{};
};
PieceLength piece_length(const Section& sec, const Piece& pc);

/// Walks along one piece to increasing arc lengths (lambda of each), reusing the previous
/// sample as the start of the next integration.
struct PieceWalker {
  const Piece& pc;
  const PieceLength& L;
  ArcWalker<PieceSpeed> walk;

  PieceWalker(const Section& sec, const Piece& piece, const PieceLength& length)
      : pc(piece), L(length), walk{L.cum.data(), PieceLength::panels, PieceSpeed{sec, piece}} {}
  double operator()(double a) {
    const double total = L.cum.back();
    if (a <= 0) return 0;
    if (a >= total) return 1;
    if (pc.kind == Piece::arc) return a / total;
    return walk(a);
  }
};

}  // namespace section::detail::gen
