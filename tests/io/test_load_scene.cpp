// io/load_scene.hpp: every JSON+OBJ scene loads with the counts SOURCE.md lists; the errors name
// the scene file; .xml goes to the FOSSSim reader (tested in test_fosssim_scene.cpp).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <massspring/integrators/fast_mass_spring.hpp>
#include <massspring/io/load_scene.hpp>
#include <string>
#include <vector>

#include "io/test_files.hpp"
#include "massspring/system/mass_spring_system.hpp"
#include "support/paths.hpp"
#include "support/uniform_forces.hpp"

namespace {

using massspring::test::add_gravity;
using massspring::test::add_uniform_force;

using massspring::Dense;
using massspring::Error;
using massspring::MassSpringSystem;
using massspring::Sparse;
using massspring::io::load_scene;
using massspring::test::TempDir;
using DenseSystem = MassSpringSystem<double, Dense>;
using SparseSystem = MassSpringSystem<double, Sparse>;

struct Expected {
  const char* file;
  int points;
  int springs;
  int pinned;
  double stiffness;
  double mass;  // 0: Voronoi
  bool small;   // cheap enough for Dense
};

// SOURCE.md's table.
const Expected kScenes[] = {
    {"flag.json", 3200, 12442, 40, 100000, 0, false},
    {"horizontal-chain.json", 10, 9, 2, 500, 1, true},
    {"net.json", 61, 156, 6, 300, 1, true},
    {"single-spring-horizontal.json", 2, 1, 1, 500, 1, true},
    {"skirt.json", 9840, 38640, 240, 100000, 0, false},
};

template <class System>
void check_scene(const Expected& e) {
  CAPTURE(e.file);
  const auto system = load_scene<System>(massspring::test::jacobson_dir() / e.file);
  using Scalar = typename System::Scalar;
  CHECK(system.num_points() == e.points);
  CHECK(system.num_springs() == e.springs);
  CHECK(system.num_pinned() == e.pinned);
  CHECK((system.stiffness().array() == Scalar(e.stiffness)).all());
  if (e.mass > 0) CHECK((system.masses().array() == Scalar(e.mass)).all());
  CHECK((system.masses().array() > 0).all());
  // pins hold their rest positions
  for (int r = 0; r < system.num_pinned(); ++r)
    CHECK(system.pin_targets().row(r) == system.rest_positions().row(system.pinned()[r]));
  // rest lengths are the rest distances
  Scalar worst = 0;
  for (int s = 0; s < system.num_springs(); ++s) {
    const Scalar d = (system.rest_positions().row(system.springs()(s, 0)) -
                      system.rest_positions().row(system.springs()(s, 1)))
                         .norm();
    worst = std::max(worst, std::abs(system.rest_lengths()(s) - d));
  }
  CHECK(worst == Scalar(0));
}

}  // namespace

TEST_CASE("load_scene loads every JSON+OBJ scene with SOURCE.md's n, springs and pins (Sparse)" *
          doctest::skip(!massspring::test::have_jacobson())) {
  for (const Expected& e : kScenes) check_scene<MassSpringSystem<double, Sparse>>(e);
}

TEST_CASE("load_scene loads the small JSON+OBJ scenes into Dense and float systems" *
          doctest::skip(!massspring::test::have_jacobson())) {
  for (const Expected& e : kScenes)
    if (e.small) {
      check_scene<MassSpringSystem<double, Dense>>(e);
      check_scene<MassSpringSystem<float, Dense>>(e);
      check_scene<MassSpringSystem<float, Sparse>>(e);
    }
}

TEST_CASE("load_scene: \"b\": [1] pins vertex 0 of the single spring, at its rest position" *
          doctest::skip(!massspring::test::have_jacobson())) {
  const auto s =
      load_scene<DenseSystem>(massspring::test::jacobson_dir() / "single-spring-horizontal.json");
  REQUIRE(s.num_pinned() == 1);
  CHECK(s.pinned()[0] == 0);
  CHECK(s.is_pinned(0));
  CHECK_FALSE(s.is_pinned(1));
  // the file: "v 0 0 0", "v 1 0 0", "f 1 2"
  CHECK(s.pin_targets().row(0) == Eigen::RowVector3d(0, 0, 0));
  CHECK(s.rest_positions().row(1) == Eigen::RowVector3d(1, 0, 0));
  CHECK(s.rest_lengths()(0) == 1.0);
}

TEST_CASE("load_scene: the cloth scenes' masses are their surface areas (density 1)" *
          doctest::skip(!massspring::test::have_jacobson())) {
  // SOURCE.md: the totals of libigl's Voronoi mass matrix
  const auto flag = load_scene<SparseSystem>(massspring::test::jacobson_dir() / "flag.json");
  CHECK(flag.masses().sum() == doctest::Approx(2.0000000000000009).epsilon(1e-12));
  const auto skirt = load_scene<SparseSystem>(massspring::test::jacobson_dir() / "skirt.json");
  CHECK(skirt.masses().sum() == doctest::Approx(5.0259740751116446).epsilon(1e-12));
}

