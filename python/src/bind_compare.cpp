// SPDX-License-Identifier: GPL-3.0-or-later
// compare on arrays: a nominal prepared once (Nominal: its geometry and foot search, see
// section/compare.h prepare_nominal) and measured sections compared with it; and on a
// whole stream against a nominal file or stream, as the compare tool runs. The options are
// the compare tool's flags as keywords.
#include "convert.h"

#include "args/compare_args.h"
#include "section/compare.h"
#include "section/extras/report.h"
#include "section/pipe/nominal_file.h"
#include "section/io/tolerances.h"
#include "section/pipe/compare_stream.h"
#include "section/pipe/schema.h"

#include <string>

namespace section::python {

namespace {

// A prepared nominal with the options it was prepared with (used when a call gives none).
struct Nominal {
  PreparedNominal prepared;
  CompareOptions options;
};

CompareOptions compare_options(const py::kwargs& kwargs) {
  // The tool's required --nominal is met by a placeholder: the nominal is the Spline.
  return tool_args<tool::CompareArgs>(kwargs, {"--nominal", "-"}).options.compare;
}

Eigen::Vector2d point_of(const py::object& p, const char* what) {
  const Array a = p.cast<Array>();
  if (a.size() != 2) throw py::value_error(std::string("compare: ") + what + ": expected two numbers (u, v)");
  return {a.data()[0], a.data()[1]};
}

Nominal make_nominal(const BSpline& curve, const py::object& le, const py::object& te, int pressure_side,
                     const py::kwargs& kwargs) {
  Nominal n;
  n.options = compare_options(kwargs);
  NominalSection s;
  s.curve = curve;
  s.le_point = point_of(le, "le_point");
  s.te_point = point_of(te, "te_point");
  s.pressure_side = pressure_side > 0 ? 1 : -1;
  py::gil_scoped_release unlocked;
  n.prepared = prepare_nominal(s, n.options);
  return n;
}

py::dict zones_of(const SectionComparison& c) {
  py::dict zones;
  for (int z = 0; z < zone_count; ++z) {
    const ZoneResult& r = c.zones[static_cast<std::size_t>(z)];
    py::dict d;
    d["points"] = r.points;
    d["min"] = r.min;
    d["max"] = r.max;
    d["form"] = r.form;
    d["length"] = r.length;
    d["unmeasured"] = r.unmeasured;
    d["measured"] = r.measured;
    zones[zone_name(static_cast<Zone>(z))] = d;
  }
  return zones;
}

py::dict points_of(const SectionComparison& c) {
  const std::size_t n = c.points.size();
  std::vector<Eigen::Vector2d> point(n), foot(n), normal(n);
  std::vector<double> t(n), before(n), after(n);
  py::array_t<int> zone(static_cast<py::ssize_t>(n));
  py::array_t<bool> outlier(static_cast<py::ssize_t>(n));
  for (std::size_t i = 0; i < n; ++i) {
    const PointDeviation& p = c.points[i];
    point[i] = p.point;
    foot[i] = p.foot;
    normal[i] = p.normal;
    t[i] = p.t;
    before[i] = p.before;
    after[i] = p.after;
    zone.mutable_data()[i] = static_cast<int>(p.zone);
    outlier.mutable_data()[i] = p.outlier;
  }
  py::dict d;
  d["point"] = array2(point);
  d["foot"] = array2(foot);
  d["normal"] = array2(normal);
  d["t"] = array1(t);
  d["before"] = array1(before);
  d["after"] = array1(after);
  d["zone"] = zone;
  d["outlier"] = outlier;
  return d;
}

py::dict compare_points(const Nominal& nominal, const Array& measured, const py::kwargs& kwargs) {
  const CompareOptions options = kwargs.empty() ? nominal.options : compare_options(kwargs);
  const std::vector<Eigen::Vector2d> q = points2(measured, "compare: points");
  SectionComparison c;
  {
    py::gil_scoped_release unlocked;
    c = compare_section(nominal.prepared, q, options);
  }
  py::dict out;
  out["angle"] = c.fit.motion.angle;
  out["translation"] = array1({c.fit.motion.translation.x(), c.fit.motion.translation.y()});
  out["iterations"] = c.fit.iterations;
  out["converged"] = c.fit.converged;
  out["rms_before"] = c.fit.rms_before;
  out["max_before"] = c.fit.max_before;
  out["rms_after"] = c.fit.rms_after;
  out["max_after"] = c.fit.max_after;
  out["hole"] = c.hole;
  out["outlier_distance"] = c.outlier_distance;
  out["outliers"] = c.outliers;
  out["points"] = points_of(c);
  out["zones"] = zones_of(c);
  return out;
}

// The compare tool on a whole stream: `nominal` a file (mesh, stream or CSV points) or a
// Stream; the tables fits, deviations, zones, compared and verdicts added to a copy of
// `measured`, and every section a tolerance names but the stream lacks judged not measured
// (the tool says those in its report and exit code).
Stream compare_measured(const Stream& measured, const py::object& nominal, const py::kwargs& kwargs) {
  for (const char* own : {"nominal", "format", "report"})
    if (kwargs.contains(own))
      throw py::value_error(std::string("compare_stream: ") + own +
                            " is the tool's; pass the nominal as the second argument, and "
                            "compare_report(stream) or verdict(stream) for the outcome");
  const tool::CompareArgs a = tool_args<tool::CompareArgs>(kwargs, {"--nominal", "-"});
  const bool given_stream = py::isinstance<Stream>(nominal);
  if (given_stream && !a.nominal_units.empty())
    throw py::value_error("compare_stream: nominal_units: a stream says its own unit (# units)");
  std::string path;
  NominalFile file;
  if (given_stream) {
    file.stream = nominal.cast<const Stream&>();
    file.kind = NominalFile::Kind::stream;
    file.name = "the nominal stream";
  } else {
    path = py::str(py::module_::import("os").attr("fspath")(nominal)).cast<std::string>();
  }
  Stream out = measured;
  {
    py::gil_scoped_release unlocked;
    CompareStreamOptions o = a.options;
    if (!a.tolerances.empty()) o.tolerances = read_tolerances(a.tolerances, tolerance_items());
    if (given_stream)
      convert_to_mm(file.stream);
    else
      file = read_nominal(path, a.nominal_units);
    convert_to_mm(out);
    const std::map<int, Frame> frames =
        schema::frames.find(out) ? section::frames(out) : std::map<int, Frame>{};
    compare_stream(out, nominal_stream(file.source(), frames, o), o);
    judge_absent_sections(out, o);
  }
  if (!file.units.warning.empty())
    PyErr_WarnEx(PyExc_UserWarning, ("compare_stream: " + path + ": " + file.units.warning).c_str(), 1);
  out.history.push_back(history("compare_stream", kwargs));
  return out;
}

std::string verdict_of(const Stream& compared) {
  switch (stream_verdict(compared)) {
    case 1:
      return "failed";
    case 2:
      return "not measured";
    case 3:
      return "uncertain";
    default:
      return "passed";
  }
}

}  // namespace

void bind_compare(py::module_& m) {
  py::class_<Nominal>(m, "Nominal",
                      "A nominal profile prepared once for comparing many measured sections with it "
                      "(its arc length, zones and foot search are built here, not per call).")
      .def(py::init(&make_nominal), py::arg("spline"), py::arg("le_point"), py::arg("te_point"),
           py::arg("pressure_side") = -1,
           "Nominal(spline, le_point, te_point, pressure_side=-1, **flags): a closed Spline, its edge "
           "points (u, v) and pressure side (+1: left of LE -> TE, -1: right; camber's params), and the "
           "compare tool's flags as keywords (fit='minimum-zone', freedom='translation', edge_zone=0.05, "
           "keep_outliers=True, ...). Raises ValueError for a profile that is not closed or edge points "
           "that leave no room for the sides.")
      .def_property_readonly("edge_zone", [](const Nominal& n) { return n.options.edge_zone; });
  m.def("compare_points", &compare_points, py::arg("nominal"), py::arg("points"));
  m.def("compare_stream", &compare_measured, py::arg("stream"), py::arg("nominal"));
  m.def("verdict", &verdict_of, py::arg("stream"),
        "The worst verdict of a compared stream: 'failed', 'not measured', 'uncertain' or 'passed' "
        "(the compare tool's exit codes 4, 5, 6 and 0; 'passed' also when nothing was toleranced).");
  m.def(
      "compare_report", [](const Stream& s) { return compare_report(s); }, py::arg("stream"),
      "The compare tool's report of a compared stream (its --report text): per section, each toleranced "
      "value with its verdict.");
}

}  // namespace section::python
