// SPDX-License-Identifier: GPL-3.0-or-later
// Synthetic blades with exact ground truth (generate.h): the designs and each section's
// truth. The exact section is generate_section.h; scans, meshes and locate() have their own
// files (generate_scan.cpp, generate_mesh.cpp, generate_locate.cpp).
#include "section/extras/generate.h"

#include "generate_index.h"
#include "generate_section.h"
#include "section/error.h"

#include <random>
#include <string>

namespace section {

using namespace detail::gen;

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
  if (stacking.lean != 0 || stacking.sweep != 0 || stacking.bow != 0)  // linear in t, not smoothstep
    d.offset += Eigen::Vector2d(stacking.sweep * t, stacking.lean * t + 4 * stacking.bow * t * (1 - t));
  return d;
}

namespace {

// A design from its numbers, in the order of SectionDesign's fields (offset 0).
SectionDesign design_of(double chord, double stagger, double inlet_angle, double outlet_angle,
                        double le_radius, double te_radius, double max_thickness, double max_thickness_pos) {
  SectionDesign d;
  d.chord = chord;
  d.stagger = stagger;
  d.inlet_angle = inlet_angle;
  d.outlet_angle = outlet_angle;
  d.le_radius = le_radius;
  d.te_radius = te_radius;
  d.max_thickness = max_thickness;
  d.max_thickness_pos = max_thickness_pos;
  return d;
}

// Centre the chord line on the z axis.
SectionDesign centred(SectionDesign d) {
  d.offset = -0.5 * d.chord * dir(d.stagger);
  return d;
}

// Hub and tip centred, 60 mm apart.
BladeDesign centred_blade(const SectionDesign& hub, const SectionDesign& tip) {
  BladeDesign b;
  b.hub = centred(hub);
  b.tip = centred(tip);
  b.span = 60;
  return b;
}

}  // namespace

// design_of(chord, stagger, inlet angle, outlet angle, LE radius, TE radius, max thickness, its position)

BladeDesign turbine_blade() {
  const SectionDesign hub = design_of(40, -10, 45, -65, 2.0, 0.5, 8, 0.3);
  const SectionDesign tip = design_of(38, -14, 40, -68, 1.8, 0.45, 7, 0.32);  // 4 degrees of twist
  return centred_blade(hub, tip);
}

BladeDesign compressor_blade() {
  const SectionDesign hub = design_of(40, 30, 45, 15, 0.3, 0.25, 2.5, 0.4);
  const SectionDesign tip = design_of(42, 36, 52, 22, 0.28, 0.22, 2.0, 0.42);  // 6 degrees of twist
  return centred_blade(hub, tip);
}

BladeDesign sharp_te_blade() {
  const SectionDesign hub = design_of(36, 35, 50, 20, 0.5, 0, 3.6, 0.35);
  const SectionDesign tip = design_of(32, 42, 55, 30, 0.4, 0, 2.6, 0.38);
  return centred_blade(hub, tip);
}

BladeDesign impulse_blade() {
  // stagger 0: c(s) mirrors onto c(1 - s) about the chord's perpendicular bisector.
  const SectionDesign hub = design_of(30, 0, 60, -60, 0.8, 0.8, 7, 0.5);
  const SectionDesign tip = design_of(28, 0, 58, -58, 0.7, 0.7, 6, 0.5);
  return centred_blade(hub, tip);
}

BladeDesign thick_root_blade() {
  const SectionDesign hub = design_of(30, -20, 35, -55, 1.5, 0.2, 8.4, 0.32);
  const SectionDesign tip = design_of(34, -25, 30, -58, 0.8, 0.12, 4.4, 0.35);
  return centred_blade(hub, tip);
}

std::vector<SectionDesign> design_family() {
  return {SectionDesign{}, turbine_blade().at(0), compressor_blade().at(60),
          design_of(30, -20, 5, -15, 0.6, 0.15, 2.4, 0.45),
          design_of(40, 30, 60, -55, 2.5, 0.8, 9, 0.3)};  // SectionDesign{}'s chord and stagger, thick
}

// ---------------------------------------------------------------------------------------
// Truth.

