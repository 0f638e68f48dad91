// integrators/fast_mass_spring.hpp: Q, energy descent, closed forms, pins, allocation, failure.
#include <doctest/doctest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <massspring/integrators/fast_mass_spring.hpp>
#include <massspring/scene/cloth.hpp>
#include <massspring/scene/make_system.hpp>
#include <memory>
#include <random>
#include <type_traits>
#include <vector>

#include "support/alloc_counter.hpp"
#include "support/uniform_forces.hpp"

namespace {

// The assignment's solver (FastMassSpringOptions::reference(): 50 plain iterations from the
// current positions, no contact term), whose properties these tests check; a test that wants an
// acceleration or another start sets it.
template <class S>
massspring::FastMassSpringOptions<typename S::Scalar> plain_options() {
  return massspring::FastMassSpringOptions<typename S::Scalar>::reference();
}

using massspring::test::add_gravity;
using massspring::test::add_uniform_force;

using massspring::Dense;
using massspring::Edges;
using massspring::Error;
using massspring::FastMassSpring;
using massspring::InitialGuess;
using massspring::MassSpringSystem;
using massspring::PinMode;
using massspring::Sparse;
template <class Scalar>
using Points = massspring::Points<Scalar>;

// A small cloth (quads with both diagonals, top corners pinned, Voronoi masses), its free points
// nudged off the rest state so that every iteration has work to do.
template <class System>
System small_cloth(int columns = 7, int rows = 5, unsigned seed = 3) {
  massspring::ClothOptions o;
  o.columns = columns;
  o.rows = rows;
  o.width = 0.6;
  o.height = 0.4;
  o.stiffness = 200;
  o.plane = massspring::ClothPlane::Horizontal;
  System s = massspring::make_system<System>(massspring::make_cloth(o));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  Points<typename System::Scalar> x = s.positions();
  for (int i = 0; i < s.num_points(); ++i)
    if (!s.is_pinned(i))
      for (int c = 0; c < 3; ++c) x(i, c) += typename System::Scalar(u(rng));
  s.set_positions(x);
  return s;
}

// A chain of n points along x, both ends pinned, m = 1, k = 500 (the JSON+OBJ scenes' chain).
template <class System>
System chain(int n = 10) {
  using Scalar = typename System::Scalar;
  Points<Scalar> v(n, 3);
  Edges e(n - 1, 2);
  for (int i = 0; i < n; ++i) v.row(i) << Scalar(i) / Scalar(n - 1), 0, 0;
  for (int i = 0; i + 1 < n; ++i) e.row(i) << i, i + 1;
  System s(v, e, Scalar(1), Scalar(500));
  s.pin(0);
  s.pin(n - 1);
  return s;
}

// Everything a step's objective depends on, frozen at the start of the step.
struct StepProblem {
  Points<double> x0, v0, targets;
  std::vector<int> pinned;
  Eigen::VectorXd m, k, r;
  Edges springs;
  double dt;
  Eigen::RowVector3d force, gravity;
  PinMode pins;
  double w;

  // gravity g [m/s^2] and force f [N] on every point: the system's Gravity and ConstantForce terms.
  template <class System, class Options>
  StepProblem(const System& s, const Options& o, double step, const Eigen::RowVector3d& g,
              const Eigen::RowVector3d& f = Eigen::RowVector3d::Zero())
      : x0(s.positions().template cast<double>()),
        v0(s.velocities().template cast<double>()),
        targets(s.pin_targets().template cast<double>()),
        pinned(s.pinned()),
        m(s.masses().template cast<double>()),
        k(s.stiffness().template cast<double>()),
        r(s.rest_lengths().template cast<double>()),
        springs(s.springs()),
        dt(step),
        force(f),
        gravity(g),
        pins(o.pins),
        w(double(o.penalty_weight)) {}

  bool held(int i) const {
    return pins == PinMode::Exact && std::find(pinned.begin(), pinned.end(), i) != pinned.end();
  }

  // E(X) of DESIGN.md, written out term by term (independent of the solver's bookkeeping).
  double energy(const Points<double>& x) const {
    double e = 0;
    for (int s = 0; s < springs.rows(); ++s) {
      const double l = (x.row(springs(s, 0)) - x.row(springs(s, 1))).norm();
      e += 0.5 * k(s) * (l - r(s)) * (l - r(s));
    }
    for (int i = 0; i < x.rows(); ++i) {
      if (held(i)) continue;
      const Eigen::RowVector3d y = x0.row(i) + dt * v0.row(i);
      e += m(i) / (2 * dt * dt) * (x.row(i) - y).squaredNorm();
      e -= x.row(i).dot(force + m(i) * gravity);
    }
    if (pins == PinMode::Penalty)
      for (std::size_t p = 0; p < pinned.size(); ++p)
        e += 0.5 * w * (x.row(pinned[p]) - targets.row(Eigen::Index(p))).squaredNorm();
    return e;
  }

  // dE/dX at the free points (rows of held points zero).
  Points<double> gradient(const Points<double>& x) const {
    Points<double> g = Points<double>::Zero(x.rows(), 3);
    for (int s = 0; s < springs.rows(); ++s) {
      const Eigen::RowVector3d d = x.row(springs(s, 0)) - x.row(springs(s, 1));
      const double l = d.norm();
      const Eigen::RowVector3d f = k(s) * (l - r(s)) * d / l;
      g.row(springs(s, 0)) += f;
      g.row(springs(s, 1)) -= f;
    }
    for (int i = 0; i < x.rows(); ++i) {
      const Eigen::RowVector3d y = x0.row(i) + dt * v0.row(i);
      g.row(i) += m(i) / (dt * dt) * (x.row(i) - y) - (force + m(i) * gravity);
    }
    if (pins == PinMode::Penalty)
      for (std::size_t p = 0; p < pinned.size(); ++p)
        g.row(pinned[p]) += w * (x.row(pinned[p]) - targets.row(Eigen::Index(p)));
    for (int i = 0; i < x.rows(); ++i)
      if (held(i)) g.row(i).setZero();
    return g;
  }
};

template <class Matrix>
Eigen::MatrixXd dense(const Matrix& m) {
  if constexpr (std::is_base_of_v<Eigen::SparseMatrixBase<Matrix>, Matrix>)
    return Eigen::MatrixXd(m.template cast<double>());
  else
    return m.template cast<double>();
}

double relative_difference(const Points<double>& a, const Points<double>& b) {
  return (a - b).norm() / b.norm();
}

}  // namespace

#define MS_SYSTEM_TYPES                                              \
  MassSpringSystem<double, Sparse>, MassSpringSystem<double, Dense>, \
      MassSpringSystem<float, Sparse>, MassSpringSystem<float, Dense>
#define MS_DOUBLE_SYSTEMS MassSpringSystem<double, Sparse>, MassSpringSystem<double, Dense>

