#pragma once
// A random sparse symmetric positive definite matrix for the storage tests.
#include <Eigen/SparseCore>
#include <massspring/storage/sparse.hpp>
#include <random>
#include <vector>

namespace massspring::test {

// A random graph Laplacian (weights in [0.5, 2]) plus a positive diagonal: n x n, `edges` random
// pairs (self-pairs skipped), from `seed`.
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

}  // namespace massspring::test
