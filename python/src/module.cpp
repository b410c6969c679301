// SPDX-License-Identifier: GPL-3.0-or-later
// The Python module libsection._libsection: the pipe's stages on numpy arrays and streams.
// python/libsection/__init__.py builds the public functions on it.
#include "convert.h"

#include "section/error.h"
#include "section/progress.h"

namespace section::python {
void bind_stream(py::module_& m);
void bind_stages(py::module_& m);
void bind_generate(py::module_& m);
void bind_compare(py::module_& m);
}  // namespace section::python

PYBIND11_MODULE(_libsection, m) {
  m.doc() = "libsection: blade section inspection (slice, smooth, fit_spline, camber) on numpy arrays";
  const auto& error = pybind11::register_exception<section::Error>(m, "Error", PyExc_ValueError);
  pybind11::register_exception<section::Cancelled>(m, "Cancelled", error.ptr());
  section::python::bind_stream(m);
  section::python::bind_stages(m);
  section::python::bind_generate(m);
  section::python::bind_compare(m);
}
