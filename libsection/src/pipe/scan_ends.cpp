// SPDX-License-Identifier: GPL-3.0-or-later
// The sections of one blade have their leading edges at the same end: a section whose LE
// lies at the other end has its ends swapped, and every value that depends on which end is
// the LE is the other end's (its LE radius the TE's). Each section chooses its LE by
// itself (thickness, bluntness, a direction given); a hole over a compressor's LE once
// made the TE the blunter end, and its LE radius came out 16-19 % off with only jump flags
// on stagger and angles, which do not cover it (evaluate_pipeline --seeds 81, 2026-12-07).
#include "pipe/camber_issues.h"
#include "section/checks.h"
#include "section/error.h"
#include "section/io/stream.h"
#include "section/pipe/camber_stream.h"
#include "section/pipe/schema.h"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace section {

namespace {

// A params row: the stream holding it, its section, its chord's direction in 3D (LE to
// TE, unit).
struct Ends {
  Stream* stream;
  int section;
  Eigen::Vector3d chord;
};

// The rows of blade sections (not `airfoil`) whose LE and TE points are known.
std::vector<Ends> blade_rows(const std::vector<Stream*>& parts) {
  std::vector<Ends> rows;
  for (Stream* s : parts) {
    const Table* params = s->find(schema::params.name);
    if (!params || params->rows() == 0) continue;
    long c[8];
    const char* names[8] = {"section", "flags", "le_x", "le_y", "le_z", "te_x", "te_y", "te_z"};
    bool all = true;
    for (int k = 0; k < 8; ++k) all = (c[k] = params->find_column(names[k])) >= 0 && all;
    if (!all) continue;
    const auto at = [&](std::size_t r, int k) { return params->at(r, std::size_t(c[k])); };
    for (std::size_t r = 0; r < params->rows(); ++r) {
      if (flags_mask(at(r, 1)) & bit(Check::airfoil)) continue;
      const Eigen::Vector3d d =
          Eigen::Vector3d(at(r, 5), at(r, 6), at(r, 7)) - Eigen::Vector3d(at(r, 2), at(r, 3), at(r, 4));
      if (!d.allFinite() || !(d.norm() > 0)) continue;
      rows.push_back({s, int(at(r, 0)), d.normalized()});
    }
  }
  return rows;
}

}  // namespace

int flag_swapped_ends(const std::vector<Stream*>& parts) {
  for (const Stream* s : parts)
    if (!s) throw Error("pipe: a stream to check is missing (a null pointer)");
  const std::vector<Ends> rows = blade_rows(parts);
  if (rows.size() < 3) return 0;  // two sections that disagree: either may be the swapped one
  // The blade's chord direction: the sections' mean. Twist turns the sections' chords by
  // tens of degrees along the span; a swapped one points over 90 degrees from the mean.
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Ends& e : rows) mean += e.chord;
  if (!(mean.norm() > 0)) return 0;
  mean.normalize();
  std::vector<const Ends*> other;
  for (const Ends& e : rows)
    if (e.chord.dot(mean) < 0) other.push_back(&e);
  if (3 * other.size() > rows.size()) return 0;  // no clear majority: the blade's LE is not known
  Eigen::Vector3d theirs = Eigen::Vector3d::Zero();
  for (const Ends& e : rows)
    if (e.chord.dot(mean) >= 0) theirs += e.chord;
  theirs.normalize();
  int flagged = 0;
  for (const Ends* e : other) {
    char text[400];
    std::snprintf(text, sizeof text,
                  "its values fail check le_choice: its leading edge lies at the other end from those of %d "
                  "of the %d sections of this blade (its chord runs %.0f deg from theirs): its ends may be "
                  "swapped, and every value that depends on which end is the LE with them; give the "
                  "leading-edge direction",
                  int(rows.size() - other.size()), int(rows.size()),
                  std::acos(std::clamp(e->chord.dot(theirs), -1.0, 1.0)) * 180 / M_PI);
    flagged += pipe::flag_section(*e->stream, e->section, Check::le_choice, text);
  }
  return flagged;
}

}  // namespace section
