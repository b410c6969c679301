// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The edges as camber_line measures them (src/edge.cpp): the edge circle fitted to a
// grown (or fixed) edge arc, refitted to the measured points, the blunt-face test
// (src/blunt_face.cpp) and the shape classification.
#include "detail/sampled_profile.h"
#include "section/camber.h"

#include <Eigen/Core>

#include <vector>

namespace section::detail {

/// A blunt (cut-off) edge: a flat face across the end of the blade.
struct Face {
  bool found = false;
  double width = 0;              ///< extent of the face
  Eigen::Vector2d mid{0, 0};     ///< its middle
  Eigen::Vector2d normal{0, 0};  ///< outward unit normal
};

/// Looks for a flat face at the end of the medial branch `from_end` (circles ordered from
/// the end inward) whose end tangent points outward along `d_end` (docs/CAMBER.md, 4b).
Face blunt_face(const SampledProfile& pr, const std::vector<InscribedCircle>& from_end,
                const Eigen::Vector2d& d_end, const CamberOptions& options);

/// The edge at the axis end `end` whose tangent points outward along d: its point, arc and
/// fitted circle, shape (`max_diameter`: the largest inscribed diameter) and circularity;
/// a face when `face` was found (the circle fit, when it succeeds, kept for
/// EdgeModel::round). Throws section::Error when the tangent misses the profile and there
/// is no face.
Edge detect_edge(const SampledProfile& pr, const InscribedCircle& end, const Eigen::Vector2d& d,
                 const Face& face, double max_diameter, const CamberOptions& options,
                 const std::vector<Eigen::Vector2d>& measured);

}  // namespace section::detail
