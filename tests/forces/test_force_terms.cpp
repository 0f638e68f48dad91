// forces/*.hpp: every term's Jacobians against central finite differences, energies against
// forces, internal forces summing to zero, closed forms, and a user-written term.
#include <doctest/doctest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <massspring/forces/evaluate.hpp>
#include <massspring/forces/gravitational_attraction.hpp>
#include <massspring/forces/gravity.hpp>
#include <massspring/forces/linear_drag.hpp>
#include <massspring/forces/springs.hpp>
#include <massspring/system/mass_spring_system.hpp>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace {

using massspring::Edges;
using massspring::ForceContext;
using massspring::JacobianSink;
using Pts = massspring::Points<double>;
using Vec = massspring::Vector<double>;
using Mat = Eigen::MatrixXd;
using System = massspring::MassSpringSystem<double, massspring::Sparse>;

// Five points, six springs with varied stiffness, rest lengths, damping; random state.
struct Fixture {
  Pts x0, v0;
  Edges e;
  Vec m, k, l0, b;
  explicit Fixture(unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    x0 = Pts::NullaryExpr(5, 3, [&] { return u(rng); });
    v0 = Pts::NullaryExpr(5, 3, [&] { return u(rng); });
    e.resize(6, 2);
    e << 0, 1, 1, 2, 2, 3, 3, 4, 4, 0, 0, 2;
    m = Vec::NullaryExpr(5, [&] { return 1.5 + u(rng); });
    k = Vec::NullaryExpr(6, [&] { return 10 + 5 * u(rng); });
    b = Vec::NullaryExpr(6, [&] { return 0.7 + 0.5 * u(rng); });
    l0.resize(6);
    // Some springs stretched, some compressed (l0 above and below the current length).
    for (int s = 0; s < 6; ++s)
      l0(s) = (x0.row(e(s, 0)) - x0.row(e(s, 1))).norm() * (s % 2 ? 1.4 : 0.6);
  }
  ForceContext<double> context(const Pts& x, const Pts& v, bool definite = false) const {
    return {x, v, m, e, k, l0, b, definite};
  }
};

// The Jacobian a term emits, as a dense 3n x 3n matrix, through the recorder/accumulator pair the
// integrators use.
template <class Emit>
Mat jacobian(int n, Emit emit) {
  std::vector<std::pair<int, int>> entries;
  auto rec = JacobianSink<double>::recorder(entries);
  emit(rec);
  std::vector<Eigen::Index> slots;
  for (auto [r, c] : entries) slots.push_back(Eigen::Index(c) * 3 * n + r);
  Mat j = Mat::Zero(3 * n, 3 * n);
  auto acc = JacobianSink<double>::accumulator(j.data(), slots, 1.0);
  emit(acc);
  CHECK(acc.count() == entries.size());
  return j;
}

// Central differences of a force function with respect to the flattened state.
template <class Force>
Mat finite_difference(const Pts& at, Force force, double h) {
  const int n = int(at.rows());
  Mat j(3 * n, 3 * n);
  for (int c = 0; c < 3 * n; ++c) {
    Pts p = at, q = at;
    p(c / 3, c % 3) += h;
    q(c / 3, c % 3) -= h;
    const Pts fp = force(p), fq = force(q);
    j.col(c) = Eigen::Map<const Vec>((fp - fq).eval().data(), 3 * n) / (2 * h);
  }
  return j;
}

template <class Term>
Pts force_of(const Term& t, const ForceContext<double>& c) {
  Pts f = Pts::Zero(c.x.rows(), 3);
  t.add_force(c, f);
  return f;
}

// A finite-difference step relative to the shortest spring: a central difference errs by about
// (h / l)^2 relative (truncation) plus eps |F| / h (rounding); h = 1e-5 min(1, l_min) keeps both
// below 1e-9 relative even for the near-coincident pair (l ~ 2e-4).
double fd_step(const Fixture& fx, const Pts& x) {
  double lmin = 1;
  for (int s = 0; s < int(fx.e.rows()); ++s)
    lmin = std::min(lmin, (x.row(fx.e(s, 0)) - x.row(fx.e(s, 1))).norm());
  return 1e-5 * lmin;
}

