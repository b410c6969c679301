// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What camber_stream says of a section beside its rows: where the other loops of a refused
// section lie, and the issues of a measured one (edges not round, not measured, measured
// with carried points or not circular; a thickest circle over a hole in the data; a camber
// line off the medial axis; an LE chosen by a near tie), with the coverage they rest on.
#include "detail/piecewise_curve.h"
#include "detail/coverage.h"
#include "section/bspline.h"
#include "section/camber.h"
#include "section/checks.h"
#include "section/io/stream.h"
#include "section/params.h"

#include <Eigen/Core>

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace section::pipe {

// The measured points' coverage of the profile (detail/coverage.h: camber's end fits use it
// too), as the checks below name it.
using detail::ContactCoverage;
using detail::edge_coverage;
using detail::edge_size;
using detail::EdgeCoverage;
using detail::ProfileCoverage;
using detail::unmeasured;

/// A section's loop-0 measured points (table points): all, and apart those the slab held
/// itself (offset 0: not carried onto the plane by the gap fill) and the carried ones with
/// their signed offset (the side of the plane each came from).
struct Measured {
  std::vector<Eigen::Vector2d> all, in_slab, carried;
  std::vector<double> carried_offset;
};

/// Fewer measured points than 16 a coefficient of the fit: it may follow their noise, and
/// its rms hide it (the noise check then takes the points' own scatter).
inline bool few_points(std::size_t points, std::size_t coefficients) {
  return points < 16 * coefficients;
}

/// Sets `check` on every params row of `stream` (camber's), with an issue (stage "camber")
/// per section saying `why`, and on every row of its thickness, walls (each wall's flags)
/// and wall_map tables where the check flags them (checks_flagging: "thickness", "wall"):
/// a check of a row's values, the stations measured along its camber line and a hollow
/// blade's walls. A row that has the check already keeps it, without a second issue.
void flag_every_row(Stream& stream, Check check, const std::string& why);

/// The same for the rows of one section (`section >= 0`); true when its params row did
/// not have the check (its issue was said now).
bool flag_section(Stream& stream, int section, Check check, const std::string& why);

/// Where a section's other loops lie, for the message that refuses it ("" when it has none);
/// `listed`: the loops slice found (id -> area), those not among `curves` said unfitted.
std::string other_loops(const std::map<std::pair<int, int>, BSpline>& curves, int section,
                        const std::map<int, double>& listed = {});

/// What a measured section's issues rest on.
struct SectionFacts {
  int section;
  const BSpline& curve;
  const detail::PiecewiseCurve& fast;  ///< `curve` in its piecewise form
  const CamberResult& camber;
  const SectionParams& params;
  EdgeCoverage le, te;
  ContactCoverage thickest[2];  ///< about the thickest circle's contacts (left, right)
  ContactCoverage longest;      ///< about the longest stretch of the profile without measured points
  const Measured& measured;
  const CamberOptions& options;  ///< as the section was measured with
  /// The most the profile may be off for its values to stand: CheckOptions::accuracy of its
  /// size (0: a hole's bridge is not judged by its bend).
  double accuracy = 0;
  double value_sigmas = 3;  ///< CheckOptions::value_sigmas: the standard errors a *_noise finding counts
};

/// Appends the issues of a measured section (stage "camber", loop 0) to `issues`: its edges
/// (shape, holes, carried points, circularity), a thickest circle touching a hole in the
/// data, a camber line off the medial axis, an LE
/// chosen by a near tie, and the checks it failed (`findings`, section/checks.h). Returns
/// the flags of them all (the params table's `flags`).
CheckBits describe_issues(const SectionFacts& facts, const std::vector<Finding>& findings,
                          std::vector<SectionIssue>& issues);

/// The words of a jump across a blade's sections (check_blade), for the section's issue.
std::string jump_note(const Jump& jump);

}  // namespace section::pipe