TEST_CASE_TEMPLATE("Q = A^T K A + M / dt^2 (+ w C^T C) is symmetric positive definite", System,
                   MS_DOUBLE_SYSTEMS) {
  const System s = small_cloth<System>(5, 4);
  const double dt = 1.0 / 30;
  // Independent: Q from the system's own A, K, M, C, multiplied out densely.
  const Eigen::MatrixXd a = dense(s.incidence());
  const Eigen::MatrixXd k = dense(s.stiffness_matrix());
  const Eigen::MatrixXd m = dense(s.mass_matrix());
  const Eigen::MatrixXd c = dense(s.pin_selector());
  const Eigen::MatrixXd base = a.transpose() * k * a + m / (dt * dt);

  for (const PinMode mode : {PinMode::Penalty, PinMode::Exact}) {
    CAPTURE(int(mode));
    FastMassSpring<System> solver(plain_options<System>());
    solver.options.pins = mode;
    solver.options.penalty_weight = 1e4;  // moderate, so that the eigenvalue test is meaningful
    solver.precompute(s, dt);
    const Eigen::MatrixXd q = dense(solver.system_matrix());
    Eigen::MatrixXd expected;
    if (mode == PinMode::Penalty) {
      expected = base + 1e4 * c.transpose() * c;
    } else {
      const auto& f = solver.free_points();
      REQUIRE(int(f.size()) == s.num_points() - s.num_pinned());
      expected.resize(Eigen::Index(f.size()), Eigen::Index(f.size()));
      for (std::size_t i = 0; i < f.size(); ++i)
        for (std::size_t j = 0; j < f.size(); ++j)
          expected(Eigen::Index(i), Eigen::Index(j)) = base(f[i], f[j]);
    }
    REQUIRE(q.rows() == expected.rows());
    CHECK((q - expected).norm() <= 1e-12 * expected.norm());
    CHECK((q - q.transpose()).norm() == 0.0);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(q);
    CHECK(eig.eigenvalues().minCoeff() > 0.0);
  }
}

TEST_CASE_TEMPLATE("the energy never increases over local-global iterations", System,
                   MS_SYSTEM_TYPES) {
  using Scalar = typename System::Scalar;
  const double dt = 1.0 / 30;
  for (const PinMode mode : {PinMode::Exact, PinMode::Penalty}) {
    if (std::is_same_v<Scalar, float> && mode == PinMode::Penalty) continue;  // see docs
    CAPTURE(int(mode));
    System s = small_cloth<System>();
    FastMassSpring<System> solver(plain_options<System>());
    solver.options.pins = mode;
    add_gravity(s, {0, Scalar(-9.8), 0});
    add_uniform_force(s, {Scalar(0.01), 0, 0});
    solver.options.initial_guess = InitialGuess::Inertial;  // so that step 1 starts off balance
    solver.precompute(s, Scalar(dt));
    // Two steps first, so that the velocities are not zero.
    solver.step(s);
    solver.step(s);
    const StepProblem problem(s, solver.options, dt, Eigen::RowVector3d(0, double(Scalar(-9.8)), 0),
                              Eigen::RowVector3d(double(Scalar(0.01)), 0, 0));
    const double tol = std::is_same_v<Scalar, float> ? 1e-5 : 1e-12;
    double previous = std::numeric_limits<double>::infinity();
    double offset = 0;
    for (int k = 1; k <= 25; ++k) {
      CAPTURE(k);
      System copy = s;
      solver.options.iterations = k;
      const massspring::StepReport report = solver.step(copy);
      REQUIRE(report.ok());
      CHECK(report.iterations == k);
      const double e = problem.energy(copy.positions().template cast<double>());
      CHECK(e <= previous + tol * std::abs(e));
      // The report's energy is E up to a constant (the held points' terms).
      if (k == 1) offset = report.energy - e;
      CHECK(report.energy - e == doctest::Approx(offset).epsilon(tol * 10).scale(std::abs(e)));
      CHECK(report.relative_decrease >= 0.0);
      CHECK(report.relative_decrease <= 1.0);
      previous = e;
    }
  }
}

TEST_CASE_TEMPLATE("converged local-global solves the implicit Euler equations", System,
                   MS_DOUBLE_SYSTEMS) {
  const double dt = 1.0 / 30;
  for (const PinMode mode : {PinMode::Exact, PinMode::Penalty}) {
    CAPTURE(int(mode));
    System s = small_cloth<System>();
    FastMassSpring<System> solver(plain_options<System>());
    solver.options.pins = mode;
    add_gravity(s, {0, -9.8, 0});
    solver.options.iterations = 20000;  // linear convergence, slow when k dt^2 / m is large
    solver.precompute(s, dt);
    solver.step(s);
    const StepProblem problem(s, solver.options, dt, Eigen::RowVector3d(0, -9.8, 0));
    const massspring::StepReport report = solver.step(s);
    REQUIRE(report.ok());
    CHECK(report.iterations == 20000);
    CHECK(report.relative_decrease <= 1e-12);
    // Stationary point of E: M (X - Y) / dt^2 = F + spring forces at the free points.
    const Points<double> x = s.positions();
    const Points<double> g = problem.gradient(x);
    double scale = 0;  // size of the inertial term, for a relative measure
    for (int i = 0; i < x.rows(); ++i)
      scale = std::max(scale, problem.m(i) / (dt * dt) * (x.row(i) - problem.x0.row(i)).norm());
    double residual = 0;
    for (int i = 0; i < x.rows(); ++i)
      if (!s.is_pinned(i)) residual = std::max(residual, g.row(i).norm());
    CHECK(residual <= 1e-10 * scale);
  }
}

TEST_CASE("Dense and Sparse give the same trajectory") {
  for (const PinMode mode : {PinMode::Exact, PinMode::Penalty}) {
    CAPTURE(int(mode));
    auto sparse = small_cloth<MassSpringSystem<double, Sparse>>();
    auto dense_system = small_cloth<MassSpringSystem<double, Dense>>();
    FastMassSpring<MassSpringSystem<double, Sparse>> a;
    FastMassSpring<MassSpringSystem<double, Dense>> b;
    a.options.pins = b.options.pins = mode;
    add_uniform_force(sparse, {0, -9.8 * 0.005, 0});
    add_uniform_force(dense_system, {0, -9.8 * 0.005, 0});
    a.precompute(sparse, 1.0 / 30);
    b.precompute(dense_system, 1.0 / 30);
    for (int frame = 0; frame < 60; ++frame) {
      REQUIRE(a.step(sparse).ok());
      REQUIRE(b.step(dense_system).ok());
    }
    CHECK(relative_difference(dense_system.positions(), sparse.positions()) <= 1e-10);
    CHECK(relative_difference(dense_system.velocities(), sparse.velocities()) <= 1e-10);
    CHECK((sparse.positions() - small_cloth<MassSpringSystem<double>>().positions()).norm() >
          0.01);  // it did move
  }
}

TEST_CASE("float agrees with double on the chain") {
  auto d = chain<MassSpringSystem<double>>();
  auto f = chain<MassSpringSystem<float>>();
  FastMassSpring<MassSpringSystem<double>> sd;
  FastMassSpring<MassSpringSystem<float>> sf;
  add_uniform_force(d, {0, -9.8, 0});
  add_uniform_force(f, {0, -9.8f, 0});
  sd.precompute(d, 1.0 / 30);
  sf.precompute(f, 1.0f / 30);
  for (int frame = 0; frame < 100; ++frame) {
    REQUIRE(sd.step(d).ok());
    REQUIRE(sf.step(f).ok());
  }
  CHECK(relative_difference(f.positions().cast<double>(), d.positions()) <= 1e-4);
  CHECK(d.positions().col(1).minCoeff() < -0.05);  // it sagged
}

