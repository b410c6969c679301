// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// evaluate_kinds: what score.cpp gives evaluate_kinds.cpp: the quantities scored and their
// targets, the pipe's params and stream read back, one section scored against the truth.
#include "section/extras/score.h"
#include "section/io/stream.h"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace kind_score {

// ---------------------------------------------------------------------------------------
// The quantities scored, their targets and the words that flag them.

enum Q { cam_rms, cam_max, chord, stagger, tmax, rle, rte, inlet, outlet, cam_angle, le_pt, te_pt, nq };

struct Quantity {
  const char* name;
  const char* unit;                      // of the error shown: um, %, deg
  double target;                         // dense data: issue 5's targets
  std::vector<const char*> issue_words;  // an issue naming the quantity (lower case)
  std::vector<const char*> flag_words;   // a flags token naming it
};

extern const Quantity quantities[nq];

// A sharp edge (true radius 0): the measured radius may be this large (um) on dense data.
constexpr double sharp_allowance_um = 20, sharp_allowance_sparse_um = 100;

struct Value {
  double error = 0;    // in the quantity's unit (um, %, deg); signed where it has a sign
  double limit = 0;    // |error| <= limit is within
  bool sharp = false;  // a radius whose truth is 0: error in um
};

// ---------------------------------------------------------------------------------------
// Reading what the pipe wrote.

// A CSV file as text cells (the params file: a flags column may hold words).
struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  long column(const std::string& name) const {
    const auto it = std::find(header.begin(), header.end(), name);
    return it == header.end() ? -1 : long(it - header.begin());
  }
};

std::vector<std::string> split(const std::string& line, char sep);
Csv read_csv(const std::string& path);

// What flags the values of one section: its issues' messages and its params row's flags.
struct SectionFlags {
  std::string issues;            // every issue message of the section, lower case, "; "-joined
  std::set<std::string> tokens;  // the flags cell's words
  bool row_flag = false;         // a non-zero number in the flags cell: the whole row (not decoded)
  bool names(Q q) const;         // an issue or a flag names quantity q
};

SectionFlags flags_of(const section::Stream& stream, const Csv& params, std::size_t row, int section);

// A section's frame: an in-plane direction at angle a (degrees against u) as an angle in xy.
struct Frame {
  Eigen::Vector3d origin, u, v, n;
  double xy_angle(double a) const {
    const Eigen::Vector3d d = std::cos(a * M_PI / 180) * u + std::sin(a * M_PI / 180) * v;
    return std::atan2(d.y(), d.x()) * 180 / M_PI;
  }
};

std::map<int, Frame> frames_of(const section::Stream& stream);

// The errors of one params row (lengths scaled by `mm` to mm) against the truth.
std::array<Value, nq> score_row(const Csv& params, std::size_t row, const Frame& frame,
                                const section::Stream& stream, int section, double mm,
                                const section::SectionTruth& t, bool dense);

}  // namespace kind_score
