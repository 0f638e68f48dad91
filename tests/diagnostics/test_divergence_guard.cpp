// diagnostics/divergence_guard.hpp: an explicit step past its stability limit is caught and
// undone bit for bit; a stable run is never flagged; non-finite steps; the limit's formula;
// validation; no allocation.
#include <doctest/doctest.h>

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <massspring/diagnostics/divergence_guard.hpp>
#include <massspring/diagnostics/energy.hpp>
#include <massspring/diagnostics/stable_time_step.hpp>
#include <massspring/forces/gravity.hpp>
#include <massspring/integrators/forward_euler.hpp>
#include <massspring/integrators/rk4.hpp>
#include <massspring/integrators/symplectic_euler.hpp>
#include <massspring/scene/chain.hpp>
#include <massspring/scene/make_system.hpp>
#include <random>

#include "support/alloc_counter.hpp"
#include "support/small_systems.hpp"

namespace {

using massspring::Dense;
using massspring::Sparse;
using Pts = massspring::Points<double>;
using SystemD = massspring::MassSpringSystem<double, Dense>;
using SystemS = massspring::MassSpringSystem<double, Sparse>;

// A stiff chain (12 points, k = 5000 N/m, 0.1 kg, both ends pinned) under gravity, its free
// points moved by up to 1 cm so that it vibrates along and across.
SystemS stiff_chain() {
  massspring::ChainOptions o;
  o.points = 12;
  o.stiffness = 5000;
  o.mass = 0.1;
  auto s = massspring::make_system<SystemS>(massspring::make_chain(o));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.01, 0.01);
  Pts x = s.positions();
  for (int i = 1; i + 1 < o.points; ++i) x.row(i) += Eigen::RowVector3d(u(rng), u(rng), u(rng));
  s.set_positions(x);
  s.add_force(massspring::Gravity<double>(Eigen::Vector3d(0, -9.81, 0)));
  return s;
}

}  // namespace

TEST_CASE("divergence_guard: SymplecticEuler at 3x the stable step blows up and is undone") {
  auto s = stiff_chain();
  const double h = massspring::stability_limit(s, massspring::ExplicitMethod::SymplecticEuler);
  massspring::SymplecticEuler<SystemS> se;
  se.precompute(s, 3 * h);
  massspring::DivergenceGuard<SystemS> guard(s);
  int blew_up_at = -1;
  for (int i = 0; i < 500 && blew_up_at < 0; ++i) {
    const Pts x = s.positions(), v = s.velocities();
    const double e = guard.energy();
    const auto r = guard.step(se, s);
    if (r.blew_up) {
      blew_up_at = i;
      CHECK_FALSE(r.ok());
      CHECK(r.finite);  // energy grew past the limit while every value was still finite
      // The state before the step, bit for bit.
      CHECK(s.positions() == x);
      CHECK(s.velocities() == v);
      CHECK(guard.energy() == e);  // the last accepted energy
      // Stepping again from the restored state blows up again and restores it again.
      const auto again = guard.step(se, s);
      CHECK(again.blew_up);
      CHECK(s.positions() == x);
      CHECK(s.velocities() == v);
    } else {
      REQUIRE(r.ok());
      CHECK(guard.energy() == doctest::Approx(massspring::total_energy(s)).epsilon(1e-15));
      CHECK(guard.energy() <= guard.limit());
    }
  }
  MESSAGE("divergence_guard: blew up at step ", blew_up_at);
  CHECK(blew_up_at >= 0);
  // A handful of steps: the energy grows by orders of magnitude per step at 3x the limit.
  CHECK(blew_up_at < 50);
}

TEST_CASE("divergence_guard: SymplecticEuler at 0.9x the stable step never blows up") {
  auto s = stiff_chain();
  const double h = massspring::stability_limit(s, massspring::ExplicitMethod::SymplecticEuler);
  massspring::SymplecticEuler<SystemS> se;
  se.precompute(s, 0.9 * h);
  massspring::DivergenceGuard<SystemS> guard(s);
  int failures = 0;
  double highest = guard.energy();
  for (int i = 0; i < 5000; ++i) {
    if (!guard.step(se, s).ok()) ++failures;
    highest = std::max(highest, guard.energy());
  }
  CHECK(failures == 0);
  // Far below the limit, not just under it: bounded energy (symplectic Euler's error is O(h)).
  CHECK(highest - guard.initial_energy() < 0.01 * (guard.limit() - guard.initial_energy()));
  CHECK((s.positions() - stiff_chain().positions()).cwiseAbs().maxCoeff() > 1e-3);  // it moved
}

