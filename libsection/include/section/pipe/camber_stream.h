// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file pipe/camber_stream.h
/// The camber stage on the stream: splines -> tables "camber", "params", "thickness", "sides".
#include "section/camber.h"
#include "section/checks.h"
#include "section/io/stream.h"

#include <string>
#include <utility>
#include <vector>

namespace section {

/// Stream stage: reads the closed splines (tables "splines", "spline_knots",
/// "spline_ctrl"), processes loop 0 of every section and writes the tables "camber",
/// "params", "thickness" and "sides" (docs/FORMAT.md). A section that fails, or has
/// more than one loop, gets an issue and the others go on. With
/// `options.across_sections` (the default) it then runs check_blade_stream,
/// flag_scan_layers and flag_swapped_ends on the stream and flags every row for a doubtful
/// unit or an unconfirmed registration its notes tell of, as the `camber` tool does; a
/// caller staging the parts of a split stream one by one turns it off and does the five
/// across the parts (the notes are in the first part).
void camber_stream(Stream& stream, const CamberOptions& options = {});

/// The columns of its input camber_stream never reads, only passes on (StageRun::unread):
/// the smoothed points, the measured points' normals and the skeleton's radii.
const std::vector<std::pair<std::string, std::string>>& camber_unread_columns();

/// The blade check (check_blade, section/checks.h) across the sections of the streams
/// given (the parts of one stream, or one whole stream), after camber_stream: each value
/// that jumps from its neighbouring sections sets its check's bit in the section's params
/// row (`flags`) and adds an issue (stage "camber") to the stream holding it. Heights: the
/// sections' centroids along the frames' mean normal. A check already set on a row is
/// left as it is, without a second issue: running it twice changes nothing.
void check_blade_stream(const std::vector<Stream*>& streams, const BladeCheckOptions& options = {});

/// True when the stream's notes say its input's unit is doubtful (slice's or camber's
/// `units_doubtful` note: read as mm though its extent suggests inches or micrometres).
bool units_doubtful(const Stream& stream);

/// Sets the `units` check's bit on every params row of `stream` and says so in an issue per
/// section: the input's unit is doubtful, so every length, and every value the length
/// defaults shaped, may be misscaled. Rows flagged before are left as they are.
void flag_doubtful_units(Stream& stream);

/// True when the stream's notes say a view merged into its input was registered but not
/// confirmed (slice --view: a `register` note ending in `unconfirmed=1`, docs/REGISTRATION.md).
bool registration_unconfirmed(const Stream& stream);

/// Sets the `registration` check's bit on every params row of `stream` and says so in an
/// issue per section: a view's points, merged into the sections, may lie slid and turned.
/// Rows flagged before are left as they are.
void flag_unconfirmed_registration(Stream& stream);

/// Views merged with a misregistration shift every section alike, but a section shows the
/// two layers (check `layers`, fitspline's `layers` column) only where its views overlap
/// closely enough to tell them apart. When at least two, and at least half, of the
/// sections of the streams given (the parts of one stream, or one whole stream; sections
/// flagged `airfoil` left out) show layers, every other section is flagged `layers` too,
/// with an issue saying so. Returns the number of sections newly flagged.
int flag_scan_layers(const std::vector<Stream*>& parts);

/// The sections of one blade have their leading edges at the same end. A section whose
/// chord (its LE point to its TE point, in 3D) runs over 90 degrees from the mean of the
/// sections' chords, where such sections are at most a third of 3 or more (sections flagged
/// `airfoil` left out), has its ends swapped: its params and thickness rows are flagged
/// `le_choice`, with an issue saying so. Returns the number of sections newly flagged.
int flag_swapped_ends(const std::vector<Stream*>& parts);

/// A stream holding one section (id 0) whose profile (loop 0) is `spline`, in the tables
/// "splines", "spline_knots" and "spline_ctrl": the input of camber_stream for a plain
/// profile (an airfoil .dat file, a CMM section). With `measured` (the profile's points),
/// also the table "points": camber_stream then checks the values against the points as it
/// does a scan's (their own scatter, the edges refitted to them, holes at the edges).
Stream profile_stream(const BSpline& spline, double rms = 0,
                      const std::vector<Eigen::Vector2d>& measured = {});

}  // namespace section
