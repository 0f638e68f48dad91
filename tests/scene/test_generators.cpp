// scene/chain.hpp, scene/net.hpp, scene/cloth.hpp: counts in closed form, positions, pins, rest
// lengths, refusals; and the committed examples/scenes are what massspring-make-scenes writes.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <massspring/scene/chain.hpp>
#include <massspring/scene/cloth.hpp>
#include <massspring/scene/net.hpp>
#include <set>
#include <string>
#include <vector>

#include "../../tools/project_scenes.hpp"
#include "io/test_files.hpp"
#include "massspring/io/json_scene.hpp"
#include "massspring/scene/face_springs.hpp"
#include "massspring/scene/make_system.hpp"
#include "massspring/system/mass_spring_system.hpp"
#include "support/paths.hpp"

namespace {

using massspring::Error;
using massspring::SceneDescription;
using System = massspring::MassSpringSystem<double, massspring::Sparse>;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

int spring_count(const SceneDescription<double>& s) {
  return int(massspring::face_springs(int(s.vertices.rows()), s.faces, s.edges).rows());
}

// How many springs have each rest length (lengths within 1e-12 relative count as one).
std::map<double, int> rest_length_histogram(const System& s) {
  std::map<double, int> h;
  for (int e = 0; e < s.num_springs(); ++e) {
    const double r = s.rest_lengths()(e);
    auto it = std::find_if(h.begin(), h.end(),
                           [r](const auto& kv) { return std::abs(kv.first - r) <= 1e-12 * r; });
    if (it == h.end())
      h[r] = 1;
    else
      ++it->second;
  }
  return h;
}

int count_near(const std::map<double, int>& h, double length) {
  for (const auto& [r, n] : h)
    if (std::abs(r - length) <= 1e-12 * length) return n;
  return 0;
}

}  // namespace

// ---- chain ---------------------------------------------------------------------------------

TEST_CASE("make_chain: n points evenly along +x, n - 1 springs of length L / (n - 1)") {
  for (int n : {2, 3, 10, 101}) {
    CAPTURE(n);
    massspring::ChainOptions o;
    o.points = n;
    o.length = 2.5;
    const auto s = massspring::make_chain(o);
    REQUIRE(s.vertices.rows() == n);
    CHECK(s.faces.empty());
    CHECK(s.edges.rows() == n - 1);
    CHECK(spring_count(s) == n - 1);
    for (int i = 0; i < n; ++i) {
      CHECK(s.vertices(i, 0) == doctest::Approx(2.5 * i / (n - 1)));
      CHECK(s.vertices(i, 1) == 0);
      CHECK(s.vertices(i, 2) == 0);
    }
    CHECK(s.vertices(n - 1, 0) == 2.5);
    for (int e = 0; e < n - 1; ++e) {
      CHECK(s.edges(e, 0) == e);
      CHECK(s.edges(e, 1) == e + 1);
    }
    const auto system = massspring::make_system<System>(s);
    CHECK(system.rest_lengths().minCoeff() == doctest::Approx(2.5 / (n - 1)).epsilon(1e-12));
    CHECK(system.rest_lengths().maxCoeff() == doctest::Approx(2.5 / (n - 1)).epsilon(1e-12));
    CHECK((system.masses().array() == 1.0).all());
    CHECK((system.stiffness().array() == 500.0).all());
  }
}

TEST_CASE("make_chain: any direction (normalised), pins, stiffness and mass") {
  massspring::ChainOptions o;
  o.points = 5;
  o.length = 2;
  o.direction = Eigen::Vector3d(0, 0, -3);
  o.stiffness = 7;
  o.mass = 0.2;
  o.pins = massspring::ChainPins::First;
  auto s = massspring::make_chain(o);
  CHECK(s.vertices.row(4) == Eigen::RowVector3d(0, 0, -2));
  CHECK(s.vertices.row(2) == Eigen::RowVector3d(0, 0, -1));
  CHECK(s.pinned == std::vector<int>{0});
  CHECK(s.stiffness == 7);
  CHECK(s.mass == 0.2);
  o.pins = massspring::ChainPins::BothEnds;
  CHECK(massspring::make_chain(o).pinned == std::vector<int>{0, 4});
  o.pins = massspring::ChainPins::None;
  CHECK(massspring::make_chain(o).pinned.empty());
  o.direction = Eigen::Vector3d(1, 1, 1);
  s = massspring::make_chain(o);
  const double end = 2 / std::sqrt(3.0);
  CHECK(s.vertices(4, 0) == doctest::Approx(end));
  CHECK(s.vertices(4, 1) == doctest::Approx(end));
  CHECK(s.vertices(4, 2) == doctest::Approx(end));
}

