#pragma once
/// @file
/// @brief What every translation unit of the Python module shares: the bound types (double,
/// Sparse), numpy conversions that check shape and dtype and raise massspring.Error with a clear
/// message, and the functions that add each concept to the module (one file each).

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>  // in every file: the casters must be the same everywhere

#include <Eigen/Core>
#include <algorithm>
#include <initializer_list>
#include <massspring/massspring.hpp>
#include <string>
#include <vector>

namespace massspring::python {

namespace py = pybind11;

/// @brief The one system type the module binds: double precision, sparse storage.
using System = MassSpringSystem<double, Sparse>;
using Points = massspring::Points<double>;
using Vec = massspring::Vector<double>;
using Vec3 = massspring::Vector3<double>;
/// @brief A row-major matrix of any shape, for input whose shape the library itself checks.
using AnyMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using IndexMatrix = Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// ---- numpy input (arrays.cpp) -------------------------------------------------------------------
// Each accepts anything numpy.asarray accepts. Real input (floating, integer or bool dtypes is not
// accepted: only integer and floating kinds) is converted to float64; index input must have an
// integer dtype with values that fit an int. Anything else raises massspring.Error naming `what`,
// the expected shape and what was given: never a crash.

/// @brief A 2-D real array, `cols` columns (any number of rows), as float64.
AnyMatrix real_matrix(py::handle obj, const std::string& what, Eigen::Index cols);
/// @brief A 2-D integer array, `cols` columns, as int.
IndexMatrix index_matrix(py::handle obj, const std::string& what, Eigen::Index cols);
/// @brief A 1-D real array of `size` entries (size < 0: any), or a scalar broadcast to `size`
/// when `scalar_ok` (size must then be >= 0).
Vec real_vector(py::handle obj, const std::string& what, Eigen::Index size, bool scalar_ok = false);
/// @brief A 1-D integer array (any size) as ints.
std::vector<int> index_vector(py::handle obj, const std::string& what);
/// @brief Three real numbers (a point, a direction, an acceleration).
Vec3 vector3(py::handle obj, const std::string& what);
/// @brief A 3 x 3 real matrix.
Eigen::Matrix3d matrix3(py::handle obj, const std::string& what);

// ---- numpy output
// --------------------------------------------------------------------------------

/// @brief A new float64 numpy array holding a copy of `m` (any Eigen dense expression).
template <class Derived>
py::array_t<double> copy_array(const Eigen::DenseBase<Derived>& m, bool vector = false) {
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> c =
      m.template cast<double>();
  if (vector) {
    py::array_t<double> out(c.size());
    std::copy(c.data(), c.data() + c.size(), out.mutable_data());
    return out;
  }
  py::array_t<double> out({c.rows(), c.cols()});
  std::copy(c.data(), c.data() + c.size(), out.mutable_data());
  return out;
}

/// @brief A new (k, 2) int32 numpy array holding a copy of `edges` (point index pairs).
inline py::array_t<int> copy_edges(const Edges& edges) {
  py::array_t<int> out({edges.rows(), Eigen::Index(2)});
  std::copy(edges.data(), edges.data() + edges.size(), out.mutable_data());  // row-major
  return out;
}

/// @brief A read-only (n, 3) float64 view of `points` (row-major, so C-contiguous) that keeps
/// `owner` alive: no copy. The view follows the buffer, so it shows later steps too.
py::array_t<double> points_view(const Points& points, py::handle owner);

// ---- objects in use by a call that released the GIL (module.cpp) -----------------------------

/// @brief Marks a system and an integrator (or guard) as in use while a call runs without the GIL,
/// so that a call on one of them from another thread raises massspring.Error instead of racing
/// (one system and one integrator per thread). Made and destroyed with the GIL held: make it
/// before the py::gil_scoped_release.
class InUse {
 public:
  InUse(std::initializer_list<const void*> objects, const char* what);
  ~InUse();
  InUse(const InUse&) = delete;
  InUse& operator=(const InUse&) = delete;

 private:
  std::vector<const void*> objects_;
};

/// @brief Throws massspring.Error when `object` is in use by a call in another thread (`what`
/// names the refused call). With the GIL held.
void check_idle(const void* object, const char* what);

// ---- the parts of the module, each in its own file --------------------------------------------

void bind_errors(py::module_& m);  // module.cpp
void bind_system(py::module_& m);  // system.cpp
void bind_forces(py::module_& m);  // forces.cpp (after bind_system)
/// @brief An argument read by the numpy input functions above (any array-like), named
/// "ArrayLike" in signatures and help() instead of pybind11's "handle".
struct ArrayLike {
  py::object value;
  operator py::handle() const { return value; }  // NOLINT: passed on as it is
};

void bind_colliders(py::module_& m);             // colliders.cpp (after bind_system)
void bind_step_report(py::module_& m);           // module.cpp
void bind_fast_mass_spring(py::module_& m);      // fast_mass_spring.cpp
void bind_explicit_integrators(py::module_& m);  // explicit_integrators.cpp
void bind_backward_euler(py::module_& m);        // backward_euler.cpp
void bind_scene_files(py::module_& m);           // scene_files.cpp
void bind_diagnostics(py::module_& m);           // diagnostics.cpp (before the integrators)
void bind_scenes(py::module_& m);                // scenes.cpp

/// @brief The Python class of System (bound in system.cpp), to add methods from other files.
inline py::class_<System> system_class(py::module_& m) {
  return py::reinterpret_borrow<py::class_<System>>(m.attr("MassSpringSystem"));
}

}  // namespace massspring::python

namespace pybind11::detail {

/// @brief Takes any Python object as an ArrayLike (checked by the function that reads it).
template <>
struct type_caster<massspring::python::ArrayLike> {
  PYBIND11_TYPE_CASTER(massspring::python::ArrayLike, const_name("ArrayLike"));
  bool load(handle source, bool) {
    value.value = reinterpret_borrow<object>(source);
    return true;
  }
  static handle cast(const massspring::python::ArrayLike& a, return_value_policy, handle) {
    return a.value.inc_ref();
  }
};

}  // namespace pybind11::detail
