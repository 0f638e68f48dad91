// integrators/backward_euler.hpp: the 1-D spring's exact recurrence (both modes), first order,
// orbits spiral in, Newton agrees with converged local-global, pins, Dense = Sparse, the
// indefinite and non-symmetric fallbacks, failure handling.
#include <doctest/doctest.h>

#include <cmath>
#include <massspring/diagnostics/energy.hpp>
#include <massspring/forces/gravitational_attraction.hpp>
#include <massspring/forces/gravity.hpp>
#include <massspring/forces/linear_drag.hpp>
#include <massspring/integrators/backward_euler.hpp>
#include <massspring/integrators/fast_mass_spring.hpp>
#include <massspring/io/json_scene.hpp>
#include <massspring/scene/cloth.hpp>
#include <massspring/scene/make_system.hpp>
#include <random>

#include "support/alloc_counter.hpp"
#include "support/paths.hpp"
#include "support/small_systems.hpp"
#include "support/uniform_forces.hpp"

namespace {

using massspring::test::add_gravity;
using massspring::test::add_uniform_force;

using massspring::BackwardEuler;
using massspring::BackwardEulerMode;
using massspring::Dense;
using massspring::Sparse;
using Pts = massspring::Points<double>;
using SystemD = massspring::MassSpringSystem<double, Dense>;
using SystemS = massspring::MassSpringSystem<double, Sparse>;

}  // namespace

TEST_CASE("BackwardEuler follows its recurrence [1 -h; h w0^2 1] (u', w') = (u, w), both modes") {
  for (auto mode : {BackwardEulerMode::Linearized, BackwardEulerMode::Newton}) {
    const double m = 0.5, k = 8, h = 0.05;
    auto s = massspring::test::oscillator<SystemS>(m, k, 1.0, 0.2, 0.1);
    BackwardEuler<SystemS> be;
    be.options.mode = mode;
    be.precompute(s, h);
    Eigen::Vector2d expect(0.2, 0.1);
    double worst = 0;
    for (int step = 0; step < 200; ++step) {
      const auto r = be.step(s);
      REQUIRE(r.ok());
      // Newton on a linear force converges in one step (the second iteration only confirms).
      if (mode == BackwardEulerMode::Newton) CHECK(r.iterations <= 2);
      expect = massspring::test::backward_euler_step(expect, h, k / m);
      worst = std::max({worst, std::abs(s.positions()(1, 0) - 1.0 - expect(0)),
                        std::abs(s.velocities()(1, 0) - expect(1))});
    }
    CHECK(worst < 1e-12);
    CHECK(s.positions()(0, 0) == 0);
  }
}

TEST_CASE("BackwardEuler is first order: halving h halves the error") {
  const auto err = [](double h) {
    auto s = massspring::test::oscillator<SystemS>(1, 4, 1.0, 0.1);
    BackwardEuler<SystemS> be;
    be.precompute(s, h);
    for (int i = 0; i < int(std::lround(1.0 / h)); ++i) be.step(s);
    return std::abs(s.positions()(1, 0) - 1.0 - 0.1 * std::cos(2.0));
  };
  const double e1 = err(1e-3), e2 = err(5e-4), e3 = err(2.5e-4);
  CHECK(e1 / e2 == doctest::Approx(2).epsilon(0.02));
  CHECK(e2 / e3 == doctest::Approx(2).epsilon(0.01));
}

TEST_CASE("BackwardEuler: an orbit spirals in, and energy decreases every step") {
  auto s = massspring::test::orbit<SystemS>();
  BackwardEuler<SystemS> be;
  be.precompute(s, 1e-2);
  double e = massspring::total_energy(s);
  for (int i = 0; i < 628; ++i) {
    const auto r = be.step(s);
    REQUIRE(r.converged);
    const double e1 = massspring::total_energy(s);
    CHECK(e1 < e);  // implicit Euler's numerical dissipation
    e = e1;
  }
  CHECK(s.positions().row(1).norm() < 1 - 0.5 * M_PI * 1e-2);
}