TEST_CASE("make_chain refuses invalid options, naming them") {
  auto with = [](auto change) {
    massspring::ChainOptions o;
    change(o);
    return o;
  };
  using O = massspring::ChainOptions;
  CHECK_THROWS_WITH_AS(massspring::make_chain(with([](O& o) { o.points = 1; })),
                       doctest::Contains("make_chain: points must be >= 2, got 1"), Error);
  for (double bad : {0.0, -1.0, kNaN, kInf})
    CHECK_THROWS_WITH_AS(massspring::make_chain(with([bad](O& o) { o.length = bad; })),
                         doctest::Contains("make_chain: length must be finite and > 0"), Error);
  CHECK_THROWS_WITH_AS(massspring::make_chain(with([](O& o) { o.direction.setZero(); })),
                       doctest::Contains("make_chain: direction must be finite and nonzero"),
                       Error);
  CHECK_THROWS_WITH_AS(massspring::make_chain(with([](O& o) { o.direction(1) = kNaN; })),
                       doctest::Contains("make_chain: direction must be finite and nonzero"),
                       Error);
  CHECK_THROWS_WITH_AS(massspring::make_chain(with([](O& o) { o.stiffness = -1; })),
                       doctest::Contains("make_chain: stiffness must be finite and >= 0"), Error);
  for (double bad : {0.0, -1.0, kNaN, kInf})
    CHECK_THROWS_WITH_AS(massspring::make_chain(with([bad](O& o) { o.mass = bad; })),
                         doctest::Contains("make_chain: mass must be finite and > 0"), Error);
}

// ---- net -----------------------------------------------------------------------------------

TEST_CASE(
    "make_net: columns x rows points in the x-z plane, rows (c - 1) + columns (r - 1) springs") {
  for (const auto& [cols, rows] :
       std::vector<std::pair<int, int>>{{2, 2}, {8, 8}, {5, 3}, {3, 9}}) {
    CAPTURE(cols);
    CAPTURE(rows);
    massspring::NetOptions o;
    o.columns = cols;
    o.rows = rows;
    o.width = 2.0;
    o.depth = 1.5;
    const auto s = massspring::make_net(o);
    REQUIRE(s.vertices.rows() == cols * rows);
    CHECK(s.faces.empty());
    const int expected = rows * (cols - 1) + cols * (rows - 1);
    CHECK(s.edges.rows() == expected);
    CHECK(spring_count(s) == expected);
    CHECK(s.vertices.col(1).isZero(0));
    CHECK(s.vertices.col(0).minCoeff() == 0);
    CHECK(s.vertices.col(0).maxCoeff() == doctest::Approx(2.0));
    CHECK(s.vertices.col(2).minCoeff() == 0);
    CHECK(s.vertices.col(2).maxCoeff() == doctest::Approx(1.5));
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < cols; ++c) {
        CHECK(s.vertices(r * cols + c, 0) == doctest::Approx(2.0 * c / (cols - 1)));
        CHECK(s.vertices(r * cols + c, 2) == doctest::Approx(1.5 * r / (rows - 1)));
      }
    // corners
    CHECK(s.pinned == std::vector<int>{0, cols - 1, (rows - 1) * cols, rows * cols - 1});
    const auto h = rest_length_histogram(massspring::make_system<System>(s));
    CHECK(count_near(h, 2.0 / (cols - 1)) + count_near(h, 1.5 / (rows - 1)) == expected);
    CHECK(count_near(h, 1.5 / (rows - 1)) == cols * (rows - 1));
  }
}

TEST_CASE("make_net: pins none, corners, border") {
  massspring::NetOptions o;
  o.columns = 5;
  o.rows = 4;
  o.pins = massspring::NetPins::None;
  CHECK(massspring::make_net(o).pinned.empty());
  o.pins = massspring::NetPins::Border;
  const auto s = massspring::make_net(o);
  CHECK(s.pinned.size() == std::size_t(2 * (5 + 4) - 4));
  for (int i : s.pinned) {
    const int r = i / 5, c = i % 5;
    CHECK((r == 0 || r == 3 || c == 0 || c == 4));
  }
  CHECK(std::set<int>(s.pinned.begin(), s.pinned.end()).size() == s.pinned.size());
}

