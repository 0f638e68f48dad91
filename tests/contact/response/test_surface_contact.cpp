// contact/response/surface_contact.hpp through the integrators' steps: no edge of the cloth
// crosses one of its triangles, and no obstacle's edge crosses the cloth, at any step end. The
// oracle is tests/support/intersections.hpp (exact predicates, written apart from the library's
// detection). Each scene is also run without the surface contact it tests, to show that it
// crosses there: a scene that never crosses would test nothing.
#include <doctest/doctest.h>

#include <Eigen/Core>
#include <cmath>
#include <massspring/contact/response/surface_contact.hpp>
#include <massspring/forces/gravity.hpp>
#include <massspring/integrators/backward_euler.hpp>
#include <massspring/integrators/fast_mass_spring.hpp>
#include <massspring/integrators/forward_euler.hpp>
#include <massspring/integrators/rk4.hpp>
#include <massspring/integrators/symplectic_euler.hpp>
#include <massspring/io/load_scene.hpp>
#include <massspring/scene/cloth.hpp>
#include <massspring/scene/contact_recipes.hpp>
#include <massspring/scene/make_system.hpp>
#include <massspring/system/mass_spring_system.hpp>
#include <optional>
#include <vector>

#include "support/alloc_counter.hpp"
#include "support/intersections.hpp"
#include "support/paths.hpp"

namespace {

using System = massspring::MassSpringSystem<double>;
using massspring::Points;
using massspring::StepReport;
using massspring::Triangles;
using massspring::contact::SelfCollision;

System surface_system(const massspring::SceneDescription<double>& scene) {
  System s = massspring::make_system<System>(scene);
  s.add_force(massspring::Gravity<double>({0, -9.81, 0}));
  REQUIRE(s.surface().rows() > 0);
  return s;
}

// Steps `steps` times; the largest count of edge-triangle crossings seen at a step end (and
// the step reports all ok).
struct Run {
  int max_crossings = 0;
  long impulses = 0;
  long zone_points = 0;
  long projected_points = 0;
  bool all_ok = true;
  double min_height = 0;  // the lowest y at the end [m]
};
template <class Stepper>
Run run(System& s, Stepper& stepper, int steps, const Eigen::Vector3d* rod = nullptr) {
  Run r;
  const massspring::Edges edges = massspring::test::triangle_edges(s.surface());
  for (int k = 0; k < steps; ++k) {
    const StepReport report = stepper.step(s);
    r.all_ok = r.all_ok && report.ok();
    r.impulses += report.contact_impulses;
    r.zone_points += report.contact_zone_points;
    r.projected_points += s.surface_contact().last_report().projected_points;
    int c = massspring::test::count_crossings(s.positions(), s.surface(), edges);
    if (rod)
      c += massspring::test::count_segment_crossings(s.positions(), s.surface(), rod[0], rod[1]);
    r.max_crossings = std::max(r.max_crossings, c);
  }
  return r;
}

double total_energy_free(const System& s) {
  double e = 0;
  for (Eigen::Index i = 0; i < s.velocities().rows(); ++i)
    e += 0.5 * s.masses()(i) * s.velocities().row(i).squaredNorm();
  return e;
}

}  // namespace

namespace {

// The ribbon of 9 x 61 points over 0.24 m x 1.8 m (3 cm spacing), held upright with a wave of
// 2 cm across its plane, its lower end 5 cm above the floor: it falls end-first and piles up.
// No bending springs, so it folds sharply; without self-collision it passes through itself.
massspring::SceneDescription<double> wavy_ribbon() {
  massspring::ClothOptions o;
  o.columns = 9;
  o.rows = 61;
  o.width = 0.24;
  o.height = 1.8;
  o.shear = massspring::ClothShear::One;
  o.pins = massspring::ClothPins::None;
  o.plane = massspring::ClothPlane::Vertical;
  massspring::SceneDescription<double> d = massspring::make_cloth(o);
  for (Eigen::Index i = 0; i < d.vertices.rows(); ++i) {
    d.vertices(i, 1) += 1.85;
    d.vertices(i, 2) += 0.02 * std::sin(7.0 * d.vertices(i, 1));
  }
  d.colliders = {massspring::detail::contact_floor()};
  return d;
}

// setup(stepper) sets the stepper's options before its precompute.
template <class Stepper, class Setup>
Run ribbon_run(bool self, int steps, double dt, int impulse_rounds, Setup setup,
               int projection_rounds = -1) {
  System s = surface_system(wavy_ribbon());
  if (self) s.set_self_collision(SelfCollision<double>{});
  if (impulse_rounds >= 0) s.surface_contact().set_impulse_rounds(impulse_rounds);
  if (projection_rounds >= 0) s.surface_contact().set_projection_rounds(projection_rounds);
  Stepper stepper;
  setup(stepper);
  stepper.precompute(s, dt);
  Run r = run(s, stepper, steps);
  r.min_height = s.positions().col(1).minCoeff();
  return r;
}

}  // namespace

