// massspring.BackwardEuler (integrators/backward_euler.hpp) and BackwardEulerOptions with the C++
// field names. It assigns the system's positions and velocities in place (same size: no new
// buffer), so the views of them stay valid.

#include "integrator.hpp"
#include "python_force.hpp"

namespace massspring::python {

void bind_backward_euler(py::module_& m) {
  using Solver = BackwardEuler<System>;
  using Options = BackwardEulerOptions<double>;
  py::enum_<BackwardEulerMode>(m, "BackwardEulerMode")
      .value("Linearized", BackwardEulerMode::Linearized)
      .value("Newton", BackwardEulerMode::Newton);

  py::class_<Options> o(m, "BackwardEulerOptions", "BackwardEuler's options; read at every step.");
  o.def(py::init<>())
      .def_readwrite("mode", &Options::mode, "Linearized (one Newton step) or Newton.")
      .def_readwrite("iterations", &Options::iterations, "Newton: most iterations (>= 1).")
      .def_readwrite("tolerance", &Options::tolerance,
                     "Newton: stop when max |dx| <= tolerance (1 + max |x|).")
      .def_readwrite("line_search", &Options::line_search, "Newton: backtracking line search.")
      .def_readwrite("contact_weight", &Options::contact_weight,
                     "Weight alpha of contact and friction inside the solve, the colliders' and "
                     "(with self-collision) the surface's own: alpha sqrt(m (m + h^2 k)) per "
                     "point, k its springs' summed stiffness (default 1, which suits dt = 1/30; "
                     "0: at the end of the step only).");
  def_energy_growth(o);

  py::class_<Solver> c(m, "BackwardEuler",
                       "Implicit Euler on (M - h dF/dv - h^2 dF/dx), linearised or Newton.");
  c.def(py::init<>())
      .def(py::init<Options>(), py::arg("options"))
      .def_readwrite("options", &Solver::options, "The options (this solver's own).");
  bind_contact_duals<Solver>(c);
  // A PythonForce without a jacobian is refused: the solve needs every term's dF/dx and dF/dv.
  bind_integrator_calls<Solver>(
      m, c, [](Solver& s, System& system) { return s.step(system); },
      [](const System& system) { return python_terms_without_jacobian(system, "BackwardEuler"); });
}

}  // namespace massspring::python
