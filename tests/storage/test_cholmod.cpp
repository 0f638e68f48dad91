// storage/cholmod.hpp: CholmodCholesky (CHOLMOD's factorization, massspring's substitution)
// against Q itself, against Eigen's SimplicialLLT and against FastMassSpring's default
// factorization. Compiled where massspring::cholmod is (CHOLMOD found); empty otherwise.
#include <doctest/doctest.h>

#if defined(MASSSPRING_HAS_CHOLMOD) && MASSSPRING_HAS_CHOLMOD

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <massspring/error.hpp>
#include <massspring/forces/gravity.hpp>
#include <massspring/integrators/fast_mass_spring.hpp>
#include <massspring/storage/cholmod.hpp>
#include <massspring/system/mass_spring_system.hpp>
#include <vector>

#include "support/alloc_counter.hpp"
#include "support/random_spd.hpp"
#include "support/small_systems.hpp"

using massspring::CholmodCholesky;
using massspring::CholmodOrdering;
using massspring::test::random_spd;

namespace {

const CholmodOrdering kOrderings[] = {CholmodOrdering::Default, CholmodOrdering::AMD,
                                      CholmodOrdering::METIS, CholmodOrdering::NESDIS,
                                      CholmodOrdering::Natural};

// The CHOLMOD_* code an explicit ordering must report (-1: CHOLMOD's own choice).
int expected_code(CholmodOrdering o) {
  switch (o) {
    case CholmodOrdering::AMD:
      return CHOLMOD_AMD;
    case CholmodOrdering::METIS:
      return CHOLMOD_METIS;
    case CholmodOrdering::NESDIS:
      return CHOLMOD_NESDIS;
    case CholmodOrdering::Natural:
      return CHOLMOD_NATURAL;
    case CholmodOrdering::Default:
      break;
  }
  return -1;
}

}  // namespace

TEST_CASE_TEMPLATE("CholmodCholesky::solve solves Q and equals Eigen's solve, in every ordering",
                   Scalar, float, double) {
  const int n = 300;
  const auto q = random_spd<Scalar>(n, 1200, 7);
  const Eigen::SimplicialLLT<Eigen::SparseMatrix<Scalar, Eigen::ColMajor, int>> eigen(q);
  REQUIRE(eigen.info() == Eigen::Success);
  const massspring::Points<Scalar> b = massspring::Points<Scalar>::Random(n, 3);
  const Eigen::Matrix<Scalar, Eigen::Dynamic, 3> expected = eigen.solve(b);
  // CHOLMOD factorizes in double and rounds the factor to Scalar; the substitution is
  // massspring's own. Measured over the five orderings: against Eigen up to 3.1e-7 (float) and
  // 8.1e-16 (double), residuals up to 2.2e-7 and 6.9e-16; the bounds leave about ten times that.
  const double tol = std::is_same_v<Scalar, float> ? 3e-6 : 1e-14;
  for (const CholmodOrdering ordering : kOrderings) {
    CAPTURE(int(ordering));
    CholmodCholesky<Scalar> llt;
    llt.ordering = ordering;
    REQUIRE(llt.compute(q));
    CHECK(llt.ok());
    CHECK(llt.rows() == n);
    if (expected_code(ordering) >= 0) {
      CHECK(llt.chosen_ordering() == expected_code(ordering));
    } else {
      CHECK(llt.chosen_ordering() >= 0);
    }
    // A permutation of the rows (the natural order: the identity).
    std::vector<int> seen(std::size_t(n), 0);
    for (int i = 0; i < n; ++i) {
      REQUIRE(llt.permutation()(i) >= 0);
      REQUIRE(llt.permutation()(i) < n);
      ++seen[std::size_t(llt.permutation()(i))];
      if (ordering == CholmodOrdering::Natural) CHECK(llt.permutation()(i) == i);
    }
    CHECK(std::all_of(seen.begin(), seen.end(), [](int c) { return c == 1; }));

    massspring::Points<Scalar> x(n, 3);
    llt.solve(b, x);
    CHECK((x - expected).norm() <= tol * expected.norm());
    CHECK((q * x - b).norm() <= tol * b.norm());
  }
}