TEST_CASE("make_net refuses invalid options, naming them") {
  auto with = [](auto change) {
    massspring::NetOptions o;
    change(o);
    return o;
  };
  using O = massspring::NetOptions;
  CHECK_THROWS_WITH_AS(massspring::make_net(with([](O& o) { o.columns = 1; })),
                       doctest::Contains("make_net: columns and rows must be >= 2, got 1 by 8"),
                       Error);
  CHECK_THROWS_WITH_AS(massspring::make_net(with([](O& o) { o.rows = 0; })),
                       doctest::Contains("make_net: columns and rows must be >= 2"), Error);
  for (double bad : {0.0, -1.0, kNaN, kInf}) {
    CHECK_THROWS_WITH_AS(massspring::make_net(with([bad](O& o) { o.width = bad; })),
                         doctest::Contains("make_net: width and depth must be finite and > 0"),
                         Error);
    CHECK_THROWS_WITH_AS(massspring::make_net(with([bad](O& o) { o.depth = bad; })),
                         doctest::Contains("make_net: width and depth must be finite and > 0"),
                         Error);
    CHECK_THROWS_WITH_AS(massspring::make_net(with([bad](O& o) { o.mass = bad; })),
                         doctest::Contains("make_net: mass must be finite and > 0"), Error);
  }
  CHECK_THROWS_WITH_AS(massspring::make_net(with([](O& o) { o.stiffness = kNaN; })),
                       doctest::Contains("make_net: stiffness must be finite and >= 0"), Error);
}

// ---- cloth ---------------------------------------------------------------------------------

TEST_CASE("make_cloth: spring counts in closed form for every shear and bending choice") {
  using massspring::ClothShear;
  for (const auto& [cols, rows] : std::vector<std::pair<int, int>>{{2, 2}, {3, 2}, {7, 5}, {4, 9}})
    for (ClothShear shear : {ClothShear::None, ClothShear::One, ClothShear::Both})
      for (bool bending : {false, true}) {
        CAPTURE(cols);
        CAPTURE(rows);
        CAPTURE(int(shear));
        CAPTURE(bending);
        massspring::ClothOptions o;
        o.columns = cols;
        o.rows = rows;
        o.width = 1.4;
        o.height = 0.9;
        o.shear = shear;
        o.bending = bending;
        const auto s = massspring::make_cloth(o);
        const double dx = 1.4 / (cols - 1), dy = 0.9 / (rows - 1);
        const int structural = rows * (cols - 1) + cols * (rows - 1);
        const int cells = (rows - 1) * (cols - 1);
        const int diagonals = shear == ClothShear::None  ? 0
                              : shear == ClothShear::One ? cells
                                                         : 2 * cells;
        const int bend = bending ? rows * (cols - 2) + cols * (rows - 2) : 0;
        CHECK(s.vertices.rows() == cols * rows);
        CHECK(spring_count(s) == structural + diagonals + bend);
        // each spring's rest length is a grid spacing, a cell diagonal or twice a spacing
        const auto h = rest_length_histogram(massspring::make_system<System>(s));
        const int along_x = count_near(h, dx) + (bending ? count_near(h, 2 * dx) : 0);
        const int along_y = count_near(h, dy) + (bending ? count_near(h, 2 * dy) : 0);
        CHECK(count_near(h, std::hypot(dx, dy)) == diagonals);
        if (std::abs(dx - 2 * dy) > 1e-9 && std::abs(dy - 2 * dx) > 1e-9 &&
            std::abs(dx - dy) > 1e-9) {
          CHECK(along_x == rows * (cols - 1) + (bending ? rows * (cols - 2) : 0));
          CHECK(along_y == cols * (rows - 1) + (bending ? cols * (rows - 2) : 0));
        }
        int total = 0;
        for (const auto& kv : h) total += kv.second;
        CHECK(total == structural + diagonals + bend);
        CHECK(along_x + along_y + count_near(h, std::hypot(dx, dy)) == total);
      }
}

TEST_CASE("make_cloth: positions, extent, plane and pins") {
  massspring::ClothOptions o;
  o.columns = 6;
  o.rows = 4;
  o.width = 1.5;
  o.height = 0.6;
  o.plane = massspring::ClothPlane::Vertical;
  auto s = massspring::make_cloth(o);
  CHECK(s.vertices.col(2).isZero(0));
  CHECK(s.vertices.col(0).maxCoeff() == doctest::Approx(1.5));
  CHECK(s.vertices.col(1).minCoeff() == doctest::Approx(-0.6));
  CHECK(s.vertices.col(1).maxCoeff() == 0);
  CHECK(s.vertices(2 * 6 + 3, 0) == doctest::Approx(3 * 0.3));
  CHECK(s.vertices(2 * 6 + 3, 1) == doctest::Approx(-2 * 0.2));
  CHECK(s.pinned == std::vector<int>{0, 5});  // the top corners
  o.plane = massspring::ClothPlane::Horizontal;
  o.pins = massspring::ClothPins::TopEdge;
  s = massspring::make_cloth(o);
  CHECK(s.vertices.col(1).isZero(0));
  CHECK(s.vertices.col(2).maxCoeff() == doctest::Approx(0.6));
  CHECK(s.pinned == std::vector<int>{0, 1, 2, 3, 4, 5});
  o.pins = massspring::ClothPins::None;
  CHECK(massspring::make_cloth(o).pinned.empty());
  // with faces and no mass, make_system gives the Voronoi areas: width * height in all
  const auto system = massspring::make_system<System>(massspring::make_cloth(o));
  CHECK(system.masses().sum() == doctest::Approx(1.5 * 0.6).epsilon(1e-12));
}

