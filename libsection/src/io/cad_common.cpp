// SPDX-License-Identifier: GPL-3.0-or-later
// What the DXF and IGES writers share.
#include "io/cad_common.h"

#include "section/error.h"
#include "section/io/stream.h"

#include <array>
#include <cmath>

namespace section::detail {

namespace {

constexpr std::array<CadUnit, 5> units_known{{
    {"mm", 4, 2, "MM"},
    {"cm", 5, 10, "CM"},
    {"m", 6, 6, "M"},
    {"in", 1, 1, "INCH"},
    {"um", 13, 9, "UM"},
}};

}  // namespace

const CadUnit& cad_unit(const std::string& units) {
  for (const auto& u : units_known)
    if (units == u.name) return u;
  throw Error("cad: unknown length unit '" + units + "' (known: mm, cm, m, in, um)");
}

std::string cad_real(double value, char exponent) {
  if (!std::isfinite(value))
    throw Error("cad: a curve has a number that is not finite (" + format_number(value) + ")");
  std::string s = format_number(value);
  const std::size_t e = s.find_first_of("eE");
  std::string mantissa = s.substr(0, e), power = e == std::string::npos ? "" : s.substr(e + 1);
  if (mantissa.find('.') == std::string::npos) mantissa += ".0";
  return power.empty() ? mantissa : mantissa + exponent + power;
}

CadSpline cad_spline(const CadCurve& curve) {
  const BSpline open = clamped(curve.spline);
  CadSpline out;
  out.degree = open.degree;
  out.closed = curve.spline.closed;
  out.knots = open.knots;
  for (const auto& c : open.control) out.control.push_back(curve.frame.to_world(c));
  return out;
}

}  // namespace section::detail
