// scene/face_springs.hpp: every vertex pair of each face, extra edges, each pair once.
#include <doctest/doctest.h>

#include <massspring/scene/face_springs.hpp>
#include <set>
#include <utility>
#include <vector>

namespace {

using massspring::Edges;
using massspring::Error;
using massspring::face_springs;

using Pairs = std::set<std::pair<int, int>>;

Pairs as_set(const Edges& e) {
  Pairs s;
  for (Eigen::Index i = 0; i < e.rows(); ++i) s.insert({e(i, 0), e(i, 1)});
  return s;
}

Edges edges(std::initializer_list<std::pair<int, int>> list) {
  Edges e(Eigen::Index(list.size()), 2);
  Eigen::Index i = 0;
  for (const auto& [a, b] : list) e.row(i++) << a, b;
  return e;
}

}  // namespace

TEST_CASE("face_springs: a triangle gives its 3 sides") {
  const Edges s = face_springs(3, {{2, 0, 1}}, Edges(0, 2));
  CHECK(s.rows() == 3);
  CHECK(as_set(s) == Pairs{{0, 1}, {0, 2}, {1, 2}});
}

TEST_CASE("face_springs: a quad gives its 4 sides and both diagonals") {
  const Edges s = face_springs(4, {{0, 1, 2, 3}}, Edges(0, 2));
  CHECK(s.rows() == 6);
  CHECK(as_set(s) == Pairs{{0, 1}, {1, 2}, {2, 3}, {0, 3}, {0, 2}, {1, 3}});
}

TEST_CASE("face_springs: two quads sharing an edge give 6 + 6 - 1 = 11") {
  // 0-1-2
  // | | |
  // 3-4-5
  const Edges s = face_springs(6, {{0, 1, 4, 3}, {1, 2, 5, 4}}, Edges(0, 2));
  CHECK(s.rows() == 11);
  CHECK(as_set(s).count({1, 4}) == 1);
}

TEST_CASE("face_springs: a polygon of k vertices gives k (k - 1) / 2 pairs") {
  for (int k = 3; k <= 8; ++k) {
    std::vector<int> face(static_cast<std::size_t>(k));
    for (int i = 0; i < k; ++i) face[std::size_t(i)] = i;
    CHECK(face_springs(k, {face}, Edges(0, 2)).rows() == k * (k - 1) / 2);
  }
}

TEST_CASE("face_springs merges duplicates, whatever their direction, and sorts the result") {
  // the quad's side 1-0 and diagonal 2-0 again as edges, an edge twice, a new edge 3-4
  const Edges extra = edges({{1, 0}, {2, 0}, {4, 3}, {3, 4}, {3, 4}});
  const Edges s = face_springs(5, {{0, 1, 2, 3}, {3, 2, 1}}, extra);
  CHECK(s.rows() == 7);
  CHECK(as_set(s) == Pairs{{0, 1}, {1, 2}, {2, 3}, {0, 3}, {0, 2}, {1, 3}, {3, 4}});
  for (Eigen::Index e = 0; e < s.rows(); ++e) {
    CHECK(s(e, 0) < s(e, 1));
    if (e > 0) CHECK(std::make_pair(s(e - 1, 0), s(e - 1, 1)) < std::make_pair(s(e, 0), s(e, 1)));
  }
}

TEST_CASE("face_springs: edges alone, and nothing at all") {
  CHECK(as_set(face_springs(3, {}, edges({{2, 1}, {0, 1}}))) == Pairs{{0, 1}, {1, 2}});
  CHECK(face_springs(0, {}, Edges(0, 2)).rows() == 0);
}

TEST_CASE("face_springs refuses out-of-range and repeated vertices, naming the face or edge") {
  CHECK_THROWS_WITH_AS(face_springs(3, {{0, 1, 2}, {0, 1, 3}}, Edges(0, 2)),
                       doctest::Contains("face 1: vertex index 3 out of range [0, 3)"), Error);
  CHECK_THROWS_WITH_AS(face_springs(3, {{0, -1, 2}}, Edges(0, 2)),
                       doctest::Contains("face 0: vertex index -1 out of range"), Error);
  CHECK_THROWS_WITH_AS(face_springs(4, {{0, 1, 2, 1}}, Edges(0, 2)),
                       doctest::Contains("face 0: vertex 1 appears twice"), Error);
  CHECK_THROWS_WITH_AS(face_springs(3, {}, edges({{0, 1}, {1, 3}})),
                       doctest::Contains("edge 1: vertex index 3 out of range"), Error);
  CHECK_THROWS_WITH_AS(face_springs(3, {}, edges({{2, 2}})),
                       doctest::Contains("edge 0 joins vertex 2 to itself"), Error);
}