TEST_CASE("make_cloth: the curtain of Liu et al. 2013 has 6561 points and 32158 springs") {
  massspring::ClothOptions o;
  o.columns = 81;
  o.rows = 81;
  o.width = 1;
  o.height = 1;
  o.shear = massspring::ClothShear::One;
  o.bending = true;
  const auto s = massspring::make_cloth(o);
  CHECK(s.vertices.rows() == 6561);
  CHECK(spring_count(s) == 32158);
}

TEST_CASE("make_cloth refuses invalid options, naming them") {
  auto with = [](auto change) {
    massspring::ClothOptions o;
    change(o);
    return o;
  };
  using O = massspring::ClothOptions;
  CHECK_THROWS_WITH_AS(massspring::make_cloth(with([](O& o) { o.rows = 1; })),
                       doctest::Contains("make_cloth: columns and rows must be >= 2"), Error);
  CHECK_THROWS_WITH_AS(massspring::make_cloth(with([](O& o) { o.width = kNaN; })),
                       doctest::Contains("make_cloth: width and height must be finite and > 0"),
                       Error);
  CHECK_THROWS_WITH_AS(massspring::make_cloth(with([](O& o) { o.height = -1; })),
                       doctest::Contains("make_cloth: width and height must be finite and > 0"),
                       Error);
  CHECK_THROWS_WITH_AS(massspring::make_cloth(with([](O& o) { o.stiffness = -kInf; })),
                       doctest::Contains("make_cloth: stiffness must be finite and >= 0"), Error);
  CHECK_THROWS_WITH_AS(massspring::make_cloth(with([](O& o) { o.mass = 0.0; })),
                       doctest::Contains("make_cloth: mass must be finite and > 0"), Error);
}

// ---- the project's scenes ------------------------------------------------------------------

TEST_CASE("project scenes: the counts and settings the project asked for") {
  std::map<std::string, SceneDescription<double>> scenes;
  for (auto& [name, scene] : massspring::examples::project_scenes()) scenes[name] = scene;
  REQUIRE(scenes.size() == 12);
  const auto& chain = scenes.at("chain");
  CHECK(chain.vertices.rows() == 10);
  CHECK(spring_count(chain) == 9);
  CHECK(chain.pinned == std::vector<int>{0, 9});
  CHECK(chain.stiffness == 500);
  CHECK(chain.mass == 1.0);
  CHECK(chain.vertices(9, 0) == 1.0);
  const auto& net = scenes.at("net");
  CHECK(net.vertices.rows() == 64);
  CHECK(spring_count(net) == 2 * 8 * 7);
  CHECK(net.pinned.size() == 4);
  CHECK(net.stiffness == 300);
  CHECK(net.mass == 1.0);
  const auto& flag = scenes.at("flag");
  CHECK(flag.vertices.rows() == 3000);
  CHECK(spring_count(flag) == 50 * 59 + 60 * 49 + 2 * 49 * 59);
  CHECK(flag.vertices.col(1).isZero(0));  // horizontal
  CHECK(flag.pinned == std::vector<int>{0, 59});
  CHECK(flag.stiffness == 1000);
  CHECK_FALSE(flag.mass.has_value());
  const auto& curtain = scenes.at("curtain");
  CHECK(curtain.vertices.rows() == 6561);
  CHECK(spring_count(curtain) == 32158);
  CHECK(curtain.vertices.col(2).isZero(0));  // vertical
  CHECK(curtain.pinned == std::vector<int>{0, 80});
  CHECK_FALSE(curtain.mass.has_value());
  // The contact scenes: self-collision on, with its defaults.
  for (const char* name : {"clothesline", "ribbon_pile", "two_cloths"}) {
    CAPTURE(name);
    REQUIRE(scenes.at(name).self_collision.has_value());
    CHECK(scenes.at(name).self_collision->thickness == 0.004);
    CHECK(scenes.at(name).self_collision->friction == 0.2);
  }
  CHECK(scenes.at("clothesline").vertices.rows() == 31 * 31);
  CHECK(scenes.at("ribbon_pile").vertices.rows() == 9 * 61);
  CHECK(scenes.at("two_cloths").vertices.rows() == 2 * 21 * 21);
}