TEST_CASE("Newton backward Euler and local-global converged agree on the same step") {
  for (auto pins : {massspring::PinMode::Exact}) {
    auto a = massspring::test::perturbed_cloth<SystemS>();
    auto b = a;
    const double h = 1.0 / 30;
    massspring::FastMassSpring<SystemS> lg;
    lg.options.pins = pins;
    add_gravity(a, Eigen::Vector3d(0, -9.8, 0));
    lg.options.iterations = 20000;  // linear convergence: run it out to rounding
    lg.options.tolerance = 0;
    lg.options.initial_guess = massspring::InitialGuess::Inertial;
    lg.precompute(a, h);
    b.add_force(massspring::Gravity<double>(Eigen::Vector3d(0, -9.8, 0)));
    BackwardEuler<SystemS> be;
    be.options.tolerance = 1e-13;
    be.precompute(b, h);
    for (int step = 0; step < 3; ++step) {
      REQUIRE(lg.step(a).ok());
      const auto r = be.step(b);
      REQUIRE(r.converged);
      // Both minimise the same incremental potential: Newton to a step of 1e-13, local-global
      // (linear rate) after 20000 iterations to rounding. They agree to 1e-12 (positions ~0.5 m).
      CHECK((a.positions() - b.positions()).cwiseAbs().maxCoeff() < 1e-12);
    }
  }
}

TEST_CASE("BackwardEuler: Dense equals Sparse; pins stay put; drag and damping terms") {
  auto d = massspring::test::perturbed_cloth<SystemD>();
  auto s = massspring::test::perturbed_cloth<SystemS>();
  for (int mode = 0; mode < 2; ++mode) {
    auto dd = d;
    auto ss = s;
    // Heavier points than the cloth's Voronoi masses keep h omega ~ 0.8: a large step that the
    // linearised scheme still follows smoothly (at h omega ~ 2 its trajectories are chaotic, and
    // rounding differences between Dense and Sparse grow to O(1)).
    dd.set_masses(Eigen::VectorXd::Constant(dd.num_points(), 0.05));
    ss.set_masses(Eigen::VectorXd::Constant(ss.num_points(), 0.05));
    Eigen::VectorXd b = Eigen::VectorXd::Constant(ss.num_springs(), 0.3);
    dd.set_damping(b);
    ss.set_damping(b);
    ss.add_force(massspring::LinearDrag<double>(0.05));
    dd.add_force(massspring::LinearDrag<double>(0.05));
    dd.add_force(massspring::Gravity<double>(Eigen::Vector3d(0, -9.8, 0)));
    ss.add_force(massspring::Gravity<double>(Eigen::Vector3d(0, -9.8, 0)));
    BackwardEuler<SystemD> bd;
    BackwardEuler<SystemS> bs;
    bd.options.mode = bs.options.mode =
        mode == 0 ? BackwardEulerMode::Linearized : BackwardEulerMode::Newton;
    bd.precompute(dd, 0.02);
    bs.precompute(ss, 0.02);
    const Pts pins0 = ss.positions()(ss.pinned(), Eigen::all);
    for (int i = 0; i < 20; ++i) {
      REQUIRE(bd.step(dd).ok());
      const auto r = bs.step(ss);
      REQUIRE(r.ok());
      if (mode == 1) CHECK(r.converged);
    }
    // Spring damping makes A non-symmetric off the spring axes: the LU path.
    CHECK(bs.last_solver_path() == massspring::LinearSolverPath::General);
    CHECK((dd.positions() - ss.positions()).cwiseAbs().maxCoeff() < 1e-12);
    CHECK(ss.positions()(ss.pinned(), Eigen::all) == pins0);
  }
}

TEST_CASE("BackwardEuler: a compressed stiff spring (indefinite A) is still solved") {
  // Two free points on a spring compressed to a tenth of its rest length, pushed sideways: the
  // exact A = M - h^2 dF/dx has negative transverse stiffness k (l - l0)/l, large here.
  Pts x = Pts::Zero(2, 3);
  x(1, 0) = 0.1;
  massspring::Edges e(1, 2);
  e << 0, 1;
  SystemS s(x, e, 1.0, 1e4);
  s.set_rest_lengths(Eigen::VectorXd::Constant(1, 1.0));
  Pts v = Pts::Zero(2, 3);
  v(1, 1) = 1;
  s.set_velocities(v);
  for (auto mode : {BackwardEulerMode::Linearized, BackwardEulerMode::Newton}) {
    auto t = s;
    BackwardEuler<SystemS> be;
    be.options.mode = mode;
    be.precompute(t, 0.05);
    const auto r = be.step(t);
    REQUIRE(r.ok());
    if (mode == BackwardEulerMode::Newton) {
      CHECK(r.converged);
      // Converged: the step satisfies M (x' - x - h v) / h^2 = F(x'), to the residual reported.
      CHECK(r.residual < 1e-6);
    } else {
      // Sparse: SimplicialLDLT after the failed Cholesky; Dense: pivoting LDLT. The same step.
      CHECK(be.last_solver_path() == massspring::LinearSolverPath::Indefinite);
      SystemD d(x, e, 1.0, 1e4);
      d.set_rest_lengths(Eigen::VectorXd::Constant(1, 1.0));
      d.set_velocities(v);
      BackwardEuler<SystemD> bd;
      bd.options.mode = mode;
      bd.precompute(d, 0.05);
      REQUIRE(bd.step(d).ok());
      CHECK(bd.last_solver_path() == massspring::LinearSolverPath::Indefinite);
      CHECK((d.positions() - t.positions()).cwiseAbs().maxCoeff() < 1e-12);
    }
    // Momentum of the free pair is conserved by every implicit Euler step (internal forces).
    CHECK((massspring::linear_momentum(t) - massspring::linear_momentum(s)).norm() < 1e-10);
  }
}

