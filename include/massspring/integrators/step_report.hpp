#pragma once
/// @file
/// @brief StepReport: what one integrator step did, and whether it succeeded.

#include <limits>

namespace massspring {

/// @brief Whether a step tested a convergence tolerance, and met it (StepReport::convergence).
enum class Convergence {
  /// No tolerance was tested: FastMassSpring with `tolerance` 0 (the default: it ran its
  /// `iterations`, as asked), linearised backward Euler (one solve) and the explicit integrators.
  /// Not a failure.
  NotTested,
  /// The tolerance was met (then `converged` is true).
  Converged,
  /// A tolerance was asked for and the iteration cap came first: the step is less accurate than
  /// asked (still `ok()` when finite).
  NotConverged,
};

/// @brief The outcome of one step. A step that fails (`ok() == false`: a failed factorization, a
/// non-finite value, an energy blow-up, or contact left unresolved) leaves the system's
/// positions and velocities exactly as they were before the step.
struct StepReport {
  /// @brief Solver iterations done in this step (local-global: global solves).
  int iterations = 0;
  /// @brief Relative energy decrease of the last iteration, (E_{k-1} - E_k) / (E_0 - E_k), where
  /// E_0 is the energy of the starting iterate; 0 when the energy did not decrease at all.
  /// NaN when the integrator does not minimise an energy.
  double relative_decrease = std::numeric_limits<double>::quiet_NaN();
  /// @brief The objective at the final iterate [J] (local-global: E(X) of
  /// docs/fast_mass_spring.md, up to a constant that does not depend on the iterate). NaN when the
  /// integrator has none.
  double energy = std::numeric_limits<double>::quiet_NaN();
  /// @brief Newton-type integrators: the largest force imbalance [N] at the start of the last
  /// iteration, max |F(x) - M (x - x^t - h v^t) / h^2|. NaN when the integrator has none.
  double residual = std::numeric_limits<double>::quiet_NaN();
  /// @brief True when the step stopped because its tolerance was met (never when the tolerance is
  /// 0: then `convergence` is NotTested, which is not a failure).
  bool converged = false;
  /// @brief NotTested (no tolerance asked), Converged or NotConverged (the cap came first).
  Convergence convergence = Convergence::NotTested;
  /// @brief True when every new position and velocity is finite. When false, nothing was changed.
  bool finite = true;
  /// @brief True when this step had to factorize again because the model changed since the last.
  bool refactorized = false;
  /// @brief True when this step had to factorize again and the matrix could not be factorized
  /// (not numerically positive definite). Nothing was changed; the next step tries again.
  bool factorization_failed = false;
  /// @brief True when the step's end state had more energy than the integrator's bound,
  /// the start energy + energy_growth (S + S_c) (integrators/detail/energy_bound.hpp: an energy
  /// blow-up), or its collision response added more than S / 2 + S_c (`contact_work`: a
  /// response that pumps energy into the springs; on whenever energy_growth > 0), or a
  /// Linearized BackwardEuler step raised the incremental potential it linearises (its linear
  /// model failed; EnergyBound::uphill()), or a DivergenceGuard found the total energy after the
  /// step beyond its limit. Nothing was changed (the guard restores the state from before the
  /// step).
  bool blew_up = false;
  /// @brief Surface contact (contact/response/surface_contact.hpp): the repulsion and collision
  /// impulses of this step, and the points its impact zones moved rigidly.
  int contact_impulses = 0;
  int contact_zone_points = 0;
  /// @brief False when surface contact could not remove every crossing within its rounds. Nothing
  /// was changed then.
  bool contact_resolved = true;
  /// @brief The energy [J] the end-of-step collision response (contact/contact_pipeline.hpp: the
  /// handler, the colliders' point response and surface contact) added to the step's end state:
  /// E after it less E before it, E the kinetic energy of the free points plus the potential of
  /// the springs and force terms (integrators/detail/energy_bound.hpp). An inelastic response
  /// that only stops approaching points gives about 0 or less; a large positive value means its
  /// position corrections stretched springs (docs/contact.md, Limits) and the step's result is
  /// suspect even when ok(); above S / 2 + S_c the step is refused (`blew_up`). 0 when the system
  /// has no collision response; NaN only when the end
  /// state is not finite (then `finite` is false).
  double contact_work = 0;

  /// @brief A step succeeded when it could factorize, its result is finite, its energy did not
  /// blow up and its contact was resolved.
  [[nodiscard]] bool ok() const {
    return finite && !blew_up && !factorization_failed && contact_resolved;
  }
};

}  // namespace massspring
