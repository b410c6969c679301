// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What the generator's samplers share (scans, grids, rows; generate.h), internal to
// section_extras: a seeded random source with our own transforms, and an approximate
// arc-length table of a section that places points exactly on its pieces.
#include "generate_section.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace section::detail::gen {

/// The height range [z_lo, z_hi] of z_min, z_max (z_max < z_min: the whole span), after
/// checking it lies in the span and the designs in it are valid; errors start with `who`.
std::pair<double, double> checked_span_range(const BladeDesign& blade, double z_min, double z_max,
                                             const std::string& who);

inline std::uint64_t splitmix(std::uint64_t x) {
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

/// Approximate arc-length table of a section: (piece, lambda) for any arc length. The
/// lambda it gives is on the exact piece, so a point placed by it lies exactly on the
/// section; only its arc length is approximate (chords of 64 steps per piece).
struct ArcTable {
  static constexpr int per_piece = 64;
  Section sec;
  std::vector<double> cum;  // 7 * per_piece + 1 cumulative chord lengths
  double perimeter = 0, te_s = 0;

  explicit ArcTable(const SectionDesign& d) : sec(make_section(d)) {
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
  /// The exact point (and normal) of section `on` (a section of the same piece layout,
  /// e.g. a neighbouring height's) where arc length a lies on this table's section.
  PieceEval eval(double a, const Section& on) const {
    const Where w = at(a);
    return piece_eval(on, on.pieces[std::size_t(w.piece)], w.lambda);
  }
};

}  // namespace section::detail::gen
