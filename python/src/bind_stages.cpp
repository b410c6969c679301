// SPDX-License-Identifier: GPL-3.0-or-later
// The stages of the pipe as Python functions: on a stream (as the tools run them) and on
// one curve's points. Options are the tools' flags as keywords (tools/args/).
#include "convert.h"

#include "args/blade_args.h"
#include "args/camber_args.h"
#include "args/fitspline_args.h"
#include "args/slice_args.h"
#include "args/smooth_args.h"
#include "section/cavity.h"
#include "section/error.h"
#include "section/io/cloud_io.h"
#include "section/io/mesh_io.h"
#include "section/io/progress_io.h"
#include "section/io/slice_file.h"
#include "section/pipe/camber_stream.h"
#include "section/pipe/plain_profile.h"
#include "section/pipe/fit_spline_stream.h"
#include "section/pipe/schema.h"
#include "section/pipe/slice_stream.h"
#include "section/pipe/smooth_stream.h"
#include "section/pipe/stacking_stream.h"
#include "section/smooth.h"
#include "section/units.h"

#include <Eigen/Geometry>

#include <optional>

namespace section::python {

namespace {

double extent_of(const std::vector<Eigen::Vector3d>& points) {
  Eigen::AlignedBox3d box;
  for (const auto& p : points) box.extend(p);
  return points.empty() ? 0 : box.sizes().maxCoeff();
}

// Planes from an (P, 6) array: origin x, y, z, normal x, y, z per row.
std::vector<Plane> planes_of(const py::object& planes, double mm) {
  const Array a = planes.cast<Array>();
  if (a.ndim() != 2 || a.shape(1) != 6)
    throw py::value_error(
        "slice: planes: expected an array of shape (P, 6): origin x, y, z and normal x, y, z");
  std::vector<Plane> out;
  for (py::ssize_t i = 0; i < a.shape(0); ++i)
    out.push_back({Eigen::Vector3d(a.at(i, 0), a.at(i, 1), a.at(i, 2)) * mm,
                   Eigen::Vector3d(a.at(i, 3), a.at(i, 4), a.at(i, 5))});
  return out;
}

// What slice reads: a cloud array, or a file (a cloud is sliced as it is read, a mesh whole).
struct SliceInput {
  std::optional<std::string> path;  ///< a cloud file sliced as it is read
  Cloud cloud;                      ///< else the cloud in memory,
  std::optional<Mesh> mesh;         ///< or a mesh
  double extent = 0;
};

// As the tool reads its input: a mesh whole; a plain profile (two columns), or a cloud to be
// cut on surfaces of revolution or taken row by row (`whole`), in memory; any other cloud
// file as it is sliced.
SliceInput slice_input(const py::object& cloud, bool whole) {
  SliceInput in;
  if (py::isinstance<py::str>(cloud) || py::hasattr(cloud, "__fspath__")) {
    const std::string path = py::str(py::module_::import("os").attr("fspath")(cloud)).cast<std::string>();
    py::gil_scoped_release unlocked;
    if (is_mesh_file(path)) {
      in.mesh = read_mesh(path);
      in.extent = extent_of(in.mesh->vertices);
    } else if (auto profile = read_profile_cloud(path)) {
      in.cloud = std::move(*profile);
      in.extent = extent_of(in.cloud.points);
    } else if (whole) {
      in.cloud = read_cloud(path);
      in.extent = extent_of(in.cloud.points);
    } else {
      in.path = path;
      in.extent = sample_extent(path);
    }
  } else {
    in.cloud.points = points3(cloud.cast<Array>(), "slice: cloud");
    in.extent = extent_of(in.cloud.points);
  }
  return in;
}

// slice as the tool runs it: the input's unit (given or guessed) converted to mm; the planes
// from `planes` or the flags, surfaces of revolution (`axis`), or the cloud's rows when no
// planes are given; a cloud file sliced as it is read. The stream's notes as the tool's: the
// unit's, then the sampling's (unless a dense scan).
Stream slice_stream(const py::object& cloud, const py::object& planes, const py::object& progress,
                    const py::kwargs& kwargs) {
  // With `planes` the tool's "one of --at, --count or --planes" is met by a placeholder --at.
  const tool::SliceArgs given = tool_args<tool::SliceArgs>(
      kwargs, planes.is_none() ? std::vector<std::string>{} : std::vector<std::string>{"--at", "0"});
  if (!given.views.empty() || !given.planes_file.empty())
    throw py::value_error("slice: view and planes files are the tool's; pass planes as an array");
  const bool rows = planes.is_none() && given.by_rows(), revolution = !given.axis.empty();
  SliceInput in = slice_input(cloud, rows || revolution);
  if (in.mesh && rows) throw py::value_error("slice: a mesh is cut by planes: give planes, at or count");
  const InputUnits units = input_units(given.units, in.extent);
  const tool::SliceArgs a = given.in_mm(units.mm);
  const Eigen::Vector3d n(a.normal[0], a.normal[1], a.normal[2]);
  const std::vector<Plane> chosen = planes.is_none() ? planes_at(n, a.at) : planes_of(planes, units.mm);
  const ProgressFn fn = progress_fn(progress);
  SliceResult result;
  std::optional<Sampling> streamed;  // the sampling of a file sliced as it is read
  {
    py::gil_scoped_release unlocked;
    for (auto& p : in.cloud.points) p *= units.mm;
    if (in.mesh)
      for (auto& v : in.mesh->vertices) v *= units.mm;
    const int count = planes.is_none() && !revolution ? a.count : 0;
    // Each section done told to `progress` (rows: their count not known before).
    std::optional<ProgressCounter> counter;
    const auto counted = [&](std::size_t total) -> SectionSink {
      if (fn) counter.emplace(fn, "slice", total);
      return [&](const SectionSlice&) {
        if (counter) counter->add(1);
      };
    };
    if (in.mesh) {
      if (revolution) {
        const std::vector<Revolution> surfaces = a.surfaces(in.mesh->vertices, units.mm);
        result = section::slice(*in.mesh, surfaces, a.options, counted(surfaces.size()));
      } else {
        const std::vector<Plane> cut = count > 0 ? planes_across(in.mesh->vertices, n, count) : chosen;
        result = section::slice(*in.mesh, cut, a.options, counted(cut.size()));
      }
    } else if (in.path) {
      CloudReadOptions read;
      read.scale = units.mm;
      result = slice_file(*in.path, PlaneSpec{chosen, n, count}, a.options, read, {}, fn,
                          [&](const Sampling& s) { streamed = s; });
    } else if (revolution) {
      const std::vector<Revolution> surfaces = a.surfaces(in.cloud.points, units.mm);
      result = section::slice(in.cloud, surfaces, a.options, counted(surfaces.size()));
    } else {
      const std::vector<Plane> cut = rows        ? std::vector<Plane>{}
                                     : count > 0 ? planes_across(in.cloud.points, n, count)
                                                 : chosen;
      result = rows ? slice_by_rows(in.cloud, n, a.options, a.rows, counted(0))
                    : section::slice(in.cloud, cut, a.options, counted(cut.size()));
    }
  }
  if (!units.warning.empty()) PyErr_WarnEx(PyExc_UserWarning, ("slice: " + units.warning).c_str(), 1);
  Stream out = to_stream(result, history("slice", kwargs), "mm");
  if (!units.note.empty()) out.notes.push_back(units.note);
  const Sampling& sampling = streamed ? *streamed : result.sampling;
  if (!in.mesh && (streamed || a.options.slab == 0) && sampling.kind != SamplingKind::dense)
    out.notes.push_back(sampling_note(sampling));
  if (!result.sections.empty() && out.issues.size() >= result.sections.size())
    throw py::value_error("slice: no section could be sliced: " + out.issues.front().message);
  return out;
}

// A stage of the pipe on a copy of `in`, as its tool runs it on a whole stream.
template <class Args, class Options>
Stream stage(const char* name, const Stream& in, const py::kwargs& kwargs,
             void (*run)(Stream&, const Options&)) {
  const Args a = tool_args<Args>(kwargs);
  Stream out = in;
  {
    py::gil_scoped_release unlocked;
    convert_to_mm(out);
    run(out, a.options);
  }
  out.history.push_back(history(name, kwargs));
  return out;
}

// blade on a copy of `in` (its --format stream): the tables blade and stacking added.
Stream blade_of(const Stream& in, const py::kwargs& kwargs) {
  for (const char* own : {"format", "plot", "lines", "allow_partial"})
    if (kwargs.contains(own))
      throw py::value_error(std::string("blade: ") + own +
                            " is the tool's; the tables 'blade' and 'stacking' are in the stream returned");
  const tool::BladeArgs a = tool_args<tool::BladeArgs>(kwargs);
  Stream out = in;
  {
    py::gil_scoped_release unlocked;
    stacking_stream(out, a.options);
  }
  out.history.push_back(history("blade", kwargs));
  return out;
}

void bind_curve_functions(py::module_& m) {
  m.def(
      "smooth_points",
      [](const Array& points, bool closed, const py::kwargs& kwargs) {
        SmoothOptions o = tool_args<tool::SmoothArgs>(kwargs).options;
        o.closed = closed;
        const auto p = points2(points, "smooth: points");
        SmoothResult r;
        {
          py::gil_scoped_release unlocked;
          r = smooth(p, o);
        }
        return array2(r.points);
      },
      py::arg("points"), py::arg("closed") = true);
  m.def(
      "fit_spline_points",
      [](const Array& points, const py::object& measured, const py::kwargs& kwargs) {
        const FitSplineOptions o = tool_args<tool::FitsplineArgs>(kwargs).options;
        const auto p = points2(points, "fit_spline: points");
        const auto q = measured.is_none() ? p : points2(measured.cast<Array>(), "fit_spline: measured");
        py::gil_scoped_release unlocked;
        return fit_spline(p, q, o).spline;
      },
      py::arg("points"), py::arg("measured") = py::none());
  m.def(
      "profile_stream", [](const BSpline& spline, double rms) { return profile_stream(spline, rms); },
      py::arg("spline"), py::arg("rms") = 0.0);
  m.def(
      "canonical_loop",
      [](const Array& points) { return array2(canonical_loop(points2(points, "canonical_loop"))); },
      py::arg("points"));
}

// A hollow section's cavities (section/cavity.h).
void bind_cavity_functions(py::module_& m) {
  m.def(
      "measure_cavity",
      [](const BSpline& profile, const BSpline& loop, int samples, double thin) {
        CavityOptions o;
        o.samples = samples;
        o.thin = thin;
        Cavity c;
        {
          py::gil_scoped_release unlocked;
          c = measure_cavity(profile, loop, o);
        }
        const char* place = c.place == LoopPlace::inside    ? "inside"
                            : c.place == LoopPlace::outside ? "outside"
                                                            : "crossing";
        py::dict out;
        out["place"] = place;
        out["area"] = c.area;
        out["length"] = c.length;
        out["centroid"] = array2({c.centroid});
        out["wall"] = c.wall;
        out["profile_point"] = array2({c.profile_point});
        out["cavity_point"] = array2({c.cavity_point});
        out["profile_t"] = c.profile_t;
        out["cavity_t"] = c.cavity_t;
        return out;
      },
      py::arg("profile"), py::arg("loop"), py::arg("samples") = CavityOptions{}.samples,
      py::arg("thin") = CavityOptions{}.thin);
  m.def(
      "side_walls",
      [](const BSpline& profile, const BSpline& loop, double t0, double t1, int samples, double thin) {
        CavityOptions o;
        o.samples = samples;
        o.thin = thin;
        std::array<CavityWall, 2> walls;
        {
          py::gil_scoped_release unlocked;
          walls = side_walls(profile, loop, t0, t1, o);
        }
        py::list out;
        for (const CavityWall& w : walls) {
          py::dict d;
          d["wall"] = w.wall;
          d["profile_point"] = array2({w.profile_point});
          d["cavity_point"] = array2({w.cavity_point});
          d["profile_t"] = w.profile_t;
          d["cavity_t"] = w.cavity_t;
          out.append(d);
        }
        return out;
      },
      py::arg("profile"), py::arg("loop"), py::arg("t0"), py::arg("t1"),
      py::arg("samples") = CavityOptions{}.samples, py::arg("thin") = CavityOptions{}.thin);
}

}  // namespace

void bind_stages(py::module_& m) {
  m.def("slice_stream", &slice_stream, py::arg("cloud"), py::arg("planes") = py::none(),
        py::arg("progress") = py::none());
  m.def("smooth_stream", [](const Stream& s, const py::kwargs& kw) {
    return stage<tool::SmoothArgs, SmoothOptions>("smooth", s, kw, smooth_stream);
  });
  m.def("fit_spline_stream", [](const Stream& s, const py::kwargs& kw) {
    return stage<tool::FitsplineArgs, FitSplineOptions>("fit_spline", s, kw, fit_spline_stream);
  });
  m.def("camber_stream", [](const Stream& s, const py::kwargs& kw) {
    return stage<tool::CamberArgs, CamberOptions>("camber", s, kw, camber_stream);
  });
  // `camber PROFILE` on a plain profile's points: fitted from their canonical start, measured,
  // and checked against the same points fitted from the other end.
  m.def("plain_profile_camber", [](const Array& points, const py::kwargs& kw) {
    const auto p = points2(points, "camber: profile");
    const tool::CamberArgs a = tool_args<tool::CamberArgs>(kw);
    Stream out;
    {
      py::gil_scoped_release unlocked;
      // The other end's fit and measurement run beside this one's.
      std::future<Stream> other = other_end_stream_async(p, a.options);
      out = plain_profile_stream(p);
      camber_stream(out, a.options);
      flag_start_dependence(out, other.get());
    }
    out.history.push_back(history("camber", kw));
    return out;
  });
  m.def("blade_stream", &blade_of, py::arg("stream"));
  bind_curve_functions(m);
  bind_cavity_functions(m);
}

}  // namespace section::python
