// SPDX-License-Identifier: GPL-3.0-or-later
// The generator's exact section: see generate_section.h.
#include "generate_section.h"

#include "section/error.h"

#include <sstream>

namespace section::detail::gen {

std::string num(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}

namespace {

// Thickness branch f(t) = 1 - (1-t)^2 - beta t (1-t)^2: f(0) = 0, f(1) = 1, f'(1) = 0,
// f'(0) = 2 - beta, f''(1) = -2 - 2 beta; monotone for beta in (-1, 2).
void branch_f(double t, double beta, double& f, double& f1, double& f2) {
  const double w = 1 - t;
  f = 1 - w * w - beta * t * w * w;
  f1 = w * (2 - beta * (1 - 3 * t));
  f2 = -2 + 4 * beta - 6 * beta * t;
}

}  // namespace

void thickness(const Geometry& g, double s, int branch, double& r, double& r1, double& r2) {
  double f, f1, f2;
  if (branch == 0) {
    branch_f(s / g.sm, g.beta_l, f, f1, f2);
    const double a = g.R - g.rl;
    r = g.rl + a * f;
    r1 = a * f1 / g.sm;
    r2 = a * f2 / (g.sm * g.sm);
  } else {
    const double l = 1 - g.sm;
    branch_f((1 - s) / l, g.beta_r, f, f1, f2);
    const double a = g.R - g.rt;
    r = g.rt + a * f;
    r1 = -a * f1 / l;
    r2 = a * f2 / (l * l);
  }
}

void camber_eval(const Geometry& g, double s, Vector2d& c, Vector2d& d1, Vector2d& d2) {
  const double t = 1 - s;
  c = t * t * t * g.b[0] + 3 * t * t * s * g.b[1] + 3 * t * s * s * g.b[2] + s * s * s * g.b[3];
  d1 = 3 * (t * t * (g.b[1] - g.b[0]) + 2 * t * s * (g.b[2] - g.b[1]) + s * s * (g.b[3] - g.b[2]));
  d2 = 6 * (t * (g.b[2] - 2 * g.b[1] + g.b[0]) + s * (g.b[3] - 2 * g.b[2] + g.b[1]));
}

Geometry make_geometry(const SectionDesign& d) {
  Geometry g;
  const Vector2d p0 = d.offset, p3 = d.offset + d.chord * dir(d.stagger);
  // Handle length of the cubic that best follows a circular arc turning by theta.
  const double theta = std::abs(d.inlet_angle - d.outlet_angle) * deg;
  const double handle =
      theta > 1e-6 ? d.chord * (2.0 / 3.0) * std::tan(theta / 4) / std::sin(theta / 2) : d.chord / 3;
  g.b = {p0, p0 + handle * dir(d.inlet_angle), p3 - handle * dir(d.outlet_angle), p3};
  g.rl = d.le_radius;
  g.rt = d.te_radius;
  g.R = d.max_thickness / 2;
  g.sm = d.max_thickness_pos;
  // Match r'' at sm on both branches (so the profile curvature is continuous there):
  // (R - rl)(1 + beta_l)/sm^2 = (R - rt)(1 + beta_r)/(1 - sm)^2 = geometric mean.
  const double k1 = (g.R - g.rl) / (g.sm * g.sm), k2 = (g.R - g.rt) / ((1 - g.sm) * (1 - g.sm));
  if (k1 > 0 && k2 > 0) {
    const double k = std::sqrt(k1 * k2);
    g.beta_l = std::clamp(k / k1 - 1, -0.8, 1.8);
    g.beta_r = std::clamp(k / k2 - 1, -0.8, 1.8);
  }
  return g;
}

SideEval side_eval(const Geometry& g, double s, int sign, int branch) {
  Vector2d c, d1, d2;
  camber_eval(g, s, c, d1, d2);
  double r, r1, r2;
  thickness(g, s, branch, r, r1, r2);
  const double gs = d1.norm();
  const Vector2d T = d1 / gs, N = rot90(T);
  const double kappa = cross(d1, d2) / (gs * gs * gs);
  const double gs1 = d1.dot(d2) / gs;
  const double rho = r1 / gs;
  const double rho1 = (r2 * gs - r1 * gs1) / (gs * gs);
  const double sig = std::sqrt(std::max(0.0, 1 - rho * rho));
  const double sig1 = sig > 0 ? -rho * rho1 / sig : 0;
  SideEval e;
  e.u = -rho * T + sign * sig * N;
  const Vector2d du = (-rho1 - sign * sig * kappa * gs) * T + (-rho * kappa * gs + sign * sig1) * N;
  e.p = c + r * e.u;
  e.dp = d1 + r1 * e.u + r * du;
  e.rho = rho;
  e.w = -sign * e.dp.dot(rot90(e.u));
  return e;
}

PieceEval piece_eval(const Section& sec, const Piece& pc, double lambda) {
  const double dt = pc.t1 - pc.t0, t = pc.t0 + lambda * dt;
  PieceEval e;
  if (pc.kind == Piece::arc) {
    e.normal = {std::cos(t), std::sin(t)};
    e.p = pc.center + pc.radius * e.normal;
    e.dp = pc.radius * dt * rot90(e.normal);
  } else {
    const SideEval s = side_eval(sec.g, t, pc.sign, pc.branch);
    e.p = s.p;
    e.dp = s.dp * dt;
    e.normal = s.u;
  }
  return e;
}

Section make_section(const SectionDesign& d) {
  Section sec;
  sec.g = make_geometry(d);
  const Geometry& g = sec.g;
  Vector2d c0, c1, d1, d2, e1;
  camber_eval(g, 0, c0, d1, d2);
  camber_eval(g, 1, c1, e1, d2);
  double r, r1, r2;
  thickness(g, 0, 0, r, r1, r2);
  const double rho0 = std::clamp(r1 / d1.norm(), -1.0, 1.0);
  thickness(g, 1, 1, r, r1, r2);
  const double rho1 = std::clamp(r1 / e1.norm(), -1.0, 1.0);
  const double phi0 = std::atan2(d1.y(), d1.x()), phi1 = std::atan2(e1.y(), e1.x());
  auto arc = [](Vector2d c, double rad, double a0, double a1) {
    return Piece{Piece::arc, a0, a1, 0, 0, c, rad};
  };
  auto side = [](int sign, int branch, double s0, double s1) {
    return Piece{Piece::side, s0, s1, sign, branch};
  };
  const double a0 = std::acos(rho0), a1 = std::acos(-rho1);
  sec.pieces = {arc(c0, g.rl, phi0 + pi, phi0 + pi + a0),  // LE point -> right side
                side(-1, 0, 0, g.sm),
                side(-1, 1, g.sm, 1),
                arc(c1, g.rt, phi1 - a1, phi1 + a1),  // around the TE point
                side(+1, 1, 1, g.sm),
                side(+1, 0, g.sm, 0),
                arc(c0, g.rl, phi0 + pi - a0, phi0 + pi)};  // left side -> LE point
  return sec;
}

namespace {

// The design's numbers alone: finite, positive where they must be, within range.
void check_numbers(const SectionDesign& d, const std::string& who) {
  const double vals[] = {d.chord,     d.stagger,       d.inlet_angle,       d.outlet_angle, d.le_radius,
                         d.te_radius, d.max_thickness, d.max_thickness_pos, d.offset.x(),   d.offset.y()};
  for (double v : vals)
    if (!std::isfinite(v)) throw Error(who + ": the section design has a non-finite parameter");
  if (d.chord <= 0) throw Error(who + ": chord " + num(d.chord) + " must be positive");
  if (d.le_radius < 0 || d.te_radius < 0)
    throw Error(who + ": edge radii must be zero (a sharp edge) or positive (le " + num(d.le_radius) +
                ", te " + num(d.te_radius) + ")");
  if (d.le_radius >= d.max_thickness / 2 || d.te_radius >= d.max_thickness / 2)
    throw Error(who + ": edge radii (le " + num(d.le_radius) + ", te " + num(d.te_radius) +
                ") must be below max_thickness/2 = " + num(d.max_thickness / 2));
  if (!(d.max_thickness_pos > 0.02 && d.max_thickness_pos < 0.98))
    throw Error(who + ": max_thickness_pos " + num(d.max_thickness_pos) + " must be in (0.02, 0.98)");
  if (std::abs(d.inlet_angle - d.outlet_angle) >= 170)
    throw Error(who + ": turning |inlet - outlet| must be below 170 degrees");
}

}  // namespace

void check_design(const SectionDesign& d, const std::string& who) {
  check_numbers(d, who);
  const Geometry g = make_geometry(d);
  constexpr int n = 1000;
  for (int branch = 0; branch < 2; ++branch)
    for (int i = 0; i <= n; ++i) {
      const double s = branch == 0 ? g.sm * i / n : g.sm + (1 - g.sm) * i / n;
      Vector2d c, d1, d2;
      camber_eval(g, s, c, d1, d2);
      if (d1.norm() < 1e-9 * d.chord) throw Error(who + ": the camber curve degenerates");
      for (int sign : {-1, 1}) {
        const SideEval e = side_eval(g, s, sign, branch);
        if (std::abs(e.rho) >= 0.98)
          throw Error(who + ": the thickness changes too fast along the camber at s = " + num(s) +
                      " (|r'| / |c'| = " + num(std::abs(e.rho)) + ", must be below 0.98)");
        // w > 0 is both regularity of the side and r < its radius of curvature.
        if (e.w <= 1e-3 * d1.norm())
          throw Error(who + ": the " + std::string(sign > 0 ? "left" : "right") + " side folds at s = " +
                      num(s) + ": the inscribed circle is wider than the side's curvature allows");
      }
    }
}

PieceLength piece_length(const Section& sec, const Piece& pc) {
  PieceLength L;
  for (int k = 0; k < PieceLength::panels; ++k)
    L.cum[k + 1] = L.cum[k] + gauss(double(k) / PieceLength::panels, double(k + 1) / PieceLength::panels,
                                    PieceSpeed{sec, pc});
  return L;
}

}  // namespace section::detail::gen
