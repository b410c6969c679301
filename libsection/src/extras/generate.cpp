// Synthetic blades with exact ground truth: see generate.h.
//
// A section is the envelope of circles r(s) on a cubic Bezier camber c(s), closed by the
// end circles' arcs. Everything is evaluated analytically (c, c', c'', r, r', r''), so
// lengths, area and centroid come from Gauss-Legendre quadrature of exact derivatives and
// profile points are placed at exact arc lengths by Newton inversion.
#include "section/extras/generate.h"

#include "section/error.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <thread>

namespace section {

namespace detail {
namespace gen {  // plain data shared by the search index and the generator

using Eigen::Vector2d;

struct Geometry {
  std::array<Vector2d, 4> b;  // Bezier control points of c(s)
  double rl = 1, rt = 1;      // r(0), r(1)
  double R = 1, sm = 0.5;     // max r and its s
  double beta_l = 0, beta_r = 0;  // shape parameters of the two thickness branches
};

struct Piece {
  enum Kind { arc, side } kind = arc;
  double t0 = 0, t1 = 0;   // angle range (arc, radians) or s range (side)
  int sign = 0, branch = 0;  // side only
  Vector2d center{0, 0};   // arc only
  double radius = 0;       // arc only
};

struct Section {
  Geometry g;
  std::array<Piece, 7> pieces;
};

}  // namespace gen

/// Bounding-box tree over consecutive runs of a polyline's segments (the curve is
/// spatially coherent, so index ranges make tight boxes): nearest-segment queries in
/// O(log n) for points near or far.
struct PolylineIndex {
  static constexpr int leaf = 8;  // segments per leaf
  std::size_t count = 0;          // number of points the index was built for
  bool closed = false;            // last point joins the first
  Eigen::Vector2d first{0, 0}, middle{0, 0};  // fingerprint: the index belongs to these points
  int leaves = 1;                 // leaf nodes are [leaves, 2 leaves)
  std::vector<Eigen::Vector2d> lo, hi;  // node boxes; node 1 is the root, children 2i, 2i+1
  // The exact profile, when the index belongs to SectionTruth::profile: where each vertex
  // lies on which piece, so locate() can refine the foot on the true curve.
  bool exact = false;
  gen::Section section;
  std::vector<int> piece;       // per vertex
  std::vector<double> lambda;   // per vertex
};

}  // namespace detail

namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;
using detail::PolylineIndex;
using detail::gen::Geometry;
using detail::gen::Piece;
using detail::gen::Section;

constexpr double pi = 3.14159265358979323846;
constexpr double deg = pi / 180;

Vector2d dir(double degrees) { return {std::cos(degrees * deg), std::sin(degrees * deg)}; }
Vector2d rot90(const Vector2d& v) { return {-v.y(), v.x()}; }
double cross(const Vector2d& a, const Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

std::string num(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}

// 10-point Gauss-Legendre on [-1, 1] (positive half; symmetric).
constexpr double gl_x[5] = {0.1488743389816312, 0.4333953941292472, 0.6794095682990244,
                            0.8650633666889845, 0.9739065285171717};
constexpr double gl_w[5] = {0.2955242247147529, 0.2692667193099963, 0.2190863625159820,
                            0.1494513491505806, 0.0666713443086881};

// 5-point rule, for the short steps between neighbouring samples.
constexpr double gl5_x[3] = {0.0, 0.5384693101056831, 0.9061798459386640};
constexpr double gl5_w[3] = {0.5688888888888889, 0.4786286704993665, 0.2369268850561891};

template <class F>
double gauss5(double a, double b, const F& f) {
  const double m = 0.5 * (a + b), h = 0.5 * (b - a);
  double sum = gl5_w[0] * f(m);
  for (int i = 1; i < 3; ++i) sum += gl5_w[i] * (f(m - h * gl5_x[i]) + f(m + h * gl5_x[i]));
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

template <class F>
double gauss(double a, double b, const F& f) {
  const double m = 0.5 * (a + b), h = 0.5 * (b - a);
  double sum = 0;
  for (int i = 0; i < 5; ++i) sum += gl_w[i] * (f(m - h * gl_x[i]) + f(m + h * gl_x[i]));
  return sum * h;
}

// ---------------------------------------------------------------------------------------
// Section geometry: camber Bezier + two-branch thickness law.

// Thickness branch f(t) = 1 - (1-t)^2 - beta t (1-t)^2: f(0) = 0, f(1) = 1, f'(1) = 0,
// f'(0) = 2 - beta, f''(1) = -2 - 2 beta; monotone for beta in (-1, 2).
void branch_f(double t, double beta, double& f, double& f1, double& f2) {
  const double w = 1 - t;
  f = 1 - w * w - beta * t * w * w;
  f1 = w * (2 - beta * (1 - 3 * t));
  f2 = -2 + 4 * beta - 6 * beta * t;
}

/// r(s) and its derivatives on a branch (0: s <= sm, 1: s >= sm); each branch is a
/// polynomial, so evaluating it slightly outside its range is harmless.
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
  const double handle = theta > 1e-6 ? d.chord * (2.0 / 3.0) * std::tan(theta / 4) / std::sin(theta / 2)
                                      : d.chord / 3;
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

/// A point of the envelope side `sign` (+1: left of c, -1: right of c) at s.
struct SideEval {
  Vector2d p, dp, u;  // point, d/ds, outward unit normal
  double rho = 0, w = 0;  // r'/|c'|; signed speed along the counterclockwise direction
};

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

// ---------------------------------------------------------------------------------------
// The closed profile as 7 pieces, counterclockwise from the LE point.

struct PieceEval {
  Vector2d p, dp, normal;  // point, d/dlambda, outward unit normal
};

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
    Piece p;
    p.kind = Piece::arc;
    p.center = c;
    p.radius = rad;
    p.t0 = a0;
    p.t1 = a1;
    return p;
  };
  auto side = [](int sign, int branch, double s0, double s1) {
    Piece p;
    p.kind = Piece::side;
    p.sign = sign;
    p.branch = branch;
    p.t0 = s0;
    p.t1 = s1;
    return p;
  };
  const double a0 = std::acos(rho0), a1 = std::acos(-rho1);
  sec.pieces = {arc(c0, g.rl, phi0 + pi, phi0 + pi + a0),  // LE point -> right side
                side(-1, 0, 0, g.sm),
                side(-1, 1, g.sm, 1),
                arc(c1, g.rt, phi1 - a1, phi1 + a1),       // around the TE point
                side(+1, 1, 1, g.sm),
                side(+1, 0, g.sm, 0),
                arc(c0, g.rl, phi0 + pi - a0, phi0 + pi)};  // left side -> LE point
  return sec;
}

/// Throws section::Error unless the design gives a valid envelope whose medial axis is c(s).
void check_design(const SectionDesign& d, const std::string& who) {
  const double vals[] = {d.chord, d.stagger, d.inlet_angle, d.outlet_angle, d.le_radius,
                         d.te_radius, d.max_thickness, d.max_thickness_pos, d.offset.x(), d.offset.y()};
  for (double v : vals)
    if (!std::isfinite(v)) throw Error(who + ": the section design has a non-finite parameter");
  if (d.chord <= 0) throw Error(who + ": chord " + num(d.chord) + " must be positive");
  if (d.le_radius <= 0 || d.te_radius <= 0)
    throw Error(who + ": edge radii must be positive (le " + num(d.le_radius) + ", te " +
                num(d.te_radius) + ")");
  if (d.le_radius >= d.max_thickness / 2 || d.te_radius >= d.max_thickness / 2)
    throw Error(who + ": edge radii (le " + num(d.le_radius) + ", te " + num(d.te_radius) +
                ") must be below max_thickness/2 = " + num(d.max_thickness / 2));
  if (!(d.max_thickness_pos > 0.02 && d.max_thickness_pos < 0.98))
    throw Error(who + ": max_thickness_pos " + num(d.max_thickness_pos) + " must be in (0.02, 0.98)");
  if (std::abs(d.inlet_angle - d.outlet_angle) >= 170)
    throw Error(who + ": turning |inlet - outlet| must be below 170 degrees");
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
          throw Error(who + ": the " + std::string(sign > 0 ? "left" : "right") +
                      " side folds at s = " + num(s) +
                      ": the inscribed circle is wider than the side's curvature allows");
      }
    }
}

