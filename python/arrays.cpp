// numpy in and out: every shape and dtype checked here raises massspring.Error (a ValueError)
// naming the argument, what was expected and what was given.

#include <climits>
#include <cmath>
#include <massspring/detail/validate.hpp>

#include "bindings.hpp"

namespace massspring::python {

namespace {

// "array of dtype float64 and shape (4, 2)"
std::string describe(const py::array& a) {
  std::string shape = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) shape += (d ? ", " : "") + std::to_string(a.shape(d));
  if (a.ndim() == 1) shape += ",";
  shape += ")";
  return "array of dtype " + std::string(py::str(a.dtype())) + " and shape " + shape;
}

py::array as_array(py::handle obj, const std::string& what) {
  try {
    return py::module_::import("numpy").attr("asarray")(obj);
  } catch (const py::error_already_set& e) {
    throw Error(what + ": not convertible to a numpy array (" + e.what() + ")");
  }
}

bool is_real(const py::array& a) {
  return a.dtype().kind() == 'f' || a.dtype().kind() == 'i' || a.dtype().kind() == 'u';
}
bool is_integer(const py::array& a) { return a.dtype().kind() == 'i' || a.dtype().kind() == 'u'; }

// The array as C-contiguous float64 (converted from any real dtype).
py::array_t<double, py::array::c_style> as_double(const py::array& a) {
  return py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
}

// The array as C-contiguous int64, each value checked to fit an int.
py::array_t<long long, py::array::c_style> as_index(const py::array& a, const std::string& what) {
  // uint64 beyond int64 would wrap in the conversion: check against the original first
  const py::object numpy = py::module_::import("numpy");
  if (a.size() > 0) {
    const py::object lo = numpy.attr("min")(a), hi = numpy.attr("max")(a);
    const py::int_ int_min(INT_MIN), int_max(INT_MAX);
    if (lo < int_min || hi > int_max)
      throw Error(what + ": index values must fit a 32-bit int, got values in [" +
                  std::string(py::str(lo)) + ", " + std::string(py::str(hi)) + "]");
  }
  return py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(a);
}

}  // namespace

AnyMatrix real_matrix(py::handle obj, const std::string& what, Eigen::Index cols) {
  const py::array a = as_array(obj, what);
  const std::string expected = "expected a real (float64) array of shape (#rows, " +
                               std::to_string(cols) + "), got an " + describe(a);
  if (!is_real(a)) throw Error(what + ": " + expected);
  if (a.ndim() != 2 || a.shape(1) != cols) {
    // an empty list has shape (0,): accept it as no rows
    if (!(a.ndim() == 1 && a.shape(0) == 0)) throw Error(what + ": " + expected);
    return AnyMatrix(0, cols);
  }
  const auto d = as_double(a);
  return Eigen::Map<const AnyMatrix>(d.data(), a.shape(0), cols);
}

IndexMatrix index_matrix(py::handle obj, const std::string& what, Eigen::Index cols) {
  const py::array a = as_array(obj, what);
  const std::string expected = "expected an integer array of shape (#rows, " +
                               std::to_string(cols) + "), got an " + describe(a);
  if (a.ndim() == 1 && a.shape(0) == 0) return IndexMatrix(0, cols);
  if (!is_integer(a) || a.ndim() != 2 || a.shape(1) != cols) throw Error(what + ": " + expected);
  const auto d = as_index(a, what);
  return Eigen::Map<
             const Eigen::Matrix<long long, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
             d.data(), a.shape(0), cols)
      .cast<int>();
}

Vec real_vector(py::handle obj, const std::string& what, Eigen::Index size, bool scalar_ok) {
  const py::array a = as_array(obj, what);
  const std::string want =
      size >= 0 ? "of shape (" + std::to_string(size) + ",)" : std::string("of one dimension");
  const std::string expected = "expected a real (float64) array " + want +
                               (scalar_ok ? " or a number" : "") + ", got an " + describe(a);
  if (!is_real(a)) throw Error(what + ": " + expected);
  if (a.ndim() == 0 && scalar_ok && size >= 0) return Vec::Constant(size, as_double(a).data()[0]);
  if (a.ndim() != 1 || (size >= 0 && a.shape(0) != size)) throw Error(what + ": " + expected);
  const auto d = as_double(a);
  return Eigen::Map<const Vec>(d.data(), a.shape(0));
}

std::vector<int> index_vector(py::handle obj, const std::string& what) {
  const py::array a = as_array(obj, what);
  if (a.ndim() == 1 && a.shape(0) == 0) return {};
  if (!is_integer(a) || a.ndim() != 1)
    throw Error(what + ": expected a one-dimensional integer array, got an " + describe(a));
  const auto d = as_index(a, what);
  return std::vector<int>(d.data(), d.data() + a.shape(0));
}

Vec3 vector3(py::handle obj, const std::string& what) { return real_vector(obj, what, 3); }

Eigen::Matrix3d matrix3(py::handle obj, const std::string& what) {
  const py::array a = as_array(obj, what);
  if (!is_real(a) || a.ndim() != 2 || a.shape(0) != 3 || a.shape(1) != 3)
    throw Error(what + ": expected a real (float64) array of shape (3, 3), got an " + describe(a));
  const auto d = as_double(a);
  return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d.data());
}

py::array_t<double> points_view(const Points& points, py::handle owner) {
  // Rows of 3 doubles, contiguous (Points is row-major): strides (24, 8) bytes.
  py::array_t<double> view({points.rows(), Eigen::Index(3)},
                           {Eigen::Index(3 * sizeof(double)), Eigen::Index(sizeof(double))},
                           points.data(), owner);
  // read-only: writes go through the validating setters (sys.positions = x)
  view.attr("setflags")(py::arg("write") = false);
  return view;
}

}  // namespace massspring::python
