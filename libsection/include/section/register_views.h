// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file register_views.h
/// Fine registration of scanner views: the views of one part, roughly aligned already (as
/// a scanner delivers them), are moved onto the first by rigid point-to-surface ICP on the
/// surface they share. A view misregistered by some micrometres otherwise shifts every
/// section it alone covers by that much (the pressure side of a blade scanned from two
/// sides), which no later fit can tell from the shape.
#include "section/cloud.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <string>
#include <vector>

namespace section {

/// Options of register_views (lengths in the clouds' units; docs/REGISTRATION.md).
struct RegisterOptions {
  double reach = 0;                        ///< pairs within this of the reference view; 0 = 3 mean spacings
  std::size_t reference_points = 2000000;  ///< reference view points kept (evenly) in its kd-tree
  std::size_t moving_points = 200000;      ///< points of each moving view paired per iteration (evenly)
  int neighbours = 20;                     ///< reference points each pair's quadric patch is fitted to
  int max_iterations = 50;                 ///< ICP iterations at most
  double tolerance = 1e-5;                 ///< stop when a step moves the pairs by less (rms, along normals)
  std::size_t min_pairs = 100;             ///< fewer pairs: the views do not overlap enough (Error)
  double weak = 0.05;                      ///< motions constrained under this share of the best: not made
  double fine_weak = 0.01;                 ///< the same in the last pass, at 3 spacings
  double trim = 3;                         ///< pairs farther than this many robust sigmas are left out
  /// A view whose motion moves a point farther than the reach is registered again at this
  /// many times the reach (one whose reach is over 1.25 times its motion, at 1.25 times it),
  /// and refused where the two motions, both on the surface, move its points over half a
  /// spacing apart; where they agree, the second is kept (docs/REGISTRATION.md, "Found again
  /// at a second reach"); 0 = not checked
  double reach_check = 2;
};

/// How one view was moved.
struct ViewRegistration {
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();  ///< maps the view onto the reference
  std::size_t pairs = 0;                                        ///< pairs used in the last iteration
  double rms_before = 0;  ///< rms distance of the pairs from the reference surface before
  double rms_after = 0;   ///< ... and after
  int iterations = 0;     ///< ICP iterations run
  /// Why the motion cannot be stood behind though it was kept (empty: nothing to say). Set
  /// where it moves the view's points nearly as far as the reach (over 0.8 of it) and 0.8
  /// of the reach does not find it again, or where a second reach leaves no motion on the
  /// surface: such a motion may have slid and turned the view along the surface
  /// (docs/REGISTRATION.md, "Near the reach").
  std::string caution;
};

/// Result of register_views: one entry per view, the first (the reference) the identity.
struct RegisterResult {
  std::vector<ViewRegistration> views;
};

/// Registers views[1..] onto views[0]. Throws section::Error naming the view when it
/// shares too little surface with the reference (fewer than min_pairs pairs), when the
/// motion found leaves it off the reference surface at 3 spacings (a reach far wider than
/// the views' misalignment: docs/REGISTRATION.md, "Check"), when its motion differs from
/// the one found at a second reach (where the reach and the motion lie far apart), or the
/// problem is degenerate. A motion kept though it could not be confirmed says so in its
/// `caution`.
RegisterResult register_views(const std::vector<Cloud>& views, const RegisterOptions& options = {});

/// One line for the stream's notes: `register view=NAME translation=x,y,z rotation=DEG
/// pairs=N rms_before=R0 rms_after=R1 iterations=K` (lengths in the cloud's units), then
/// ` unconfirmed=1` where the registration has a caution.
std::string describe(const ViewRegistration& registration, const std::string& name);

/// The views merged into one cloud, each moved by its registration.
Cloud merge_views(const std::vector<Cloud>& views, const RegisterResult& registration);

}  // namespace section
