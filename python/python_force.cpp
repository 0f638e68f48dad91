// massspring.PythonForce: a force term written in Python. forces(x, v) -> f gives the force
// (x, v, f: (n, 3) float64 arrays in m, m/s and N); jacobian(x, v) -> (dfdx, dfdv), optional, gives
// dF/dx [N/m] and dF/dv [N s/m] as 3n x 3n matrices (coordinate 3 i + a is point i's axis a), each
// a scipy.sparse matrix, a dense array or None (zero).
//
// In the system the term is one of two C++ terms (forces/force_term.hpp): PythonTerm, without
// Jacobians (the explicit integrators and FastMassSpring evaluate its force only, as for any
// term), and PythonJacobianTerm, whose add_dfdx/add_dfdv hand the matrices to BackwardEuler. Each
// evaluation takes the GIL (the steps run without it) and copies x and v into new arrays.
//
// A JacobianSink needs the same entries at every call. The pattern of a term's matrix is the
// entries of its first call at a system size: a sparse matrix's stored entries (explicit zeros
// included), every entry of a dense one. Later calls may leave pattern entries out (zero) but not
// put a nonzero outside it.

#include "python_force.hpp"

#include <algorithm>
#include <memory>
#include <string>
#include <typeinfo>
#include <utility>
#include <vector>

namespace massspring::python {

namespace {

// The callables and the term's name, shared by every copy of a term (a system's copies too).
struct Callbacks {
  py::object forces, jacobian;  // jacobian: None when not given
  std::string name;
  bool symmetric = false;

  Callbacks() = default;
  Callbacks(const Callbacks&) = delete;
  Callbacks& operator=(const Callbacks&) = delete;
  ~Callbacks() {
    if (!Py_IsInitialized()) {  // at interpreter exit: nothing left to release them to
      forces.release();
      jacobian.release();
      return;
    }
    const py::gil_scoped_acquire gil;
    forces = py::object();
    jacobian = py::object();
  }
};

// What the Python class holds: its callables, shared with the terms added from it.
struct PythonForce {
  std::shared_ptr<const Callbacks> callbacks;
};

std::string label(const Callbacks& cb) { return "PythonForce \"" + cb.name + "\""; }

// f += forces(x, v), with the GIL; a wrong shape or dtype raises massspring.Error naming the term.
void add_python_forces(const Callbacks& cb, const ForceContext<double>& c, Points& f) {
  const py::gil_scoped_acquire gil;
  const py::object out = cb.forces(copy_array(c.x), copy_array(c.v));
  const std::string what = label(cb) + ": forces(x, v)";
  const AnyMatrix r = real_matrix(out, what, 3);
  if (r.rows() != c.x.rows())
    throw Error(detail::message(what, ": expected a real (float64) array of shape (", c.x.rows(),
                                ", 3), one row per point, got ", r.rows(), " rows"));
  f += r;
}

// One matrix as coordinate entries (repeated entries add up).
struct Entries {
  std::vector<int> rows, cols;
  std::vector<double> values;
};

// The entries of a returned dF/dx or dF/dv: None (no entries), a scipy.sparse matrix (its stored
// entries, through tocoo()) or anything numpy.asarray takes (every entry); dim x dim.
Entries entries_of(py::handle m, Eigen::Index dim, const std::string& what) {
  Entries e;
  if (m.is_none()) return e;
  const std::string shape_wanted = detail::message("expected a matrix of shape (", dim, ", ", dim,
                                                   ") (3 n by 3 n, n = ", dim / 3, " points)");
  if (py::hasattr(m, "tocoo")) {
    const py::object coo = m.attr("tocoo")();
    const py::tuple shape = coo.attr("shape");
    const auto rows = shape[0].cast<long long>(), cols = shape[1].cast<long long>();
    if (rows != dim || cols != dim)
      throw Error(detail::message(what, ": ", shape_wanted, ", got a sparse one of shape (", rows,
                                  ", ", cols, ")"));
    e.rows = index_vector(coo.attr("row"), what + " (its rows)");
    e.cols = index_vector(coo.attr("col"), what + " (its columns)");
    const Vec v =
        real_vector(coo.attr("data"), what + " (its values)", Eigen::Index(e.rows.size()));
    e.values.assign(v.data(), v.data() + v.size());
    return e;
  }
  const AnyMatrix d = real_matrix(m, what, dim);
  if (d.rows() != dim)
    throw Error(detail::message(what, ": ", shape_wanted, ", got ", d.rows(), " rows"));
  const auto size = std::size_t(dim * dim);
  e.rows.reserve(size);
  e.cols.reserve(size);
  e.values.reserve(size);
  for (Eigen::Index r = 0; r < dim; ++r)
    for (Eigen::Index c = 0; c < dim; ++c) {
      e.rows.push_back(int(r));
      e.cols.push_back(int(c));
      e.values.push_back(d(r, c));
    }
  return e;
}

// A matrix with the pattern of the first call at a size (see the file): take() this call's
// entries, then emit() the pattern's entries in the same order at every call.
class PatternedMatrix {
 public:
  void take(const Entries& e, Eigen::Index dim, const std::string& what) {
    if (dim != dim_) {
      pattern_.clear();
      for (std::size_t k = 0; k < e.rows.size(); ++k) pattern_.emplace_back(e.rows[k], e.cols[k]);
      std::sort(pattern_.begin(), pattern_.end());
      pattern_.erase(std::unique(pattern_.begin(), pattern_.end()), pattern_.end());
      dim_ = dim;
    }
    values_.assign(pattern_.size(), 0.0);
    for (std::size_t k = 0; k < e.rows.size(); ++k) {
      const std::pair<int, int> at(e.rows[k], e.cols[k]);
      if (at.first < 0 || at.first >= dim || at.second < 0 || at.second >= dim)
        throw Error(detail::message(what, ": entry (", at.first, ", ", at.second,
                                    ") out of range [0, ", dim, ")"));
      const auto it = std::lower_bound(pattern_.begin(), pattern_.end(), at);
      if (it == pattern_.end() || *it != at) {
        if (e.values[k] != 0.0)
          throw Error(detail::message(
              what, ": nonzero entry (", at.first, ", ", at.second,
              ") outside the pattern of its first call: return the same sparsity pattern at "
              "every call (explicit zeros count), or a dense matrix"));
        continue;
      }
      values_[std::size_t(it - pattern_.begin())] += e.values[k];
    }
  }
  void emit(JacobianSink<double>& sink) const {
    for (std::size_t k = 0; k < pattern_.size(); ++k)
      sink.add(pattern_[k].first, pattern_[k].second, values_[k]);
  }

