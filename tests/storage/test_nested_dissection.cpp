// storage/nested_dissection.hpp: the symbolic nonzero count against real factors, the graph of a
// matrix, and nested dissection's orders: permutations, separators that split grids in two,
// less fill than AMD where the theory says so, and clear errors.
#include <doctest/doctest.h>

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <massspring/storage/nested_dissection.hpp>
#include <numeric>
#include <random>
#include <vector>

namespace {

using SpMat = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// Q's pattern for springs between points: diagonal 1 + sum of stiffness, -1 per spring.
SpMat laplacian(int n, const std::vector<std::pair<int, int>>& edges) {
  std::vector<Eigen::Triplet<double, int>> t;
  for (int i = 0; i < n; ++i) t.emplace_back(i, i, 1.0);
  for (const auto& [a, b] : edges) {
    t.emplace_back(a, a, 1.0);
    t.emplace_back(b, b, 1.0);
    t.emplace_back(a, b, -1.0);
    t.emplace_back(b, a, -1.0);
  }
  SpMat q(n, n);
  q.setFromTriplets(t.begin(), t.end());
  return q;
}

// An N x N grid in the plane z = 0, point r * N + c at (c, r, 0): neighbours along rows and
// columns, and the diagonals of each quad (none, one or both).
struct Grid {
  int n = 0;
  Eigen::Matrix<double, Eigen::Dynamic, 3> xyz;
  std::vector<std::pair<int, int>> edges;
};

Grid grid(int size, int diagonals) {
  Grid g;
  g.n = size * size;
  g.xyz.resize(g.n, 3);
  for (int r = 0; r < size; ++r)
    for (int c = 0; c < size; ++c) {
      g.xyz.row(r * size + c) << c, r, 0;
      if (c + 1 < size) g.edges.emplace_back(r * size + c, r * size + c + 1);
      if (r + 1 < size) g.edges.emplace_back(r * size + c, (r + 1) * size + c);
      if (r + 1 < size && c + 1 < size) {
        if (diagonals >= 1) g.edges.emplace_back(r * size + c, (r + 1) * size + c + 1);
        if (diagonals >= 2) g.edges.emplace_back(r * size + c + 1, (r + 1) * size + c);
      }
    }
  return g;
}

Eigen::Index factor_nonzeros(const SpMat& q, const std::vector<int>& order) {
  const int n = int(q.rows());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> p(n);
  for (int k = 0; k < n; ++k) p.indices()(order[std::size_t(k)]) = k;
  SpMat permuted(n, n);
  permuted.selfadjointView<Eigen::Lower>() = q.selfadjointView<Eigen::Lower>().twistedBy(p);
  const Eigen::SimplicialLLT<SpMat, Eigen::Lower, Eigen::NaturalOrdering<int>> llt(permuted);
  REQUIRE(llt.info() == Eigen::Success);
  return llt.matrixL().nestedExpression().nonZeros();
}

std::vector<int> amd_order(const SpMat& q) {
  SpMat full = q;
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse;
  Eigen::AMDOrdering<int>()(full, inverse);
  return {inverse.indices().data(), inverse.indices().data() + inverse.size()};
}

bool is_permutation(std::vector<int> order, int n) {
  std::sort(order.begin(), order.end());
  std::vector<int> identity(static_cast<std::size_t>(n));
  std::iota(identity.begin(), identity.end(), 0);
  return order == identity;
}

// Sizes of the connected components of the graph without the vertices in `removed`.
std::vector<int> components(int n, const std::vector<std::pair<int, int>>& edges,
                            const std::vector<bool>& removed) {
  std::vector<int> root(static_cast<std::size_t>(n));
  std::iota(root.begin(), root.end(), 0);
  const auto find = [&](int v) {
    while (root[std::size_t(v)] != v)
      v = root[std::size_t(v)] = root[std::size_t(root[std::size_t(v)])];
    return v;
  };
  for (const auto& [a, b] : edges)
    if (!removed[std::size_t(a)] && !removed[std::size_t(b)]) root[std::size_t(find(a))] = find(b);
  std::vector<int> size(static_cast<std::size_t>(n), 0);
  for (int v = 0; v < n; ++v)
    if (!removed[std::size_t(v)]) ++size[std::size_t(find(v))];
  std::vector<int> out;
  for (int s : size)
    if (s > 0) out.push_back(s);
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST_CASE("graph_of: the symmetric off-diagonal pattern, each edge once per end") {
  // Entries at (1, 0) only, at (2, 1) and (1, 2), an explicit zero at (3, 0), a diagonal.
  std::vector<Eigen::Triplet<double, int>> t = {{0, 0, 4.0},  {1, 0, -1.0}, {2, 1, -1.0},
                                                {1, 2, -1.0}, {3, 0, 0.0},  {3, 3, 1.0}};
  SpMat a(4, 4);
  a.setFromTriplets(t.begin(), t.end());
  const massspring::Graph g = massspring::graph_of(a);
  CHECK(g.size() == 4);
  CHECK(g.start == std::vector<int>{0, 2, 4, 5, 6});
  CHECK(g.neighbours == std::vector<int>{1, 3, 0, 2, 1, 0});
  CHECK_THROWS_WITH_AS(massspring::graph_of(SpMat(3, 4)),
                       "graph_of: the matrix must be square, got 3 x 4", massspring::Error);
}

TEST_CASE("cholesky_nonzeros equals the nonzeros of the factor Eigen computes, in any order") {
  std::mt19937 rng(17);
  for (const int n : {1, 2, 30, 200}) {
    CAPTURE(n);
    std::uniform_int_distribution<int> index(0, n - 1);
    std::vector<std::pair<int, int>> edges;
    for (int e = 0; e < 3 * n; ++e) {
      const int a = index(rng), b = index(rng);
      if (a != b) edges.emplace_back(a, b);
    }
    const SpMat q = laplacian(n, edges);
    const massspring::Graph g = massspring::graph_of(q);
    std::vector<int> order(static_cast<std::size_t>(n));
    std::iota(order.begin(), order.end(), 0);
    for (int trial = 0; trial < 3; ++trial) {
      CHECK(massspring::cholesky_nonzeros(g, order) == std::size_t(factor_nonzeros(q, order)));
      std::shuffle(order.begin(), order.end(), rng);
    }
    const std::vector<int> amd = amd_order(q);
    CHECK(massspring::cholesky_nonzeros(g, amd) == std::size_t(factor_nonzeros(q, amd)));
  }
  const massspring::Graph g = massspring::graph_of(laplacian(3, {{0, 1}}));
  CHECK_THROWS_WITH_AS(massspring::cholesky_nonzeros(g, {0, 0, 1}),
                       "cholesky_nonzeros: the order is not a permutation of 0 .. 2 (entry 1 is 0)",
                       massspring::Error);
}

TEST_CASE("nested_dissection: the last vertices cut a grid into two halves") {
  // 4-neighbour 31 x 31 grid: the top separator is one grid line (31 points), which leaves two
  // connected halves of (961 - 31) / 2 = 465 points, up to the line moved by one.
  const Grid g = grid(31, 0);
  const massspring::Graph graph = massspring::graph_of(laplacian(g.n, g.edges));
  const std::vector<int> order = massspring::nested_dissection(g.xyz, graph);
  REQUIRE(is_permutation(order, g.n));
  std::vector<bool> removed(static_cast<std::size_t>(g.n), false);
  for (int k = g.n - 31; k < g.n; ++k) removed[std::size_t(order[std::size_t(k)])] = true;
  const std::vector<int> parts = components(g.n, g.edges, removed);
  REQUIRE(parts.size() == 2);
  CHECK(parts[0] >= 465 - 31);
  CHECK(parts[1] <= 465 + 31);
  // The first half in the order is one of them (ordered before anything of the other).
  std::vector<bool> first(static_cast<std::size_t>(g.n), false);
  for (int k = 0; k < parts[0]; ++k) first[std::size_t(order[std::size_t(k)])] = true;
  for (const auto& [a, b] : g.edges)
    if (!removed[std::size_t(a)] && !removed[std::size_t(b)])
      CHECK(first[std::size_t(a)] == first[std::size_t(b)]);
}

TEST_CASE("nested_dissection: less fill than AMD on large grids, a valid order on any graph") {
  // George's theory: O(n log n) fill for nested dissection of a planar grid; minimum degree
  // grows faster. Measured here (counts, deterministic): both diagonals, 128 x 128.
  const Grid g = grid(128, 2);
  const SpMat q = laplacian(g.n, g.edges);
  const massspring::Graph graph = massspring::graph_of(q);
  const std::vector<int> nd = massspring::nested_dissection(g.xyz, graph);
  REQUIRE(is_permutation(nd, g.n));
  const std::size_t nd_nnz = massspring::cholesky_nonzeros(graph, nd);
  const std::size_t amd_nnz = massspring::cholesky_nonzeros(graph, amd_order(q));
  CHECK(double(nd_nnz) <= 0.92 * double(amd_nnz));

  // Points that coincide, and a graph in pieces: still a permutation (split by index).
  std::vector<std::pair<int, int>> edges = {{0, 1}, {1, 2}, {4, 5}};
  const massspring::Graph small = massspring::graph_of(laplacian(40, edges));
  const Eigen::Matrix<double, Eigen::Dynamic, 3> same =
      Eigen::Matrix<double, Eigen::Dynamic, 3>::Zero(40, 3);
  CHECK(is_permutation(massspring::nested_dissection(same, small), 40));
  massspring::NestedDissectionOptions o;
  o.leaf_size = 1;
  CHECK(is_permutation(massspring::nested_dissection(same, small, o), 40));
  // Small random graphs down to single vertices, random or coincident points, every leaf size.
  std::mt19937 rng(23);
  for (int n = 1; n <= 12; ++n)
    for (int trial = 0; trial < 20; ++trial) {
      std::uniform_int_distribution<int> index(0, n - 1);
      std::vector<std::pair<int, int>> random_edges;
      for (int e = 0; e < 2 * n; ++e) {
        const int a = index(rng), b = index(rng);
        if (a != b) random_edges.emplace_back(a, b);
      }
      const massspring::Graph rg = massspring::graph_of(laplacian(n, random_edges));
      Eigen::Matrix<double, Eigen::Dynamic, 3> xyz =
          Eigen::Matrix<double, Eigen::Dynamic, 3>::Random(n, 3);
      if (trial % 2 == 1) xyz.setZero();
      o.leaf_size = 1 + trial % 3;
      std::size_t nonzeros = 0;
      const std::vector<int> order = massspring::nested_dissection(xyz, rg, o, &nonzeros);
      CHECK(is_permutation(order, n));
      // The count it reports is that of the order it returns, not of the variant it dropped
      // (cholesky_nonzeros itself is checked against Eigen's factors above).
      CHECK(nonzeros == massspring::cholesky_nonzeros(rg, order));
    }
}

TEST_CASE("nested_dissection refuses bad input with a clear error") {
  const massspring::Graph g = massspring::graph_of(laplacian(3, {{0, 1}}));
  Eigen::Matrix<double, Eigen::Dynamic, 3> xyz =
      Eigen::Matrix<double, Eigen::Dynamic, 3>::Zero(2, 3);
  CHECK_THROWS_WITH_AS(
      massspring::nested_dissection(xyz, g),
      "nested_dissection: coordinates are 2 x 3 for a graph of 3 vertices (need 3 x 3)",
      massspring::Error);
  xyz = Eigen::Matrix<double, Eigen::Dynamic, 3>::Zero(3, 3);
  xyz(1, 2) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH_AS(massspring::nested_dissection(xyz, g),
                       doctest::Contains("coordinate (1, 2) is not finite"), massspring::Error);
  xyz(1, 2) = 0;
  massspring::NestedDissectionOptions o;
  o.leaf_size = 0;
  CHECK_THROWS_WITH_AS(massspring::nested_dissection(xyz, g, o),
                       "nested_dissection: leaf_size must be >= 1, got 0", massspring::Error);
}
