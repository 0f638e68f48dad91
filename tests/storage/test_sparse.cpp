// storage/sparse.hpp: the fused n x 3 solve against Eigen's own SimplicialLLT::solve, and no
// allocation per solve.
#include <doctest/doctest.h>

#include <massspring/storage/sparse.hpp>
#include <random>
#include <vector>

#include "support/alloc_counter.hpp"

namespace {

// A random sparse SPD matrix: a random graph Laplacian (weights > 0) plus a positive diagonal.
template <class Scalar>
Eigen::SparseMatrix<Scalar, Eigen::ColMajor, int> random_spd(int n, int edges, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> index(0, n - 1);
  std::uniform_real_distribution<double> weight(0.5, 2.0);
  std::vector<Eigen::Triplet<Scalar, int>> t;
  for (int e = 0; e < edges; ++e) {
    const int i = index(rng), j = index(rng);
    if (i == j) continue;
    const auto w = Scalar(weight(rng));
    t.emplace_back(i, i, w);
    t.emplace_back(j, j, w);
    t.emplace_back(i, j, -w);
    t.emplace_back(j, i, -w);
  }
  for (int i = 0; i < n; ++i) t.emplace_back(i, i, Scalar(weight(rng)));
  return massspring::storage_traits<massspring::Sparse, Scalar>::from_triplets(n, n, t);
}

}  // namespace

TEST_CASE_TEMPLATE("SparseCholesky::solve equals Eigen's SimplicialLLT::solve", Scalar, float,
                   double) {
  const int n = 300;
  const auto q = random_spd<Scalar>(n, 1200, 7);
  massspring::SparseCholesky<Scalar> llt;
  REQUIRE(llt.compute(q));
  CHECK(llt.rows() == n);
  CHECK(llt.factor_nonzeros() == llt.factor().nonZeros());

  const massspring::Points<Scalar> b = massspring::Points<Scalar>::Random(n, 3);
  massspring::Points<Scalar> x(n, 3);
  llt.solve(b, x);
  const Eigen::Matrix<Scalar, Eigen::Dynamic, 3> expected = llt.factorization().solve(b);
  const double tol = std::is_same_v<Scalar, float> ? 1e-5 : 1e-13;
  CHECK((x - expected).norm() <= tol * expected.norm());
  // and it solves the system itself
  CHECK((q * x - b).norm() <= tol * 10 * b.norm());
}

TEST_CASE("SparseCholesky::solve allocates nothing and may solve in place") {
  const int n = 200;
  const auto q = random_spd<double>(n, 800, 11);
  massspring::SparseCholesky<double> llt;
  REQUIRE(llt.compute(q));
  massspring::Points<double> b = massspring::Points<double>::Random(n, 3);
  const massspring::Points<double> b0 = b;
  massspring::Points<double> x(n, 3);
  std::size_t allocations = 0;
  {
    massspring::test::CountAllocations count;
    llt.solve(b, x);
    llt.solve(b, b);  // in place
    allocations = count.count();
  }
  CHECK(allocations == 0);
  CHECK((x - b).norm() == 0.0);
  CHECK((q * x - b0).norm() <= 1e-12 * b0.norm());
}

TEST_CASE("SparseCholesky reports a matrix that is not positive definite") {
  std::vector<Eigen::Triplet<double, int>> t = {{0, 0, 1.0}, {1, 1, -1.0}};
  const auto q = massspring::storage_traits<massspring::Sparse, double>::from_triplets(2, 2, t);
  massspring::SparseCholesky<double> llt;
  CHECK_FALSE(llt.compute(q));
  CHECK_FALSE(llt.ok());
}

TEST_CASE("storage_traits<Sparse>::from_triplets sums duplicates") {
  std::vector<Eigen::Triplet<double, int>> t = {{0, 1, 2.0}, {0, 1, 3.0}, {1, 0, -1.0}};
  const auto m = massspring::storage_traits<massspring::Sparse, double>::from_triplets(2, 3, t);
  CHECK(m.rows() == 2);
  CHECK(m.cols() == 3);
  CHECK(m.coeff(0, 1) == 5.0);
  CHECK(m.coeff(1, 0) == -1.0);
  CHECK(m.nonZeros() == 2);
}
