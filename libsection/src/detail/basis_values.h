// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The B-spline basis values of one knot span from the knots about it, for loops over many
// parameters of one curve (least-squares fits).
#include "section/bspline.h"

namespace section::detail {

/// Degree: `degree` when 0, else equal to it (the loops unrolled).
template <int Degree>
inline void basis_values_of(const double* u, int degree, double t, double* value) {
  const int p = Degree > 0 ? Degree : degree;
  double left[max_spline_degree + 1], right[max_spline_degree + 1];
  value[0] = 1.0;
  for (int r = 1; r <= p; ++r) {
    left[r] = t - u[1 - r];
    right[r] = u[r] - t;
    double saved = 0.0;
    for (int s = 0; s < r; ++s) {
      const double sum = right[s + 1] + left[r - s];
      const double temp = sum == 0 ? 0 : value[s] / sum;
      value[s] = saved + right[s + 1] * temp;
      saved = left[r - s] * temp;
    }
    value[r] = saved;
  }
}

/// The degree + 1 basis functions non-zero at t in the knot span that starts at u[0]
/// (u[d]: the knot d after it, d = 1 - degree .. degree), into `value`: Piegl and Tiller's
/// A2.3 at derivative 0 with the same operations in the same order as BSpline's evaluation
/// (src/bspline.cpp), whose values they are bit for bit.
inline void basis_values(const double* u, int degree, double t, double* value) {
  if (degree == 3)
    basis_values_of<3>(u, degree, t, value);
  else
    basis_values_of<0>(u, degree, t, value);
}

}  // namespace section::detail
