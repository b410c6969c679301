// SPDX-License-Identifier: GPL-3.0-or-later
// The stream, the B-spline and the file readers as Python objects.
#include "convert.h"

#include "section/checks.h"
#include "section/io/cloud_io.h"
#include "section/io/csv.h"
#include "section/io/progress_io.h"
#include "section/io/stream.h"
#include "section/pipe/fit_spline_stream.h"

#include <pybind11/stl.h>

namespace section::python {

namespace {

py::list issue_list(const Stream& s) {
  py::list out;
  for (const auto& i : s.issues)
    out.append(py::dict(py::arg("section") = i.section, py::arg("loop") = i.loop, py::arg("stage") = i.stage,
                        py::arg("message") = i.message));
  return out;
}

std::vector<std::string> table_names(const Stream& s) {
  std::vector<std::string> out;
  for (const auto& t : s.tables) out.push_back(t.name);
  return out;
}

const Table& table_of(const Stream& s, const std::string& name) {
  if (const Table* t = s.find(name)) return *t;
  std::string known;
  for (const auto& t : s.tables) known += (known.empty() ? "" : ", ") + t.name;
  throw py::key_error("the stream has no '" + name + "' table (it has: " + known + ")");
}

void bind_stream_class(py::module_& m) {
  py::class_<Stream>(m, "Stream",
                     "The pipe stream that slice | smooth | fitspline | camber pass along (docs/FORMAT.md): "
                     "named numeric tables, units, history and per-section issues.")
      .def(py::init<>())
      .def_readonly("units", &Stream::units, "length unit of every coordinate")
      .def_readonly("history", &Stream::history, "one line per stage that wrote the stream")
      .def_readonly("notes", &Stream::notes, "free '# key value' lines")
      .def_property_readonly("issues", &issue_list,
                             "sections (or loops) that failed: dicts section, loop, stage, message")
      .def_property_readonly("tables", &table_names, "names of the tables, in stream order")
      .def(
          "table", [](const Stream& s, const std::string& name) { return table_dict(table_of(s, name)); },
          py::arg("name"),
          "A table as a dict: column name -> 1-D float64 array (pandas.DataFrame(...) takes it).")
      .def("__getitem__",
           [](const Stream& s, const std::string& name) { return table_dict(table_of(s, name)); })
      .def("__contains__", [](const Stream& s, const std::string& name) { return s.find(name) != nullptr; })
      .def_property_readonly(
          "params", [](const Stream& s) { return table_dict(table_of(s, "params")); },
          "The params table (written by camber): column -> array, one row per section.")
      .def(
          "csv", [](const Stream& s, const std::string& name) { return format_csv(table_of(s, name)); },
          py::arg("name"), "A table as the CSV the tools write (camber --params): header, then the rows.")
      .def("text", &format_stream, "The whole stream as text (what the tools write).")
      .def(
          "write", [](const Stream& s, const std::string& path) { write_stream(path, s); }, py::arg("path"),
          "Writes the stream to a file ('-' = standard output).")
      .def(
          "splines", [](const Stream& s) { return splines(s); },
          "The fitted splines (written by fitspline): dict (section, loop) -> Spline.")
      .def("__repr__", [](const Stream& s) {
        return "<libsection.Stream: " + std::to_string(s.tables.size()) + " tables, " +
               std::to_string(s.issues.size()) + " issues, units " + s.units + ">";
      });
}

py::array evaluate(const BSpline& b, const Array& t, int k) {
  const double* p = t.data();
  std::vector<Eigen::Vector2d> out;
  for (py::ssize_t i = 0; i < t.size(); ++i) out.push_back(b.derivative(p[i], k));
  Array a = array2(out);
  if (t.ndim() == 0) return a.reshape({2});
  return a;
}

void bind_spline(py::module_& m) {
  py::class_<BSpline>(m, "Spline",
                      "A planar B-spline (bspline.h): closed curves store n control points and the n + 1 "
                      "breakpoints of one period.")
      .def(py::init([](int degree, const Array& knots, const Array& control, bool closed) {
             BSpline b;
             b.degree = degree;
             b.closed = closed;
             b.knots.assign(knots.data(), knots.data() + knots.size());
             b.control = points2(control, "control");
             (void)b.point(b.knots.empty() ? 0 : b.knots.front());  // checks the counts
             return b;
           }),
           py::arg("degree"), py::arg("knots"), py::arg("control"), py::arg("closed") = true)
      .def_readonly("degree", &BSpline::degree)
      .def_readonly("closed", &BSpline::closed)
      .def_property_readonly("knots", [](const BSpline& b) { return array1(b.knots); })
      .def_property_readonly("control", [](const BSpline& b) { return array2(b.control); })
      .def_property_readonly("t_min", &BSpline::t_min)
      .def_property_readonly("t_max", &BSpline::t_max)
      .def(
          "__call__", [](const BSpline& b, const Array& t) { return evaluate(b, t, 0); }, py::arg("t"),
          "Points at parameters t: shape (2,) for a number, (N, 2) for N parameters.")
      .def(
          "derivative", [](const BSpline& b, const Array& t, int k) { return evaluate(b, t, k); },
          py::arg("t"), py::arg("k") = 1, "k-th derivatives at parameters t.")
      .def("curvature", &BSpline::curvature, py::arg("t"),
           "Signed curvature at t (counterclockwise positive).")
      .def("clamped", &clamped, "The same curve with a clamped knot vector (as DXF and IGES write it).")
      .def(
          "sample", [](const BSpline& b, int count) { return array2(sample(b, count)); }, py::arg("count"),
          "count points spread evenly in parameter (closed: the end point not repeated).")
      .def("__repr__", [](const BSpline& b) {
        return "<libsection.Spline: degree " + std::to_string(b.degree) + ", " +
               std::to_string(b.control.size()) + " control points, " + (b.closed ? "closed" : "open") + ">";
      });
}

}  // namespace

void bind_stream(py::module_& m) {
  bind_stream_class(m);
  bind_spline(m);
  m.def("read_stream", &read_stream, py::arg("path"), py::call_guard<py::gil_scoped_release>(),
        "Reads a stream written by the tools (a file, or '-' for standard input).");
  m.def(
      "parse_stream",
      [](const std::string& text, const std::string& source) { return parse_stream(text, source); },
      py::arg("text"), py::arg("source") = "<string>", "Parses a stream held in a string.");
  m.def(
      "read_cloud",
      [](const std::string& path, const py::object& progress) {
        const ProgressFn fn = progress_fn(progress);
        Cloud c;
        {
          py::gil_scoped_release unlocked;
          c = fn ? read_cloud(path, {}, fn) : read_cloud(path);
        }
        return array3(c.points);
      },
      py::arg("path"), py::arg("progress") = py::none(),
      "Reads a point cloud file (.xyz .asc .txt .csv .ply) as an (N, 3) array; progress(stage, done, total) "
      "is told the points read and cancels the reading by returning False.");
  m.def(
      "failed_checks",
      [](double flags, const py::object& column) {
        const CheckBits mask = flags_mask(flags);
        const CheckBits bits =
            column.is_none() ? mask : checks_flagging(mask, column.cast<std::string>().c_str());
        std::vector<std::string> names;
        for (const auto& c : check_names)
          if (bits & bit(c.check)) names.push_back(c.name);
        return names;
      },
      py::arg("flags"), py::arg("column") = py::none(),
      "The names of the checks a flags value holds (a params or thickness row's 'flags'), in bit order; with "
      "column, those that flag that params column ('max_thickness', 'le_radius', ...): a value they name is "
      "not to be trusted bare (docs/CAMBER.md, 'Checks').");
}

}  // namespace section::python
