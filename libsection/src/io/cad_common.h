// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What the DXF and IGES writers share: numbers as CAD readers take them, unit codes, and
// each curve's clamped form in 3D.
#include "section/io/cad.h"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace section::detail {

/// A length unit's codes in the two formats.
struct CadUnit {
  const char* name;       ///< as CadOptions::units has it
  int dxf;                ///< DXF $INSUNITS
  int iges;               ///< IGES global parameter 14 (units flag)
  const char* iges_name;  ///< IGES global parameter 15
};

/// The codes of `units`; throws section::Error naming the units known.
const CadUnit& cad_unit(const std::string& units);

/// A real number as CAD readers take it: the shortest text that reads back to the same double,
/// always with a decimal point, the exponent (if any) marked by `exponent` ('E' or 'D').
/// Throws section::Error for a non-finite number.
std::string cad_real(double value, char exponent = 'E');

/// A curve's clamped form (bspline.h) in 3D: its knots and control points mapped through the
/// frame.
struct CadSpline {
  int degree = 3;
  bool closed = false;  ///< the loop is closed (the clamped form's ends meet)
  std::vector<double> knots;
  std::vector<Eigen::Vector3d> control;
};

/// The clamped form of `curve` in 3D.
CadSpline cad_spline(const CadCurve& curve);

}  // namespace section::detail
