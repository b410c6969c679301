// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file extras/report.h
/// The verdicts of a compared stream as text (compare --report): the blade's verdict, then
/// each section's and each toleranced value of it.
#include <string>

namespace section {

struct Stream;

/// The report of the tables "zones", "compared" and "verdicts" (compare_stream): a first
/// line with the blade's verdict (PASS, FAIL or NOT MEASURED and the counts), then per
/// section its verdict and one line per toleranced value: the measured extremes or value,
/// the nominal and deviation, the limits and the verdict. Throws section::Error when the
/// stream has no "verdicts" table.
std::string compare_report(const Stream& stream);

}  // namespace section