// Checks dF/dx and dF/dv of a term against central differences (see fd_step); 1e-6 relative
// fails for any wrong entry.
template <class Term>
void check_jacobians(const Term& t, const Fixture& fx, const Pts& x, const Pts& v) {
  const int n = int(x.rows());
  const auto c = fx.context(x, v);
  const Mat jx = jacobian(n, [&](JacobianSink<double>& s) {
    if constexpr (massspring::detail::has_dfdx<Term, double>::value) t.add_dfdx(c, s);
  });
  const Mat jv = jacobian(n, [&](JacobianSink<double>& s) {
    if constexpr (massspring::detail::has_dfdv<Term, double>::value) t.add_dfdv(c, s);
  });
  const Mat fdx = finite_difference(
      x, [&](const Pts& p) { return force_of(t, fx.context(p, v)); }, fd_step(fx, x));
  const Mat fdv = finite_difference(
      v, [&](const Pts& p) { return force_of(t, fx.context(x, p)); }, fd_step(fx, x));
  const double sx = std::max(1.0, fdx.cwiseAbs().maxCoeff());
  const double sv = std::max(1.0, fdv.cwiseAbs().maxCoeff());
  CHECK((jx - fdx).cwiseAbs().maxCoeff() / sx < 1e-6);
  CHECK((jv - fdv).cwiseAbs().maxCoeff() / sv < 1e-6);
}

// F = -dE/dx by central differences of the energy.
template <class Term>
void check_energy_gradient(const Term& t, const Fixture& fx, const Pts& x) {
  const Pts f = force_of(t, fx.context(x, fx.v0));
  double worst = 0;
  for (int c = 0; c < int(x.size()); ++c) {
    Pts p = x, q = x;
    const double h = fd_step(fx, x);
    p(c / 3, c % 3) += h;
    q(c / 3, c % 3) -= h;
    const double g = (t.energy(fx.context(p, fx.v0)) - t.energy(fx.context(q, fx.v0))) / (2 * h);
    worst = std::max(worst, std::abs(g + f(c / 3, c % 3)));
  }
  CHECK(worst < 1e-6 * std::max(1.0, f.cwiseAbs().maxCoeff()));
}

// Internal forces: zero net force and zero net torque about the origin.
void check_internal(const Pts& f, const Pts& x) {
  const double scale = std::max(1.0, f.cwiseAbs().maxCoeff());
  CHECK(f.colwise().sum().norm() < 1e-12 * scale);
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();
  for (int i = 0; i < int(x.rows()); ++i)
    torque += x.row(i).transpose().cross(f.row(i).transpose());
  CHECK(torque.norm() < 1e-12 * scale * std::max(1.0, x.cwiseAbs().maxCoeff()));
}

// States to test at: random, a nearly collinear pair, a nearly coincident pair.
std::vector<Pts> states(const Fixture& fx) {
  Pts collinear = fx.x0;
  collinear.row(1) = collinear.row(0) + Eigen::RowVector3d(0.5, 1e-7, 0);
  Pts close = fx.x0;
  close.row(2) = close.row(1) + Eigen::RowVector3d(1e-4, -2e-4, 5e-5);
  return {fx.x0, collinear, close};
}

}  // namespace

TEST_CASE("Springs: Jacobian and energy gradient match finite differences; internal") {
  for (unsigned seed : {1u, 2u, 3u}) {
    const Fixture fx(seed);
    for (const Pts& x : states(fx)) {
      massspring::Springs<double> t;
      check_jacobians(t, fx, x, fx.v0);
      check_energy_gradient(t, fx, x);
      check_internal(force_of(t, fx.context(x, fx.v0)), x);
    }
  }
}