// The ribbon at dt = 1/30, one test case per integrator so that ctest runs them side by side.
namespace {
void ribbon_ten_iterations(massspring::FastMassSpring<System>& fms) { fms.options.iterations = 10; }
constexpr double kRibbonDt = 1.0 / 30;
}  // namespace

TEST_CASE(
    "surface contact: a ribbon piles onto the floor, crossing itself without self-collision "
    "(the scene tests something)") {
  using FMS = massspring::FastMassSpring<System>;
  CHECK(ribbon_run<FMS>(false, 60, kRibbonDt, -1, ribbon_ten_iterations).max_crossings > 0);
}

TEST_CASE(
    "surface contact: a ribbon piles onto the floor without crossing itself, at dt = 1/30 "
    "(FastMassSpring)") {
  using FMS = massspring::FastMassSpring<System>;
  SUBCASE("no crossing at any step end, and contact did work") {
    const Run r = ribbon_run<FMS>(true, 60, kRibbonDt, -1, ribbon_ten_iterations);
    CHECK(r.all_ok);
    CHECK(r.max_crossings == 0);
    CHECK(r.impulses > 0);
    CHECK(r.min_height >= 0);  // and no point under the floor
  }
  SUBCASE("the projection alone (no impulse rounds) keeps it free of crossings too") {
    const Run r = ribbon_run<FMS>(true, 60, kRibbonDt, 0, ribbon_ten_iterations);
    CHECK(r.all_ok);
    CHECK(r.max_crossings == 0);
    CHECK(r.projected_points > 0);
  }
  SUBCASE("rigid impact zones alone (no impulse or projection rounds) keep it free too") {
    const Run r = ribbon_run<FMS>(true, 60, kRibbonDt, 0, ribbon_ten_iterations, 0);
    CHECK(r.all_ok);
    CHECK(r.max_crossings == 0);
    CHECK(r.zone_points > 0);
  }
}

namespace {
void check_ribbon_backward_euler(massspring::BackwardEulerMode mode) {
  using BE = massspring::BackwardEuler<System>;
  const Run r = ribbon_run<BE>(true, 20, kRibbonDt, -1, [&](BE& be) { be.options.mode = mode; });
  CHECK(r.all_ok);
  CHECK(r.max_crossings == 0);
  CHECK(r.impulses + r.zone_points > 0);
}
}  // namespace

TEST_CASE(
    "surface contact: a ribbon piles onto the floor without crossing itself, at dt = 1/30 "
    "(BackwardEuler, Newton)") {
  check_ribbon_backward_euler(massspring::BackwardEulerMode::Newton);
}

// The linearised step cannot hold this ribbon at dt = 1/30: its one linear solve a step flings
// points at step 3 (3,584% strain, with no contact yet), and from step 4 the contact response
// pumps energy into the springs (10.5 kJ in one step, 11.5 times the scene's energy scale S).
// What is checked is that this is reported (the response's limit S / 2 + S_c refuses the step, the
// state kept) and that no step end has a crossing.
TEST_CASE(
    "surface contact: a ribbon at dt = 1/30 under linearised BackwardEuler never crosses itself, "
    "and its blow-up is reported") {
  using BE = massspring::BackwardEuler<System>;
  const Run r = ribbon_run<BE>(true, 20, kRibbonDt, -1, [&](BE& be) {
    be.options.mode = massspring::BackwardEulerMode::Linearized;
  });
  CHECK_FALSE(r.all_ok);
  CHECK(r.max_crossings == 0);
}

