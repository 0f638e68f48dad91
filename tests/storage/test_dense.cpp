// storage/dense.hpp: the dense n x 3 solve against an independent dense solve, no allocation.
#include <doctest/doctest.h>

#include <Eigen/LU>
#include <massspring/storage/dense.hpp>
#include <vector>

#include "support/alloc_counter.hpp"

TEST_CASE_TEMPLATE("DenseCholesky::solve solves Q x = b for three columns", Scalar, float, double) {
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  const int n = 40;
  const Matrix r = Matrix::Random(n, n);
  const Matrix q = r * r.transpose() + Scalar(n) * Matrix::Identity(n, n);
  massspring::DenseCholesky<Scalar> llt;
  REQUIRE(llt.compute(q));
  CHECK(llt.factor_nonzeros() == n * (n + 1) / 2);
  const massspring::Points<Scalar> b = massspring::Points<Scalar>::Random(n, 3);
  massspring::Points<Scalar> x(n, 3);
  llt.solve(b, x);
  const Matrix expected = q.fullPivLu().solve(Matrix(b));  // independent: LU, not Cholesky
  const double tol = std::is_same_v<Scalar, float> ? 1e-5 : 1e-13;
  CHECK((Matrix(x) - expected).norm() <= tol * expected.norm());
}

TEST_CASE("DenseCholesky::solve allocates nothing") {
  const int n =
      300;  // large enough that Eigen would use heap blocking for a matrix right-hand side
  const Eigen::MatrixXd r = Eigen::MatrixXd::Random(n, n);
  const Eigen::MatrixXd q = r * r.transpose() + n * Eigen::MatrixXd::Identity(n, n);
  massspring::DenseCholesky<double> llt;
  REQUIRE(llt.compute(q));
  massspring::Points<double> b = massspring::Points<double>::Random(n, 3);
  massspring::Points<double> x(n, 3);
  std::size_t allocations = 0;
  {
    massspring::test::CountAllocations count;
    llt.solve(b, x);
    allocations = count.count();
  }
  CHECK(allocations == 0);
  CHECK((q * x - b).norm() <= 1e-12 * b.norm());
}

TEST_CASE("DenseCholesky reports a matrix that is not positive definite") {
  Eigen::MatrixXd q(2, 2);
  q << 1, 2, 2, 1;  // eigenvalues 3 and -1
  massspring::DenseCholesky<double> llt;
  CHECK_FALSE(llt.compute(q));
}

TEST_CASE("storage_traits<Dense>::from_triplets sums duplicates") {
  std::vector<Eigen::Triplet<double, int>> t = {{0, 1, 2.0}, {0, 1, 3.0}, {1, 0, -1.0}};
  const auto m = massspring::storage_traits<massspring::Dense, double>::from_triplets(2, 3, t);
  Eigen::MatrixXd expected(2, 3);
  expected << 0, 5, 0, -1, 0, 0;
  CHECK(m == expected);
}
