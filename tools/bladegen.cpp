// SPDX-License-Identifier: GPL-3.0-or-later
// bladegen: synthetic blade scans and meshes with exact ground truth.
#include "args/bladegen_args.h"

#include "section/cloud.h"
#include "section/error.h"
#include "section/extras/generate.h"
#include "section/extras/generate_rotor.h"
#include "section/mesh.h"
#include "section/io/cloud_io.h"
#include "section/io/mesh_io.h"
#include "section/io/stream.h"

#include <cstdio>
#include <string>
#include <vector>

namespace {

using section::tool::BladegenArgs;

void write_truth(const std::string& path, const section::BladeDesign& blade, const std::vector<double>& at) {
  std::string out =
      "z,chord,stagger,inlet_angle,outlet_angle,camber_length,max_thickness,max_thickness_pos,"
      "le_radius,te_radius,le_x,le_y,te_x,te_y,le_center_x,le_center_y,te_center_x,te_center_y,"
      "area,centroid_x,centroid_y,perimeter\n";
  for (double z : at) {
    if (z < 0 || z > blade.span)
      throw section::Error("bladegen: --at " + section::format_number(z) + " is outside the span [0, " +
                           section::format_number(blade.span) + "]");
    const section::SectionTruth t = section::section_truth(blade.at(z));
    const double v[] = {z,
                        t.chord,
                        t.stagger,
                        t.inlet_angle,
                        t.outlet_angle,
                        t.camber_length,
                        t.max_thickness,
                        t.max_thickness_pos,
                        t.le_radius,
                        t.te_radius,
                        t.le_point.x(),
                        t.le_point.y(),
                        t.te_point.x(),
                        t.te_point.y(),
                        t.le_center.x(),
                        t.le_center.y(),
                        t.te_center.x(),
                        t.te_center.y(),
                        t.area,
                        t.centroid.x(),
                        t.centroid.y(),
                        t.perimeter};
    for (std::size_t i = 0; i < std::size(v); ++i) out += (i ? "," : "") + section::format_number(v[i]);
    out += '\n';
  }
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) throw section::Error("bladegen: " + path + ": cannot open for writing");
  const bool ok = std::fwrite(out.data(), 1, out.size(), f) == out.size();
  if (std::fclose(f) != 0 || !ok) throw section::Error("bladegen: " + path + ": write error");
}

// The coordinates in --units (the generator's are in mm), on the rotor's surfaces with --rotor.
section::Cloud in_units(const BladegenArgs& a, section::Cloud cloud, double scale) {
  if (!a.rotor.empty()) cloud = section::rotor_cloud(a.rotor_design(), cloud);
  if (scale != 1)
    for (auto& p : cloud.points) p *= scale;
  return cloud;
}

void run_bladegen(const BladegenArgs& a) {
  const section::BladeDesign blade = a.blade();
  const double scale = 1 / section::tool::mm_per_unit(a.units);
  if (a.points && a.second_view.empty())
    section::write_cloud(a.output, in_units(a, section::generate_scan(blade, a.scan).cloud, scale));
  if (a.points && !a.second_view.empty()) {
    const std::vector<section::Cloud> views = section::views_of(section::generate_scan(blade, a.scan));
    section::write_cloud(a.output, in_units(a, views[0], scale));
    section::write_cloud(a.second_view, in_units(a, views[1], scale));
  }
  if (!a.grid.empty())
    section::write_cloud(a.output, in_units(a, section::generate_grid(blade, a.grid_settings()), scale));
  if (a.rows > 0)
    section::write_cloud(a.output, in_units(a, section::generate_rows(blade, a.rows_settings()), scale));
  if (a.mesh) {
    section::Mesh mesh = a.rotor.empty() ? section::generate_mesh(blade, a.profile_points, a.layers)
                                         : section::rotor_mesh(a.rotor_design(), a.profile_points, a.layers);
    if (scale != 1)
      for (auto& v : mesh.vertices) v *= scale;
    section::write_mesh(a.output, mesh);
  }
  if (!a.truth.empty())
    write_truth(a.truth, blade, a.at.empty() ? section::row_heights(blade, a.rows_settings()) : a.at);
}

}  // namespace

int main(int argc, char** argv) {
  return section::tool::run<BladegenArgs>(argc, argv, run_bladegen);
}
