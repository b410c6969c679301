// SPDX-License-Identifier: GPL-3.0-or-later
#include "section/units.h"

#include "section/error.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace section {

const std::vector<LengthUnit>& length_units() {
  static const std::vector<LengthUnit> units = {
      {"mm", 1.0}, {"m", 1000.0}, {"cm", 10.0}, {"um", 0.001}, {"in", 25.4}};
  return units;
}

double mm_per_unit(std::string_view unit) {
  std::string known;
  for (const auto& u : length_units()) {
    if (unit == u.name) return u.mm;
    known += (known.empty() ? "" : ", ") + std::string(u.name);
  }
  throw Error("units: unknown length unit '" + std::string(unit) + "' (known: " + known + ")");
}

UnitGuess guess_unit(double extent) {
  // Turbine, compressor and propeller blades measure a few mm to a few m: 1 to 10000 in mm.
  if (extent > 0 && extent < 1) return {"m", true};
  if (extent >= 1 && extent < 10) return {"in", true};
  if (extent > 10000) return {"um", true};
  return {"mm", false};
}

InputUnits input_units(const std::string& given, double extent, const std::string& flag) {
  InputUnits in;
  char text[256];
  if (!given.empty()) {
    in.unit = given;
    in.mm = mm_per_unit(given);
    if (in.mm != 1) in.note = "units_from " + given + " (given; converted to mm)";
    // A unit given by mistake (a scan in mm said to be in m) makes a blade of another size.
    const double mm = extent * in.mm;
    if (extent > 0 && (mm < 1 || mm > 10000)) {
      std::snprintf(text, sizeof text,
                    "the input is %.3g %s across, %.3g mm: %s than a blade (1 mm to 10 m); check %s", extent,
                    given.c_str(), mm, mm < 1 ? "smaller" : "larger", flag.c_str());
      in.warning = text;
    }
    return in;
  }
  const UnitGuess guess = guess_unit(extent);
  if (guess.unit == "m") {
    in.unit = "m";
    in.mm = 1000;
    std::snprintf(text, sizeof text,
                  "the input is %.3g across: taken to be in metres and converted to mm (give %s to "
                  "say which unit it is in)",
                  extent, flag.c_str());
    in.warning = text;
    in.note = "units_from m (guessed from the extent; converted to mm)";
  } else if (guess.doubtful) {
    const bool inches = guess.unit == "in";
    std::snprintf(text, sizeof text,
                  "the input is %.3g across: read as mm, though it looks like %s; give %s %s if it is, "
                  "or %s mm (its parameters are flagged 'units' until then)",
                  extent, inches ? "inches" : "micrometres", flag.c_str(), guess.unit.c_str(), flag.c_str());
    in.warning = text;
    in.doubtful = true;
    in.note = "units_doubtful " + guess.unit + " (read as mm; the extent suggests " +
              (inches ? "inches" : "micrometres") + ")";
  }
  return in;
}

namespace {

// `value` to 3 significant digits and at most `decimals` after the point, without an
// exponent or trailing zeros, then `unit`.
std::string short_number(double value, int decimals, const char* unit) {
  char text[64];
  if (!std::isfinite(value)) {
    std::snprintf(text, sizeof text, "%g%s", value, unit);
    return text;
  }
  const double size = std::abs(value);
  // Past 1e15 the digits would not fit the text (and mean nothing): with an exponent.
  if (size >= 1e15) {
    std::snprintf(text, sizeof text, "%.3g%s", value, unit);
    return text;
  }
  const int leading = size > 0 ? static_cast<int>(std::floor(std::log10(size))) : 0;
  const int shown = std::max(0, std::min(decimals, 2 - leading));
  std::snprintf(text, sizeof text, "%.*f", shown, value);
  std::string out = text;
  if (out.find('.') != std::string::npos) {
    out.erase(out.find_last_not_of('0') + 1);
    if (out.back() == '.') out.pop_back();
  }
  if (out == "-0") out = "0";
  return out + unit;
}

}  // namespace

std::string format_length(double mm) {
  return short_number(mm, 4, " mm");
}

std::string format_angle(double degrees) {
  return short_number(degrees, 3, " deg");
}

std::string format_share(double fraction) {
  return short_number(100 * fraction, 2, "%");
}

}  // namespace section
