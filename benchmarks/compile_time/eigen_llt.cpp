// scripts/compile_time.sh: the yardstick, Eigen's own SimplicialLLT factorizing a sparse matrix
// built from triplets and solving for an n x 3 right-hand side.
#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <vector>

int main() {
  std::vector<Eigen::Triplet<double>> triplets;
  for (int i = 0; i < 3; ++i) triplets.emplace_back(i, i, 2.0);
  Eigen::SparseMatrix<double> q(3, 3);
  q.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> llt(q);
  const Eigen::MatrixX3d b = Eigen::MatrixX3d::Ones(3, 3);
  const Eigen::MatrixX3d x = llt.solve(b);
  return llt.info() == Eigen::Success && x(0, 0) > 0 ? 0 : 1;
}