TEST_CASE("load_scene picks the format by extension, in any case") {
  TempDir dir;
  dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  dir.write("upper.JSON", R"({"obj": "tri.obj", "b": [1], "k": 10})");
  const auto s = load_scene<DenseSystem>(dir / "upper.JSON");
  CHECK(s.num_points() == 3);
  CHECK(s.num_springs() == 3);
  CHECK(s.masses().sum() == doctest::Approx(0.5));  // the triangle's area

  // .XML goes to the FOSSSim reader
  const auto xml = dir.write("scene.XML",
                             "<scene>\n<duration time=\"1\"/>\n"
                             "<integrator type=\"explicit-euler\" dt=\"0.1\"/>\n"
                             "<particle m=\"2\" px=\"1\" py=\"2\" vx=\"0\" vy=\"0\" fixed=\"0\"/>\n"
                             "</scene>\n");
  const auto x = load_scene<DenseSystem>(xml);
  CHECK(x.num_points() == 1);
  CHECK(x.masses()(0) == 2);
  const auto obj = dir.write("scene.obj", "v 0 0 0\n");
  CHECK_THROWS_WITH_AS(
      load_scene<DenseSystem>(obj),
      massspring::test::contains(obj.string() + ": unsupported scene format \".obj\": "
                                                "supported are .json (JSON+OBJ scene), .xml "
                                                "(FOSSSim XML scene)"),
      Error);
  CHECK_THROWS_WITH_AS(load_scene<DenseSystem>(dir / "noext"),
                       doctest::Contains("unsupported scene format \"\""), Error);
  const auto missing = dir / "missing.json";
  CHECK_THROWS_WITH_AS(load_scene<DenseSystem>(missing),
                       massspring::test::contains(missing.string() + ": cannot read JSON scene"),
                       Error);
}

TEST_CASE("load_scene puts the scene's path in front of make_system's errors") {
  TempDir dir;
  // springs only and no "m": no surface to take masses from
  dir.write("chain.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n");
  const auto chain = dir.write("chain.json", R"({"obj": "chain.obj", "b": [], "k": 1})");
  CHECK_THROWS_WITH_AS(
      load_scene<SparseSystem>(chain),
      massspring::test::contains(chain.string() + ": scene has no faces to take masses from"),
      Error);
  // vertex 4 (index 3, line 4) lies on no face: its Voronoi mass would be 0
  const auto loose_obj =
      dir.write("loose.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nf 1 2 3\nf 3 4\n");
  const auto loose = dir.write("loose.json", R"({"obj": "loose.obj", "b": [], "k": 1})");
  CHECK_THROWS_WITH_AS(load_scene<SparseSystem>(loose),
                       massspring::test::contains(loose.string() + ": " + loose_obj.string() +
                                                  ":4: vertex 4: lies on no face"),
                       Error);
  // with "m" both load
  dir.write("loose_m.json", R"({"obj": "loose.obj", "b": [4], "k": 1, "m": 2})");
  const auto s = load_scene<SparseSystem>(dir / "loose_m.json");
  CHECK(s.num_springs() == 4);
  CHECK(s.pinned() == std::vector<int>{3});
}

TEST_CASE("the JSON+OBJ flag and skirt run 100 frames with their settings, finite throughout" *
          doctest::skip(!massspring::test::have_jacobson())) {
  // The JSON+OBJ scenes' conventions: dt = 1/30, a force of (0, -9.8, 0) N on every point,
  // penalty pins w = 1e10 at the rest positions, 50 iterations per step from the current positions.
  for (const char* file : {"flag.json", "skirt.json"}) {
    CAPTURE(file);
    auto system = load_scene<SparseSystem>(massspring::test::jacobson_dir() / file);
    massspring::FastMassSpring<SparseSystem> solver;
    solver.options.pins = massspring::PinMode::Penalty;
    add_uniform_force(system, {0, -9.8, 0});
    solver.precompute(system, 1.0 / 30);
    const double start_y = system.positions().col(1).mean();
    int first_bad = -1;
    for (int frame = 0; frame < 100 && first_bad < 0; ++frame) {
      const auto report = solver.step(system);
      if (!report.ok() || !system.positions().allFinite() || !system.velocities().allFinite())
        first_bad = frame;
    }
    CHECK(first_bad == -1);
    // It fell, and the pins held.
    CHECK(system.positions().col(1).mean() < start_y - 0.01);
    double worst = 0;
    for (int r = 0; r < system.num_pinned(); ++r)
      worst = std::max(worst, (system.positions().row(system.pinned()[std::size_t(r)]) -
                               system.pin_targets().row(r))
                                  .norm());
    CHECK(worst < 1e-6);
  }
}
