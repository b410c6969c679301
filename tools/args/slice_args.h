// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// slice's command line: its options and help text (tools/slice.cpp runs them).
#include "common/tool.h"

#include "section/register_views.h"
#include "section/revolution.h"
#include "section/slice.h"

#include <string>
#include <vector>

namespace section::tool {

struct SliceArgs {
  static constexpr const char* name = "slice";
  static const char* const description;
  Common common;
  std::vector<double> normal{0, 0, 1};     ///< --normal x,y,z
  std::vector<double> at;                  ///< --at: plane offsets along the normal
  int count = 0;                           ///< --count: planes spread evenly over the part
  std::string planes_file;                 ///< --planes: CSV file of planes
  bool rows = false;                       ///< --rows: each row of points a section as it lies
  std::vector<double> axis;                ///< --axis px,py,pz,dx,dy,dz: surfaces of revolution about it
  std::vector<double> radii;               ///< --radius: cylinders
  std::vector<double> cones;               ///< --cone: a0,r0,a1,r1 per cone
  std::vector<std::string> streamlines;    ///< --streamline: files of (axial, radius) points
  std::string unroll;                      ///< --unroll: "" = cylinder for cylinders, else conformal
  double r_ref = 0;                        ///< --r-ref: the unrolled plane's reference radius (0 = chosen)
  std::vector<std::string> views;          ///< --view: other views of the part, registered onto the input
  RegisterOptions register_options;        ///< --view-reach
  SliceOptions options;                    ///< --slab, --cell, --band-*, --fill-*, --threads
  std::string units;                       ///< --units: the input's length unit ("" = mm, or m by its extent)
  std::vector<std::string> lengths_given;  ///< the length options given (in the input's unit)
  /// Declares the options on `app`, bound to these fields.
  void declare(CLI::App& app);
  /// The options with every length given converted to mm (`mm` = the input unit's mm).
  SliceArgs in_mm(double mm) const;
  /// The surfaces of revolution of --axis about `points` (in mm; streamline files in the
  /// input's unit, `mm` of it): cylinders (--radius, --count over the points' radii, or
  /// each row at constant radius), cones, streamlines; --unroll and --r-ref applied, the
  /// reference direction (theta = 0) from the points.
  std::vector<Revolution> surfaces(const std::vector<Eigen::Vector3d>& points, double mm) const;
  /// True when no planes are given: the rows are taken as sections (--rows, or a cloud
  /// that is sparse rows or a single profile).
  bool by_rows() const { return axis.empty() && (rows || (at.empty() && count == 0 && planes_file.empty())); }
};

}  // namespace section::tool