 private:
  Eigen::Index dim_ = -1;
  std::vector<std::pair<int, int>> pattern_;
  std::vector<double> values_;
};

// A term without Jacobians: its force only.
class PythonTerm {
 public:
  explicit PythonTerm(std::shared_ptr<const Callbacks> cb) : cb_(std::move(cb)) {}
  static constexpr bool velocity_dependent = true;  // forces(x, v) may read v
  [[nodiscard]] const char* name() const { return cb_->name.c_str(); }
  void add_force(const ForceContext<double>& c, Points& f) const { add_python_forces(*cb_, c, f); }

 private:
  std::shared_ptr<const Callbacks> cb_;
};

// A term with Jacobians. jacobian(x, v) is called once per state: add_dfdx and add_dfdv at the
// same (x, v) share one call. `Symmetric`: the user's promise that dF/dx and dF/dv are symmetric
// (BackwardEuler may then use Cholesky); otherwise an LU.
template <bool Symmetric>
class PythonJacobianTerm {
 public:
  explicit PythonJacobianTerm(std::shared_ptr<const Callbacks> cb) : cb_(std::move(cb)) {}
  static constexpr bool velocity_dependent = true;
  static constexpr bool symmetric = Symmetric;
  [[nodiscard]] const char* name() const { return cb_->name.c_str(); }
  void add_force(const ForceContext<double>& c, Points& f) const { add_python_forces(*cb_, c, f); }
  void add_dfdx(const ForceContext<double>& c, JacobianSink<double>& sink) const {
    evaluate(c);
    dfdx_.emit(sink);
  }
  void add_dfdv(const ForceContext<double>& c, JacobianSink<double>& sink) const {
    evaluate(c);
    dfdv_.emit(sink);
  }

 private:
  // jacobian(x, v) into dfdx_ and dfdv_, unless they already hold it for this (x, v).
  void evaluate(const ForceContext<double>& c) const {
    if (x_.rows() == c.x.rows() && x_ == c.x && v_ == c.v) return;
    x_.resize(0, 3);  // not valid until both matrices are taken
    const py::gil_scoped_acquire gil;
    const std::string what = label(*cb_) + ": jacobian(x, v)";
    const py::object out = cb_->jacobian(copy_array(c.x), copy_array(c.v));
    if (!py::isinstance<py::tuple>(out) && !py::isinstance<py::list>(out))
      throw Error(what + ": expected a pair (dfdx, dfdv), got " +
                  std::string(py::str(py::type::handle_of(out).attr("__name__"))));
    const auto pair = py::reinterpret_borrow<py::sequence>(out);
    if (py::len(pair) != 2)
      throw Error(
          detail::message(what, ": expected a pair (dfdx, dfdv), got ", py::len(pair), " items"));
    const Eigen::Index dim = 3 * c.x.rows();
    dfdx_.take(entries_of(pair[0], dim, what + " dfdx"), dim, what + " dfdx");
    dfdv_.take(entries_of(pair[1], dim, what + " dfdv"), dim, what + " dfdv");
    x_ = c.x;
    v_ = c.v;
  }

