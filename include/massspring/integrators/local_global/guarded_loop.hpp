#pragma once
/// @file
/// @brief The energy-guarded loop of FastMassSpring's accelerated iterations, and the tolerance
/// test every loop shares. An accelerator (chebyshev.hpp, anderson.hpp) proposes iterates; the
/// loop evaluates the energy E at each (in the local step that builds its right-hand side),
/// replaces an iterate the accelerator does not accept by the accelerator's plain fallback, stops
/// on the tolerance, and takes the global step. E is the objective of one implicit-Euler step
/// (Liu et al. 2013, eq. 4; docs/fast_mass_spring.md); the plain iteration never increases it, so
/// the guard keeps the accelerated iterations monotone too.

#include <cstddef>

#include "massspring/integrators/step_report.hpp"

namespace massspring::local_global {

/// @brief decrease / total, or 0 when total is not > 0.
inline double relative(double decrease, double total) { return total > 0 ? decrease / total : 0.0; }

/// @brief The tolerance stop after iteration k (k > 0): true, with report.converged set, when the
/// relative decrease (E_{k-1} - E_k) / (E_0 - E_k) is <= tolerance (never when tolerance is 0).
/// Records the relative decrease in the report.
inline bool tolerance_met(StepReport& report, double tolerance, int k, double e0, double e_prev,
                          double e) {
  if (!(tolerance > 0) || k == 0) return false;
  report.relative_decrease = relative(e_prev - e, e0 - e);
  if (report.relative_decrease <= tolerance) {
    report.converged = true;
    return true;
  }
  return false;
}

/// @brief Runs up to `iterations` accelerated local-global iterations and returns the final
/// iterate (one of the accelerator's buffers).
///
/// @param it the solver's iteration: `double local(const Scalar* x, Scalar* w)` (the local step
///   at x into w's right-hand side, returning E(x)), `void global(Scalar* w)` (w = Q^-1 w, pins
///   restored) and `double energy(const Scalar* x)` (E(x), recording the springs' directions).
///   What a local step updates besides w stays updated when the loop then rejects x: with
///   FastMassSpring's contact term, a rejected iterate's dual update counts, and the plain
///   iterate's follows it (docs/contact.md, "Contact inside the iteration", on what that does).
/// @param acc the accelerator: `x()` the current iterate, `w()` the buffer the step writes,
///   `accepts(e, e_prev)`, `reject()` (back to its plain iterate, whose energy is <= e_prev),
///   `advance()` (the next iterate from w = G(x)), and `fallback()` (the plain iterate to return
///   when the last one's energy is above the last accepted, or null when there is none).
/// @param rejections counts the rejected iterates.
template <class Iteration, class Accelerator>
auto guarded_loop(Iteration& it, Accelerator& acc, int iterations, double tolerance,
                  StepReport& report, std::size_t& rejections) {
  double e0 = 0, e_prev = 0;
  for (int k = 0; k < iterations; ++k) {
    double e = it.local(acc.x(), acc.w());
    if (k == 0) e0 = e;
    if (k > 0 && !acc.accepts(e, e_prev)) {
      // The energy rose (or is not finite): the plain iterate instead.
      acc.reject();
      e = it.local(acc.x(), acc.w());
      ++rejections;
    }
    if (tolerance_met(report, tolerance, k, e0, e_prev, e)) break;
    e_prev = e;
    it.global(acc.w());  // w = G(x_k)
    ++report.iterations;
    acc.advance();
  }
  // The last iterate is accepted only when its energy is not above the last evaluated one;
  // otherwise the plain iterate (never above it) is returned.
  auto* x = acc.x();
  double e = it.energy(x);
  if (report.iterations > 0 && !(e <= e_prev)) {
    if (auto* plain = acc.fallback()) {
      x = plain;
      e = it.energy(x);
    }
  }
  report.energy = e;
  if (!report.converged && report.iterations > 0)
    report.relative_decrease = relative(e_prev - e, e0 - e);
  return x;
}

}  // namespace massspring::local_global