TEST_CASE("divergence_guard: non-finite steps are reported and change nothing") {
  // (u, w) = (0.1, 10) on a unit spring: ForwardEuler with h = 1e308 makes x = 1 + h w overflow;
  // the integrator refuses it.
  auto s = massspring::test::oscillator<SystemS>(1, 1, 1.0, 0.1, 10);
  const Pts x0 = s.positions(), v0 = s.velocities();
  massspring::DivergenceGuard<SystemS> guard(s);
  massspring::ForwardEuler<SystemS> fe;
  fe.precompute(s, 1e308);
  const auto r = guard.step(fe, s);
  CHECK_FALSE(r.finite);
  CHECK_FALSE(r.blew_up);
  CHECK_FALSE(r.ok());
  CHECK(s.positions() == x0);
  CHECK(s.velocities() == v0);
  // With h = 1e200 the state stays finite (~1e201 m) but its spring energy (~1e402 J) does not:
  // the guard restores the state, reporting both.
  fe.precompute(s, 1e200);
  const auto q = guard.step(fe, s);
  CHECK(q.blew_up);
  CHECK_FALSE(q.finite);
  CHECK(s.positions() == x0);
  CHECK(s.velocities() == v0);
  CHECK(guard.energy() == guard.initial_energy());
}

TEST_CASE("divergence_guard: limit = E(0) + growth S, S from the documented formula") {
  auto s = massspring::test::perturbed_cloth<SystemS>(4);
  s.add_force(massspring::Gravity<double>(Eigen::Vector3d(0, -9.81, 0)));
  Pts v = Pts::Zero(s.num_points(), 3);
  v.col(2).setConstant(0.3);
  for (const int i : s.pinned()) v.row(i).setZero();
  s.set_velocities(v);
  // S = |E(0)| + K(0) + sum_e k_e l0_e^2 / 2 + D sum_i |F_i(x0, v0)|, evaluated here directly.
  const double e0 = massspring::total_energy(s);
  double springs = 0;
  for (int e = 0; e < s.num_springs(); ++e)
    springs += 0.5 * s.stiffness()(e) * s.rest_lengths()(e) * s.rest_lengths()(e);
  Pts f;
  massspring::total_force(s, s.positions(), s.velocities(), f);
  double force_sum = 0;
  for (int i = 0; i < s.num_points(); ++i) force_sum += f.row(i).norm();
  const Eigen::RowVector3d extent =
      s.positions().colwise().maxCoeff() - s.positions().colwise().minCoeff();
  const double scale =
      std::abs(e0) + massspring::kinetic_energy(s) + springs + extent.norm() * force_sum;

  for (const double growth : {100.0, 0.5, 1e6}) {
    massspring::DivergenceOptions o;
    o.growth = growth;
    const massspring::DivergenceGuard<SystemS> guard(s, o);
    CHECK(guard.initial_energy() == e0);
    CHECK(guard.energy() == e0);
    CHECK(guard.scale() == doctest::Approx(scale).epsilon(1e-12));
    CHECK(guard.limit() == guard.initial_energy() + growth * guard.scale());
  }
  CHECK(massspring::DivergenceGuard<SystemS>(s).limit() ==
        e0 + 100 * massspring::DivergenceGuard<SystemS>(s).scale());
  for (const double bad : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(),
                           std::numeric_limits<double>::infinity()}) {
    massspring::DivergenceOptions o;
    o.growth = bad;
    CHECK_THROWS_AS(massspring::DivergenceGuard<SystemS>(s, o), massspring::Error);
  }
  // A guard made for another system refuses this one.
  massspring::DivergenceGuard<SystemS> guard(s);
  auto other = massspring::test::oscillator<SystemS>(1, 1, 1.0, 0.1);
  massspring::SymplecticEuler<SystemS> se;
  se.precompute(other, 0.01);
  CHECK_THROWS_AS(guard.step(se, other), massspring::Error);
}

TEST_CASE("divergence_guard: step() allocates nothing (SymplecticEuler, RK4; Dense, Sparse)") {
  auto s = massspring::test::perturbed_cloth<SystemS>();
  auto d = massspring::test::perturbed_cloth<SystemD>();
  s.add_force(massspring::Gravity<double>(Eigen::Vector3d(0, -9.81, 0)));
  d.add_force(massspring::Gravity<double>(Eigen::Vector3d(0, -9.81, 0)));
  massspring::DivergenceGuard<SystemS> gs(s);
  massspring::DivergenceGuard<SystemD> gd(d);
  massspring::SymplecticEuler<SystemS> se;
  massspring::RK4<SystemD> rk4;
  se.precompute(s, 1e-3);
  rk4.precompute(d, 1e-3);
  {
    massspring::test::CountAllocations count;
    for (int i = 0; i < 50; ++i) {
      REQUIRE(gs.step(se, s).ok());
      REQUIRE(gd.step(rk4, d).ok());
    }
    CHECK(count.count() == 0);
  }
  CHECK(gs.energy() != gs.initial_energy());  // it did step
}
