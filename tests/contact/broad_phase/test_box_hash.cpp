// contact/broad_phase/box_hash.hpp against the brute-force answer: every stored box that
// overlaps a query box is reported exactly once, and nothing else, whatever the cell size.
#include <doctest/doctest.h>

#include <Eigen/Core>
#include <massspring/contact/broad_phase/box_hash.hpp>
#include <random>
#include <vector>

namespace {
using Box = massspring::contact::AlignedBox3<double>;

Box random_box(std::mt19937& rng, double spread, double size) {
  std::uniform_real_distribution<double> at(-spread, spread), extent(0, size);
  Box b;
  b.lo = Eigen::Vector3d(at(rng), at(rng), at(rng));
  b.hi = b.lo + Eigen::Vector3d(extent(rng), extent(rng), extent(rng));
  return b;
}
}  // namespace

TEST_CASE("BoxHash reports each overlapping box once, and only those (brute force)") {
  std::mt19937 rng(7);
  std::vector<Box> boxes;
  for (int i = 0; i < 400; ++i) boxes.push_back(random_box(rng, 1.0, 0.3));
  massspring::contact::BoxHash<double> hash;
  for (const double cell : {0.01, 0.1, 0.5, 3.0}) {
    CAPTURE(cell);
    hash.build(boxes, cell);
    for (int q = 0; q < 200; ++q) {
      const Box query = random_box(rng, 1.2, 0.4);
      std::vector<int> seen(boxes.size(), 0);
      hash.query(query, [&](int i) { ++seen[std::size_t(i)]; });
      for (std::size_t i = 0; i < boxes.size(); ++i) {
        const bool overlap = (boxes[i].lo.array() <= query.hi.array()).all() &&
                             (query.lo.array() <= boxes[i].hi.array()).all();
        REQUIRE(seen[i] == int(overlap));
      }
    }
  }
}

TEST_CASE("BoxHash: boxes that only touch overlap; negative coordinates hash like any others") {
  std::vector<Box> boxes = {{Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(0, 0, 0)},
                            {Eigen::Vector3d(-3, -3, -3), Eigen::Vector3d(-2.5, -2.5, -2.5)}};
  massspring::contact::BoxHash<double> hash;
  hash.build(boxes, 0.25);
  std::vector<int> hits;
  hash.query({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1)},
             [&](int i) { hits.push_back(i); });
  CHECK(hits == std::vector<int>{0});
  hits.clear();
  hash.query({Eigen::Vector3d(-2.6, -2.6, -2.6), Eigen::Vector3d(-2.55, -2.55, -2.55)},
             [&](int i) { hits.push_back(i); });
  CHECK(hits == std::vector<int>{1});
}

TEST_CASE("BoxHash: a box far larger than the cells is listed, not hashed, and still found once") {
  // 1 km boxes among 1 mm cells: 10^18 cells each, were they hashed.
  std::mt19937 rng(11);
  std::vector<Box> boxes;
  for (int i = 0; i < 100; ++i) boxes.push_back(random_box(rng, 1.0, 0.01));
  boxes.push_back({Eigen::Vector3d(-500, -500, -500), Eigen::Vector3d(500, 500, 500)});
  boxes.push_back({Eigen::Vector3d(2, 2, 2), Eigen::Vector3d(900, 900, 900)});
  massspring::contact::BoxHash<double> hash;
  hash.build(boxes, 1e-3);
  std::vector<Box> queries;
  for (int q = 0; q < 100; ++q) queries.push_back(random_box(rng, 1.2, 0.02));
  queries.push_back({Eigen::Vector3d(-1000, -1, -1), Eigen::Vector3d(1000, 1, 1)});  // large too
  for (const Box& query : queries) {
    std::vector<int> seen(boxes.size(), 0);
    hash.query(query, [&](int i) { ++seen[std::size_t(i)]; });
    for (std::size_t i = 0; i < boxes.size(); ++i)
      REQUIRE(seen[i] == int(boxes[i].overlaps(query)));
  }
}

TEST_CASE("BoxHash: with a bound, exactly the overlapping boxes above it, hashed or large") {
  // Each stored box queried with its own index lists every overlapping pair once (brute force).
  std::mt19937 rng(13);
  std::vector<Box> boxes;
  for (int i = 0; i < 300; ++i) boxes.push_back(random_box(rng, 1.0, 0.3));
  boxes[17] = {Eigen::Vector3d(-50, -50, -50), Eigen::Vector3d(50, 50, 50)};  // too large to hash
  boxes[250] = {Eigen::Vector3d(-0.5, -60, -0.5), Eigen::Vector3d(0.5, 60, 0.5)};
  massspring::contact::BoxHash<double> hash;
  for (const double cell : {0.005, 0.1, 3.0}) {
    CAPTURE(cell);
    hash.build(boxes, cell);
    std::vector<int> pair_count(boxes.size() * boxes.size(), 0);
    for (std::size_t a = 0; a < boxes.size(); ++a)
      hash.query(
          boxes[a], [&](int b) { ++pair_count[a * boxes.size() + std::size_t(b)]; }, int(a));
    for (std::size_t a = 0; a < boxes.size(); ++a)
      for (std::size_t b = 0; b < boxes.size(); ++b)
        REQUIRE(pair_count[a * boxes.size() + b] == int(b > a && boxes[a].overlaps(boxes[b])));
  }
}
