// The compiled module `massspring._core` (re-exported by the package `massspring`,
// python/massspring/__init__.py): massspring.Error, StepReport, and each concept's file in order
// (the system first: the force terms and colliders add methods to it; the diagnostics'
// DivergenceGuard before the integrators, which add its step() for each of them).

#include <massspring/version.hpp>
#include <unordered_set>

#include "bindings.hpp"
#include "python_force.hpp"

namespace massspring::python {

namespace {
// Objects in use by a call that released the GIL; read and written with the GIL held only.
std::unordered_set<const void*>& in_use() {
  static std::unordered_set<const void*> objects;
  return objects;
}
}  // namespace

void check_idle(const void* object, const char* what) {
  if (in_use().count(object))
    throw Error(detail::message(what,
                                ": the system or integrator is in use by a step in another "
                                "thread (use one system and one integrator per thread)"));
}

InUse::InUse(std::initializer_list<const void*> objects, const char* what) {
  for (const void* o : objects) check_idle(o, what);
  for (const void* o : objects)
    if (in_use().insert(o).second) objects_.push_back(o);
}

InUse::~InUse() {
  for (const void* o : objects_) in_use().erase(o);
}

void bind_errors(py::module_& m) {
  // massspring::Error -> massspring.Error, a ValueError carrying the library's message.
  py::register_exception<Error>(m, "Error", PyExc_ValueError);
}

void bind_step_report(py::module_& m) {
  py::enum_<Convergence>(m, "Convergence",
                         "Whether a step tested a tolerance, and met it (NotTested is not a "
                         "failure: no tolerance was asked for).")
      .value("NotTested", Convergence::NotTested)
      .value("Converged", Convergence::Converged)
      .value("NotConverged", Convergence::NotConverged);
  // The share of the energy scale the collision response may add in one step before the step is
  // refused (integrators/detail/energy_bound.hpp), for messages that name that refusal.
  m.attr("CONTACT_LIMIT_SHARE") = detail::EnergyBound<System>::kContactShare;
  py::class_<StepReport>(m, "StepReport", "What one step did (integrators/step_report.hpp).")
      .def(py::init<>())
      .def_readonly("iterations", &StepReport::iterations, "Iterations (local-global or Newton).")
      .def_readonly("relative_decrease", &StepReport::relative_decrease,
                    "Relative energy decrease of the last iteration (NaN when not tracked).")
      .def_readonly("energy", &StepReport::energy, "Final energy where tracked, else NaN.")
      .def_readonly("residual", &StepReport::residual, "Final residual where tracked, else NaN.")
      .def_readonly("converged", &StepReport::converged,
                    "True when the tolerance was met (never when no tolerance was asked for).")
      .def_readonly("convergence", &StepReport::convergence,
                    "Convergence.NotTested (no tolerance asked), Converged or NotConverged.")
      .def_readonly("finite", &StepReport::finite)
      .def_readonly("refactorized", &StepReport::refactorized)
      .def_readonly("factorization_failed", &StepReport::factorization_failed)
      .def_readonly(
          "blew_up", &StepReport::blew_up,
          "True when the end state's energy passed the integrator's bound (energy_growth) "
          "or a DivergenceGuard's, or the contact response added more than S / 2 + S_c "
          "(contact_work), or a Linearized BackwardEuler step raised the incremental "
          "potential it linearises (its linear model failed): nothing changed.")
      .def_readonly("contact_impulses", &StepReport::contact_impulses,
                    "Surface contact's repulsion and collision impulses in this step.")
      .def_readonly("contact_zone_points", &StepReport::contact_zone_points,
                    "Points surface contact's impact zones moved rigidly in this step.")
      .def_readonly("contact_resolved", &StepReport::contact_resolved,
                    "False when surface contact could not remove every crossing (nothing changed).")
      .def_readonly(
          "contact_work", &StepReport::contact_work,
          "Energy [J] the end-of-step contact response added to the end state (kinetic "
          "of the free points plus potential, after less before); 0 without contact. Above "
          "S / 2 + S_c the step is refused (blew_up).")
      .def("ok", &StepReport::ok,
           "finite, not blown up, the factorization succeeded and the contact was resolved")
      .def("__repr__", [](const StepReport& r) {
        return detail::message("StepReport(iterations=", r.iterations, ", convergence=",
                               r.convergence == Convergence::NotTested   ? "NotTested"
                               : r.convergence == Convergence::Converged ? "Converged"
                                                                         : "NotConverged",
                               ", finite=", r.finite ? "True" : "False",
                               ", refactorized=", r.refactorized ? "True" : "False",
                               ", factorization_failed=", r.factorization_failed ? "True" : "False",
                               ", blew_up=", r.blew_up ? "True" : "False", ")");
      });
}

}  // namespace massspring::python

PYBIND11_MODULE(_core, m) {
  using namespace massspring::python;
  m.doc() =
      "massspring: mass-spring simulation (MassSpringSystem<double, Sparse>) with the C++ "
      "library's names; see docs/python.md.";
  m.attr("__version__") = massspring::version_string;
  bind_errors(m);
  bind_system(m);
  bind_forces(m);
  bind_python_force(m);  // after every other add_force overload
  bind_colliders(m);
  bind_step_report(m);
  bind_diagnostics(m);  // DivergenceGuard, before the integrators add its step() for each
  bind_fast_mass_spring(m);
  bind_explicit_integrators(m);
  bind_backward_euler(m);
  bind_scene_files(m);
  bind_scenes(m);
}