TEST_CASE("CholmodCholesky: its factor L is the Cholesky factor of P Q P^T") {
  const int n = 200;
  const auto q = random_spd<double>(n, 700, 3);
  for (const CholmodOrdering ordering : kOrderings) {
    CAPTURE(int(ordering));
    CholmodCholesky<double> llt;
    llt.ordering = ordering;
    REQUIRE(llt.compute(q));
    const auto view = llt.lower();
    const Eigen::Map<const Eigen::SparseMatrix<double, Eigen::ColMajor, int>> l(
        n, n, view.outer[n], view.outer, view.inner, view.value);
    CHECK(llt.factor_nonzeros() == l.nonZeros());
    for (int j = 0; j < n; ++j) {  // lower triangular, the diagonal first and positive
      REQUIRE(view.inner[view.outer[j]] == j);
      CHECK(view.value[view.outer[j]] > 0);
      for (int p = view.outer[j]; p < view.outer[j + 1]; ++p) CHECK(view.inner[p] >= j);
    }
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> perm(llt.permutation());
    Eigen::SparseMatrix<double, Eigen::ColMajor, int> pqp(n, n);
    pqp = q.twistedBy(perm);  // row permutation()[i] of P Q P^T is row i of Q
    const Eigen::MatrixXd llt_product = Eigen::MatrixXd(l) * Eigen::MatrixXd(l).transpose();
    // Measured: 2.2e-16 to 3.7e-16 over the orderings; the bound leaves about ten times that.
    CHECK((llt_product - Eigen::MatrixXd(pqp)).norm() <= 4e-15 * Eigen::MatrixXd(pqp).norm());
  }
}

TEST_CASE("CholmodCholesky refuses a matrix that is not positive definite") {
  auto q = random_spd<double>(50, 150, 2);
  q.coeffRef(17, 17) = -1.0;
  CholmodCholesky<double> llt;
  CHECK_FALSE(llt.compute(q));
  CHECK_FALSE(llt.ok());
}

TEST_CASE("FastMassSpring with CholmodCholesky: the trajectory of the default factorization") {
  using System = massspring::MassSpringSystem<double>;
  const System start = massspring::test::perturbed_cloth<System>(3);
  System a = start, b = a;
  for (System* s : {&a, &b}) s->add_force(massspring::Gravity<double>(Eigen::Vector3d(0, -9.8, 0)));
  const auto plain = massspring::FastMassSpringOptions<double>::reference();
  massspring::FastMassSpring<System> eigen(plain);
  massspring::FastMassSpring<System, CholmodCholesky<double>> cholmod(plain);
  eigen.options.iterations = cholmod.options.iterations = 20;
  eigen.precompute(a, 1.0 / 30);
  cholmod.precompute(b, 1.0 / 30);
  for (int frame = 0; frame < 10; ++frame) {
    REQUIRE(eigen.step(a).ok());
    REQUIRE(cholmod.step(b).ok());
  }
  // The same iteration; the two factors (different orders, CHOLMOD's supernodal arithmetic)
  // round differently. Measured: 5.7e-15 of the largest coordinate after 10 steps; the bound
  // leaves about ten times that.
  const double scale = a.positions().cwiseAbs().maxCoeff();
  CHECK((a.positions() - b.positions()).cwiseAbs().maxCoeff() <= 6e-14 * scale);
  CHECK(a.positions() != start.positions());  // it moved

  // No allocation per step, as with the default factorization.
  std::size_t allocations = 0;
  {
    massspring::test::CountAllocations count;
    for (int frame = 0; frame < 3; ++frame) cholmod.step(b);
    allocations = count.count();
  }
  CHECK(allocations == 0);

  // What CHOLMOD cannot do is refused with a message naming the option.
  cholmod.options.ordering = massspring::FillOrdering::NestedDissection;
  CHECK_THROWS_WITH_AS(cholmod.step(b), doctest::Contains("NestedDissection"), massspring::Error);
  cholmod.options.ordering = massspring::FillOrdering::Auto;
  cholmod.options.threads = 2;
  CHECK_THROWS_WITH_AS(cholmod.step(b), doctest::Contains("threads"), massspring::Error);
}

#endif
