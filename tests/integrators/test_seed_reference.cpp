// reference/seed/seed_reference.hpp: the reference solver's formulas (SeedFastMassSpring) against
// FastMassSpring set up as for the JSON+OBJ scenes (penalty pins w = 1e10, a force (0, -9.8, 0) per
// point, iterations starting from the current positions, 50 of them, dt = 1/30).
#include <doctest/doctest.h>

#include <Eigen/Core>
#include <algorithm>
#include <massspring/forces/gravity.hpp>
#include <massspring/integrators/fast_mass_spring.hpp>
#include <massspring/scene/cloth.hpp>
#include <massspring/scene/make_system.hpp>
#include <massspring/system/mass_spring_system.hpp>
#include <vector>

#include "seed/seed_reference.hpp"

namespace {

using massspring::test::SeedFastMassSpring;
using SparseSystem = massspring::MassSpringSystem<double, massspring::Sparse>;

constexpr double kDt = 1.0 / 30;
constexpr int kFrames = 10;

// The JSON+OBJ scenes' settings; their force, (0, -9.8, 0) N on every point, is a ConstantForce
// term on the system (the reference solver takes it as its own option).
massspring::FastMassSpringOptions<double> assignment_options() {
  auto o = massspring::FastMassSpringOptions<double>::reference();
  o.pins = massspring::PinMode::Penalty;
  o.penalty_weight = 1e10;
  o.initial_guess = massspring::InitialGuess::Current;
  o.iterations = 50;
  return o;
}

// |X_ours - X_ref| / |X_ref| (X_ref: the reference solver's) after each of kFrames frames
// (Frobenius norms); the largest.
template <class System>
double largest_relative_difference(System system, const SparseSystem& sparse) {
  using Scalar = typename System::Scalar;
  system.add_force(
      massspring::ConstantForce<Scalar>(massspring::Vector3<Scalar>(0, Scalar(-9.8), 0)));
  massspring::FastMassSpring<System> ours(assignment_options());
  ours.precompute(system, kDt);
  SeedFastMassSpring seed;
  seed.precompute(sparse, kDt);
  double worst = 0;
  for (int frame = 0; frame < kFrames; ++frame) {
    const auto report = ours.step(system);
    REQUIRE(report.finite);
    seed.step();
    const Eigen::MatrixXd x = system.positions();
    const double diff = (x - seed.positions()).norm() / seed.positions().norm();
    CAPTURE(frame);
    CHECK(diff <= 1e-9);
    worst = std::max(worst, diff);
  }
  // The scene moved: the comparison is not between two systems at rest.
  const Eigen::MatrixXd rest = sparse.rest_positions();
  CHECK((seed.positions() - rest).norm() > 1e-3 * rest.norm());
  return worst;
}

// A 10-point chain along x, mass 1, k = 500 (the JSON+OBJ scenes' horizontal chain), pinned as
// asked.
template <class System>
System seed_chain(const std::vector<int>& pins) {
  const int n = 10;
  massspring::Points<double> v(n, 3);
  massspring::Edges e(n - 1, 2);
  for (int i = 0; i < n; ++i) v.row(i) << 0.1 * i, 0, 0;
  for (int i = 0; i + 1 < n; ++i) e.row(i) << i, i + 1;
  System system(v, e, 1.0, 500.0);
  system.pin(pins);
  return system;
}

massspring::SceneDescription<double> seed_cloth(bool voronoi_masses) {
  massspring::ClothOptions o;
  o.columns = 7;
  o.rows = 5;
  o.shear = massspring::ClothShear::Both;
  o.pins = massspring::ClothPins::TopCorners;
  o.stiffness = 1000;
  if (!voronoi_masses) o.mass = 0.01;
  return massspring::make_cloth(o);
}

}  // namespace

TEST_CASE_TEMPLATE("SeedFastMassSpring and FastMassSpring (penalty pins) agree on a cloth", Storage,
                   massspring::Dense, massspring::Sparse) {
  using System = massspring::MassSpringSystem<double, Storage>;
  for (const bool voronoi : {true, false}) {
    CAPTURE(voronoi);
    const auto scene = seed_cloth(voronoi);
    const double worst = largest_relative_difference(massspring::make_system<System>(scene),
                                                     massspring::make_system<SparseSystem>(scene));
    MESSAGE("cloth 7 x 5, largest relative difference over ", kFrames, " frames: ", worst);
  }
}

TEST_CASE_TEMPLATE("SeedFastMassSpring and FastMassSpring (penalty pins) agree on a chain", Storage,
                   massspring::Dense, massspring::Sparse) {
  using System = massspring::MassSpringSystem<double, Storage>;
  for (const auto& pins : {std::vector<int>{0, 9}, std::vector<int>{0}}) {
    CAPTURE(pins.size());
    largest_relative_difference(seed_chain<System>(pins), seed_chain<SparseSystem>(pins));
  }
}

TEST_CASE("SeedFastMassSpring and FastMassSpring agree from a moving start") {
  // Nonzero initial velocities exercise U_prev = U - dt V against Y = X + dt V.
  auto system = seed_chain<SparseSystem>({0});
  massspring::Points<double> v = massspring::Points<double>::Zero(10, 3);
  for (int i = 1; i < 10; ++i) v.row(i) << 0, 0.3 * i, -0.1 * i;
  system.set_velocities(v);
  largest_relative_difference(system, system);
}

TEST_CASE("SeedFastMassSpring: a system at rest without external force stays at rest") {
  auto system = massspring::make_system<SparseSystem>(seed_cloth(true));
  SeedFastMassSpring::Options o;
  o.external_force.setZero();
  SeedFastMassSpring seed(o);
  seed.precompute(system, kDt);
  for (int frame = 0; frame < 3; ++frame) seed.step();
  const Eigen::MatrixXd rest = system.rest_positions();
  CHECK((seed.positions() - rest).norm() <= 1e-12 * rest.norm());
  CHECK(seed.velocities().norm() <= 1e-9);
}

TEST_CASE("SeedFastMassSpring: Q, the factor and its preconditions") {
  auto system = seed_chain<SparseSystem>({0, 9});
  SeedFastMassSpring seed;
  CHECK_THROWS_AS(seed.step(), std::logic_error);
  CHECK_THROWS_AS(seed.precompute(system, 0.0), std::invalid_argument);
  seed.precompute(system, kDt);
  // Q of a chain is tridiagonal: n diagonal + 2 (n - 1) off-diagonal entries; its factor (no fill
  // in a path) holds n + (n - 1).
  CHECK(seed.system_matrix().nonZeros() == 10 + 2 * 9);
  CHECK(seed.factor_nonzeros() == 10 + 9);
  // Diagonal of Q at an end point: k + m / dt^2 + w.
  CHECK(seed.system_matrix().coeff(0, 0) == doctest::Approx(500 + 900 + 1e10));
  system.set_pin_target(9, massspring::Vector3<double>(1, 1, 1));
  CHECK_THROWS_AS(seed.precompute(system, kDt), std::invalid_argument);
}
