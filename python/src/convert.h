// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What the bindings share: numpy arrays to and from Eigen points, Python keywords to a
// tool's command line (tools/args/), and the stream as a Python object.
#include "common/tool.h"
#include "section/bspline.h"
#include "section/io/stream.h"
#include "section/progress.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>

#include <sstream>
#include <string>
#include <vector>

namespace section::python {

namespace py = pybind11;

/// A float64 array in C order (converted from any numeric array-like).
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// Rows of an (N, 2) or (N, 3) array as points; throws ValueError naming `what` on another
/// shape or a value that is not finite.
std::vector<Eigen::Vector2d> points2(const Array& a, const char* what);
std::vector<Eigen::Vector3d> points3(const Array& a, const char* what);

/// Points as an (N, 2) or (N, 3) array.
Array array2(const std::vector<Eigen::Vector2d>& points);
Array array3(const std::vector<Eigen::Vector3d>& points);
/// Numbers as a 1-D array.
Array array1(const std::vector<double>& values);

/// A keyword argument as command-line words: `--name value` (underscores as dashes; a
/// sequence comma-joined, numbers in the shortest round-trip form), `--name` alone for
/// True, nothing for False or None.
void add_flag(std::vector<std::string>& words, const std::string& name, const py::handle& value);

/// The history line of a stage run from Python: `libsection.NAME` and the flags given.
std::string history(const char* name, const py::kwargs& kwargs);

/// The tool's command line made of `kwargs` (and `extra` words first) read into its `Args`,
/// as the tool reads its own; bad usage raises ValueError with the tool's message.
template <class Args>
Args tool_args(const py::kwargs& kwargs, std::vector<std::string> words = {}) {
  for (const auto& [key, value] : kwargs) add_flag(words, py::cast<std::string>(key), value);
  words.insert(words.begin(), Args::name);
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  Args args;
  std::ostringstream out, err;
  const int code = tool::parse(static_cast<int>(argv.size()), argv.data(), args, out, err);
  if (code >= 0) {
    std::string message = err.str().empty() ? out.str() : err.str();
    const std::size_t run = message.find("\nRun '");
    throw py::value_error(message.substr(0, run));
  }
  return args;
}

/// A Python callable fn(stage, done, total) as a ProgressFn (None: none); it runs with the
/// GIL held, and a return value of False cancels the call (section::Cancelled).
ProgressFn progress_fn(const py::object& fn);

/// The stream's tables as Python sees them.
py::dict table_dict(const Table& table);

}  // namespace section::python