TEST_CASE_TEMPLATE("a single spring with one pinned end settles at 1 + 9.8 / 500", System,
                   MS_SYSTEM_TYPES) {
  using Scalar = typename System::Scalar;
  // The JSON+OBJ scenes' single-spring-horizontal scene: (0,0,0)-(1,0,0), pin at 0, k = 500, m = 1.
  Points<Scalar> v(2, 3);
  v << 0, 0, 0, 1, 0, 0;
  Edges e(1, 2);
  e << 0, 1;
  System s(v, e, Scalar(1), Scalar(500));
  s.pin(0);
  FastMassSpring<System> solver(plain_options<System>());
  add_uniform_force(s, {0, Scalar(-9.8), 0});
  solver.precompute(s, Scalar(1.0 / 30));
  // It swings down as a pendulum, which implicit Euler damps slowly (about 0.5 % a step).
  for (int frame = 0; frame < 6000; ++frame) REQUIRE(solver.step(s).ok());
  const double tol = std::is_same_v<Scalar, float> ? 1e-5 : 1e-9;
  const Eigen::RowVector3d x = s.positions().row(1).template cast<double>();
  CHECK(x(0) == doctest::Approx(0.0).scale(1).epsilon(tol));
  CHECK(x(1) == doctest::Approx(-(1.0 + 9.8 / 500)).epsilon(tol));
  CHECK(x(2) == 0.0);
  CHECK(s.positions().row(0).isZero(0));
}

TEST_CASE("a vertical spring follows implicit Euler's recurrence and oscillates at sqrt(k/m)") {
  // Pin at the origin, a mass m below it on the y axis: along the axis the spring is exactly
  // linear, so the step is y' = (m (2 y - y_prev) / h^2 - k r - m g) / (m / h^2 + k).
  const double k = 500, m = 2, r = 1, g = 9.8, h = 1e-3;
  Points<double> v(2, 3);
  v << 0, 0, 0, 0, -r, 0;
  Edges e(1, 2);
  e << 0, 1;
  MassSpringSystem<double> s(v, e, m, k);
  s.pin(0);
  const double equilibrium = -(r + m * g / k), amplitude = 1e-3;
  Points<double> x0 = s.positions();
  x0(1, 1) = equilibrium + amplitude;
  s.set_positions(x0);
  FastMassSpring<MassSpringSystem<double>> solver;
  add_gravity(s, {0, -g, 0});
  solver.options.iterations = 3;
  solver.precompute(s, h);

  const double omega = std::sqrt(k / m);
  const double period = 2 * M_PI / omega;
  double y = x0(1, 1), y_prev = y;  // at rest
  std::vector<double> crossings;
  double worst = 0;
  for (int n = 1; n * h < 4 * period; ++n) {
    REQUIRE(solver.step(s).ok());
    // The recurrence applied to the solver's own last two positions, every step.
    const double expected = (m * (2 * y - y_prev) / (h * h) - k * r - m * g) / (m / (h * h) + k);
    worst = std::max(worst, std::abs(s.positions()(1, 1) - expected));
    y_prev = y;
    y = s.positions()(1, 1);
    // zero crossings of y - equilibrium, linearly interpolated
    const double a = y_prev - equilibrium, b = y - equilibrium;
    if ((a > 0) != (b > 0)) crossings.push_back((n - 1 + a / (a - b)) * h);
  }
  CHECK(worst <= 1e-14);  // |y| is about 1: a few rounding errors
  CHECK(s.positions()(1, 0) == 0.0);
  REQUIRE(crossings.size() >= 6);
  const double measured =
      M_PI * double(crossings.size() - 1) / (crossings.back() - crossings.front());
  // Implicit Euler's own frequency is atan(omega h) / h; the exact one is sqrt(k/m).
  CHECK(measured == doctest::Approx(std::atan(omega * h) / h).epsilon(1e-6));
  CHECK(measured == doctest::Approx(omega).epsilon(1e-3));
}

TEST_CASE_TEMPLATE("pinned points: penalty moves them < 1e-6, exact not at all", System,
                   MS_DOUBLE_SYSTEMS) {
  for (const PinMode mode : {PinMode::Penalty, PinMode::Exact}) {
    CAPTURE(int(mode));
    System s = small_cloth<System>();
    const Points<double> targets = s.pin_targets();
    FastMassSpring<System> solver(plain_options<System>());
    solver.options.pins = mode;
    add_uniform_force(s, {0, -9.8, 0});  // the JSON+OBJ scenes' force: 9.8 N per point
    solver.precompute(s, 1.0 / 30);
    double worst = 0;
    for (int frame = 0; frame < 50; ++frame) {
      REQUIRE(solver.step(s).ok());
      for (int p = 0; p < s.num_pinned(); ++p)
        worst = std::max(
            worst,
            (s.positions().row(s.pinned()[std::size_t(p)]) - targets.row(p)).cwiseAbs().maxCoeff());
    }
    if (mode == PinMode::Exact)
      CHECK(worst == 0.0);
    else
      CHECK(worst < 1e-6);
  }
}

TEST_CASE_TEMPLATE("step() allocates nothing", System, MS_SYSTEM_TYPES) {
  for (const PinMode mode : {PinMode::Exact, PinMode::Penalty}) {
    for (const double tolerance : {0.0, 1e-6}) {
      CAPTURE(int(mode));
      CAPTURE(tolerance);
      System s = small_cloth<System>();
      FastMassSpring<System> solver(plain_options<System>());
      solver.options.pins = mode;
      solver.options.allow_float_penalty = true;  // allocation is the point here, not accuracy
      solver.options.tolerance = typename System::Scalar(tolerance);
      add_gravity(s, {0, -9.8f, 0});
      solver.precompute(s, 1.0f / 30);
      std::size_t allocations = 0;
      {
        massspring::test::CountAllocations count;
        for (int frame = 0; frame < 3; ++frame) solver.step(s);
        allocations = count.count();
      }
      CHECK(allocations == 0);
      CHECK(s.positions().allFinite());
    }
  }
}

TEST_CASE("the model's changes: re-factorize only for masses, stiffness, pins and options") {
  using System = MassSpringSystem<double>;
  System s = chain<System>();
  FastMassSpring<System> solver(plain_options<System>());
  add_uniform_force(s, {0, -9.8, 0});
  solver.precompute(s, 1.0 / 30);
  CHECK_FALSE(solver.step(s).refactorized);

  // Free: rest lengths, pin targets, state.
  s.set_rest_lengths(s.rest_lengths() * 0.5);
  s.set_pin_target(9, Eigen::Vector3d(0.8, 0.1, 0));
  CHECK_FALSE(solver.step(s).refactorized);
  CHECK(s.positions().row(9) == Eigen::RowVector3d(0.8, 0.1, 0));  // exact pins follow at once
  CHECK_FALSE(solver.step(s).refactorized);

  // Not free.
  s.set_stiffness(s.stiffness() * 2);
  CHECK(solver.step(s).refactorized);
  CHECK_FALSE(solver.step(s).refactorized);
  s.set_masses(s.masses() * 2);
  CHECK(solver.step(s).refactorized);
  s.unpin(9);
  CHECK(solver.step(s).refactorized);
  CHECK(solver.free_points().size() == 9);
  solver.options.pins = PinMode::Penalty;
  CHECK(solver.step(s).refactorized);
  solver.options.penalty_weight = 1e9;
  CHECK(solver.step(s).refactorized);
  solver.options.iterations = 7;  // free
  const auto report = solver.step(s);
  CHECK_FALSE(report.refactorized);
  CHECK(report.iterations == 7);
}

TEST_CASE("a shorter rest length moves the equilibrium: r + m g / k") {
  Points<double> v(2, 3);
  v << 0, 0, 0, 0, -1, 0;
  Edges e(1, 2);
  e << 0, 1;
  MassSpringSystem<double> s(v, e, 1.0, 500.0);
  s.pin(0);
  s.set_rest_lengths(Eigen::VectorXd::Constant(1, 0.5));
  FastMassSpring<MassSpringSystem<double>> solver;
  add_uniform_force(s, {0, -9.8, 0});
  solver.precompute(s, 1.0 / 30);
  for (int frame = 0; frame < 300; ++frame) solver.step(s);
  CHECK(s.positions()(1, 1) == doctest::Approx(-(0.5 + 9.8 / 500)).epsilon(1e-10));
}

