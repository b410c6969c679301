// SPDX-License-Identifier: GPL-3.0-or-later
// section_params: blade section parameters from a mesh through libsection's public API.
//
//   section_params [MESH [Z...]]
//
// Cuts MESH (.stl .obj .off .ply) by planes z = Z (default: three planes across its
// height), fits a closed B-spline to each section's profile, finds its mean-camber line
// and prints the section parameters. Without MESH it cuts a synthetic turbine blade
// (generate.h) and prints, next to each value, its error against the exact design.
#include <section/camber.h>
#include <section/error.h>
#include <section/fit_spline.h>
#include <section/extras/generate.h>
#include <section/io/mesh_io.h>
#include <section/mesh.h>
#include <section/params.h>
#include <section/slice.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  try {
    const bool synthetic = argc < 2;
    const section::BladeDesign blade = section::turbine_blade();
    // Rings 1 mm apart on the 60 mm span; the planes below fall between rings.
    const section::Mesh mesh =
        synthetic ? section::generate_mesh(blade, 1000, 61) : section::read_mesh(argv[1]);

    std::vector<double> z;
    for (int i = 2; i < argc; ++i) z.push_back(std::atof(argv[i]));
    if (z.empty()) {
      double lo = mesh.vertices.front().z(), hi = lo;
      for (const auto& v : mesh.vertices) lo = std::min(lo, v.z()), hi = std::max(hi, v.z());
      for (double f : {0.25, 0.5, 0.75}) z.push_back(lo + f * (hi - lo) + 0.01 * (hi - lo) / 3);
    }

    // 1. Slice: one section per plane, its closed loops ordered counterclockwise.
    const section::SliceResult sliced = section::slice(mesh, section::planes_at({0, 0, 1}, z));
    std::printf("%8s %10s %10s %10s %10s %9s %9s %9s\n", "z", "chord", "max_thick", "le_radius", "te_radius",
                "stagger", "inlet", "outlet");
    int failed = 0;
    for (const auto& s : sliced.sections) {
      const double height = z[s.id];
      if (!s.error.empty() || s.morphology.loops.empty()) {
        std::printf("%8.3f  section failed: %s\n", height, s.error.c_str());
        ++failed;
        continue;
      }
      try {
        // 2. Fit: a closed cubic B-spline through the profile (loop 0), refined against it.
        const auto& profile = s.morphology.loops[0].points;
        const section::FitSplineResult fit = section::fit_spline(profile, profile);
        // 3. Camber line (inscribed circles) and 4. the parameters measured on it.
        const section::CamberResult camber = section::camber_line(fit.spline);
        const section::SectionParams p = section::section_params(fit.spline, camber);
        std::printf("%8.3f %10.4f %10.4f %10.4f %10.4f %9.3f %9.3f %9.3f\n", height, p.chord, p.max_thickness,
                    p.le_radius, p.te_radius, p.stagger, p.inlet_angle, p.outlet_angle);
        if (synthetic) {
          const section::SectionTruth t = section::section_truth(blade.at(height), 20000);
          std::printf("%8s %10.1f %10.1f %10.1f %10.1f %9.3f %9.3f %9.3f   (error, um and deg)\n", "",
                      1e3 * (p.chord - t.chord), 1e3 * (p.max_thickness - t.max_thickness),
                      1e3 * (p.le_radius - t.le_radius), 1e3 * (p.te_radius - t.te_radius),
                      p.stagger - t.stagger, p.inlet_angle - t.inlet_angle, p.outlet_angle - t.outlet_angle);
        }
      } catch (const section::Error& e) {  // one section failing does not stop the others
        std::printf("%8.3f  section failed: %s\n", height, e.what());
        ++failed;
      }
    }
    return failed == static_cast<int>(sliced.sections.size()) ? 1 : 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "section_params: error: %s\n", e.what());
    return 1;
  }
}
