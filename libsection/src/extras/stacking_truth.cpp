// SPDX-License-Identifier: GPL-3.0-or-later
// The exact whole-blade values of a generated blade (stacking_truth.h).
#include "section/extras/stacking_truth.h"

#include "section/error.h"

#include <algorithm>
#include <cmath>

namespace section {

std::vector<StackingTruth> stacking_truth(const BladeDesign& blade, const std::vector<double>& heights) {
  if (heights.size() < 2) throw Error("stacking_truth: at least 2 heights are needed");
  std::vector<StackingTruth> out;
  for (double z : heights) {
    const SectionTruth s = section_truth(blade.at(z));
    StackingTruth t;
    t.z = z;
    t.stagger = s.stagger;
    t.chord = s.chord;
    t.max_thickness = s.max_thickness;
    t.centroid = {s.centroid.x(), s.centroid.y(), z};
    t.le = {s.le_point.x(), s.le_point.y(), z};
    t.te = {s.te_point.x(), s.te_point.y(), z};
    out.push_back(t);
  }
  const auto [lo, hi] = std::minmax_element(heights.begin(), heights.end());
  const StackingTruth &ref = out.front(), &hub = out[std::size_t(lo - heights.begin())],
                      &tip = out[std::size_t(hi - heights.begin())];
  if (!(tip.z > hub.z)) throw Error("stacking_truth: the heights are all equal");
  for (StackingTruth& t : out) {
    t.twist = std::remainder(t.stagger - ref.stagger, 360.0);
    t.lean = t.centroid.y() - ref.centroid.y();
    t.sweep = t.centroid.x() - ref.centroid.x();
    const double w = (t.z - hub.z) / (tip.z - hub.z);
    t.bow = t.centroid.y() - (hub.centroid.y() + w * (tip.centroid.y() - hub.centroid.y()));
    t.axial_bow = t.centroid.x() - (hub.centroid.x() + w * (tip.centroid.x() - hub.centroid.x()));
  }
  return out;
}

}  // namespace section