TEST_CASE("gravity as an acceleration is the per-point force m g") {
  using System = MassSpringSystem<double>;
  System a = small_cloth<System>(), b = a;
  FastMassSpring<System> sa, sb;
  add_gravity(a, {0, -9.8, 0});
  add_uniform_force(b, {0, -9.8, 0});
  sa.precompute(a, 0.01);
  sb.precompute(b, 0.01);
  // With unit masses the two are the same force, so the trajectories agree to the bit.
  Eigen::VectorXd ones = Eigen::VectorXd::Ones(a.num_points());
  a.set_masses(ones);
  b.set_masses(ones);
  for (int frame = 0; frame < 10; ++frame) {
    sa.step(a);
    sb.step(b);
  }
  CHECK(a.positions() == b.positions());
}

TEST_CASE("the tolerance stop") {
  using System = MassSpringSystem<double>;
  System s = small_cloth<System>();
  FastMassSpring<System> solver(plain_options<System>());
  add_gravity(s, {0, -9.8, 0});
  solver.options.iterations = 1000;
  solver.options.tolerance = 1e-4;
  solver.precompute(s, 1.0 / 30);
  const auto report = solver.step(s);
  CHECK(report.converged);
  CHECK(report.iterations < 1000);
  CHECK(report.iterations > 1);
  CHECK(report.relative_decrease <= 1e-4);
  solver.options.tolerance = 0;
  solver.options.iterations = 13;
  const auto fixed = solver.step(s);
  CHECK_FALSE(fixed.converged);
  CHECK(fixed.iterations == 13);
}

TEST_CASE("both starting guesses reach the same minimiser") {
  using System = MassSpringSystem<double>;
  System a = small_cloth<System>();
  add_gravity(a, {0, -9.8, 0});
  System b = a;
  FastMassSpring<System> sa, sb;
  for (auto* solver : {&sa, &sb})
    solver->options.iterations = 20000;  // to the end: the minimiser, not a stopping rule
  sb.options.initial_guess = InitialGuess::Inertial;
  sa.precompute(a, 1.0 / 30);
  sb.precompute(b, 1.0 / 30);
  for (int frame = 0; frame < 3; ++frame) {
    sa.step(a);
    sb.step(b);
  }
  CHECK(relative_difference(a.positions(), b.positions()) <= 1e-12);
}

TEST_CASE("a step whose result is not finite reports it and keeps the last good state") {
  using System = MassSpringSystem<double>;
  System s = chain<System>();
  FastMassSpring<System> solver(plain_options<System>());
  add_uniform_force(s, {0, -9.8, 0});
  solver.precompute(s, 1.0 / 30);
  REQUIRE(solver.step(s).ok());
  const Points<double> x = s.positions(), v = s.velocities();
  // A finite but enormous rest length: k r overflows to infinity in the right-hand side.
  Eigen::VectorXd r = s.rest_lengths();
  r(3) = 1e307;
  s.set_rest_lengths(r);
  const auto report = solver.step(s);
  CHECK_FALSE(report.ok());
  CHECK_FALSE(report.finite);
  CHECK(s.positions() == x);
  CHECK(s.velocities() == v);
}

TEST_CASE_TEMPLATE(
    "one iteration minimises the global step's quadratic for d(x0), on irregular graphs", System,
    MS_SYSTEM_TYPES) {
  // x1 of one iteration from x0 (the current positions) must make the gradient of
  // sum_e k_e / 2 |x_i - x_j - d_e|^2 + sum_i m_i / (2 dt^2) |x_i - y_i|^2 - f . x vanish at the
  // free points, with d_e = r_e (x0_i - x0_j) / |x0_i - x0_j| computed here from the positions
  // (or, for a spring of zero length, from the rest positions, the direction precompute
  // records). Random graphs with an odd and an even number of springs, listed in both
  // orientations, rows with runs of one to several springs, one spring of zero length and two
  // pinned points: the spring pass takes springs in pairs across rows, and an odd last one alone.
  using Scalar = typename System::Scalar;
  const double dt = 0.05;
  for (const int m : {31, 32, 17, 2, 1}) {
    CAPTURE(m);
    const int n = 12;
    std::mt19937 rng(unsigned(100 + m));
    std::uniform_real_distribution<double> u(-1, 1);
    std::uniform_int_distribution<int> index(0, n - 1);
    Points<Scalar> rest(n, 3);
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) rest(i, c) = Scalar(u(rng));
    // m distinct pairs in random order and orientation.
    std::vector<std::pair<int, int>> pairs;
    for (int a = 0; a < n; ++a)
      for (int b = a + 1; b < n; ++b) {
        const bool flip = index(rng) % 2 == 1;
        pairs.emplace_back(flip ? b : a, flip ? a : b);
      }
    std::shuffle(pairs.begin(), pairs.end(), rng);
    Edges springs(m, 2);
    for (int e = 0; e < m; ++e)
      springs.row(e) << pairs[std::size_t(e)].first, pairs[std::size_t(e)].second;
    System s(rest, springs, Scalar(1), Scalar(1));
    Eigen::Matrix<Scalar, Eigen::Dynamic, 1> k(m), masses(n);
    for (int e = 0; e < m; ++e) k(e) = Scalar(50 + 50 * (u(rng) + 1));
    for (int i = 0; i < n; ++i) masses(i) = Scalar(0.5 + (u(rng) + 1) / 2);
    s.set_stiffness(k);
    s.set_masses(masses);
    for (int i = 0, pins = 0; pins < 2; ++i)  // two points off spring 0
      if (i != springs(0, 0) && i != springs(0, 1)) s.pin(i), ++pins;
    // Off the rest state; spring 0's ends put on one place (zero length).
    Points<Scalar> x = rest;
    for (int i = 0; i < n; ++i)
      if (!s.is_pinned(i))
        for (int c = 0; c < 3; ++c) x(i, c) += Scalar(0.2 * u(rng));
    x.row(springs(0, 1)) = x.row(springs(0, 0));
    s.set_positions(x);
    Points<Scalar> v = Points<Scalar>::Zero(n, 3);
    for (int i = 0; i < n; ++i)
      if (!s.is_pinned(i)) v.row(i) << Scalar(u(rng)), Scalar(u(rng)), Scalar(u(rng));
    s.set_velocities(v);

    FastMassSpring<System> solver(plain_options<System>());
    solver.options.iterations = 1;
    solver.options.initial_guess = InitialGuess::Current;
    add_gravity(s, massspring::Vector3<Scalar>(0, Scalar(-9.8), 0));
    solver.precompute(s, Scalar(dt));
    const StepProblem problem(s, solver.options, dt,
                              Eigen::RowVector3d(0, double(Scalar(-9.8)), 0));
    REQUIRE(solver.step(s).ok());
    const Points<double> x1 = s.positions().template cast<double>();

    Points<double> gradient = Points<double>::Zero(n, 3);
    double scale = 0;  // the largest term, for the tolerance
    for (int e = 0; e < m; ++e) {
      const int i = springs(e, 0), j = springs(e, 1);
      Eigen::RowVector3d u0 = problem.x0.row(i) - problem.x0.row(j);
      if (u0.norm() == 0) u0 = (rest.row(i) - rest.row(j)).template cast<double>();
      const Eigen::RowVector3d d = problem.r(e) * u0.normalized();
      const Eigen::RowVector3d f = problem.k(e) * (x1.row(i) - x1.row(j) - d);
      gradient.row(i) += f;
      gradient.row(j) -= f;
      scale = std::max(scale, problem.k(e) * (x1.row(i) - x1.row(j)).norm());
    }
    for (int i = 0; i < n; ++i) {
      const Eigen::RowVector3d y = problem.x0.row(i) + dt * problem.v0.row(i);
      gradient.row(i) +=
          problem.m(i) / (dt * dt) * (x1.row(i) - y) - problem.m(i) * problem.gravity;
      scale = std::max(scale, problem.m(i) / (dt * dt) * x1.row(i).norm());
    }
    for (int i = 0; i < n; ++i)
      if (s.is_pinned(i)) {
        CHECK(x1.row(i) == problem.x0.row(i));  // exact pins do not move
        gradient.row(i).setZero();
      }
    // Rounding only: tens of units of the Scalar's epsilon of the largest term (5 pass).
    CHECK(gradient.cwiseAbs().maxCoeff() <=
          50 * double(std::numeric_limits<Scalar>::epsilon()) * scale);
  }
}