namespace {
// Two 9 x 9 cloths of 0.4 m (5 cm spacing) over the floor: one 2 cm above it, one 4 cm above
// that, shifted by half a cell. Stable step of the 1000 N/m springs on 2 g points: about 1.4 ms.
massspring::SceneDescription<double> stacked_cloths() {
  massspring::SceneDescription<double> upper =
      massspring::detail::contact_cloth(9, 9, 0.4, 0.4, 0.06);
  for (Eigen::Index i = 0; i < upper.vertices.rows(); ++i) upper.vertices(i, 0) += 0.025;
  massspring::SceneDescription<double> both = massspring::detail::disjoint_union(
      massspring::detail::contact_cloth(9, 9, 0.4, 0.4, 0.02), upper);
  both.colliders = {massspring::detail::contact_floor()};
  return both;
}
}  // namespace

TEST_CASE_TEMPLATE(
    "surface contact: explicit integrators at their stable step, a cloth dropped onto another",
    Stepper, massspring::SymplecticEuler<System>, massspring::RK4<System>) {
  const massspring::SceneDescription<double> both = stacked_cloths();
  for (const bool self : {false, true}) {
    CAPTURE(self);
    System s = surface_system(both);
    if (self) s.set_self_collision(SelfCollision<double>{});
    Stepper stepper;
    stepper.precompute(s, 1.0 / 2000);
    const Run r = run(s, stepper, 300);
    if (self) {
      CHECK(r.all_ok);
      CHECK(r.max_crossings == 0);
      CHECK(r.impulses > 0);
    } else {
      CHECK(r.max_crossings > 0);
    }
  }
}

TEST_CASE("surface contact: a cloth dropped on a 1 cm rod hangs on it at dt = 1/30") {
  const double dt = 1.0 / 30;
  const massspring::SceneDescription<double> scene = massspring::clothesline_scene();
  const Eigen::Vector3d rod[2] = {scene.colliders[1].a, scene.colliders[1].b};
  // Hanging: some of the cloth above the rod's top (y = 1.01), all of it above y = 0.3.
  const auto hanging = [](const System& s) {
    return s.positions().col(1).maxCoeff() > 1.01 && s.positions().col(1).minCoeff() > 0.3;
  };
  SUBCASE("without a surface, the rod passes between the points (the points on it stay)") {
    System s = surface_system(scene);
    const Triangles faces = s.surface();
    s.set_surface(Triangles(0, 3));
    massspring::FastMassSpring<System> fms;
    fms.options.iterations = 10;
    fms.precompute(s, dt);
    int crossings = 0;
    for (int k = 0; k < 30; ++k) {
      fms.step(s);
      crossings = std::max(crossings, massspring::test::count_segment_crossings(
                                          s.positions(), faces, rod[0], rod[1]));
    }
    CHECK(crossings > 0);
  }
  SUBCASE("with it (and self-collision), nothing crosses and the cloth hangs on the rod") {
    System s = surface_system(scene);
    s.set_self_collision(SelfCollision<double>{});
    massspring::FastMassSpring<System> fms;
    fms.options.iterations = 10;
    fms.precompute(s, dt);
    const Run r = run(s, fms, 30, rod);
    CHECK(r.all_ok);
    CHECK(r.max_crossings == 0);
    CHECK(hanging(s));
  }
}

TEST_CASE(
    "surface contact: the drape scene stays on its ball at dt = 1/30 (no face cuts its core)") {
  // examples/scenes/drape.json: a 1.2 m cloth dropped on a sphere (centre (0, 0.4, 0), r = 0.3)
  // over a floor. Its centre point lands on the top at step 7; before the sphere's centre met
  // the cloth's triangles, the cloth cut through the ball within a dozen steps and lay flat on
  // the floor under it.
  System s = massspring::io::load_scene<System>(massspring::test::source_dir() / "examples" /
                                                "scenes" / "drape.json");  // with its gravity
  REQUIRE(s.forces().size() == 1);
  massspring::FastMassSpring<System> fms;
  fms.options.iterations = 50;
  fms.precompute(s, 1.0 / 30);
  const Eigen::Vector3d centre(0, 0.4, 0);
  const double keep = 0.3 / 2;  // (radius + thickness) / 2, thickness 0
  double nearest = 1e9;         // of any triangle to the centre, over the step ends [m]
  for (int k = 0; k < 45; ++k) {
    CHECK(fms.step(s).ok());
    for (Eigen::Index t = 0; t < s.surface().rows(); ++t) {
      const auto corner = [&](int c) -> Eigen::Vector3d {
        return s.positions().row(s.surface()(t, c)).transpose();
      };
      nearest = std::min(nearest, massspring::test::intersections_detail::point_triangle_distance(
                                      centre, corner(0), corner(1), corner(2)));
    }
  }
  CHECK(nearest >= keep);
  CHECK(s.positions().col(1).maxCoeff() > 0.69);  // still on the ball's top (y = 0.7)
}

