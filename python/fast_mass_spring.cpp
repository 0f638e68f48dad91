// massspring.FastMassSpring (integrators/local_global/): the local-global solver of Liu et al.
// 2013, and FastMassSpringOptions with the C++ field names (solver.options.iterations = 10).
// FastMassSpring writes the system's positions and velocities in place, so the views of them stay
// valid.

#include "integrator.hpp"

namespace massspring::python {

namespace {

using Solver = FastMassSpring<System>;
using Options = FastMassSpringOptions<double>;

}  // namespace

void bind_fast_mass_spring(py::module_& m) {
  py::enum_<PinMode>(m, "PinMode", "How FastMassSpring holds pinned points.")
      .value("Exact", PinMode::Exact)
      .value("Penalty", PinMode::Penalty);
  py::enum_<InitialGuess>(m, "InitialGuess", "Where the iterations start.")
      .value("Current", InitialGuess::Current)
      .value("Inertial", InitialGuess::Inertial);
  py::enum_<Acceleration>(m, "Acceleration")
      .value("None_", Acceleration::None)  // None is a Python keyword
      .value("Chebyshev", Acceleration::Chebyshev)
      .value("Anderson", Acceleration::Anderson);
  py::enum_<FillOrdering>(m, "FillOrdering")
      .value("Auto", FillOrdering::Auto)
      .value("Solver", FillOrdering::Solver)
      .value("NestedDissection", FillOrdering::NestedDissection);

  py::class_<Options> o(m, "FastMassSpringOptions",
                        "FastMassSpring's options (integrators/local_global/options.hpp); read at "
                        "every step, checked there (massspring.Error).");
  o.def(py::init<>())
      .def_property(
          "iterations", [](const Options& x) { return x.iterations; },
          [](Options& x, int n) {
            if (n < 1)  // the message step() would give, at the assignment
              throw Error(detail::message("FastMassSpring: options.iterations must be >= 1, got ",
                                          n));
            x.iterations = n;
          },
          "Most iterations per step (>= 1; checked when set).")
      .def_readwrite("tolerance", &Options::tolerance,
                     "Stop when the relative energy decrease is <= this (0: never).")
      .def_readwrite("pins", &Options::pins)
      .def_readwrite("penalty_weight", &Options::penalty_weight, "w for PinMode.Penalty [N/m].")
      .def_readwrite("contact_weight", &Options::contact_weight,
                     "Weight of the collider projection inside the iterations (0: off).")
      .def_property(
          "external_force", [](const Options& x) { return copy_array(x.external_force, true); },
          [](Options& x, const py::handle& f) {
            x.external_force = vector3(f, "options.external_force");
          },
          "A force [N] on every point (a copy: assign the whole vector).")
      .def_property(
          "gravity", [](const Options& x) { return copy_array(x.gravity, true); },
          [](Options& x, const py::handle& g) {
            x.gravity = vector3(g, "options.gravity");
            if (!x.gravity.isZero())
              py::module_::import("warnings")
                  .attr("warn")("options.gravity is deprecated: add massspring.Gravity to the "
                                "system instead (with both, gravity acts twice)",
                                py::module_::import("builtins").attr("DeprecationWarning"), 2);
          },
          "Deprecated: add a Gravity term to the system. An acceleration [m/s^2] of every point, "
          "on top of the system's terms (a copy: assign the whole vector).")
      .def_readwrite("initial_guess", &Options::initial_guess)
      .def_readwrite("acceleration", &Options::acceleration)
      .def_readwrite("chebyshev_rho", &Options::chebyshev_rho, "In [0, 1); 0: estimated.")
      .def_readwrite("chebyshev_gamma", &Options::chebyshev_gamma)
      .def_readwrite("chebyshev_delay", &Options::chebyshev_delay)
      .def_readwrite("chebyshev_estimate_iterations", &Options::chebyshev_estimate_iterations)
      .def_readwrite("anderson_window", &Options::anderson_window)
      .def_readwrite("allow_float_penalty", &Options::allow_float_penalty)
      .def_readwrite("threads", &Options::threads, "Threads for the substitutions (OpenMP).")
      .def_readwrite("simd", &Options::simd)
      .def_readwrite("ordering", &Options::ordering);

  py::class_<Solver> c(m, "FastMassSpring",
                       "Local-global implicit Euler for springs (Liu et al. 2013): "
                       "precompute(system, dt) factorises once, step(system) per frame.");
  c.def(py::init<>())
      .def(py::init<const Options&>(), py::arg("options"))
      .def_readwrite("options", &Solver::options,
                     "The options (this solver's own: solver.options.iterations = 10 changes "
                     "them).")
      .def_property_readonly(
          "chebyshev_rho", [](const Solver& s) { return double(s.chebyshev_rho()); },
          "The rho Chebyshev uses (options' or the estimate; 0 before it is estimated).")
      .def_property_readonly("rejections", &Solver::rejections);
  bind_integrator_calls<Solver>(m, c, [](Solver& s, System& system) { return s.step(system); });
}

}  // namespace massspring::python