TEST_CASE("a zero-length spring keeps its last direction") {
  // Two free points joined by a spring of rest length 1 are pushed onto each other exactly.
  Points<double> v(2, 3);
  v << 0, 0, 0, 1, 0, 0;
  Edges e(1, 2);
  e << 0, 1;
  MassSpringSystem<double> s(v, e, 1.0, 100.0);
  Points<double> x(2, 3);
  x << 0.5, 0, 0, 0.5, 0, 0;
  s.set_positions(x);
  FastMassSpring<MassSpringSystem<double>> solver;
  solver.options.iterations = 1;
  solver.precompute(s, 0.1);  // last direction: along +x (from the rest positions)
  REQUIRE(solver.step(s).ok());
  CHECK(s.positions().allFinite());
  // The spring pushes the points apart along x, symmetrically.
  CHECK(s.positions()(0, 0) < 0.5);
  CHECK(s.positions()(1, 0) > 0.5);
  CHECK(s.positions()(0, 0) + s.positions()(1, 0) == doctest::Approx(1.0));
  CHECK(s.positions().col(1).isZero(0));
}

TEST_CASE("a zero-length spring takes its direction from the end of the previous step") {
  // At rest the spring lies along x; a first step with the points apart along y records y; then
  // the points are put on top of each other and the spring must push them apart along y, not x.
  Points<double> v(2, 3);
  v << 0, 0, 0, 1, 0, 0;
  Edges e(1, 2);
  e << 0, 1;
  MassSpringSystem<double> s(v, e, 1.0, 100.0);
  FastMassSpring<MassSpringSystem<double>> solver;
  solver.options.iterations = 1;
  solver.precompute(s, 0.1);  // the spring's direction is x here
  Points<double> x(2, 3);
  x << 0.5, 0, 0, 0.5, 0.1, 0;
  s.set_positions(x);
  REQUIRE(solver.step(s).ok());
  CHECK(s.positions().col(0).isConstant(0.5));  // stayed on the y axis
  x << 0.5, 0.05, 0, 0.5, 0.05, 0;
  s.set_positions(x);
  s.set_velocities(Points<double>::Zero(2, 3));
  REQUIRE(solver.step(s).ok());
  CHECK(s.positions().col(0).isConstant(0.5));
  CHECK(s.positions()(1, 1) - s.positions()(0, 1) > 0.01);  // point 1 above point 0, as before
  CHECK(s.positions().col(2).isZero(0));
}

TEST_CASE(
    "options.ordering: Auto takes the order with fewer nonzeros, and every order takes one step") {
  // Liu et al.'s curtain (81 x 81, one diagonal, bending springs; here 1.2 m wide, exact pins):
  // nested dissection of the rest positions fills less than AMD (about 6%).
  using System = MassSpringSystem<double, Sparse>;
  massspring::ClothOptions o;
  o.columns = o.rows = 81;
  o.shear = massspring::ClothShear::One;
  o.bending = true;
  o.plane = massspring::ClothPlane::Vertical;
  o.stiffness = 1000;
  System start = massspring::make_system<System>(massspring::make_cloth(o));
  {
    FastMassSpring<System> warm(plain_options<System>());
    add_gravity(start, {0, -9.8, 0});
    warm.precompute(start, 1.0 / 30);
    for (int frame = 0; frame < 3; ++frame) warm.step(start);
  }
  const auto run = [&](massspring::FillOrdering ordering, Eigen::Index* nonzeros) {
    System s = start;
    FastMassSpring<System> solver(plain_options<System>());
    solver.options.iterations = 10;
    solver.options.ordering = ordering;
    solver.precompute(s, 1.0 / 30);
    *nonzeros = solver.factor_nonzeros();
    REQUIRE(solver.step(s).ok());
    return Points<double>(s.positions());
  };
  Eigen::Index own = 0, nd = 0, automatic = 0;
  const Points<double> x_own = run(massspring::FillOrdering::Solver, &own);
  const Points<double> x_nd = run(massspring::FillOrdering::NestedDissection, &nd);
  const Points<double> x_auto = run(massspring::FillOrdering::Auto, &automatic);
  // Independent: Eigen's own SimplicialLLT (AMD) of the same Q.
  {
    System s = start;
    FastMassSpring<System> solver(plain_options<System>());
    solver.precompute(s, 1.0 / 30);
    const Eigen::SimplicialLLT<Eigen::SparseMatrix<double, Eigen::ColMajor, int>> eigen(
        solver.system_matrix());
    CHECK(own == eigen.matrixL().nestedExpression().nonZeros());
  }
  CHECK(nd < own);
  CHECK(automatic == std::min(nd, own));
  // The order changes rounding only (as Sparse against Dense above).
  CHECK(relative_difference(x_nd, x_own) <= 1e-10);
  CHECK(relative_difference(x_auto, x_own) <= 1e-10);

  // A change of the option re-factorizes at the next step.
  System s = start;
  FastMassSpring<System> solver(plain_options<System>());
  solver.options.ordering = massspring::FillOrdering::Solver;
  solver.precompute(s, 1.0 / 30);
  CHECK(solver.factor_nonzeros() == own);
  solver.options.ordering = massspring::FillOrdering::NestedDissection;
  const massspring::StepReport report = solver.step(s);
  CHECK(report.refactorized);
  CHECK(solver.factor_nonzeros() == nd);

  // Dense takes no order: Auto is its own, NestedDissection is refused.
  using DenseSystem = MassSpringSystem<double, Dense>;
  DenseSystem d = chain<DenseSystem>();
  FastMassSpring<DenseSystem> dense(plain_options<DenseSystem>());
  dense.precompute(d, 0.1);
  dense.options.ordering = massspring::FillOrdering::NestedDissection;
  CHECK_THROWS_WITH_AS(dense.step(d), doctest::Contains("takes no given elimination order"), Error);
}

