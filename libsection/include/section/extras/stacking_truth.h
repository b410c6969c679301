// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file extras/stacking_truth.h
/// The exact whole-blade values of a generated blade (generate.h) at given heights, by the
/// definitions of docs/BLADE.md for a planar stack along z (axial +x, tangential +y):
/// computed from the exact sections, independently of the stacking stage.
#include "section/extras/generate.h"

#include <Eigen/Core>
#include <vector>

namespace section {

/// The true values at one height (mm, degrees).
struct StackingTruth {
  double z = 0;          ///< the height (span coordinate)
  double stagger = 0;    ///< angle of TE point - LE point against +x
  double twist = 0;      ///< stagger - the first height's
  double lean = 0;       ///< centroid y - the first height's
  double sweep = 0;      ///< centroid x - the first height's
  double bow = 0;        ///< centroid y - the line through the lowest and highest heights' centroids
  double axial_bow = 0;  ///< the same in x
  double chord = 0, max_thickness = 0;
  Eigen::Vector3d centroid{0, 0, 0}, le{0, 0, 0}, te{0, 0, 0};  ///< in 3D
};

/// The truth at `heights` (mm, at least 2, distinct); the reference is heights[0], the
/// bow's line runs through the lowest and the highest. Throws section::Error otherwise.
std::vector<StackingTruth> stacking_truth(const BladeDesign& blade, const std::vector<double>& heights);

}  // namespace section