TEST_CASE("BackwardEuler: refuses bad input; failure leaves the state") {
  auto s = massspring::test::oscillator<SystemS>(1, 1, 1, 0.1);
  BackwardEuler<SystemS> be;
  CHECK_THROWS_WITH_AS(be.step(s), "BackwardEuler: step() before precompute()", massspring::Error);
  CHECK_THROWS_WITH_AS(be.precompute(s, -1.0), "BackwardEuler: dt must be finite and > 0, got -1",
                       massspring::Error);
  be.precompute(s, 0.1);
  be.options.iterations = 0;
  CHECK_THROWS_WITH_AS(be.step(s), "BackwardEuler: iterations must be >= 1, got 0",
                       massspring::Error);
  be.options.iterations = 5;
  Pts v = Pts::Zero(2, 3);
  v(1, 0) = 1e308;
  s.set_velocities(v);
  const Pts x0 = s.positions();
  const auto r = be.step(s);
  CHECK_FALSE(r.ok());
  CHECK(s.positions() == x0);
  CHECK(s.velocities() == v);
}

TEST_CASE("BackwardEuler with Dense storage allocates nothing in step()") {
  // Sparse storage allocates inside Eigen's numeric factorization (a permuted copy of A per
  // solve); Dense assembles and factorizes into storage sized by precompute().
  for (auto mode : {BackwardEulerMode::Linearized, BackwardEulerMode::Newton}) {
    auto s = massspring::test::perturbed_cloth<SystemD>();
    s.add_force(massspring::Gravity<double>(Eigen::Vector3d(0, -9.8, 0)));
    BackwardEuler<SystemD> be;
    be.options.mode = mode;
    be.precompute(s, 0.01);
    REQUIRE(be.step(s).ok());
    massspring::test::CountAllocations count;
    for (int i = 0; i < 5; ++i) REQUIRE(be.step(s).ok());
    CHECK(count.count() == 0);
  }
}

TEST_CASE(
    "StepReport::convergence: NotTested without a tolerance, Converged or NotConverged with") {
  using massspring::Convergence;
  massspring::ClothOptions o;
  o.columns = 8;
  o.rows = 6;
  const SystemS start = massspring::make_system<SystemS>(massspring::make_cloth(o));
  auto first_step = [&](auto& solver) {
    SystemS s = start;
    s.add_force(massspring::Gravity<double>({0, -9.8, 0}));
    solver.precompute(s, 1.0 / 30);
    return solver.step(s);
  };
  SUBCASE("FastMassSpring, tolerance 0 (the default): its iterations ran as asked, not a failure") {
    massspring::FastMassSpring<SystemS> solver;
    const massspring::StepReport r = first_step(solver);
    CHECK(r.ok());
    CHECK(r.iterations == solver.options.iterations);
    CHECK_FALSE(r.converged);
    CHECK(r.convergence == Convergence::NotTested);
  }
  SUBCASE("FastMassSpring, a tolerance met before the cap") {
    massspring::FastMassSpring<SystemS> solver;
    solver.options.tolerance = 1e-3;
    const massspring::StepReport r = first_step(solver);
    CHECK(r.converged);
    CHECK(r.iterations < solver.options.iterations);
    CHECK(r.convergence == Convergence::Converged);
  }
  SUBCASE("FastMassSpring, the cap before the tolerance (every accelerator)") {
    for (auto a : {massspring::Acceleration::None, massspring::Acceleration::Chebyshev,
                   massspring::Acceleration::Anderson}) {
      massspring::FastMassSpring<SystemS> solver;
      solver.options.acceleration = a;
      solver.options.tolerance = 1e-30;
      solver.options.iterations = 3;
      const massspring::StepReport r = first_step(solver);
      CHECK(r.ok());
      CHECK_FALSE(r.converged);
      CHECK(r.convergence == Convergence::NotConverged);
    }
  }
  SUBCASE("BackwardEuler: Newton tests its tolerance, the linearised step does not") {
    BackwardEuler<SystemS> newton;
    newton.options.mode = BackwardEulerMode::Newton;
    const massspring::StepReport r = first_step(newton);
    CHECK(r.converged);
    CHECK(r.convergence == Convergence::Converged);
    BackwardEuler<SystemS> capped;
    capped.options.mode = BackwardEulerMode::Newton;
    capped.options.tolerance = 0;
    capped.options.iterations = 1;
    CHECK(first_step(capped).convergence == Convergence::NotConverged);
    BackwardEuler<SystemS> linearized;
    linearized.options.mode = BackwardEulerMode::Linearized;
    const massspring::StepReport l = first_step(linearized);
    CHECK(l.ok());
    CHECK(l.convergence == Convergence::NotTested);
  }
}