TEST_CASE("invalid options and time steps are refused") {
  using System = MassSpringSystem<double>;
  System s = chain<System>();
  FastMassSpring<System> solver(plain_options<System>());
  CHECK_THROWS_WITH_AS(solver.step(s), "FastMassSpring: step() before precompute()", Error);
  CHECK_THROWS_WITH_AS(solver.precompute(s, 0.0),
                       "FastMassSpring: dt must be finite and > 0, got 0", Error);
  CHECK_THROWS_WITH_AS(solver.precompute(s, -0.1), doctest::Contains("got -0.1"), Error);
  CHECK_THROWS_WITH_AS(solver.precompute(s, std::numeric_limits<double>::infinity()),
                       doctest::Contains("dt must be finite"), Error);
  solver.precompute(s, 0.1);
  solver.options.iterations = 0;
  CHECK_THROWS_WITH_AS(solver.step(s), "FastMassSpring: options.iterations must be >= 1, got 0",
                       Error);
  solver.options.iterations = 5;
  solver.options.tolerance = -1;
  CHECK_THROWS_WITH_AS(solver.step(s), doctest::Contains("options.tolerance"), Error);
  solver.options.tolerance = 0;
  solver.options.penalty_weight = 0;
  CHECK_THROWS_WITH_AS(solver.step(s), doctest::Contains("options.penalty_weight"), Error);
  solver.options.penalty_weight = 1e10;
}

// ---- acceleration (Chebyshev, Anderson) and float -------------------------------------------

TEST_CASE_TEMPLATE("accelerated local-global converges to the converged plain solution of the step",
                   System, MS_DOUBLE_SYSTEMS) {
  using massspring::Acceleration;
  for (const PinMode mode : {PinMode::Exact, PinMode::Penalty}) {
    CAPTURE(int(mode));
    System start = small_cloth<System>();
    FastMassSpring<System> warm(plain_options<System>());
    warm.options.pins = mode;
    add_gravity(start, {0, -9.8, 0});
    warm.precompute(start, 1.0 / 30);
    warm.step(start);  // non-zero velocities
    const StepProblem problem(start, warm.options, 1.0 / 30, Eigen::RowVector3d(0, -9.8, 0));

    // The reference: plain local-global run to the end (monotone, linear convergence).
    System plain = start;
    warm.options.iterations = 20000;
    REQUIRE(warm.step(plain).ok());
    const Points<double> reference = plain.positions();
    const double e_star = problem.energy(reference);
    // ... which is a stationary point of E (the implicit Euler equations), independently checked.
    // (relative to the inertial term's size, free points; as in the test of the plain solver).
    const Points<double> g = problem.gradient(reference);
    double residual = 0, scale = 0;
    for (int i = 0; i < g.rows(); ++i) {
      scale = std::max(scale, problem.m(i) / (problem.dt * problem.dt) *
                                  (reference.row(i) - problem.x0.row(i)).norm());
      if (!start.is_pinned(i)) residual = std::max(residual, g.row(i).norm());
    }
    REQUIRE(residual <= 1e-10 * scale);

    for (const Acceleration acceleration : {Acceleration::Chebyshev, Acceleration::Anderson}) {
      CAPTURE(int(acceleration));
      System s = start;
      FastMassSpring<System> solver(plain_options<System>());
      solver.options.pins = mode;
      solver.options.acceleration = acceleration;
      solver.options.iterations = 3000;
      solver.precompute(s, 1.0 / 30);
      const massspring::StepReport report = solver.step(s);
      REQUIRE(report.ok());
      CHECK(s.positions().allFinite());
      CHECK(s.velocities().allFinite());
      CHECK(relative_difference(s.positions(), reference) <= 1e-9);
      CHECK(problem.energy(s.positions()) <= e_star + 1e-12 * std::abs(e_star));
      if (acceleration == Acceleration::Chebyshev) {
        CHECK(solver.chebyshev_rho() > 0.0);
        CHECK(solver.chebyshev_rho() < 1.0);
      }
    }
  }
}

// Peng et al. 2018, Algorithm 2, written out plainly: the history as lists of dense columns, the
// least-squares problem by a dense LDLT, and the local-global map G(x) = x - Q_ff^-1 dE/dx_f (the
// global step of the local step at x) with Q_ff assembled here from the masses and springs.
namespace {

struct ReferenceAnderson {
  const StepProblem& problem;
  Eigen::LDLT<Eigen::MatrixXd> q;  // Q on the free points (exact pins), one coordinate
  std::vector<int> free;           // free point of each row of Q

  explicit ReferenceAnderson(const StepProblem& p) : problem(p) {
    std::vector<int> row(std::size_t(p.x0.rows()), -1);
    for (int i = 0; i < int(p.x0.rows()); ++i)
      if (!p.held(i)) {
        row[std::size_t(i)] = int(free.size());
        free.push_back(i);
      }
    Eigen::MatrixXd qff =
        Eigen::MatrixXd::Zero(Eigen::Index(free.size()), Eigen::Index(free.size()));
    for (std::size_t r = 0; r < free.size(); ++r)
      qff(Eigen::Index(r), Eigen::Index(r)) = p.m(free[r]) / (p.dt * p.dt);
    for (int e = 0; e < int(p.springs.rows()); ++e) {
      const int a = row[std::size_t(p.springs(e, 0))], b = row[std::size_t(p.springs(e, 1))];
      if (a >= 0) qff(a, a) += p.k(e);
      if (b >= 0) qff(b, b) += p.k(e);
      if (a >= 0 && b >= 0) qff(a, b) -= p.k(e), qff(b, a) -= p.k(e);
    }
    q.compute(qff);
  }

  // The free coordinates of x as one vector (point-major), and back.
  Eigen::VectorXd flat(const Points<double>& x) const {
    Eigen::VectorXd v(3 * Eigen::Index(free.size()));
    for (std::size_t r = 0; r < free.size(); ++r)
      v.segment<3>(3 * Eigen::Index(r)) = x.row(free[r]).transpose();
    return v;
  }
  Points<double> points(const Eigen::VectorXd& v) const {
    Points<double> x = problem.x0;
    for (std::size_t p = 0; p < problem.pinned.size(); ++p)
      x.row(problem.pinned[p]) = problem.targets.row(Eigen::Index(p));
    for (std::size_t r = 0; r < free.size(); ++r)
      x.row(free[r]) = v.segment<3>(3 * Eigen::Index(r)).transpose();
    return x;
  }
  double energy(const Eigen::VectorXd& v) const { return problem.energy(points(v)); }
  Eigen::VectorXd map(const Eigen::VectorXd& v) const {
    const Points<double> grad = problem.gradient(points(v));
    Eigen::MatrixXd g(Eigen::Index(free.size()), 3);
    for (std::size_t r = 0; r < free.size(); ++r) g.row(Eigen::Index(r)) = grad.row(free[r]);
    const Eigen::MatrixXd step = q.solve(g);
    Eigen::VectorXd out = v;
    for (std::size_t r = 0; r < free.size(); ++r)
      out.segment<3>(3 * Eigen::Index(r)) -= step.row(Eigen::Index(r)).transpose();
    return out;
  }

