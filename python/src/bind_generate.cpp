// SPDX-License-Identifier: GPL-3.0-or-later
// The blade generator (section/extras/generate.h) as the submodule libsection.generate: blades
// with exact ground truth, for tests and trials.
#include "convert.h"

#include "args/bladegen_args.h"
#include "section/extras/generate.h"

#include <pybind11/stl.h>

namespace section::python {

namespace {

BladeDesign blade(const std::string& kind) {
  std::string known;
  for (const auto& p : tool::blade_presets) {
    if (kind == p.name) return p.blade();
    known += (known.empty() ? "" : ", ") + std::string(p.name);
  }
  throw py::value_error("generate: unknown kind '" + kind + "' (known: " + known + ")");
}

py::dict truth(const std::string& kind, double z, int samples) {
  SectionTruth t;
  {
    const BladeDesign b = blade(kind);
    py::gil_scoped_release unlocked;
    t = section_truth(b.at(z), samples);
  }
  py::dict d;
  d["profile"] = array2(t.profile);
  d["profile_normal"] = array2(t.profile_normal);
  d["camber"] = array2(t.camber);
  d["camber_radius"] = array1(t.camber_radius);
  for (const auto& [name, value] :
       std::vector<std::pair<const char*, double>>{{"chord", t.chord},
                                                   {"camber_length", t.camber_length},
                                                   {"max_thickness", t.max_thickness},
                                                   {"max_thickness_pos", t.max_thickness_pos},
                                                   {"le_radius", t.le_radius},
                                                   {"te_radius", t.te_radius},
                                                   {"stagger", t.stagger},
                                                   {"inlet_angle", t.inlet_angle},
                                                   {"outlet_angle", t.outlet_angle},
                                                   {"area", t.area},
                                                   {"perimeter", t.perimeter}})
    d[name] = value;
  for (const auto& [name, p] :
       std::vector<std::pair<const char*, Eigen::Vector2d>>{{"le_point", t.le_point},
                                                            {"te_point", t.te_point},
                                                            {"le_center", t.le_center},
                                                            {"te_center", t.te_center},
                                                            {"centroid", t.centroid}})
    d[name] = array1({p.x(), p.y()});
  return d;
}

Array scan(const std::string& kind, double spacing, double noise, int holes, double density_min,
           double misregistration, double outliers, double z_min, double z_max, std::uint64_t seed) {
  ScanOptions o;
  o.spacing = spacing;
  o.noise = noise;
  o.holes = holes;
  o.density_min = density_min;
  o.misregistration = misregistration;
  o.outlier_fraction = outliers;
  o.z_min = z_min;
  o.z_max = z_max;
  o.seed = seed;
  const BladeDesign b = blade(kind);
  Scan s;
  {
    py::gil_scoped_release unlocked;
    s = generate_scan(b, o);
  }
  return array3(s.cloud.points);
}

}  // namespace

void bind_generate(py::module_& m) {
  py::module_ g =
      m.def_submodule("generate", "Synthetic blades with exact ground truth (bladegen's generator).");
  g.def("kinds", [] {
    std::vector<std::string> out;
    for (const auto& p : tool::blade_presets) out.emplace_back(p.name);
    return out;
  });
  g.def("truth", &truth, py::arg("kind") = "turbine", py::arg("z") = 30.0, py::arg("samples") = 20000,
        "The exact section of a blade at height z (mm): profile (M, 2) counterclockwise from the LE point, "
        "camber line, and the true parameters (mm, degrees), in the plane z = const (u = x, v = y).");
  g.def(
      "scan", &scan, py::arg("kind") = "turbine", py::arg("spacing") = 0.08, py::arg("noise") = 0.0,
      py::arg("holes") = 0, py::arg("density_min") = 1.0, py::arg("misregistration") = 0.0,
      py::arg("outliers") = 0.0, py::arg("z_min") = 0.0, py::arg("z_max") = -1.0, py::arg("seed") = 1,
      "A synthetic scan of the blade's side surface as an (N, 3) array (mm): noise sigma along the normal, "
      "holes, density, a misregistered second view, outliers, the height range z_min..z_max (z_max < z_min: "
      "the whole span), random seed.");
}

}  // namespace section::python
