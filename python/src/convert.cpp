// SPDX-License-Identifier: GPL-3.0-or-later
// What the bindings share.
#include "convert.h"

#include <cmath>

namespace section::python {

namespace {

template <int D>
std::vector<Eigen::Matrix<double, D, 1>> points(const Array& a, const char* what) {
  if (a.ndim() != 2 || a.shape(1) != D)
    throw py::value_error(
        std::string(what) + ": expected an array of shape (N, " + std::to_string(D) + "), got " +
        std::to_string(a.ndim()) + " dimensions" +
        (a.ndim() == 2 ? " of shape (" + std::to_string(a.shape(0)) + ", " + std::to_string(a.shape(1)) + ")"
                       : std::string()));
  std::vector<Eigen::Matrix<double, D, 1>> out(static_cast<std::size_t>(a.shape(0)));
  const double* p = a.data();
  for (std::size_t i = 0; i < out.size(); ++i)
    for (int k = 0; k < D; ++k) {
      const double v = p[i * D + k];
      if (!std::isfinite(v))
        throw py::value_error(std::string(what) + ": row " + std::to_string(i) +
                              " holds a value that is not finite");
      out[i][k] = v;
    }
  return out;
}

template <int D>
Array array(const std::vector<Eigen::Matrix<double, D, 1>>& points) {
  Array out({static_cast<py::ssize_t>(points.size()), static_cast<py::ssize_t>(D)});
  double* p = out.mutable_data();
  for (std::size_t i = 0; i < points.size(); ++i)
    for (int k = 0; k < D; ++k) p[i * D + k] = points[i][k];
  return out;
}

std::string word(const py::handle& v) {
  if (py::isinstance<py::bool_>(v)) return v.cast<bool>() ? "1" : "0";
  if (py::isinstance<py::int_>(v)) return std::to_string(v.cast<long long>());
  if (py::isinstance<py::float_>(v)) return format_number(v.cast<double>());
  if (py::isinstance<py::str>(v)) return v.cast<std::string>();
  if (py::hasattr(v, "__fspath__")) return py::str(v.attr("__fspath__")()).cast<std::string>();
  if (py::hasattr(v, "item") && py::hasattr(v, "ndim") && v.attr("ndim").cast<int>() == 0)
    return word(v.attr("item")());  // a numpy scalar
  throw py::type_error("cannot pass a " +
                       py::str(py::type::handle_of(v).attr("__name__")).cast<std::string>() +
                       " as an option");
}

}  // namespace

std::vector<Eigen::Vector2d> points2(const Array& a, const char* what) {
  return points<2>(a, what);
}
std::vector<Eigen::Vector3d> points3(const Array& a, const char* what) {
  return points<3>(a, what);
}
Array array2(const std::vector<Eigen::Vector2d>& p) {
  return array<2>(p);
}
Array array3(const std::vector<Eigen::Vector3d>& p) {
  return array<3>(p);
}
Array array1(const std::vector<double>& values) {
  Array out(static_cast<py::ssize_t>(values.size()));
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

void add_flag(std::vector<std::string>& words, const std::string& name, const py::handle& value) {
  std::string flag = "--" + name;
  for (char& c : flag)
    if (c == '_') c = '-';
  if (value.is_none() || (py::isinstance<py::bool_>(value) && !value.cast<bool>())) return;
  words.push_back(flag);
  if (py::isinstance<py::bool_>(value)) return;
  const bool sequence = !py::isinstance<py::str>(value) && py::hasattr(value, "__iter__") &&
                        !(py::hasattr(value, "ndim") && value.attr("ndim").cast<int>() == 0);
  if (!sequence) {
    words.push_back(word(value));
    return;
  }
  std::string joined;
  for (const auto& item : value) joined += (joined.empty() ? "" : ",") + word(item);
  words.push_back(joined);
}

ProgressFn progress_fn(const py::object& fn) {
  if (fn.is_none()) return {};
  return [fn](const ProgressEvent& e) {
    py::gil_scoped_acquire locked;
    const py::object answer = fn(e.stage, e.done, e.total);
    return answer.is_none() || answer.cast<bool>();
  };
}

py::dict table_dict(const Table& t) {
  py::dict out;
  const std::size_t rows = t.rows(), cols = t.columns.size();
  for (std::size_t c = 0; c < cols; ++c) {
    Array column(static_cast<py::ssize_t>(rows));
    double* p = column.mutable_data();
    for (std::size_t r = 0; r < rows; ++r) p[r] = t.values[r * cols + c];
    out[py::str(t.columns[c])] = column;
  }
  return out;
}

std::string history(const char* name, const py::kwargs& kwargs) {
  std::vector<std::string> words;
  for (const auto& [key, value] : kwargs) add_flag(words, py::cast<std::string>(key), value);
  std::string line = std::string("libsection.") + name;
  for (const auto& w : words) line += " " + w;
  return line;
}

}  // namespace section::python