TEST_CASE_TEMPLATE("surface contact: impulses between cloth parts keep momentum and add no energy",
                   Stepper, massspring::ForwardEuler<System>, massspring::SymplecticEuler<System>,
                   massspring::RK4<System>) {
  // Two free triangles, 1 cm apart, that close at 1 m/s each (2 cm per step of 1/50 s): no
  // gravity, no collider, no spring, so only the surface contact acts on the step.
  massspring::SceneDescription<double> d;
  d.vertices.resize(6, 3);
  d.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0,  //
      0.2, 0.2, 0.01, 1.2, 0.3, 0.01, 0.1, 1.1, 0.01;
  d.faces = {{0, 1, 2}, {3, 4, 5}};
  d.mass = 1.0;
  System s = massspring::make_system<System>(d);
  Eigen::VectorXd masses(6);
  masses << 1, 2, 3, 1.5, 0.5, 2.5;
  s.set_masses(masses);
  REQUIRE(s.surface().rows() == 2);
  for (int i = 0; i < 3; ++i) s.velocities().row(i) << 0.1, 0, 1;
  for (int i = 3; i < 6; ++i) s.velocities().row(i) << -0.2, 0.3, -1;
  s.set_self_collision(SelfCollision<double>{0.004, 0.3});
  Stepper stepper;
  stepper.precompute(s, 1.0 / 50);
  const auto momentum = [](const System& sys) {
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (Eigen::Index i = 0; i < sys.masses().size(); ++i)
      p += sys.masses()(i) * sys.velocities().row(i).transpose();
    return p;
  };
  const Eigen::Vector3d p0 = momentum(s);
  const double e0 = total_energy_free(s);
  const StepReport r = stepper.step(s);
  CHECK(r.ok());
  CHECK(r.contact_impulses > 0);
  CHECK((momentum(s) - p0).norm() <= 1e-12 * p0.norm());
  CHECK(total_energy_free(s) <= e0 * (1 + 1e-12));
  CHECK(massspring::test::count_crossings(s.positions(), s.surface()) == 0);
  CHECK(massspring::test::min_separation(s.positions(), s.surface(),
                                         massspring::test::triangle_edges(s.surface())) > 0);
}

TEST_CASE("surface contact: a step it cannot resolve is reported and leaves the last good state") {
  System s = surface_system(stacked_cloths());  // the upper cloth lands on the lower one
  s.set_self_collision(SelfCollision<double>{});
  s.surface_contact().set_impulse_rounds(0).set_max_rounds(
      1);  // detection once, no room to respond
  massspring::FastMassSpring<System> fms;
  fms.options.iterations = 10;
  fms.precompute(s, 1.0 / 30);
  bool refused = false;
  for (int k = 0; k < 45 && !refused; ++k) {
    const Points<double> x = s.positions(), v = s.velocities();
    const StepReport r = fms.step(s);
    if (!r.contact_resolved) {
      refused = true;
      CHECK_FALSE(r.ok());
      CHECK(s.positions() == x);
      CHECK(s.velocities() == v);
    }
  }
  CHECK(refused);
}

