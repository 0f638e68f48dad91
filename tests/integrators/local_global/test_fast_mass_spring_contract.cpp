// integrators/local_global/fast_mass_spring.hpp: the step's contract (a failed re-factorization is
// a status, never a throw, and changes nothing), the declared uniform damping any force term may
// state, and options.simd.
#include <doctest/doctest.h>

#include <massspring/forces/gravity.hpp>
#include <massspring/forces/linear_drag.hpp>
#include <massspring/integrators/backward_euler.hpp>
#include <massspring/integrators/fast_mass_spring.hpp>
#include <massspring/scene/cloth.hpp>
#include <massspring/scene/make_system.hpp>
#include <vector>

namespace {

using System = massspring::MassSpringSystem<double, massspring::Sparse>;

System contract_cloth() {
  massspring::ClothOptions o;
  o.columns = 9;
  o.rows = 7;
  o.stiffness = 300;
  System s = massspring::make_system<System>(massspring::make_cloth(o));
  s.add_force(massspring::Gravity<double>({0, -9.8, 0}));
  return s;
}

// SparseCholesky whose compute() fails while `fail` is set (a Q that is not positive definite).
struct FailingCholesky : massspring::SparseCholesky<double> {
  static inline bool fail = false;
  bool compute(const Matrix& q) { return !fail && massspring::SparseCholesky<double>::compute(q); }
  bool compute(const Matrix& q, const std::vector<int>& order) {
    return !fail && massspring::SparseCholesky<double>::compute(q, order);
  }
};

// F = -beta v, declaring it: the library may fold it into its matrices. (LinearDrag's formulas,
// written again by a user.)
struct DeclaredDamping {
  double beta;
  [[nodiscard]] double linear_damping() const { return beta; }
  void add_force(const massspring::ForceContext<double>& c, massspring::Points<double>& f) const {
    f -= beta * c.v;
  }
  void add_dfdv(const massspring::ForceContext<double>& c,
                massspring::JacobianSink<double>& j) const {
    for (int i = 0; i < int(c.x.rows()); ++i) j.add_diagonal(i, -beta);
  }
};

// The same force, not declared: an explicit term for FastMassSpring.
struct UndeclaredDamping {
  double beta;
  void add_force(const massspring::ForceContext<double>& c, massspring::Points<double>& f) const {
    f -= beta * c.v;
  }
};

}  // namespace

TEST_CASE("A failed re-factorization in step() is reported, changes nothing, and is retried") {
  System s = contract_cloth();
  massspring::FastMassSpring<System, FailingCholesky> solver;
  solver.options.iterations = 10;
  FailingCholesky::fail = false;
  solver.precompute(s, 1.0 / 30);
  REQUIRE(solver.step(s).ok());
  s.set_stiffness(Eigen::VectorXd::Constant(s.num_springs(), 400.0));  // a new revision
  const System before = s;
  FailingCholesky::fail = true;
  massspring::StepReport r;
  CHECK_NOTHROW(r = solver.step(s));
  CHECK(r.refactorized);
  CHECK(r.factorization_failed);
  CHECK_FALSE(r.ok());
  CHECK(r.iterations == 0);
  CHECK(s.positions() == before.positions());
  CHECK(s.velocities() == before.velocities());
  // Still failing: tried again, not skipped.
  CHECK(solver.step(s).factorization_failed);
  FailingCholesky::fail = false;
  r = solver.step(s);
  CHECK(r.refactorized);
  CHECK(r.ok());
  CHECK(s.positions() != before.positions());
  // precompute() is not a step: there the failure is an error.
  FailingCholesky::fail = true;
  CHECK_THROWS_AS(solver.precompute(s, 1.0 / 30), massspring::Error);
  FailingCholesky::fail = false;
}

TEST_CASE("A term declaring linear_damping() is folded like LinearDrag, in both implicit solvers") {
  const double beta = 0.7;
  System with_drag = contract_cloth(), declared = contract_cloth(), undeclared = contract_cloth();
  with_drag.add_force(massspring::LinearDrag<double>(beta));
  declared.add_force(DeclaredDamping{beta});
  undeclared.add_force(UndeclaredDamping{beta});
  const auto& last = declared.forces()[declared.forces().size() - 1];
  CHECK(last.linear_damping);
  CHECK(last.linear_damping_coefficient() == beta);
  CHECK_FALSE(undeclared.forces()[undeclared.forces().size() - 1].linear_damping);
  {
    System a = with_drag, b = declared, c = undeclared;
    massspring::FastMassSpring<System> sa, sb, sc;
    for (auto* solver : {&sa, &sb, &sc}) solver->options.iterations = 8;
    sa.precompute(a, 1.0 / 30);
    sb.precompute(b, 1.0 / 30);
    sc.precompute(c, 1.0 / 30);
    for (int frame = 0; frame < 5; ++frame) {
      REQUIRE(sa.step(a).ok());
      REQUIRE(sb.step(b).ok());
      REQUIRE(sc.step(c).ok());
    }
    CHECK(a.positions() == b.positions());
    // Undeclared, the same force is explicit (evaluated at the step's start): another trajectory.
    CHECK(a.positions() != c.positions());
  }
  {
    System a = with_drag, b = declared;
    massspring::BackwardEuler<System> sa, sb;
    sa.precompute(a, 1.0 / 30);
    sb.precompute(b, 1.0 / 30);
    for (int frame = 0; frame < 3; ++frame) {
      const auto ra = sa.step(a), rb = sb.step(b);
      REQUIRE(ra.ok());
      REQUIRE(rb.ok());
      CHECK(ra.energy == rb.energy);  // both have the incremental potential (drag folded in)
    }
    CHECK(a.positions() == b.positions());
  }
}

TEST_CASE("options.simd = false takes the baseline substitution; the default takes the CPU's") {
  System a = contract_cloth(), b = contract_cloth();
  massspring::FastMassSpring<System> sa, sb;
  for (auto* solver : {&sa, &sb}) solver->options.iterations = 10;
  sb.options.simd = false;
  sa.precompute(a, 1.0 / 30);
  sb.precompute(b, 1.0 / 30);
  for (int frame = 0; frame < 4; ++frame) {
    REQUIRE(sa.step(a).ok());
    REQUIRE(sb.step(b).ok());
  }
  CHECK_FALSE(sb.factorization().simd());
  CHECK(sa.factorization().simd() == massspring::detail::cpu_has_avx2_fma());
}
