// storage/sparse.hpp: the fused n x 3 solve against Eigen's own SimplicialLLT::solve, the factor
// in the Ordering's and in a given order, and no allocation per solve.
#include <doctest/doctest.h>

#include <algorithm>
#include <massspring/storage/sparse.hpp>
#include <numeric>
#include <random>
#include <vector>

#include "support/alloc_counter.hpp"
#include "support/random_spd.hpp"

using massspring::test::random_spd;

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
  const Eigen::SimplicialLLT<Eigen::SparseMatrix<Scalar, Eigen::ColMajor, int>> eigen(q);
  REQUIRE(eigen.info() == Eigen::Success);
  const Eigen::Matrix<Scalar, Eigen::Dynamic, 3> expected = eigen.solve(b);
  const double tol = std::is_same_v<Scalar, float> ? 1e-5 : 1e-13;
  CHECK((x - expected).norm() <= tol * expected.norm());
  // and it solves the system itself
  CHECK((q * x - b).norm() <= tol * 10 * b.norm());
}

TEST_CASE("SparseCholesky: its own order is Eigen's AMD, with Eigen's factor") {
  const auto q = random_spd<double>(250, 900, 5);
  massspring::SparseCholesky<double> ours;
  REQUIRE(ours.compute(q));
  const Eigen::SimplicialLLT<Eigen::SparseMatrix<double, Eigen::ColMajor, int>> eigen(q);
  REQUIRE(eigen.info() == Eigen::Success);
  CHECK(ours.permutation() == eigen.permutationP().indices());
  const Eigen::SparseMatrix<double> expected = eigen.matrixL();
  const Eigen::SparseMatrix<double> got = ours.factor();
  CHECK(got.nonZeros() == expected.nonZeros());
  // The same entries; the sums within a column may be taken in another order (Eigen permutes Q
  // itself, here it arrives permuted), so equal to rounding.
  CHECK(Eigen::MatrixXd(got - expected).norm() <= 1e-14 * Eigen::MatrixXd(expected).norm());
}

TEST_CASE("SparseCholesky with a given order: P Q P^T = L L^T in that order, solves Q") {
  const int n = 240;
  const auto q = random_spd<double>(n, 800, 9);
  std::vector<int> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937(4));
  massspring::SparseCholesky<double> llt;
  REQUIRE(llt.compute(q, order));
  for (int k = 0; k < n; ++k) CHECK(llt.permutation()(order[std::size_t(k)]) == k);
  // Independent: L L^T against Q permuted densely (row order[k] of Q is row k).
  const Eigen::MatrixXd dq(q);
  Eigen::MatrixXd pqp(n, n);
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) pqp(a, b) = dq(order[std::size_t(a)], order[std::size_t(b)]);
  const Eigen::MatrixXd l(llt.factor());
  CHECK((l * l.transpose() - pqp).norm() <= 1e-13 * pqp.norm());
  CHECK(llt.factor_nonzeros() ==
        Eigen::Index(massspring::cholesky_nonzeros(massspring::graph_of(q), order)));
  const massspring::Points<double> b = massspring::Points<double>::Random(n, 3);
  massspring::Points<double> x(n, 3);
  llt.solve(b, x);
  CHECK((q * x - b).norm() <= 1e-12 * b.norm());
}

TEST_CASE("SparseCholesky refuses an order that is not a permutation of Q's rows") {
  const auto q = random_spd<double>(5, 8, 1);
  massspring::SparseCholesky<double> llt;
  CHECK_THROWS_WITH_AS(llt.compute(q, {0, 1, 2, 3}),
                       "SparseCholesky: the order has 4 entries for 5 unknowns", massspring::Error);
  CHECK_THROWS_WITH_AS(llt.compute(q, {0, 1, 2, 3, 3}),
                       "SparseCholesky: the order is not a permutation of 0 .. 4 (entry 4 is 3)",
                       massspring::Error);
  CHECK_THROWS_WITH_AS(llt.compute(q, {0, 1, 2, 3, 5}), doctest::Contains("entry 4 is 5"),
                       massspring::Error);
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

#ifdef _OPENMP
TEST_CASE("SparseCholesky with threads: a valid split, and the same solution bit for bit") {
  for (const int threads : {2, 3}) {
    for (const int edges : {0, 600, 1200}) {
      CAPTURE(threads);
      CAPTURE(edges);
      const int n = 300;
      const auto q = random_spd<double>(n, edges, 13);
      massspring::SparseCholesky<double> serial, parallel;
      parallel.set_threads(threads);
      REQUIRE(serial.compute(q));
      REQUIRE(parallel.compute(q));
      CHECK(parallel.threads() == threads);
      // The split: every row once; a part's rows have their parent in the same part or the top,
      // the top's rows have theirs in the top (so each part substitutes without the others).
      const auto v = parallel.lower();
      REQUIRE(v.parts == threads);
      std::vector<int> label(n, -2);
      for (int t = 0; t <= threads; ++t)
        for (int q_ = v.part_start[t]; q_ < v.part_start[t + 1]; ++q_) {
          REQUIRE(label[v.schedule[q_]] == -2);
          label[v.schedule[q_]] = t == threads ? -1 : t;
          if (q_ > v.part_start[t]) CHECK(v.schedule[q_ - 1] < v.schedule[q_]);  // ascending
        }
      REQUIRE(v.part_start[threads + 1] == n);
      for (int j = 0; j < n; ++j) {
        REQUIRE(label[j] != -2);
        for (int p = v.outer[j] + 1; p < v.outer[j + 1]; ++p) {  // every ancestor of j
          const int i = v.inner[p];
          CHECK((label[i] == -1 || label[i] == label[j]));
        }
      }
      const massspring::Points<double> b = massspring::Points<double>::Random(n, 3);
      massspring::Points<double> x1(n, 3), x2(n, 3);
      // With the AVX2 substitution where the CPU has it (the default), and with the SSE2 one.
      for (const bool simd : {true, false}) {
        CAPTURE(simd);
        serial.set_simd(simd);
        parallel.set_simd(simd);
        CHECK(serial.simd() == parallel.simd());
        serial.solve(b, x1);
        parallel.solve(b, x2);
        CHECK(x1 == x2);
        CHECK((q * x2 - b).norm() <= 1e-12 * b.norm());
      }
    }
  }
}
#endif

TEST_CASE("SparseCholesky::set_threads refuses bad counts") {
  massspring::SparseCholesky<double> llt;
  CHECK_THROWS_WITH_AS(llt.set_threads(0), doctest::Contains("threads must be >= 1, got 0"),
                       massspring::Error);
#ifndef _OPENMP
  CHECK_THROWS_WITH_AS(llt.set_threads(2), doctest::Contains("needs OpenMP"), massspring::Error);
#endif
}