TEST_CASE("surface contact: a copy of a system has its own pass and steps as the original does") {
  const massspring::SceneDescription<double> both = stacked_cloths();  // self-collision on below
  System s = surface_system(both);
  s.set_self_collision(SelfCollision<double>{});
  massspring::SymplecticEuler<System> stepper;
  stepper.precompute(s, 1.0 / 2000);
  for (int k = 0; k < 100; ++k) stepper.step(s);
  System copy = s;  // copy construction
  System assigned = surface_system(wavy_ribbon());
  assigned = s;  // copy assignment
  CHECK(&copy.surface_contact() != &s.surface_contact());
  CHECK(&assigned.surface_contact() != &s.surface_contact());
  copy.surface_contact().set_max_rounds(1);  // the original's pass keeps its own
  CHECK(s.surface_contact().max_rounds() == 64);
  copy.surface_contact().set_max_rounds(64);
  int impulses = 0;
  for (int k = 0; k < 200; ++k) {
    const StepReport r = stepper.step(s);
    impulses += r.contact_impulses;
    CHECK(stepper.step(copy).contact_impulses == r.contact_impulses);
    CHECK(stepper.step(assigned).contact_impulses == r.contact_impulses);
  }
  CHECK(impulses > 0);
  CHECK(copy.positions() == s.positions());
  CHECK(copy.velocities() == s.velocities());
  CHECK(assigned.positions() == s.positions());
  System moved = std::move(copy);
  stepper.step(moved);
  stepper.step(s);
  CHECK(moved.positions() == s.positions());
}

// The pass keeps its work arrays (the broad phase's boxes, hashes and pairs, kept from step to
// step): once the two cloths lie on the floor and on each other, a step allocates nothing.
TEST_CASE("surface contact: once the work arrays have grown, a step allocates nothing") {
  System s = surface_system(stacked_cloths());
  s.set_self_collision(SelfCollision<double>{});
  massspring::FastMassSpring<System> solver;
  solver.options.iterations = 10;
  solver.options.initial_guess = massspring::InitialGuess::Inertial;
  solver.options.contact_weight = 1;
  solver.options.acceleration = massspring::Acceleration::Anderson;
  solver.precompute(s, 1.0 / 30);
  for (int k = 0; k < 60; ++k) REQUIRE(solver.step(s).ok());  // 2 s: both cloths down
  long impulses = 0;
  std::size_t allocations = 0;
  {
    massspring::test::CountAllocations count;
    for (int k = 0; k < 30; ++k) {
      const StepReport r = solver.step(s);
      impulses += r.contact_impulses;
      if (!r.ok()) break;
    }
    allocations = count.count();
  }
  CHECK(allocations == 0);
  CHECK(impulses > 0);  // the pass worked in the counted steps
  CHECK(massspring::test::count_crossings(s.positions(), s.surface()) == 0);
}

TEST_CASE("surface contact: a mesh's vertices outside its triangles are not part of its surface") {
  // A square of two triangles moving down at 1 m/s, no force, through y = 0.5 in one step of
  // 0.05 s (0.52 -> 0.47 m), over a mesh whose one triangle is 5 m below and whose fourth vertex,
  // in no triangle (as a state scene's two corners that keep the mesh's frame), lies at
  // (0.05, 0.5, 0.05), inside the square. Symplectic Euler without force moves every point by
  // h v: the pass must leave that motion as it is (no impulse).
  Points<double> x(4, 3);
  x << 0, 0.52, 0, 0.1, 0.52, 0, 0.1, 0.52, 0.1, 0, 0.52, 0.1;
  massspring::Edges springs(5, 2);
  springs << 0, 1, 1, 2, 2, 3, 3, 0, 0, 2;
  System s(x, springs, 0.01, 10.0);
  Triangles square(2, 3);
  square << 0, 1, 2, 0, 2, 3;
  s.set_surface(square);
  s.velocities().col(1).setConstant(-1);
  Points<double> mesh(4, 3);
  mesh << -1, -4.5, -1, 1, -4.5, -1, 0, -4.5, 1, 0.05, 0.5, 0.05;
  Triangles one(1, 3);
  one << 0, 1, 2;
  s.add_collider(massspring::contact::Collider<double>::mesh(mesh, one));
  massspring::SymplecticEuler<System> solver;
  solver.precompute(s, 0.05);
  const StepReport r = solver.step(s);
  REQUIRE(r.ok());
  CHECK(r.contact_impulses == 0);
  CHECK(r.contact_zone_points == 0);
  for (int i = 0; i < 4; ++i) CHECK(s.positions()(i, 1) == doctest::Approx(0.47).epsilon(1e-12));
}