  std::shared_ptr<const Callbacks> cb_;
  mutable PatternedMatrix dfdx_, dfdv_;
  mutable Points x_ = Points(0, 3), v_ = Points(0, 3);  // the state they were taken at
};

}  // namespace

std::string python_terms_without_jacobian(const System& system, const char* integrator) {
  const auto& terms = system.forces();
  for (int k = 0; k < terms.size(); ++k)
    if (terms[k].target(typeid(PythonTerm)))
      return detail::message(
          integrator, ": force term ", k, " (PythonForce \"", terms[k].name,
          "\") has no jacobian, and ", integrator,
          " needs dF/dx and dF/dv of every term: give PythonForce(forces, jacobian=...), or use "
          "FastMassSpring or an explicit integrator (SymplecticEuler, RK4, ForwardEuler), which "
          "evaluate its force only");
  return {};
}

void bind_python_force(py::module_& m) {
  py::class_<PythonForce>(
      m, "PythonForce",
      "A force term written in Python (docs/python.md).\n"
      "PythonForce(forces, jacobian=None, name=None, symmetric=False): forces(x, v) -> f, with x, "
      "v and f (n, 3) float64 arrays [m, m/s, N]; jacobian(x, v) -> (dfdx, dfdv), 3n x 3n "
      "matrices [N/m, N s/m] (scipy.sparse, dense or None for zero; coordinate 3 i + a is point "
      "i's axis a), needed by BackwardEuler only; symmetric: both are symmetric (BackwardEuler "
      "may use Cholesky). Each evaluation is a Python call, with the GIL.")
      .def(py::init([](const py::object& forces, const py::object& jacobian, const py::object& name,
                       bool symmetric) {
             if (!PyCallable_Check(forces.ptr()))
               throw Error("PythonForce: forces must be a callable forces(x, v) -> f, got " +
                           std::string(py::str(py::type::handle_of(forces).attr("__name__"))));
             if (!jacobian.is_none() && !PyCallable_Check(jacobian.ptr()))
               throw Error(
                   "PythonForce: jacobian must be None or a callable jacobian(x, v) -> (dfdx, "
                   "dfdv), got " +
                   std::string(py::str(py::type::handle_of(jacobian).attr("__name__"))));
             auto cb = std::make_shared<Callbacks>();
             cb->forces = forces;
             cb->jacobian = jacobian;
             cb->symmetric = symmetric;
             if (!name.is_none()) {
               cb->name = py::str(name);
             } else {
               const py::object own = py::getattr(forces, "__name__", py::none());
               cb->name = py::isinstance<py::str>(own) && std::string(py::str(own)) != "<lambda>"
                              ? std::string(py::str(own))
                              : std::string("python force");
             }
             return PythonForce{std::move(cb)};
           }),
           py::arg("forces"), py::arg("jacobian") = py::none(), py::arg("name") = py::none(),
           py::arg("symmetric") = false)
      .def_property_readonly("name", [](const PythonForce& p) { return p.callbacks->name; })
      .def_property_readonly("forces", [](const PythonForce& p) { return p.callbacks->forces; })
      .def_property_readonly("jacobian", [](const PythonForce& p) { return p.callbacks->jacobian; })
      .def_property_readonly("symmetric",
                             [](const PythonForce& p) { return p.callbacks->symmetric; })
      .def("__repr__", [](const PythonForce& p) {
        return "PythonForce(name=\"" + p.callbacks->name +
               "\", jacobian=" + (p.callbacks->jacobian.is_none() ? "None" : "given") + ")";
      });

  py::class_<System> system = system_class(m);
  system.def(
      "add_force",
      [](System& s, const PythonForce& p) {
        check_idle(&s, "add_force");
        if (p.callbacks->jacobian.is_none()) return s.add_force(PythonTerm(p.callbacks));
        if (p.callbacks->symmetric) return s.add_force(PythonJacobianTerm<true>(p.callbacks));
        return s.add_force(PythonJacobianTerm<false>(p.callbacks));
      },
      py::arg("term"),
      "Adds the Python term (its callables are shared, not copied); returns its index in "
      "forces. New revision.");
  // Last: anything no overload above took.
  system.def(
      "add_force",
      [](System&, const py::object& term) -> int {
        throw py::type_error(
            std::string(
                "add_force: expected a force term (Gravity, ConstantForce, LinearDrag, "
                "GravitationalAttraction, VortexForce, PenaltyForce, or PythonForce(forces, "
                "jacobian=None) for a term written in Python: docs/python.md), got ") +
            Py_TYPE(term.ptr())->tp_name);
      },
      py::arg("term"));
}

}  // namespace massspring::python
