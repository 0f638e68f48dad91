// massspring.FastMassSpring (integrators/local_global/): the local-global solver of Liu et al.
// 2013, and FastMassSpringOptions with the C++ field names (solver.options.iterations = 10).
// FastMassSpring writes the system's positions and velocities in place, so the views of them stay
// valid.

#include <massspring/integrators/local_global/option_names.hpp>
#include <string>
#include <type_traits>

#include "integrator.hpp"

namespace massspring::python {

namespace {

using Solver = FastMassSpring<System>;
using Options = FastMassSpringOptions<double>;

// The error for an option that was removed: it names the force term that replaces it.
py::attribute_error removed(const std::string& name) {
  const char* term = name == "gravity" ? "Gravity" : "ConstantForce";
  return py::attribute_error("options." + name + " was removed: add massspring." + term +
                             "(...) to the system with system.add_force, which every integrator "
                             "honours");
}

}  // namespace

void bind_fast_mass_spring(py::module_& m) {
  // Each enumeration also reads and writes the names of option_names.hpp, the command line's:
  // Acceleration.from_name("chebyshev"), Acceleration.Chebyshev.text == "chebyshev".
  const auto names = [](auto& e) {
    using Enum = typename std::decay_t<decltype(e)>::type;
    e.def_static("from_name", &parse_option<Enum>, py::arg("name"),
                 "The value a name spells (massspring.Error for an unknown name).")
        .def_property_readonly(
            "text", [](Enum v) { return std::string(option_name(v)); }, "The value's name.");
  };
  py::enum_<PinMode> pins(m, "PinMode", "How FastMassSpring holds pinned points.");
  pins.value("Exact", PinMode::Exact).value("Penalty", PinMode::Penalty);
  names(pins);
  py::enum_<InitialGuess> guess(m, "InitialGuess", "Where the iterations start.");
  guess.value("Current", InitialGuess::Current).value("Inertial", InitialGuess::Inertial);
  names(guess);
  py::enum_<Acceleration> acceleration(m, "Acceleration");
  acceleration
      .value("None_", Acceleration::None)  // None is a Python keyword
      .value("Chebyshev", Acceleration::Chebyshev)
      .value("Anderson", Acceleration::Anderson);
  names(acceleration);
  py::enum_<FillOrdering> ordering(m, "FillOrdering");
  ordering.value("Auto", FillOrdering::Auto)
      .value("Solver", FillOrdering::Solver)
      .value("NestedDissection", FillOrdering::NestedDissection);
  names(ordering);

  py::class_<Options> o(m, "FastMassSpringOptions",
                        "FastMassSpring's options (integrators/local_global/options.hpp); read at "
                        "every step, checked there (massspring.Error).");
  o.def(py::init<>())
      .def_property(
          "iterations", [](const Options& x) { return x.iterations; },
          [](Options& x, int n) {
            if (n < 1)  // the message step() would give, at the assignment
              throw Error(
                  detail::message("FastMassSpring: options.iterations must be >= 1, got ", n));
            x.iterations = n;
          },
          "Most iterations per step (>= 1; checked when set).")
      .def_readwrite("tolerance", &Options::tolerance,
                     "Stop when the relative energy decrease is <= this (0: never).")
      .def_readwrite("pins", &Options::pins)
      .def_readwrite("penalty_weight", &Options::penalty_weight, "w for PinMode.Penalty [N/m].")
      .def_readwrite("contact_weight", &Options::contact_weight,
                     "Weight alpha of contact and friction inside the iteration: alpha sqrt(m "
                     "(m + dt^2 k)) / dt^2 per point, k its springs' summed stiffness (default "
                     "1; 0: contact only at the end of the step).");
  def_energy_growth(o)
      .def_static("reference", &Options::reference,
                  "The assignment's plain iteration: 50 iterations from the current "
                  "positions, no acceleration, no contact term.")
      // Removed options: assigning one names what replaces it (a force term on the system).
      .def_property(
          "external_force", [](const Options&) -> py::object { throw removed("external_force"); },
          [](Options&, const py::handle&) { throw removed("external_force"); },
          "Removed: add massspring.ConstantForce to the system.")
      .def_property(
          "gravity", [](const Options&) -> py::object { throw removed("gravity"); },
          [](Options&, const py::handle&) { throw removed("gravity"); },
          "Removed: add massspring.Gravity to the system.")
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
                       "precompute(system, dt) factorizes once, step(system) per frame.");
  c.def(py::init<>())
      .def(py::init<const Options&>(), py::arg("options"))
      .def_readwrite("options", &Solver::options,
                     "The options (this solver's own: solver.options.iterations = 10 changes "
                     "them).")
      .def_property_readonly(
          "chebyshev_rho", [](const Solver& s) { return double(s.chebyshev_rho()); },
          "The rho Chebyshev uses (options' or the estimate; 0 before it is estimated).")
      .def_property_readonly("rejections", &Solver::rejections);
  bind_contact_duals<Solver>(c);
  bind_integrator_calls<Solver>(m, c, [](Solver& s, System& system) { return s.step(system); });
}

}  // namespace massspring::python
