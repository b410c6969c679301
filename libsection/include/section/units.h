// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file units.h
/// Length units. The stream's lengths are in mm: input in another unit is converted on
/// reading, so that every default length (stated in mm) fits the data.
#include <string>
#include <string_view>
#include <vector>

namespace section {

/// A length unit the tools read.
struct LengthUnit {
  const char* name;  ///< as given to --units: "mm", "m", "cm", "um", "in"
  double mm;         ///< millimetres in one unit
};

/// Every unit --units takes.
const std::vector<LengthUnit>& length_units();

/// Millimetres in one `unit`; throws section::Error `units: unknown length unit 'U' (known:
/// mm, m, cm, um, in)`.
double mm_per_unit(std::string_view unit);

/// The unit a blade is likely given in, from its extent (the largest side of its bounding
/// box, in the numbers of the file).
struct UnitGuess {
  std::string unit = "mm";  ///< "m" under 1, "in" from 1 to 10, "mm" from 10 to 10000, "um" above
  bool doubtful = false;    ///< the extent is not that of a blade in mm (under 10 or over 10000)
};

/// The likely unit of a blade `extent` across (see UnitGuess): turbine, compressor and
/// propeller blades measure 10 mm to 10 m. Under 1 it is metres (nothing else fits); from 1
/// to 10 inches are likelier than a blade of a few mm, and over 10000 micrometres.
UnitGuess guess_unit(double extent);

/// The unit of an input and how it is taken.
struct InputUnits {
  std::string unit = "mm";  ///< the input's unit
  double mm = 1;            ///< its millimetres: coordinates are multiplied by this on reading
  std::string warning;      ///< set when the unit was not given and the extent makes it doubtful
  std::string note;         ///< for the stream: how the unit was taken ("" for mm as given or assumed)
  bool doubtful = false;    ///< read as mm though the extent suggests another unit (inches, um)
};

/// The unit of an input `extent` across (numbers as in the file; 0 = unknown): `given` when
/// not empty (throws section::Error for an unknown unit), else mm unless the extent says
/// metres (converted, with a warning); an extent that suggests inches or micrometres is
/// read as mm, with a warning, and marked doubtful (the params rows are then flagged). The
/// warnings name `flag`, the option that gives the unit.
InputUnits input_units(const std::string& given, double extent, const std::string& flag = "--units");

/// Numbers in messages (warnings, issues, errors) for people: three significant digits,
/// no exponent, trailing zeros dropped, and the unit. The stream and CSV keep every digit.
/// A length in mm to at most 4 decimals (0.1 um): 0.025885718 -> "0.0259 mm", 17.269 ->
/// "17.3 mm", 1234.7 -> "1235 mm".
std::string format_length(double mm);
/// An angle in degrees to at most 3 decimals: 0.17812 -> "0.178 deg".
std::string format_angle(double degrees);
/// A fraction (of the chord, the profile, the camber line) as a percentage to at most 2
/// decimals: 0.05 -> "5%", 0.025886 -> "2.59%".
std::string format_share(double fraction);

}  // namespace section