  // `iterations` accelerated iterations from x0 with a history of `window` columns; the energy
  // check and its fallback as FastMassSpringOptions documents them. Returns the accepted iterate.
  Points<double> run(int iterations, int window, int* rejections) const {
    Eigen::VectorXd x = flat(problem.x0), g_last, f_last;
    std::vector<Eigen::VectorXd> df, dg;
    double e_prev = 0;
    for (int k = 0; k < iterations; ++k) {
      double e = energy(x);
      if (k > 0 && !(e < e_prev)) {  // rejected: the plain step from the last accepted iterate
        x = g_last;
        df.clear(), dg.clear(), g_last.resize(0);
        e = energy(x);
        ++*rejections;
      }
      e_prev = e;
      const Eigen::VectorXd g = map(x), f = g - x;
      if (g_last.size() > 0) {
        df.push_back(f - f_last), dg.push_back(g - g_last);
        if (int(df.size()) > window) df.erase(df.begin()), dg.erase(dg.begin());
      }
      g_last = g, f_last = f;
      x = g;
      if (!df.empty()) {
        const Eigen::Index c = Eigen::Index(df.size());
        Eigen::MatrixXd a(x.size(), c), b(x.size(), c);
        for (Eigen::Index j = 0; j < c; ++j)
          a.col(j) = df[std::size_t(j)], b.col(j) = dg[std::size_t(j)];
        Eigen::MatrixXd normal = a.transpose() * a;
        const double eps = 1e-12 * normal.trace() / double(c) + std::numeric_limits<double>::min();
        normal.diagonal().array() += eps;
        const Eigen::VectorXd theta = normal.ldlt().solve(a.transpose() * f);
        x = g - b * theta;
      }
    }
    if (!(energy(x) <= e_prev)) x = g_last;
    return points(x);
  }
};

}  // namespace

TEST_CASE_TEMPLATE(
    "Anderson's iterates are those of a plain implementation of Peng et al.'s Algorithm 2", System,
    MS_DOUBLE_SYSTEMS) {
  // 20 x 16 points (954 free coordinates: several of the solver's blocks of rows, the last one
  // partial), windows that wrap the history several times, one that never fills.
  System start = small_cloth<System>(20, 16, 7);
  FastMassSpring<System> warm(plain_options<System>());
  add_gravity(start, {0, -9.8, 0});
  warm.precompute(start, 1.0 / 30);
  warm.step(start);  // non-zero velocities
  const StepProblem problem(start, warm.options, 1.0 / 30, Eigen::RowVector3d(0, -9.8, 0));
  const ReferenceAnderson reference(problem);
  REQUIRE(reference.q.info() == Eigen::Success);
  for (const int window : {1, 3, 5, 16}) {
    CAPTURE(window);
    for (const int iterations : {1, 2, 12}) {
      CAPTURE(iterations);
      System s = start;
      FastMassSpring<System> solver(plain_options<System>());
      solver.options.acceleration = massspring::Acceleration::Anderson;
      solver.options.anderson_window = window;
      solver.options.iterations = iterations;
      solver.precompute(s, 1.0 / 30);
      REQUIRE(solver.step(s).ok());
      int rejections = 0;
      const Points<double> expected = reference.run(iterations, window, &rejections);
      CHECK(rejections == int(solver.rejections()));
      CHECK(relative_difference(s.positions(), expected) <= 1e-11);
      // ... and accelerated: closer to the step's minimiser than as many plain iterations.
      if (iterations == 12) {
        System plain = start;
        warm.options.iterations = iterations;
        REQUIRE(warm.step(plain).ok());
        CHECK(problem.energy(s.positions()) < problem.energy(plain.positions()));
      }
    }
  }
}

TEST_CASE("accelerated local-global needs fewer iterations than plain for the same energy") {
  using System = MassSpringSystem<double>;
  using massspring::Acceleration;
  System start = small_cloth<System>(12, 10);
  FastMassSpring<System> solver(plain_options<System>());
  add_gravity(start, {0, -9.8, 0});
  solver.precompute(start, 1.0 / 30);
  solver.step(start);
  const StepProblem problem(start, solver.options, 1.0 / 30, Eigen::RowVector3d(0, -9.8, 0));
  System plain = start;
  solver.options.iterations = 60;
  solver.step(plain);
  const double target = problem.energy(plain.positions());
  for (const Acceleration acceleration : {Acceleration::Chebyshev, Acceleration::Anderson}) {
    CAPTURE(int(acceleration));
    System s = start;
    FastMassSpring<System> fast(plain_options<System>());
    fast.options.acceleration = acceleration;
    fast.options.iterations = 30;
    fast.precompute(s, 1.0 / 30);
    REQUIRE(fast.step(s).ok());
    CHECK(problem.energy(s.positions()) <= target);
  }
}

TEST_CASE_TEMPLATE("accelerated steps never return an energy above their start, nor non-finite",
                   System, MS_SYSTEM_TYPES) {
  using Scalar = typename System::Scalar;
  using massspring::Acceleration;
  for (const Acceleration acceleration : {Acceleration::Chebyshev, Acceleration::Anderson}) {
    CAPTURE(int(acceleration));
    System s = small_cloth<System>();
    FastMassSpring<System> solver(plain_options<System>());
    add_gravity(s, {0, Scalar(-9.8), 0});
    solver.options.acceleration = acceleration;
    // A rho far too large and no delay: the iteration would diverge without its energy check.
    solver.options.chebyshev_rho = Scalar(0.9999);
    solver.options.chebyshev_delay = 1;
    solver.options.initial_guess = InitialGuess::Inertial;
    solver.precompute(s, Scalar(1.0 / 30));
    for (int frame = 0; frame < 20; ++frame) {
      const StepProblem problem(s, solver.options, 1.0 / 30,
                                Eigen::RowVector3d(0, double(Scalar(-9.8)), 0));
      const Points<double> x0 =
          (s.positions() + Scalar(1.0 / 30) * s.velocities()).template cast<double>();
      for (const int k : {1, 2, 3, 7, 15}) {
        System copy = s;
        solver.options.iterations = k;
        const massspring::StepReport report = solver.step(copy);
        REQUIRE(report.ok());
        REQUIRE(copy.positions().allFinite());
        const double tol = std::is_same_v<Scalar, float> ? 1e-5 : 1e-12;
        const double e0 = problem.energy(x0),
                     e = problem.energy(copy.positions().template cast<double>());
        CHECK(e <= e0 + tol * std::abs(e0));
      }
      solver.options.iterations = 10;
      REQUIRE(solver.step(s).ok());
    }
  }
}

TEST_CASE_TEMPLATE("accelerated step() allocates nothing", System, MS_SYSTEM_TYPES) {
  using massspring::Acceleration;
  for (const Acceleration acceleration : {Acceleration::Chebyshev, Acceleration::Anderson}) {
    for (const double tolerance : {0.0, 1e-6}) {
      CAPTURE(int(acceleration));
      CAPTURE(tolerance);
      System s = small_cloth<System>();
      FastMassSpring<System> solver(plain_options<System>());
      solver.options.acceleration = acceleration;
      solver.options.tolerance = typename System::Scalar(tolerance);
      add_gravity(s, {0, -9.8f, 0});
      solver.precompute(s, 1.0f / 30);
      solver.step(s);  // Chebyshev estimates rho on its first step (no allocation either)
      std::size_t allocations = 0;
      {
        massspring::test::CountAllocations count;
        for (int frame = 0; frame < 3; ++frame) solver.step(s);
        allocations = count.count();
      }
      CHECK(allocations == 0);
      CHECK(s.positions().allFinite());
    }
  }
}

TEST_CASE("float with penalty pins is refused unless allowed, naming the problem") {
  using System = MassSpringSystem<float>;
  System s = chain<System>();
  FastMassSpring<System> solver(plain_options<System>());
  solver.options.pins = PinMode::Penalty;
  CHECK_THROWS_WITH_AS(solver.precompute(s, 1.0f / 30),
                       doctest::Contains("PinMode::Penalty in float"), Error);
  solver.options.pins = PinMode::Exact;
  solver.precompute(s, 1.0f / 30);
  solver.options.pins = PinMode::Penalty;  // changed between steps: refused at the step
  CHECK_THROWS_WITH_AS(solver.step(s), doctest::Contains("use PinMode::Exact"), Error);
  solver.options.allow_float_penalty = true;
  CHECK(solver.step(s).ok());
  // double accepts penalty pins without the flag
  MassSpringSystem<double> d = chain<MassSpringSystem<double>>();
  FastMassSpring<MassSpringSystem<double>> dsolver;
  dsolver.options.pins = PinMode::Penalty;
  CHECK_NOTHROW(dsolver.precompute(d, 1.0 / 30));
}