TEST_CASE("Springs: closed form of one spring, and the definite projection is PSD") {
  Fixture fx(4);
  fx.e.resize(1, 2);
  fx.e << 0, 1;
  fx.k = Vec::Constant(1, 50);
  fx.l0 = Vec::Constant(1, 2);
  fx.b = Vec::Zero(1);
  Pts x = Pts::Zero(5, 3);
  x(1, 0) = 1.5;  // compressed by 0.5
  const Pts f = force_of(massspring::Springs<double>{}, fx.context(x, fx.v0));
  // F_0 = k (l - l0) n with n from 0 to 1: 50 * (-0.5) * (+x) pushes point 0 to -x.
  CHECK(f(0, 0) == doctest::Approx(-25).epsilon(1e-15));
  CHECK(f(1, 0) == doctest::Approx(25).epsilon(1e-15));
  CHECK(massspring::Springs<double>{}.energy(fx.context(x, fx.v0)) ==
        doctest::Approx(0.5 * 50 * 0.25).epsilon(1e-15));
  const Mat exact = jacobian(5, [&](JacobianSink<double>& s) {
    massspring::Springs<double>{}.add_dfdx(fx.context(x, fx.v0), s);
  });
  const Mat projected = jacobian(5, [&](JacobianSink<double>& s) {
    massspring::Springs<double>{}.add_dfdx(fx.context(x, fx.v0, true), s);
  });
  // Compressed: -dF/dx has negative transverse eigenvalues k (l - l0)/l; the projection has none.
  const Eigen::VectorXd ev_exact = Eigen::SelfAdjointEigenSolver<Mat>(-exact).eigenvalues();
  const Eigen::VectorXd ev_proj = Eigen::SelfAdjointEigenSolver<Mat>(-projected).eigenvalues();
  CHECK(ev_exact.minCoeff() == doctest::Approx(2 * 50 * (1.5 - 2) / 1.5).epsilon(1e-12));
  CHECK(ev_proj.minCoeff() > -1e-12);
}

TEST_CASE("Springs: a zero-rest-length spring is linear, F_i = k (x_j - x_i), even at l = 0") {
  Fixture fx(5);
  fx.l0.setZero();
  Pts x = fx.x0;
  x.row(1) = x.row(0);  // spring 0 at zero length
  const Pts f = force_of(massspring::Springs<double>{}, fx.context(x, fx.v0));
  CHECK(f.allFinite());
  check_jacobians(massspring::Springs<double>{}, fx, fx.x0, fx.v0);
  check_energy_gradient(massspring::Springs<double>{}, fx, fx.x0);
}

TEST_CASE("SpringDamping: Jacobians match finite differences; internal; only along the axis") {
  for (unsigned seed : {1u, 2u, 3u}) {
    const Fixture fx(seed);
    for (const Pts& x : states(fx)) {
      massspring::SpringDamping<double> t;
      check_jacobians(t, fx, x, fx.v0);
      check_internal(force_of(t, fx.context(x, fx.v0)), x);
    }
  }
  // Relative velocity across the spring is not damped; along it, F = -b (u . n) n.
  Fixture fx(6);
  fx.e.resize(1, 2);
  fx.e << 0, 1;
  fx.b = Vec::Constant(1, 0.5);
  fx.k = fx.l0 = Vec::Ones(1);
  Pts x = Pts::Zero(5, 3), v = Pts::Zero(5, 3);
  x(1, 0) = 2;
  v(1, 1) = 3;  // across
  CHECK(force_of(massspring::SpringDamping<double>{}, fx.context(x, v)).norm() == 0);
  v(1, 0) = 4;  // along: separating at 4 m/s
  const Pts f = force_of(massspring::SpringDamping<double>{}, fx.context(x, v));
  CHECK(f(0, 0) == doctest::Approx(0.5 * 4).epsilon(1e-15));
  CHECK(f(1, 0) == doctest::Approx(-0.5 * 4).epsilon(1e-15));
}

TEST_CASE("GravitationalAttraction: Jacobian, energy gradient, internal, inverse square") {
  for (unsigned seed : {1u, 2u}) {
    const Fixture fx(seed);
    for (double softening : {0.0, 0.3}) {
      const auto t = massspring::GravitationalAttraction<double>::all_pairs(5, 0.7, softening);
      CHECK(t.pairs().size() == 10);
      for (const Pts& x : {fx.x0, states(fx)[1]}) {
        check_jacobians(t, fx, x, fx.v0);
        check_energy_gradient(t, fx, x);
        check_internal(force_of(t, fx.context(x, fx.v0)), x);
      }
    }
  }
  Fixture fx(7);
  fx.m = Vec::Constant(5, 2);
  Pts x = Pts::Zero(5, 3);
  x(1, 1) = 3;
  const massspring::GravitationalAttraction<double> t({{0, 1, 0.5}});
  const Pts f = force_of(t, fx.context(x, fx.v0));
  CHECK(f(0, 1) == doctest::Approx(0.5 * 2 * 2 / 9).epsilon(1e-15));  // towards 1: +y
  CHECK(t.energy(fx.context(x, fx.v0)) == doctest::Approx(-0.5 * 2 * 2 / 3).epsilon(1e-15));
  CHECK_THROWS_WITH_AS(massspring::GravitationalAttraction<double>({{2, 2, 1.0}}),
                       "gravitational attraction pair 0 attracts point 2 to itself",
                       massspring::Error);
  CHECK_THROWS_WITH_AS(massspring::GravitationalAttraction<double>({{0, 1, -1.0}}),
                       "gravitational attraction pair 0: G must be finite and >= 0, got -1",
                       massspring::Error);
}

