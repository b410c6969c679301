// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The maps of a surface of revolution (section/revolution.h) with the meridian's running
// lengths made once: what slicing a cloud calls for every point.
#include "section/revolution.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace section::detail {

/// A point's foot on the meridian: arc length m, signed distance w, and where (a, r).
struct MeridianFoot {
  double m = 0, w = 0;
  Eigen::Vector2d ar{0, 0};
};

class RevolutionMap {
public:
  /// Checks the surface (check_surface) and makes the running lengths of its meridian.
  explicit RevolutionMap(const Revolution& surface);

  /// (a, r, theta) of a 3D point.
  Eigen::Vector3d cylindrical(const Eigen::Vector3d& p) const;
  /// The foot of (a, r) on the meridian (its end segments extended).
  MeridianFoot foot(const Eigen::Vector2d& ar) const;
  /// (a, r) of the meridian at arc length m (extended beyond its ends).
  Eigen::Vector2d at(double m) const;
  /// The meridian's unit tangent (da/dm, dr/dm) at m.
  Eigen::Vector2d tangent(double m) const;
  /// m' = integral dm / r from the first point, and back (NaN beyond an apex).
  double m_prime(double m) const;
  double m_of_prime(double mp) const;

  /// The place of a 3D point (surface_place).
  SurfacePlace place(const Eigen::Vector3d& p) const;
  /// (m, theta) of unrolled coordinates, and back.
  Eigen::Vector2d m_theta(const Eigen::Vector2d& uv) const;
  Eigen::Vector2d unrolled(double m, double theta) const;
  /// The 3D point at (m, theta).
  Eigen::Vector3d point(double m, double theta) const;

  const Revolution& surface() const { return s_; }

private:
  // A box over the pieces [lo, hi) of the meridian; leaves hold up to 4 pieces.
  struct Node {
    Eigen::AlignedBox2d box;
    int lo = 0, hi = 0, left = -1, right = -1;
  };
  int build(int lo, int hi);
  void consider(int k, const Eigen::Vector2d& ar, MeridianFoot& best, double& best_d2, int& best_k) const;
  int segment_of(const std::vector<double>& running, double x) const;
  static double segment_prime(double x, double r, double dr);
  Revolution s_;
  Eigen::Vector3d e2_;                   // axis x reference: theta = 90 degrees
  std::vector<double> length_, m_, mp_;  // per segment; running m and m' at each point
  std::vector<Eigen::Vector2d> t_;       // unit tangent per segment
  std::vector<Node> nodes_;              // the tree of boxes (empty for up to 2 pieces)
};

/// The surfaces, a zero reference (theta = 0) replaced by reference_of the points (made
/// once for all); throws section::Error when there are none.
std::vector<Revolution> with_references(const std::vector<Revolution>& surfaces,
                                        const std::vector<Eigen::Vector3d>& points);

}  // namespace section::detail