TEST_CASE("invalid acceleration options are refused") {
  using System = MassSpringSystem<double>;
  System s = chain<System>();
  FastMassSpring<System> solver(plain_options<System>());
  solver.precompute(s, 0.1);
  solver.options.chebyshev_rho = 1.0;
  CHECK_THROWS_WITH_AS(solver.step(s), doctest::Contains("chebyshev_rho"), Error);
  solver.options.chebyshev_rho = 0;
  solver.options.chebyshev_gamma = 0;
  CHECK_THROWS_WITH_AS(solver.step(s), doctest::Contains("chebyshev_gamma"), Error);
  solver.options.chebyshev_gamma = 1;
  solver.options.chebyshev_delay = 0;
  CHECK_THROWS_WITH_AS(solver.step(s), doctest::Contains("chebyshev_delay"), Error);
  solver.options.chebyshev_delay = 2;
  solver.options.anderson_window = 0;
  CHECK_THROWS_WITH_AS(solver.step(s), doctest::Contains("anderson_window"), Error);
  solver.options.anderson_window = 17;
  CHECK_THROWS_WITH_AS(solver.step(s), doctest::Contains("anderson_window"), Error);
}

// ---- threads -------------------------------------------------------------------------------

TEST_CASE("options.simd = false: the SSE2 substitution, within rounding of the default") {
  using System = MassSpringSystem<double>;
  System a = small_cloth<System>(24, 20);
  add_gravity(a, {0, -9.8, 0});
  System b = a;
  // The plain iteration: the bound below is its rounding (Anderson's mixing would amplify it).
  FastMassSpring<System> wide(plain_options<System>()), narrow(plain_options<System>());
  for (auto* solver : {&wide, &narrow}) solver->options.iterations = 20;
  narrow.options.simd = false;
  wide.precompute(a, 1.0 / 30);
  narrow.precompute(b, 1.0 / 30);
  for (int frame = 0; frame < 10; ++frame) {
    REQUIRE(wide.step(a).ok());
    REQUIRE(narrow.step(b).ok());
  }
  CHECK_FALSE(narrow.factorization().simd());
#ifdef MASSSPRING_HAVE_SIMD_PATH
  CHECK(wide.factorization().simd() == massspring::detail::cpu_has_avx2_fma());
#else
  CHECK_FALSE(wide.factorization().simd());
#endif
  // The same iteration with other roundings: after 10 steps of this 24 x 20 cloth the positions
  // differ by 4.0e-15 of their largest coordinate (measured; 1.8e-15 when the AVX2 rows split
  // their sums in two, like the SSE2 rows, instead of four); the bound leaves five times that.
  const double scale = a.positions().cwiseAbs().maxCoeff();
  CHECK((a.positions() - b.positions()).cwiseAbs().maxCoeff() <= 2e-14 * scale);
  if (wide.factorization().simd()) CHECK(a.positions() != b.positions());
  // Switching takes effect at the next step, without refactorizing.
  narrow.options.simd = true;
  CHECK_FALSE(narrow.step(b).refactorized);
  CHECK(narrow.factorization().simd() == wide.factorization().simd());
}

TEST_CASE("A copy of a precomputed solver steps on buffers of its own") {
  // The solver keeps no pointer into its own buffers between calls: a copy, made after
  // precompute() and then outliving the original, follows the original's trajectory.
  // (Dense storage: Eigen's sparse factorizations cannot be copied, so neither can a Sparse
  // solver.)
  using System = MassSpringSystem<double, Dense>;
  static_assert(std::is_copy_constructible_v<FastMassSpring<System>>);
  System a = small_cloth<System>(6, 5);
  add_gravity(a, {0, -9.8, 0});
  System b = a;
  FastMassSpring<System> reference(plain_options<System>());
  auto original = std::make_unique<FastMassSpring<System>>(plain_options<System>());
  for (auto* solver : {&reference, original.get()}) solver->options.iterations = 10;
  reference.precompute(a, 1.0 / 30);
  original->precompute(b, 1.0 / 30);
  for (int frame = 0; frame < 2; ++frame) {
    REQUIRE(reference.step(a).ok());
    REQUIRE(original->step(b).ok());
  }
  FastMassSpring<System> copy(*original);
  original.reset();
  FastMassSpring<System> moved(std::move(copy));
  for (int frame = 0; frame < 3; ++frame) {
    REQUIRE(reference.step(a).ok());
    const auto report = moved.step(b);
    REQUIRE(report.ok());
    CHECK_FALSE(report.refactorized);
  }
  CHECK(a.positions() == b.positions());
  CHECK(a.velocities() == b.velocities());
}

TEST_CASE("options.threads: refused below 1, and on Dense storage above 1") {
  using System = MassSpringSystem<double>;
  System s = small_cloth<System>();
  FastMassSpring<System> solver(plain_options<System>());
  solver.options.threads = 0;
  CHECK_THROWS_WITH_AS(solver.precompute(s, 0.1),
                       "FastMassSpring: options.threads must be >= 1, got 0", Error);
  using DenseSystem = MassSpringSystem<double, Dense>;
  DenseSystem d = small_cloth<DenseSystem>();
  FastMassSpring<DenseSystem> dense(plain_options<DenseSystem>());
  dense.options.threads = 2;
  CHECK_THROWS_WITH_AS(dense.precompute(d, 0.1), doctest::Contains("one thread only"), Error);
#ifndef _OPENMP
  solver.options.threads = 2;
  CHECK_THROWS_WITH_AS(solver.precompute(s, 0.1), doctest::Contains("needs OpenMP"), Error);
#endif
}

#ifdef _OPENMP
TEST_CASE("options.threads = 2 gives the one-thread trajectory bit for bit, allocation-free") {
  using System = MassSpringSystem<double>;
  for (const auto acceleration :
       {massspring::Acceleration::None, massspring::Acceleration::Chebyshev}) {
    CAPTURE(int(acceleration));
    System a = small_cloth<System>(24, 20);
    add_gravity(a, {0, -9.8, 0});
    System b = a;
    FastMassSpring<System> one, two;
    for (auto* solver : {&one, &two}) {
      solver->options.acceleration = acceleration;
      solver->options.iterations = 20;
    }
    two.options.threads = 2;
    one.precompute(a, 1.0 / 30);
    two.precompute(b, 1.0 / 30);
    for (int frame = 0; frame < 5; ++frame) {
      one.step(a);
      two.step(b);
    }
    CHECK(a.positions() == b.positions());
    CHECK(a.velocities() == b.velocities());
    std::size_t allocations = 0;
    {
      massspring::test::CountAllocations count;
      for (int frame = 0; frame < 3; ++frame) two.step(b);
      allocations = count.count();
    }
    CHECK(allocations == 0);
    for (int frame = 0; frame < 3; ++frame) one.step(a);
    CHECK(a.positions() == b.positions());
    // Back to one thread at the next step, without refactorizing: still the same.
    two.options.threads = 1;
    for (int frame = 0; frame < 3; ++frame) {
      one.step(a);
      CHECK_FALSE(two.step(b).refactorized);
    }
    CHECK(a.positions() == b.positions());
  }
}
#endif