// Linearized BackwardEuler takes one Newton step on the incremental potential
//   phi(x) = sum_i m_i |x_i - x_i^0 - h v_i^0|^2 / (2 h^2) + U(x)
// from the guess x^0 + h v^0. examples/scenes/flag.json (3,200 points, no colliders) under
// gravity at 1/30 s: the first steps lower phi, then one raises it (its matrix is indefinite
// where springs compress) and the state runs away. That step is refused (blew_up), nothing
// changed; with the check off (energy_growth 0) the same step is committed, and phi computed here
// from the committed state shows it went uphill.
TEST_CASE("BackwardEuler Linearized: a step whose linear solve raises phi is refused") {
  const massspring::SceneDescription<double> scene = massspring::io::read_json_scene<double>(
      massspring::test::source_dir() / "examples" / "scenes" / "flag.json");
  const double h = 1.0 / 30;
  const auto phi = [h](const SystemS& s, const Pts& x0, const Pts& v0, const Pts& x) {
    double inertia = 0;
    for (Eigen::Index i = 0; i < x.rows(); ++i)
      inertia += s.masses()(i) * (x.row(i) - x0.row(i) - h * v0.row(i)).squaredNorm();
    return inertia / (2 * h * h) + massspring::potential_energy(s, x);
  };
  // The first step that the check refuses, and the state before it.
  SystemS checked = massspring::make_system<SystemS>(scene);
  checked.add_force(massspring::Gravity<double>({0, -9.8, 0}));
  BackwardEuler<SystemS> linearized;
  linearized.options.mode = BackwardEulerMode::Linearized;
  linearized.precompute(checked, h);
  int refused = 0;
  for (int k = 1; k <= 20 && refused == 0; ++k) {
    const Pts x0 = checked.positions(), v0 = checked.velocities();
    const massspring::StepReport report = linearized.step(checked);
    if (report.ok()) continue;
    refused = k;
    CHECK(report.blew_up);
    CHECK(report.finite);
    CHECK(checked.positions() == x0);  // nothing changed
    CHECK(checked.velocities() == v0);
  }
  REQUIRE(refused > 1);

  // The same run with the checks off: every step before `refused` lowered phi, that one raised it.
  SystemS unchecked = massspring::make_system<SystemS>(scene);
  unchecked.add_force(massspring::Gravity<double>({0, -9.8, 0}));
  BackwardEuler<SystemS> off;
  off.options.mode = BackwardEulerMode::Linearized;
  off.options.energy_growth = 0;
  off.precompute(unchecked, h);
  for (int k = 1; k <= refused; ++k) {
    const Pts x0 = unchecked.positions(), v0 = unchecked.velocities();
    Pts guess = x0 + h * v0;
    for (const int p : unchecked.pinned()) guess.row(p) = x0.row(p);  // the flag's pins are still
    const double before = phi(unchecked, x0, v0, guess);
    REQUIRE(off.step(unchecked).ok());
    const double after = phi(unchecked, x0, v0, unchecked.positions());
    CAPTURE(k);
    if (k < refused)
      CHECK(after <= before);
    else
      CHECK(after > before + 0.01 * std::abs(before));
  }
}
