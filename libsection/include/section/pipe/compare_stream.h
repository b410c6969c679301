// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file pipe/compare_stream.h
/// The compare stage on the stream (docs/COMPARE.md): each section of a measured stream
/// (through camber) against its nominal, matched by plane: tables "fits", "deviations",
/// "zones", "compared" and "verdicts". The nominal comes as a mesh (sliced on the measured
/// planes), a stream (its sections matched by plane) or sections of points; it gets its
/// spline and its camber and params from the same code as the measurement
/// (fit_spline_stream, camber_stream).
#include "section/camber.h"
#include "section/compare.h"
#include "section/fit_spline.h"
#include "section/frame.h"
#include "section/io/stream.h"
#include "section/mesh.h"
#include "section/units.h"

#include <map>
#include <string>
#include <vector>

namespace section {

/// Options of nominal_stream and compare_stream.
struct CompareStreamOptions {
  CompareOptions compare;             ///< the fit, zones, holes and outliers
  std::vector<Tolerance> tolerances;  ///< the values' tolerances (io/tolerances.h reads them)
  /// How a value's uncertainty (the params' standard errors, `<column>_sigma`) enters its
  /// verdict; a value camber flagged is uncertain under either rule.
  DecisionRule decision = DecisionRule::guarded;
  double coverage = 2;            ///< the expanded uncertainty U = coverage x the standard error
  bool whole = false;             ///< one motion for every section (compare_blade)
  CamberOptions camber;           ///< the nominal's camber line and params
  FitSplineOptions fit_spline;    ///< the nominal's spline (mesh sections, points)
  double plane_tolerance = 1e-3;  ///< length: a nominal section or point this near a measured plane is on it
  int threads = 0;                ///< worker threads over the sections; 0 = all cores
};

/// A nominal blade: one of these.
struct NominalSource {
  const Mesh* mesh = nullptr;      ///< a closed mesh, sliced on each measured plane
  const Stream* stream = nullptr;  ///< a stream through fitspline (or camber): sections matched by plane
  /// Points along each section's profile, in order: columns section, u, v (in the measured
  /// frames, by section id) or x, y, z (each point on the measured plane it lies on).
  const Table* points = nullptr;
  std::string name;  ///< the nominal's file, for messages
};

/// Converts a nominal mesh or table of points (columns x, y, z or u, v) given in `unit` to
/// mm in place (the stream's unit); `unit` "" takes it from the nominal's extent as
/// input_units does (under 1 across: metres, with a warning). Returns how the unit was taken:
/// its `warning` says what to check (the option named `--nominal-units`). Throws
/// section::Error for an unknown unit.
InputUnits nominal_to_mm(Mesh* mesh, Table* points, const std::string& unit);

/// The nominal of each measured section (`frames`, by id), in its frame and under its id:
/// the tables "frames", "points" (mesh, points), "splines", "spline_knots", "spline_ctrl"
/// and camber_stream's tables. A section without a nominal gets an issue (stage "compare").
/// `frames` are in mm (those of a stream after convert_to_mm); a nominal stream in another
/// unit is read as converted to mm, a mesh or points are taken as in mm (nominal_to_mm).
/// Throws section::Error on a nominal that cannot be used at all (no section matches, a
/// table without the columns needed).
Stream nominal_stream(const NominalSource& source, const std::map<int, Frame>& frames,
                      const CompareStreamOptions& options = {});

/// Compares every section of `stream` (loop 0 of its "points" table, else its spline; its
/// "params") with `nominal` (from nominal_stream) and writes the tables "fits",
/// "deviations", "zones", "compared" and "verdicts" (docs/FORMAT.md). A section that fails
/// gets an issue and every toleranced value of it is not measured; the others go on.
/// `stream` is converted to mm first (convert_to_mm: the options and tolerances are in mm),
/// `nominal` read as converted; throws section::Error when the nominal was made on frames
/// other than the stream's (farther than `plane_tolerance`: frames given in another unit).
void compare_stream(Stream& stream, const Stream& nominal, const CompareStreamOptions& options = {});

/// For each section a tolerance row names (not every section's `*` row) that `compared` has no
/// verdict for (compare_stream's tables over the whole blade, as the compare tool gathers its
/// parts): its rows in "zones", "compared" and "verdicts" with every toleranced value not
/// measured, and an issue naming the tolerance row. A tolerance that judges nothing is not
/// left silent (a section id mistyped, or a plane not sliced).
void judge_absent_sections(Stream& compared, const CompareStreamOptions& options);

/// The values compare_stream compares (the "compared" table's item codes, in order): params
/// columns, then fit_shift and fit_rotation.
const std::vector<std::string>& compared_items();

/// Every item a tolerance may name: the compared values, and per zone ("", "_le", "_te",
/// "_pressure", "_suction") `profile` (the deviations) and `form`.
std::vector<std::string> tolerance_items();

/// The stream's worst verdict over the "verdicts" table: 1 when a value failed, else 2 when
/// one was not measured, else 3 when one was uncertain, else 0 (also without a verdict).
int stream_verdict(const Stream& stream);

}  // namespace section