TEST_CASE("Gravity, ConstantForce, LinearDrag: closed forms and Jacobians") {
  const Fixture fx(8);
  const massspring::Gravity<double> g(Eigen::Vector3d(0, -9.81, 0));
  const Pts fg = force_of(g, fx.context(fx.x0, fx.v0));
  for (int i = 0; i < 5; ++i) CHECK(fg(i, 1) == doctest::Approx(-9.81 * fx.m(i)).epsilon(1e-15));
  check_energy_gradient(g, fx, fx.x0);
  const massspring::ConstantForce<double> cf(Eigen::Vector3d(0, -9.8, 1));
  const Pts fc = force_of(cf, fx.context(fx.x0, fx.v0));
  CHECK((fc.rowwise() - Eigen::RowVector3d(0, -9.8, 1)).norm() == 0);
  check_energy_gradient(cf, fx, fx.x0);
  const massspring::LinearDrag<double> d(0.25);
  CHECK((force_of(d, fx.context(fx.x0, fx.v0)) + 0.25 * fx.v0).norm() == 0);
  check_jacobians(d, fx, fx.x0, fx.v0);
  CHECK_THROWS_WITH_AS(massspring::LinearDrag<double>(-1),
                       "linear drag: beta must be finite and >= 0, got -1", massspring::Error);
  CHECK_THROWS_AS(massspring::Gravity<double>(Eigen::Vector3d(0, NAN, 0)), massspring::Error);
}

namespace {
// A user's own term: a linear spring from every point to the origin, F = -c x, E = c/2 |x|^2.
struct Tether {
  double c = 2;
  void add_force(const ForceContext<double>& ctx, Pts& f) const { f -= c * ctx.x; }
  double energy(const ForceContext<double>& ctx) const { return 0.5 * c * ctx.x.squaredNorm(); }
  void add_dfdx(const ForceContext<double>& ctx, JacobianSink<double>& j) const {
    for (int i = 0; i < int(ctx.x.rows()); ++i) j.add_diagonal(i, -c);
  }
};
}  // namespace

TEST_CASE("A user-written term plugs into a system, with energy and Jacobian detected") {
  Pts x(3, 3);
  x << 0, 0, 0, 1, 0, 0, 2, 0, 0;
  Edges e(2, 2);
  e << 0, 1, 1, 2;
  System s(x, e, 1.0, 10.0);
  const auto before = s.revision();
  CHECK(s.add_force(Tether{}) == 0);
  CHECK(s.revision() != before);
  const auto& term = s.forces()[0];
  CHECK(term.has_energy);
  CHECK(term.has_dfdx);
  CHECK_FALSE(term.has_dfdv);
  CHECK_FALSE(term.velocity_dependent);
  CHECK(std::string(term.name) == "force term");
  CHECK(s.forces().find<Tether>() != nullptr);
  CHECK(massspring::is_conservative(s));
  // total_force = springs (at rest: 0) + tether.
  Pts f;
  massspring::total_force(s, s.positions(), s.velocities(), f);
  CHECK((f + 2 * x).norm() == 0);
  CHECK(massspring::potential_energy(s, s.positions()) == doctest::Approx(0.5 * 2 * 5));
  s.add_force(massspring::LinearDrag<double>(0.1));
  CHECK_FALSE(massspring::is_conservative(s));
  // Copies carry their own terms.
  System copy = s;
  CHECK(copy.forces().size() == 2);
  s.clear_forces();
  CHECK(copy.forces().size() == 2);
  CHECK(s.forces().empty());
}

TEST_CASE("add_force refuses attraction pairs out of range, naming the term") {
  Pts x = Pts::Zero(2, 3);
  x(1, 0) = 1;
  Edges e(1, 2);
  e << 0, 1;
  System s(x, e, 1.0, 1.0);
  CHECK_THROWS_WITH_AS(s.add_force(massspring::GravitationalAttraction<double>({{0, 2, 1.0}})),
                       "gravitational attraction: point index 2 out of range [0, 2)",
                       massspring::Error);
  CHECK(s.forces().empty());
}