TEST_CASE("the committed examples/scenes are exactly what massspring-make-scenes writes now") {
  const auto committed = massspring::test::source_dir() / "examples" / "scenes";
  REQUIRE(std::filesystem::is_directory(committed));
  massspring::test::TempDir dir;
  std::set<std::string> expected_files;
  for (const auto& [name, scene] : massspring::examples::project_scenes()) {
    CAPTURE(name);
    massspring::io::write_json_scene(dir / (name + ".json"), scene);
    // and the committed scene loads as the generator's description
    const auto loaded = massspring::io::read_json_scene(committed / (name + ".json"));
    CHECK(loaded.vertices == scene.vertices);
    CHECK(loaded.faces == scene.faces);
    CHECK(loaded.edges == scene.edges);
    CHECK(loaded.pinned == scene.pinned);
    CHECK(loaded.stiffness == scene.stiffness);
    CHECK(loaded.mass == scene.mass);
    CHECK(loaded.colliders.size() == scene.colliders.size());
  }
  // Every file written (the JSON, its OBJ, a mesh collider's OBJ) is committed as written.
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    const std::string file = entry.path().filename().string();
    expected_files.insert(file);
    CAPTURE(file);
    CHECK(massspring::test::read_bytes(committed / file) ==
          massspring::test::read_bytes(entry.path()));
  }
  std::set<std::string> present;
  for (const auto& entry : std::filesystem::directory_iterator(committed))
    present.insert(entry.path().filename().string());
  CHECK(present == expected_files);
}

TEST_CASE("generators: origin puts point 0 there, center the middle of the bounding box") {
  using V = massspring::Vector3<double>;
  const V at(0.25, 1.5, -0.75);
  auto middle = [](const SceneDescription<double>& s) {
    return V(((s.vertices.colwise().minCoeff() + s.vertices.colwise().maxCoeff()) / 2).transpose());
  };
  massspring::ClothOptions cloth;
  cloth.columns = 5;
  cloth.rows = 4;
  cloth.plane = massspring::ClothPlane::Horizontal;
  const SceneDescription<double> plain = massspring::make_cloth(cloth);
  cloth.center = at;
  const SceneDescription<double> centred = massspring::make_cloth(cloth);
  // a rigid translation: the same shape, its middle at `at` (0.6 m and 0.5 m from its corner)
  CHECK((centred.vertices.rowwise() - centred.vertices.row(0))
            .isApprox(plain.vertices.rowwise() - plain.vertices.row(0), 1e-15));
  CHECK((middle(centred) - at).norm() < 1e-15);
  CHECK((centred.vertices.row(0).transpose() - V(at.x() - 0.6, at.y(), at.z() - 0.5)).norm() <
        1e-15);
  cloth.center.reset();
  cloth.origin = at;
  CHECK(massspring::make_cloth(cloth).vertices.row(0).transpose() == at);

  massspring::ChainOptions chain;
  chain.direction = V(0, 0, -1);
  chain.length = 2;
  chain.center = at;
  const SceneDescription<double> c = massspring::make_chain(chain);
  CHECK((middle(c) - at).norm() < 1e-15);
  CHECK((c.vertices.row(0).transpose() - V(at.x(), at.y(), at.z() + 1)).norm() < 1e-15);
  chain.center.reset();
  chain.origin = at;
  CHECK(massspring::make_chain(chain).vertices.row(0).transpose() == at);

  massspring::NetOptions net;
  net.center = at;
  CHECK((middle(massspring::make_net(net)) - at).norm() < 1e-15);
  net.center.reset();
  net.origin = at;
  CHECK(massspring::make_net(net).vertices.row(0).transpose() == at);

  // refused: both, or a non-finite point
  net.center = at;
  CHECK_THROWS_WITH_AS(massspring::make_net(net),
                       "make_net: give origin (where point 0 goes) or center (where the middle "
                       "goes), not both",
                       Error);
  cloth.origin.reset();
  cloth.center = V(0, kNaN, 0);
  CHECK_THROWS_WITH_AS(massspring::make_cloth(cloth),
                       "make_cloth: center must be finite, got (0, nan, 0)", Error);
}
