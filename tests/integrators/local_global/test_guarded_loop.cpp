// integrators/local_global/guarded_loop.hpp: the energy guard and the tolerance stop, on a toy
// fixed-point iteration whose energy and map are closed forms.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <massspring/integrators/local_global/guarded_loop.hpp>

namespace {

// E(x) = x^2 / 2 on one unknown; the plain map G(x) = x / 2 halves it, so E(G(x)) = E(x) / 4.
struct Toy {
  int locals = 0, globals = 0;
  double local(const double* x, double* w) {
    ++locals;
    w[0] = x[0];  // the right-hand side: here the iterate itself
    return x[0] * x[0] / 2;
  }
  void global(double* w) {
    ++globals;
    w[0] /= 2;
  }
  double energy(const double* x) { return x[0] * x[0] / 2; }
};

// Proposes x_{k+1} = factor G(x_k); its plain fallback is G(x_k).
struct Scaled {
  double factor;
  std::array<double, 3> b{};  // x, w, the plain iterate G(x_k)
  double* x() { return &b[0]; }
  double* w() { return &b[1]; }
  static bool accepts(double e, double e_prev) { return e < e_prev; }
  void reject() { b[0] = b[2]; }
  void advance() {
    b[2] = b[1];
    b[0] = factor * b[1];
  }
  double* fallback() {
    b[0] = b[2];
    return &b[0];
  }
};

}  // namespace

TEST_CASE("guarded_loop: accepted iterates run the accelerator's map, energy reported") {
  Toy it;
  Scaled acc{1.5};  // 1.5 G(x) = 0.75 x: still descends
  acc.b[0] = 1;
  massspring::StepReport report;
  std::size_t rejections = 0;
  const double* x = massspring::local_global::guarded_loop(it, acc, 4, 0.0, report, rejections);
  CHECK(rejections == 0);
  CHECK(report.iterations == 4);
  CHECK(x[0] == doctest::Approx(std::pow(0.75, 4)).epsilon(1e-15));
  CHECK(report.energy == doctest::Approx(std::pow(0.75, 8) / 2).epsilon(1e-15));
}

TEST_CASE("guarded_loop: an iterate that raises the energy is replaced by the plain one") {
  Toy it;
  Scaled acc{-3};  // -3 G(x) = -1.5 x: E rises by 2.25 at every proposal
  acc.b[0] = 1;
  massspring::StepReport report;
  std::size_t rejections = 0;
  const double* x = massspring::local_global::guarded_loop(it, acc, 5, 0.0, report, rejections);
  // Every proposal after the first iterate is rejected for G of the last accepted one; the last
  // proposal too, by the final check: the result is the plain iteration's, (1/2)^5.
  CHECK(rejections == 4);
  CHECK(report.iterations == 5);
  CHECK(x[0] == 1.0 / 32);
  CHECK(report.energy == 1.0 / 32 / 32 / 2);
  // The plain iteration's relative decrease, (E_3 - E_4) / (E_0 - E_4) with E_k = 4^-k / 2.
  const double e0 = 0.5, e4 = std::pow(0.25, 4) / 2, e5 = std::pow(0.25, 5) / 2;
  CHECK(report.relative_decrease == doctest::Approx((e4 - e5) / (e0 - e5)).epsilon(1e-14));
}

TEST_CASE("guarded_loop: the tolerance stops at the first small relative decrease") {
  // Plain halving: (E_{k-1} - E_k) / (E_0 - E_k) = 3 / (4^k - 1) at iteration k: 1, 0.2, then
  // 3/63 = 0.048 <= 0.05 at k = 3, judged before that iteration's global step.
  Toy it;
  Scaled acc{1};
  acc.b[0] = 1;
  massspring::StepReport report;
  std::size_t rejections = 0;
  massspring::local_global::guarded_loop(it, acc, 50, 0.05, report, rejections);
  CHECK(report.converged);
  CHECK(report.iterations == 3);
  CHECK(report.relative_decrease == doctest::Approx(3.0 / 63).epsilon(1e-14));
  CHECK(it.globals == 3);  // no global step after the stop
}