// Arc-length inversion within one piece: panels with cumulative lengths, Newton inside.
struct PieceLength {
  static constexpr int panels = 24;
  std::array<double, panels + 1> cum{};
};

PieceLength piece_length(const Section& sec, const Piece& pc) {
  PieceLength L;
  for (int k = 0; k < PieceLength::panels; ++k)
    L.cum[k + 1] = L.cum[k] + gauss(double(k) / PieceLength::panels, double(k + 1) / PieceLength::panels,
                                    [&](double l) { return piece_eval(sec, pc, l).dp.norm(); });
  return L;
}

/// Walks along one piece to increasing arc lengths, reusing the previous sample as the
/// start of the next integration.
struct PieceWalker {
  const Section& sec;
  const Piece& pc;
  const PieceLength& L;
  int panel = -1;
  double lam_prev = 0, a_prev = 0;

  double operator()(double a) {
    const double total = L.cum.back();
    if (a <= 0) return 0;
    if (a >= total) return 1;
    if (pc.kind == Piece::arc) return a / total;
    int k = int(std::upper_bound(L.cum.begin(), L.cum.end(), a) - L.cum.begin()) - 1;
    k = std::clamp(k, 0, PieceLength::panels - 1);
    const double l0 = double(k) / PieceLength::panels, l1 = double(k + 1) / PieceLength::panels;
    if (k != panel || a < a_prev) {
      panel = k;
      lam_prev = l0;
      a_prev = L.cum[k];
    }
    auto speed = [&](double l) { return piece_eval(sec, pc, l).dp.norm(); };
    const double lam = advance(speed, lam_prev, a_prev, a, l0 - 1e-3, l1 + 1e-3);
    lam_prev = lam;
    a_prev = a;
    return std::clamp(lam, 0.0, 1.0);
  }
};

// ---------------------------------------------------------------------------------------
// Polyline search grid.

std::shared_ptr<const PolylineIndex> build_index(const std::vector<Vector2d>& pts, bool closed) {
  auto idx = std::make_shared<PolylineIndex>();
  const std::size_t n = pts.size();
  idx->count = n;
  idx->closed = closed;
  if (n == 0) return idx;
  idx->first = pts.front();
  idx->middle = pts[n / 2];
  const std::size_t nseg = closed ? n : n - 1;
  const std::size_t nleaf = std::max<std::size_t>(1, (nseg + PolylineIndex::leaf - 1) / PolylineIndex::leaf);
  int leaves = 1;
  while (std::size_t(leaves) < nleaf) leaves *= 2;
  idx->leaves = leaves;
  const double inf = std::numeric_limits<double>::infinity();
  idx->lo.assign(std::size_t(2 * leaves), Vector2d(inf, inf));
  idx->hi.assign(std::size_t(2 * leaves), Vector2d(-inf, -inf));
  for (std::size_t i = 0; i < nseg; ++i) {
    const std::size_t node = std::size_t(leaves) + i / PolylineIndex::leaf;
    for (const Vector2d& p : {pts[i], pts[(i + 1) % n]}) {
      idx->lo[node] = idx->lo[node].cwiseMin(p);
      idx->hi[node] = idx->hi[node].cwiseMax(p);
    }
  }
  for (int node = leaves - 1; node >= 1; --node) {
    idx->lo[std::size_t(node)] = idx->lo[std::size_t(2 * node)].cwiseMin(idx->lo[std::size_t(2 * node + 1)]);
    idx->hi[std::size_t(node)] = idx->hi[std::size_t(2 * node)].cwiseMax(idx->hi[std::size_t(2 * node + 1)]);
  }
  return idx;
}

struct Nearest {
  std::size_t segment = 0;
  double t = 0, d2 = std::numeric_limits<double>::infinity();
};