namespace {

// The profile at n equal arc-length steps from the LE point, with the piece and lambda of
// each vertex (for locate's refinement on the exact curve).
void sample_profile(const Section& sec, std::size_t n, SectionTruth& t, std::vector<int>& vpiece,
                    std::vector<double>& vlambda) {
  std::array<PieceLength, 7> len;
  std::array<double, 8> cum{};
  for (int i = 0; i < 7; ++i) {
    len[i] = piece_length(sec, sec.pieces[i]);
    cum[i + 1] = cum[i] + len[i].cum.back();
  }
  t.perimeter = cum[7];
  t.te_s = cum[3] + 0.5 * len[3].cum.back();
  t.profile.resize(n);
  t.profile_s.resize(n);
  t.profile_normal.resize(n);
  vpiece.resize(n);
  vlambda.resize(n);
  int piece = 0;
  std::vector<PieceWalker> walkers;
  for (int i = 0; i < 7; ++i) walkers.emplace_back(sec, sec.pieces[i], len[i]);
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
}

// Area and centroid by Green's theorem on the exact pieces (relative to c(0) to avoid
// cancellation).
void area_and_centroid(const Section& sec, const Vector2d& c0, SectionTruth& t) {
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
}

// The camber curve's ends: c(0), c(1) and the unit tangents there.
struct CamberEnds {
  Vector2d c0, c1, T0, T1;
};

CamberEnds camber_ends(const Geometry& g) {
  Vector2d c0, c1, d0, d1, dd;
  camber_eval(g, 0, c0, d0, dd);
  camber_eval(g, 1, c1, d1, dd);
  return {c0, c1, d0.normalized(), d1.normalized()};
}

// Edge circles and points, chord, stagger and metal angles.
void edges(const Geometry& g, const CamberEnds& ends, SectionTruth& t) {
  const Vector2d &T0 = ends.T0, &T1 = ends.T1;
  t.le_center = ends.c0;
  t.te_center = ends.c1;
  t.le_radius = g.rl;
  t.te_radius = g.rt;
  t.le_point = ends.c0 - g.rl * T0;
  t.te_point = ends.c1 + g.rt * T1;
  t.chord = (t.te_point - t.le_point).norm();
  const Vector2d ch = t.te_point - t.le_point;
  t.stagger = std::atan2(ch.y(), ch.x()) / deg;
  t.inlet_angle = std::atan2(T0.y(), T0.x()) / deg;
  t.outlet_angle = std::atan2(T1.y(), T1.x()) / deg;
}

// |c'(s)|: what the camber curve's arc lengths integrate.
struct CamberSpeed {
  const Geometry& g;
  double operator()(double s) const {
    Vector2d c, e1, e2;
    camber_eval(g, s, c, e1, e2);
    return e1.norm();
  }
};

// The camber line [LE point, c(0)] + c(s) + [c(1), TE point] at nc equal arc-length steps,
// with the inscribed radius at each point; the camber length and max thickness position.
void sample_camber(const Geometry& g, const CamberEnds& ends, std::size_t nc, SectionTruth& t) {
  const CamberSpeed speed{g};
  constexpr int cpanels = 64;
  std::array<double, cpanels + 1> ccum{};
  for (int k = 0; k < cpanels; ++k)
    ccum[k + 1] = ccum[k] + gauss(double(k) / cpanels, double(k + 1) / cpanels, speed);
  const double lbez = ccum.back();
  const int k_sm = std::min(cpanels - 1, int(g.sm * cpanels));
  const double l_sm = ccum[k_sm] + gauss(double(k_sm) / cpanels, g.sm, speed);  // camber length c(0) to c(sm)
  t.camber_length = g.rl + lbez + g.rt;
  t.max_thickness = 2 * g.R;
  t.max_thickness_pos = (g.rl + l_sm) / t.camber_length;
  t.camber.resize(nc);
  t.camber_radius.resize(nc);
  t.camber_s.resize(nc);
  t.camber_begin = nc;
  t.camber_end = nc;
  ArcWalker<CamberSpeed> walk{ccum.data(), cpanels, speed};
  for (std::size_t j = 0; j < nc; ++j) {
    const double a = t.camber_length * double(j) / double(nc - 1);
    t.camber_s[j] = a;
    if (a < g.rl) {
      t.camber[j] = t.le_point + a * ends.T0;
      t.camber_radius[j] = g.rl;
    } else if (a <= g.rl + lbez) {
      if (t.camber_begin == nc) t.camber_begin = j;
      t.camber_end = j + 1;
      const double s = walk(a - g.rl);
      Vector2d c, e1, e2;
      camber_eval(g, s, c, e1, e2);
      double r, r1, r2;
      thickness(g, s, s <= g.sm ? 0 : 1, r, r1, r2);
      t.camber[j] = c;
      t.camber_radius[j] = r;
    } else {
      t.camber[j] = ends.c1 + (a - g.rl - lbez) * ends.T1;
      t.camber_radius[j] = g.rt;
    }
  }
  t.camber.back() = t.te_point;
  t.camber_radius.back() = g.rt;
}

}  // namespace

SectionTruth section_truth(const SectionDesign& design, int samples) {
  if (samples < 16) throw Error("section_truth: samples " + std::to_string(samples) + " must be at least 16");
  check_design(design, "section_truth");
  const Section sec = make_section(design);
  const std::size_t n = std::size_t(samples);
  SectionTruth t;
  std::vector<int> vpiece;
  std::vector<double> vlambda;
  sample_profile(sec, n, t, vpiece, vlambda);
  const CamberEnds ends = camber_ends(sec.g);
  area_and_centroid(sec, ends.c0, t);
  edges(sec.g, ends, t);
  sample_camber(sec.g, ends, std::max<std::size_t>(n / 2, 8), t);
  const auto idx = build_index(t.profile, true);
  idx->exact = true;
  idx->section = sec;
  idx->piece = std::move(vpiece);
  idx->lambda = std::move(vlambda);
  t.profile_index = idx;
  t.camber_index = build_index(t.camber, false);
  return t;
}

std::vector<Eigen::Vector2d> noisy_profile(const SectionTruth& truth, double spacing, double sigma,
                                           std::uint64_t seed, std::vector<Eigen::Vector2d>* normals) {
  if (!(spacing > 0) || !(sigma >= 0))
    throw Error("noisy_profile: spacing must be above 0 and sigma at least 0");
  std::mt19937_64 rng(seed);
  // A normal distribution needs a deviation above 0: sigma 0 draws nothing.
  std::normal_distribution<double> noise(0, sigma > 0 ? sigma : 1);
  std::vector<Eigen::Vector2d> pts;
  const int count = static_cast<int>(truth.perimeter / spacing);
  for (int i = 0; i < count; ++i) {
    const std::size_t j = static_cast<std::size_t>(i) * truth.profile.size() / std::size_t(count);
    pts.push_back(truth.profile[j] + (sigma > 0 ? noise(rng) : 0.0) * truth.profile_normal[j]);
    if (normals) normals->push_back(truth.profile_normal[j]);
  }
  return pts;
}

}  // namespace section