void test_segment(const std::vector<Vector2d>& pts, std::size_t i, const Vector2d& q, Nearest& best) {
  const Vector2d& a = pts[i];
  const Vector2d& b = pts[(i + 1) % pts.size()];
  const Vector2d ab = b - a;
  const double l2 = ab.squaredNorm();
  const double t = l2 > 0 ? std::clamp((q - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  const double d2 = (a + t * ab - q).squaredNorm();
  if (d2 < best.d2) best = {i, t, d2};
}

Nearest nearest(const std::vector<Vector2d>& pts, bool closed, const PolylineIndex* idx,
                const Vector2d& q) {
  Nearest best;
  const std::size_t n = pts.size();
  if (n == 0) return best;
  if (n == 1) return {0, 0, (pts[0] - q).squaredNorm()};
  const std::size_t nseg = closed ? n : n - 1;
  if (!idx || idx->count != n || idx->closed != closed || idx->first != pts.front() ||
      idx->middle != pts[n / 2]) {
    for (std::size_t i = 0; i < nseg; ++i) test_segment(pts, i, q, best);
    return best;
  }
  auto box_d2 = [&](int node) {
    const Vector2d& lo = idx->lo[std::size_t(node)];
    const Vector2d& hi = idx->hi[std::size_t(node)];
    const double dx = std::max({lo.x() - q.x(), 0.0, q.x() - hi.x()});
    const double dy = std::max({lo.y() - q.y(), 0.0, q.y() - hi.y()});
    return dx * dx + dy * dy;
  };
  int stack[64];
  int top = 0;
  stack[top++] = 1;
  while (top > 0) {
    const int node = stack[--top];
    if (box_d2(node) >= best.d2) continue;
    if (node >= idx->leaves) {
      const std::size_t i0 = std::size_t(node - idx->leaves) * PolylineIndex::leaf;
      const std::size_t i1 = std::min(nseg, i0 + PolylineIndex::leaf);
      for (std::size_t i = i0; i < i1; ++i) test_segment(pts, i, q, best);
    } else {
      const int l = 2 * node, r = 2 * node + 1;
      // Box distance, ties (query inside both boxes) broken by distance to the box centre.
      auto key = [&](int c) {
        const double d = box_d2(c);
        return d > 0 ? d : -1.0 / (1.0 + (0.5 * (idx->lo[std::size_t(c)] + idx->hi[std::size_t(c)]) - q).squaredNorm());
      };
      const double dl = key(l), dr = key(r);
      // nearer child on top of the stack
      if (dl < dr) {
        stack[top++] = r;
        stack[top++] = l;
      } else {
        stack[top++] = l;
        stack[top++] = r;
      }
    }
  }
  return best;
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Designs.

SectionDesign BladeDesign::at(double z) const {
  const double t = span > 0 ? std::clamp(z / span, 0.0, 1.0) : 0.0;
  const double w = t * t * (3 - 2 * t);  // smoothstep: parameters flat at hub and tip
  auto mix = [w](double a, double b) { return a + w * (b - a); };
  SectionDesign d;
  d.chord = mix(hub.chord, tip.chord);
  d.stagger = mix(hub.stagger, tip.stagger);
  d.inlet_angle = mix(hub.inlet_angle, tip.inlet_angle);
  d.outlet_angle = mix(hub.outlet_angle, tip.outlet_angle);
  d.le_radius = mix(hub.le_radius, tip.le_radius);
  d.te_radius = mix(hub.te_radius, tip.te_radius);
  d.max_thickness = mix(hub.max_thickness, tip.max_thickness);
  d.max_thickness_pos = mix(hub.max_thickness_pos, tip.max_thickness_pos);
  d.offset = hub.offset + w * (tip.offset - hub.offset);
  return d;
}

namespace {
// Centre the chord line on the z axis.
SectionDesign centred(SectionDesign d) {
  d.offset = -0.5 * d.chord * dir(d.stagger);
  return d;
}
}  // namespace

BladeDesign turbine_blade() {
  BladeDesign b;
  b.hub.chord = 40;
  b.hub.stagger = -10;
  b.hub.inlet_angle = 45;
  b.hub.outlet_angle = -65;
  b.hub.le_radius = 2.0;
  b.hub.te_radius = 0.5;
  b.hub.max_thickness = 8;
  b.hub.max_thickness_pos = 0.3;
  b.tip = b.hub;
  b.tip.chord = 38;
  b.tip.stagger = -14;  // 4 degrees of twist
  b.tip.inlet_angle = 40;
  b.tip.outlet_angle = -68;
  b.tip.le_radius = 1.8;
  b.tip.te_radius = 0.45;
  b.tip.max_thickness = 7;
  b.tip.max_thickness_pos = 0.32;
  b.hub = centred(b.hub);
  b.tip = centred(b.tip);
  b.span = 60;
  return b;
}

BladeDesign compressor_blade() {
  BladeDesign b;
  b.hub.chord = 40;
  b.hub.stagger = 30;
  b.hub.inlet_angle = 45;
  b.hub.outlet_angle = 15;
  b.hub.le_radius = 0.3;
  b.hub.te_radius = 0.25;
  b.hub.max_thickness = 2.5;
  b.hub.max_thickness_pos = 0.4;
  b.tip = b.hub;
  b.tip.chord = 42;
  b.tip.stagger = 36;  // 6 degrees of twist
  b.tip.inlet_angle = 52;
  b.tip.outlet_angle = 22;
  b.tip.le_radius = 0.28;
  b.tip.te_radius = 0.22;
  b.tip.max_thickness = 2.0;
  b.tip.max_thickness_pos = 0.42;
  b.hub = centred(b.hub);
  b.tip = centred(b.tip);
  b.span = 60;
  return b;
}

std::vector<SectionDesign> design_family() {
  std::vector<SectionDesign> out;
  out.push_back(SectionDesign{});
  out.push_back(turbine_blade().at(0));
  out.push_back(compressor_blade().at(60));
  SectionDesign d;
  d.chord = 30;
  d.stagger = -20;
  d.inlet_angle = 5;
  d.outlet_angle = -15;
  d.le_radius = 0.6;
  d.te_radius = 0.15;
  d.max_thickness = 2.4;
  d.max_thickness_pos = 0.45;
  out.push_back(d);
  d = SectionDesign{};
  d.inlet_angle = 60;
  d.outlet_angle = -55;
  d.le_radius = 2.5;
  d.te_radius = 0.8;
  d.max_thickness = 9;
  d.max_thickness_pos = 0.3;
  out.push_back(d);
  return out;
}

// ---------------------------------------------------------------------------------------
// Truth.

SectionTruth section_truth(const SectionDesign& design, int samples) {
  if (samples < 16) throw Error("section_truth: samples " + std::to_string(samples) + " must be at least 16");
  check_design(design, "section_truth");
  const Section sec = make_section(design);
  const Geometry& g = sec.g;
  SectionTruth t;

  // Profile lengths and exact arc-length sampling.
  std::array<PieceLength, 7> len;
  std::array<double, 8> cum{};
  for (int i = 0; i < 7; ++i) {
    len[i] = piece_length(sec, sec.pieces[i]);
    cum[i + 1] = cum[i] + len[i].cum.back();
  }
  t.perimeter = cum[7];
  t.te_s = cum[3] + 0.5 * len[3].cum.back();
  const std::size_t n = std::size_t(samples);
  t.profile.resize(n);
  t.profile_s.resize(n);
  t.profile_normal.resize(n);
  std::vector<int> vpiece(n);
  std::vector<double> vlambda(n);
  int piece = 0;
  std::vector<PieceWalker> walkers;
  for (int i = 0; i < 7; ++i) walkers.push_back(PieceWalker{sec, sec.pieces[i], len[i]});
  for (std::size_t j = 0; j < n; ++j) {
    const double a = t.perimeter * double(j) / double(n);
    while (piece < 6 && a >= cum[piece + 1]) ++piece;
    const Piece& pc = sec.pieces[piece];
    const double lam = walkers[piece](a - cum[piece]);
    const PieceEval e = piece_eval(sec, pc, lam);
    vpiece[j] = piece;
    vlambda[j] = lam;
    t.profile[j] = e.p;
    t.profile_normal[j] = e.normal;
    t.profile_s[j] = a;
  }

  // Area and centroid by Green's theorem on the exact pieces (relative to c(0) to avoid
  // cancellation).
  Vector2d c0, c1, d0, d1, dd;
  camber_eval(g, 0, c0, d0, dd);
  camber_eval(g, 1, c1, d1, dd);
  double area = 0, mx = 0, my = 0;
  for (const Piece& pc : sec.pieces)
    for (int k = 0; k < 64; ++k) {
      const double l0 = k / 64.0, l1 = (k + 1) / 64.0;
      area += gauss(l0, l1, [&](double l) {
        const PieceEval e = piece_eval(sec, pc, l);
        const Vector2d p = e.p - c0;
        return 0.5 * cross(p, e.dp);
      });
      mx += gauss(l0, l1, [&](double l) {
        const PieceEval e = piece_eval(sec, pc, l);
        const double x = e.p.x() - c0.x();
        return 0.5 * x * x * e.dp.y();
      });
      my += gauss(l0, l1, [&](double l) {
        const PieceEval e = piece_eval(sec, pc, l);
        const double y = e.p.y() - c0.y();
        return -0.5 * y * y * e.dp.x();
      });
    }
  t.area = area;
  t.centroid = c0 + Vector2d(mx, my) / area;

  // Edges.
  const Vector2d T0 = d0.normalized(), T1 = d1.normalized();
  t.le_center = c0;
  t.te_center = c1;
  t.le_radius = g.rl;
  t.te_radius = g.rt;
  t.le_point = c0 - g.rl * T0;
  t.te_point = c1 + g.rt * T1;
  t.chord = (t.te_point - t.le_point).norm();
  const Vector2d ch = t.te_point - t.le_point;
  t.stagger = std::atan2(ch.y(), ch.x()) / deg;
  t.inlet_angle = std::atan2(T0.y(), T0.x()) / deg;
  t.outlet_angle = std::atan2(T1.y(), T1.x()) / deg;

  // Camber line: [LE point, c(0)] + c(s) + [c(1), TE point], exact arc-length sampling.
  auto speed = [&](double s) {
    Vector2d c, e1, e2;
    camber_eval(g, s, c, e1, e2);
    return e1.norm();
  };
  constexpr int cpanels = 64;
  std::array<double, cpanels + 1> ccum{};
  for (int k = 0; k < cpanels; ++k) ccum[k + 1] = ccum[k] + gauss(double(k) / cpanels, double(k + 1) / cpanels, speed);
  const double lbez = ccum.back();
  double l_sm = 0;  // camber length from c(0) to c(sm)
  {
    const int k = std::min(cpanels - 1, int(g.sm * cpanels));
    l_sm = ccum[k] + gauss(double(k) / cpanels, g.sm, speed);
  }
  t.camber_length = g.rl + lbez + g.rt;
  t.max_thickness = 2 * g.R;
  t.max_thickness_pos = (g.rl + l_sm) / t.camber_length;
  const std::size_t nc = std::max<std::size_t>(n / 2, 8);
  t.camber.resize(nc);
  t.camber_radius.resize(nc);
  t.camber_s.resize(nc);
  t.camber_begin = nc;
  t.camber_end = nc;
  int cpanel = -1;
  double s_prev = 0, b_prev = 0;
  for (std::size_t j = 0; j < nc; ++j) {
    const double a = t.camber_length * double(j) / double(nc - 1);
    t.camber_s[j] = a;
    if (a < g.rl) {
      t.camber[j] = t.le_point + a * T0;
      t.camber_radius[j] = g.rl;
    } else if (a <= g.rl + lbez) {
      if (t.camber_begin == nc) t.camber_begin = j;
      t.camber_end = j + 1;
      const double b = a - g.rl;
      int k = int(std::upper_bound(ccum.begin(), ccum.end(), b) - ccum.begin()) - 1;
      k = std::clamp(k, 0, cpanels - 1);
      if (k != cpanel || b < b_prev) {
        cpanel = k;
        s_prev = double(k) / cpanels;
        b_prev = ccum[k];
      }
      double s = advance(speed, s_prev, b_prev, b, double(k) / cpanels - 1e-3, double(k + 1) / cpanels + 1e-3);
      s_prev = s;
      b_prev = b;
      s = std::clamp(s, 0.0, 1.0);
      Vector2d c, e1, e2;
      camber_eval(g, s, c, e1, e2);
      double r, r1, r2;
      thickness(g, s, s <= g.sm ? 0 : 1, r, r1, r2);
      t.camber[j] = c;
      t.camber_radius[j] = r;
    } else {
      t.camber[j] = c1 + (a - g.rl - lbez) * T1;
      t.camber_radius[j] = g.rt;
    }
  }
  t.camber.back() = t.te_point;
  t.camber_radius.back() = g.rt;
  {
    auto idx = std::const_pointer_cast<PolylineIndex>(build_index(t.profile, true));
    idx->exact = true;
    idx->section = sec;
    idx->piece = std::move(vpiece);
    idx->lambda = std::move(vlambda);
    t.profile_index = idx;
  }
  t.camber_index = build_index(t.camber, false);
  return t;
}

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
  if (!idx || !idx->exact || idx->piece.size() != n || n < 3 || idx->first != pts.front() ||
      idx->middle != pts[n / 2])
    return loc;
  // The polyline's nearest segment can be off along the curve where the distance is flat
  // (a query near a centre of curvature), so walk the exact vertices downhill to the
  // nearest one, then minimise over the true curve between its neighbours.
  auto vd2 = [&](std::size_t i) { return (pts[i] - p).squaredNorm(); };
  std::size_t v = vd2(nb.segment) <= vd2((nb.segment + 1) % n) ? nb.segment : (nb.segment + 1) % n;
  for (std::size_t steps = 0; steps < n; ++steps) {
    const std::size_t l = (v + n - 1) % n, r = (v + 1) % n;
    if (vd2(l) < vd2(v) && vd2(l) <= vd2(r)) v = l;
    else if (vd2(r) < vd2(v)) v = r;
    else break;
  }
  // Curve position u in [-1, 1]: pieces and lambdas from vertex v-1 through v to v+1.
  const Section& sec = idx->section;
  struct Span {
    int piece;
    double l0, l1;
  };
  std::array<Span, 16> spans;  // the curve from vertex v-1 to v+1, piece by piece
  std::size_t nspans = 0;
  {
    const std::size_t vs[3] = {(v + n - 1) % n, v, (v + 1) % n};
    for (int q = 0; q < 2; ++q) {
      int pa = idx->piece[vs[q]], pb = idx->piece[vs[q + 1]];
      double la = idx->lambda[vs[q]], lb = idx->lambda[vs[q + 1]];
      if (vs[q + 1] == 0) pb = 7, lb = 0;  // closing segment ends at the start of piece 0 = end of piece 6
      if (pb == 7) pb = 6, lb = 1;
      for (int pc = pa; pc <= pb; ++pc) {
        const double a0 = pc == pa ? la : 0.0, a1 = pc == pb ? lb : 1.0;
        if (a1 > a0 && nspans < spans.size()) spans[nspans++] = {pc, a0, a1};
      }
    }
  }
  if (nspans == 0) return loc;
  // Golden section over the concatenated spans, parametrised by x in [0, spans.size()].
  auto eval = [&](double x) {
    const std::size_t i = std::min(nspans - 1, std::size_t(std::max(0.0, x)));
    const double f = std::clamp(x - double(i), 0.0, 1.0);
    const Span& sp = spans[i];
    PieceEval e = piece_eval(sec, sec.pieces[std::size_t(sp.piece)], sp.l0 + f * (sp.l1 - sp.l0));
    e.dp *= sp.l1 - sp.l0;
    return e;
  };
  auto curve = [&](double x) { return eval(x).p; };
  auto slope = [&](double x) {  // half the derivative of the squared distance
    const PieceEval e = eval(x);
    return (e.p - p).dot(e.dp);
  };
  // Illinois regula falsi on the slope, bracketed by the neighbouring vertices; golden
  // section first when they do not bracket a minimum.
  double lo = 0, hi = double(nspans);
  double sl = slope(lo), sh = slope(hi);
  if (!(sl < 0 && sh > 0)) {
    const double g = 0.3819660112501051;
    double x1 = lo + g * (hi - lo), x2 = hi - g * (hi - lo);
    double f1 = (curve(x1) - p).squaredNorm(), f2 = (curve(x2) - p).squaredNorm();
    for (int it = 0; it < 60 && hi - lo > 1e-12; ++it) {
      if (f1 <= f2) {
        hi = x2, x2 = x1, f2 = f1, x1 = lo + g * (hi - lo), f1 = (curve(x1) - p).squaredNorm();
      } else {
        lo = x1, x1 = x2, f1 = f2, x2 = hi - g * (hi - lo), f2 = (curve(x2) - p).squaredNorm();
      }
    }
    sl = slope(lo), sh = slope(hi);
  }
  double xm = 0.5 * (lo + hi);
  if (sl < 0 && sh > 0) {
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
  }
  const double dist = (curve(xm) - p).norm();
  if (!(dist <= 1.001 * loc.distance + 1e-6)) return loc;  // should not happen: keep the polyline answer
  loc.distance = dist;
  // Arc length: from vertex v-1 (exact profile_s) along the spans to the foot.
  double s_foot = truth.profile_s[(v + n - 1) % n];
  for (std::size_t i = 0; i < nspans && double(i) < xm; ++i) {
    const Span& sp = spans[i];
    const double f = std::min(1.0, xm - double(i));
    const Piece& pc = sec.pieces[std::size_t(sp.piece)];
    s_foot += gauss5(sp.l0, sp.l0 + f * (sp.l1 - sp.l0), [&](double l) { return piece_eval(sec, pc, l).dp.norm(); });
  }
  loc.s = s_foot >= truth.perimeter ? s_foot - truth.perimeter : s_foot;
  return loc;
}

double camber_distance(const SectionTruth& truth, const Eigen::Vector2d& p) {
  if (truth.camber.empty()) throw Error("camber_distance: the section truth has no camber line");
  return std::sqrt(nearest(truth.camber, false, truth.camber_index.get(), p).d2);
}

// ---------------------------------------------------------------------------------------
// Scan.

namespace {

std::uint64_t splitmix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// Our own transforms: std::*_distribution differ between standard libraries.
struct Rng {
  std::mt19937_64 engine;
  explicit Rng(std::uint64_t seed) : engine(splitmix(seed)) {}
  double uniform() { return double(engine() >> 11) * (1.0 / 9007199254740992.0); }  // [0, 1)
  double uniform(double a, double b) { return a + (b - a) * uniform(); }
  /// Box-Muller: a standard normal value from two uniforms in [0, 1).
  static double normal(double u1, double u2) {
    return std::sqrt(-2 * std::log(1.0 - u1)) * std::cos(2 * pi * u2);
  }
};

/// Approximate arc-length table of a section: (piece, lambda) for any arc length.
struct RowTable {
  static constexpr int per_piece = 64;
  Section sec;
  std::vector<double> cum;  // 7 * per_piece + 1 cumulative chord lengths
  double perimeter = 0, te_s = 0;

  void build(const SectionDesign& d) {
    sec = make_section(d);
    cum.assign(7 * per_piece + 1, 0);
    Vector2d prev = piece_eval(sec, sec.pieces[0], 0).p;
    for (int i = 0; i < 7; ++i)
      for (int k = 1; k <= per_piece; ++k) {
        const Vector2d p = piece_eval(sec, sec.pieces[i], double(k) / per_piece).p;
        cum[i * per_piece + k] = cum[i * per_piece + k - 1] + (p - prev).norm();
        prev = p;
      }
    perimeter = cum.back();
    te_s = 0.5 * (cum[3 * per_piece] + cum[4 * per_piece]);
  }
  struct Where {
    int piece;
    double lambda;
    std::size_t node;  // table node before a
    double f;          // fraction towards the next node
  };
  /// Where arc length a in [0, perimeter) lies.
  Where at(double a) const {
    std::size_t k = std::size_t(std::upper_bound(cum.begin(), cum.end(), a) - cum.begin());
    k = std::clamp<std::size_t>(k, 1, cum.size() - 1) - 1;
    const double f = std::clamp(cum[k + 1] > cum[k] ? (a - cum[k]) / (cum[k + 1] - cum[k]) : 0.0, 0.0, 1.0);
    return {int(k / per_piece), (double(k % per_piece) + f) / per_piece, k, f};
  }
};

/// For each node of `table`, the z component of the unnormalised surface normal
/// (u, -u . dp/dz), from the sections of the same table layout at zl and zh.
std::vector<double> normal_z(const RowTable& table, const Section& lo, const Section& hi, double dz) {
  std::vector<double> gz(table.cum.size());
  for (std::size_t k = 0; k < gz.size(); ++k) {
    const std::size_t piece = std::min<std::size_t>(6, k / RowTable::per_piece);
    const double lam = double(k - piece * RowTable::per_piece) / RowTable::per_piece;
    const PieceEval e = piece_eval(table.sec, table.sec.pieces[piece], lam);
    const Vector2d dpdz = (piece_eval(hi, hi.pieces[piece], lam).p - piece_eval(lo, lo.pieces[piece], lam).p) / dz;
    gz[k] = -e.normal.dot(dpdz);
  }
  return gz;
}

/// Coarse but accurate (< 2 um) distance from p to the profile of a section.
double coarse_distance(const Section& sec, const Vector2d& p) {
  constexpr int m = 128;
  double best = std::numeric_limits<double>::infinity();
  Vector2d prev = piece_eval(sec, sec.pieces[0], 0).p;
  for (const Piece& pc : sec.pieces)
    for (int k = 1; k <= m; ++k) {
      const Vector2d q = piece_eval(sec, pc, double(k) / m).p;
      const Vector2d ab = q - prev;
      const double l2 = ab.squaredNorm();
      const double t = l2 > 0 ? std::clamp((p - prev).dot(ab) / l2, 0.0, 1.0) : 0.0;
      best = std::min(best, (prev + t * ab - p).squaredNorm());
      prev = q;
    }
  return std::sqrt(best);
}

struct Hole {
  double sigma, z, radius;  // position as a fraction of the perimeter, height, radius (mm)
};

struct Field {  // smooth keep-probability in [density_min, 1]
  double dmin = 1;
  int m1 = 1, m2 = 2;
  double k1 = 0, k2 = 0, f1 = 0, f2 = 0;
  double operator()(double sigma, double z) const {
    const double f = 0.5 + 0.25 * (std::cos(2 * pi * m1 * sigma + k1 * z + f1) +
                                   std::cos(2 * pi * m2 * sigma + k2 * z + f2));
    return dmin + (1 - dmin) * f;
  }
};

struct RowOutput {
  std::vector<Vector3d> points;
  std::vector<std::uint8_t> outlier;
};

}  // namespace

ScanOptions inspection_scan() {
  ScanOptions o;
  o.spacing = 0.08;
  o.noise = 0.005;
  o.holes = 5;
  o.density_min = 0.25;
  o.outlier_fraction = 0.0002;
  return o;
}

Cloud scan_bands(const BladeDesign& blade, const std::vector<double>& heights, const ScanOptions& options,
                 double half_band) {
  Cloud cloud;
  for (double z : heights) {
    ScanOptions o = options;
    o.z_min = z - half_band;
    o.z_max = z + half_band;
    o.seed = options.seed * 100 + static_cast<std::uint64_t>(std::floor(z));
    const Scan s = generate_scan(blade, o);
    cloud.points.insert(cloud.points.end(), s.cloud.points.begin(), s.cloud.points.end());
  }
  return cloud;
}

std::vector<Cloud> views_of(const Scan& scan) {
  std::vector<Cloud> views(2);
  for (std::size_t i = 0; i < scan.cloud.points.size(); ++i)
    views[i < scan.view.size() && scan.view[i] ? 1 : 0].points.push_back(scan.cloud.points[i]);
  return views;
}

Scan generate_scan(const BladeDesign& blade, const ScanOptions& o) {
  const std::string who = "generate_scan";
  if (!(o.spacing > 0) || !std::isfinite(o.spacing)) throw Error(who + ": spacing must be positive");
  if (!(o.noise >= 0) || !std::isfinite(o.noise)) throw Error(who + ": noise must be zero or positive");
  if (o.holes < 0) throw Error(who + ": holes must be zero or positive");
  if (!(o.density_min > 0 && o.density_min <= 1)) throw Error(who + ": density_min must be in (0, 1]");
  if (!(o.misregistration >= 0) || !std::isfinite(o.misregistration))
    throw Error(who + ": misregistration must be zero or positive");
  if (!(o.outlier_fraction >= 0 && o.outlier_fraction < 1))
    throw Error(who + ": outlier_fraction must be in [0, 1)");
  if (!(blade.span > 0)) throw Error(who + ": the blade span must be positive");
  double z_lo = 0, z_hi = blade.span;
  if (o.z_max >= o.z_min) {
    z_lo = o.z_min;
    z_hi = o.z_max;
  }
  if (z_lo < 0 || z_hi > blade.span + 1e-12 || z_hi <= z_lo)
    throw Error(who + ": z range [" + num(z_lo) + ", " + num(z_hi) + "] must be a non-empty part of the span [0, " +
                num(blade.span) + "]");
  for (int i = 0; i <= 8; ++i) check_design(blade.at(z_lo + (z_hi - z_lo) * i / 8), who);

  const int rows = std::max(1, int(std::lround((z_hi - z_lo) / o.spacing)));
  const double dz = (z_hi - z_lo) / rows;
  const double mid_perimeter = [&] {
    RowTable t;
    t.build(blade.at(0.5 * (z_lo + z_hi)));
    return t.perimeter;
  }();
  const double estimate = 1.2 * rows * mid_perimeter / o.spacing;
  if (estimate > 4e8)
    throw Error(who + ": about " + num(estimate) + " points requested; increase the spacing or reduce the z range");

  // Global random features: density field, holes, outlier box, misregistration.
  Rng rng(o.seed ^ 0x5eed0001ULL);
  Field field;
  field.dmin = o.density_min;
  field.m1 = 1 + int(rng.uniform() * 2);
  field.m2 = 2 + int(rng.uniform() * 2);
  field.k1 = 2 * pi / rng.uniform(15, 40);
  field.k2 = -2 * pi / rng.uniform(15, 40);
  field.f1 = rng.uniform(0, 2 * pi);
  field.f2 = rng.uniform(0, 2 * pi);
  std::vector<Hole> holes(std::size_t(o.holes));
  for (Hole& h : holes) h = {rng.uniform(), rng.uniform(z_lo, z_hi), rng.uniform(0.25, 1.0)};
  Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (int i = 0; i <= 8; ++i) {
    RowTable t;
    t.build(blade.at(z_lo + (z_hi - z_lo) * i / 8));
    for (const Piece& pc : t.sec.pieces)
      for (int k = 0; k <= 64; ++k) {
        const Vector2d p = piece_eval(t.sec, pc, k / 64.0).p;
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
  }
  const Vector3d box_lo(lo.x() - 2, lo.y() - 2, z_lo - 2), box_hi(hi.x() + 2, hi.y() + 2, z_hi + 2);
  Vector2d shift{0, 0};  // view 1: towards the pressure (right, -N) side of the mid camber
  {
    const Geometry g = make_geometry(blade.at(0.5 * (z_lo + z_hi)));
    Vector2d c, d1, d2;
    camber_eval(g, 0.5, c, d1, d2);
    shift = -o.misregistration * rot90(d1.normalized());
  }
  const double overlap = 1.5;  // mm each side of the view boundaries at LE and TE

  const int tasks = 2 * rows;
  std::vector<RowOutput> out(static_cast<std::size_t>(tasks));
  auto run_task = [&](int task) {
    const int view = task / rows, row = task % rows;
    const double z0 = z_lo + (row + 0.5) * dz;
    RowTable table;  // arc length -> (piece, lambda) at z0
    table.build(blade.at(z0));
    const double h = std::min(0.5, 0.25 * blade.span);
    const double zl = std::max(0.0, z0 - h), zh = std::min(blade.span, z0 + h);
    const std::vector<double> gz =
        normal_z(table, make_section(blade.at(zl)), make_section(blade.at(zh)), std::max(zh - zl, 1e-12));
    // Point heights take one of `levels` values per row, each with its exact section, so
    // every point lies exactly on the blade at its height without rebuilding a section
    // per point (steps of dz/levels, far below the scanner's resolution).
    constexpr int levels = 64;
    std::vector<Section> level_sec;
    level_sec.reserve(levels);
    for (int l = 0; l < levels; ++l) level_sec.push_back(make_section(blade.at(z0 + ((l + 0.5) / levels - 0.5) * dz)));
    std::vector<const Hole*> near_holes;
    for (const Hole& hl : holes)
      if (std::abs(hl.z - z0) < hl.radius + dz) near_holes.push_back(&hl);
    const double P = table.perimeter;
    // view 1: right (pressure) side with half of each edge; view 0: the rest; overlap bands.
    const double a0 = view == 1 ? -overlap : table.te_s - overlap;
    const double a1 = view == 1 ? table.te_s + overlap : P + overlap;
    const int m = std::max(1, int(std::lround((a1 - a0) / o.spacing)));
    const double da = (a1 - a0) / m;
    Rng r(o.seed * 0x100000001b3ULL + std::uint64_t(task) * 0x9e3779b97f4a7c15ULL + 17);
    Rng rout(o.seed * 0x2545f4914f6cdd1dULL + std::uint64_t(task) * 0x9e3779b97f4a7c15ULL + 91);
    RowOutput& res = out[std::size_t(task)];
    res.points.reserve(std::size_t(m));
    for (int j = 0; j < m; ++j) {
      // Draw the same numbers for every candidate, so options change points, not the sequence.
      const double ja = r.uniform(-0.3, 0.3), jz = r.uniform();
      const double keep = r.uniform(), outl = r.uniform(), u1 = r.uniform(), u2 = r.uniform();
      double a = a0 + (j + 0.5 + ja) * da;
      a -= P * std::floor(a / P);
      const int level = std::min(levels - 1, int(jz * levels));
      const double z = z0 + ((level + 0.5) / levels - 0.5) * dz;
      const double sigma = a / P;
      if (keep >= field(sigma, z)) continue;
      bool in_hole = false;
      for (const Hole* hl : near_holes) {
        double ds = sigma - hl->sigma;
        ds -= std::round(ds);
        const double du = ds * P, dzh = z - hl->z;
        if (du * du + dzh * dzh < hl->radius * hl->radius) in_hole = true;
      }
      if (in_hole) continue;
      if (outl < o.outlier_fraction) {
        for (;;) {
          const Vector3d q(rout.uniform(box_lo.x(), box_hi.x()), rout.uniform(box_lo.y(), box_hi.y()),
                           rout.uniform(box_lo.z(), box_hi.z()));
          const Section sq = make_section(blade.at(std::clamp(q.z(), 0.0, blade.span)));
          // 0.21: the in-plane distance bounds the 3D one from below up to the surface slope.
          if (coarse_distance(sq, q.head<2>()) >= 0.21) {
            res.points.push_back(q);
            res.outlier.push_back(1);
            break;
          }
        }
        continue;
      }
      const RowTable::Where w = table.at(a);
      const Section& sec = level_sec[std::size_t(level)];
      const PieceEval e = piece_eval(sec, sec.pieces[std::size_t(w.piece)], w.lambda);
      const double nz = gz[w.node] + w.f * (gz[std::min(w.node + 1, gz.size() - 1)] - gz[w.node]);
      const Vector3d n3 = Vector3d(e.normal.x(), e.normal.y(), nz).normalized();
      Vector3d p(e.p.x(), e.p.y(), z);
      if (o.noise > 0) p += (o.noise * Rng::normal(u1, u2)) * n3;
      if (view == 1) p.head<2>() += shift;
      res.points.push_back(p);
      res.outlier.push_back(0);
    }
  };
  const unsigned hw = std::max(1u, std::min(8u, std::thread::hardware_concurrency()));
  std::atomic<int> next{0};
  auto worker = [&] {
    for (int task; (task = next.fetch_add(1)) < tasks;) run_task(task);
  };
  std::vector<std::thread> threads;
  for (unsigned i = 1; i < hw; ++i) threads.emplace_back(worker);
  worker();
  for (auto& th : threads) th.join();

  Scan scan;
  std::size_t total = 0;
  for (const RowOutput& r : out) total += r.points.size();
  scan.cloud.points.reserve(total);
  scan.outlier.reserve(total);
  scan.view.reserve(total);
  for (int task = 0; task < tasks; ++task) {
    RowOutput& r = out[std::size_t(task)];
    scan.cloud.points.insert(scan.cloud.points.end(), r.points.begin(), r.points.end());
    scan.outlier.insert(scan.outlier.end(), r.outlier.begin(), r.outlier.end());
    scan.view.insert(scan.view.end(), r.points.size(), std::uint8_t(task / rows));
    r = RowOutput{};
  }
  return scan;
}

// ---------------------------------------------------------------------------------------
// Mesh.

namespace {

/// Ear clipping of a simple counterclockwise polygon; triangles as indices into `poly`.
std::vector<std::array<int, 3>> ear_clip(const std::vector<Vector2d>& poly) {
  const int n = int(poly.size());
  std::vector<int> prev(poly.size()), next(poly.size());
  for (int i = 0; i < n; ++i) {
    prev[i] = (i + n - 1) % n;
    next[i] = (i + 1) % n;
  }
  auto area2 = [&](int a, int b, int c) { return cross(poly[b] - poly[a], poly[c] - poly[a]); };
  auto inside = [&](int a, int b, int c, int p) {  // p in the closed triangle abc (ccw)
    return area2(a, b, p) >= 0 && area2(b, c, p) >= 0 && area2(c, a, p) >= 0;
  };
  std::vector<std::array<int, 3>> tris;
  tris.reserve(poly.size());
  int remaining = n, i = 0, failures = 0;
  while (remaining > 3) {
    const int a = prev[i], c = next[i];
    bool ear = area2(a, i, c) > 0;
    if (ear)
      for (int k = next[c]; k != a; k = next[k]) {
        if (area2(prev[k], k, next[k]) > 0) continue;  // only reflex vertices can lie inside an ear
        if (inside(a, i, c, k) && poly[k] != poly[a] && poly[k] != poly[c]) {
          ear = false;
          break;
        }
      }
    if (ear || failures > remaining) {  // clip anyway on degenerate input rather than loop
      tris.push_back({a, i, c});
      next[a] = c;
      prev[c] = a;
      --remaining;
      failures = 0;
    } else {
      ++failures;
    }
    i = c;
  }
  tris.push_back({prev[i], i, next[i]});
  return tris;
}

}  // namespace

Mesh generate_mesh(const BladeDesign& blade, int profile_points, int layers) {
  if (profile_points < 16) throw Error("generate_mesh: profile_points must be at least 16");
  if (layers < 2) throw Error("generate_mesh: layers must be at least 2");
  if (!(blade.span > 0)) throw Error("generate_mesh: the blade span must be positive");
  Mesh mesh;
  const int n = profile_points;
  mesh.vertices.reserve(std::size_t(n) * std::size_t(layers));
  std::vector<Vector2d> bottom, top;
  for (int k = 0; k < layers; ++k) {
    const double z = blade.span * k / (layers - 1);
    // Equal arc-length steps from the LE point: ring vertex i matches across layers.
    const SectionTruth t = section_truth(blade.at(z), n);
    for (const Vector2d& p : t.profile) mesh.vertices.emplace_back(p.x(), p.y(), z);
    if (k == 0) bottom = t.profile;
    if (k == layers - 1) top = t.profile;
  }
  for (int k = 0; k + 1 < layers; ++k)
    for (int i = 0; i < n; ++i) {
      const int a = k * n + i, b = k * n + (i + 1) % n, c = (k + 1) * n + (i + 1) % n, d = (k + 1) * n + i;
      mesh.triangles.push_back({a, b, c});
      mesh.triangles.push_back({a, c, d});
    }
  for (const auto& tri : ear_clip(bottom)) mesh.triangles.push_back({tri[0], tri[2], tri[1]});  // faces -z
  const int off = (layers - 1) * n;
  for (const auto& tri : ear_clip(top)) mesh.triangles.push_back({off + tri[0], off + tri[1], off + tri[2]});
  return mesh;
}

}  // namespace section
