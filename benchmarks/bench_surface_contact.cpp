// What surface contact costs (contact/response/surface_contact.hpp).
//
// - LargeDrape/contact:{0,1,2,3}/from:{1,5}: a FastMassSpring step (10 iterations from the
//   inertial prediction, drape_solver()'s setting, dt = 1/30) of the 81 x 81 cloth of
//   scene/contact_recipes.hpp's large_drape_scene (2 m, 1.9 kg, k = 1000 N/m), the mean over 30
//   steps in a row from the cloth after `from` seconds of falling with self-collision on (1: over
//   the ball, its edges reaching for the floor; 5: draped, still sliding slowly), then that state
//   again (restored untimed). Steps in a row, not one step repeated: the obstacles' broad phase
//   keeps its pairs from step to step while the cloth stays in its boxes, so a repeated step
//   would time only that. contact 0: no collider and no surface (the springs and gravity only); 1:
//   the floor and the sphere (the colliders' point response and the contact term); 2: those and the
//   surface with self-collision (thickness 4 mm, friction 0.2); 3: those and the surface without
//   self-collision (its end-of-step pass against the obstacles' thin parts: the sphere's centre).
// - BoxHash/grid:N: the broad phase alone on an N x N cloth with one diagonal per cell, each
//   point moved by a random step of up to half the spacing: building the hash of the triangles'
//   swept boxes and querying every point's. Time per point should stay about flat as N grows.
//   (The hash serves the obstacles' pairs; self-collision walks the tree below.)
// - ConeTree/grid:N/motion:{0,1}: the self-collision broad phase alone (see the function).
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <massspring/contact/broad_phase/box_hash.hpp>
#include <massspring/contact/broad_phase/normal_cone_tree.hpp>
#include <massspring/contact/self_collision.hpp>
#include <massspring/forces/gravity.hpp>
#include <massspring/integrators/fast_mass_spring.hpp>
#include <massspring/scene/cloth.hpp>
#include <massspring/scene/contact_recipes.hpp>
#include <massspring/scene/make_system.hpp>
#include <random>
#include <utility>
#include <vector>

namespace {

using System = massspring::MassSpringSystem<double, massspring::Sparse>;
using FastMassSpring = massspring::FastMassSpring<System>;

System large_drape(int contact) {
  massspring::SceneDescription<double> scene = massspring::large_drape_scene();
  if (contact == 0) {
    scene.colliders.clear();
  }
  System s = massspring::make_system<System>(scene);
  s.add_force(massspring::Gravity<double>({0, -9.81, 0}));
  if (contact < 2)
    s.set_surface(massspring::Triangles(0, 3));
  else if (contact == 2)
    s.set_self_collision(massspring::contact::SelfCollision<double>{});
  return s;
}

// The drape's solver: 10 iterations from the inertial prediction with Anderson acceleration,
// contact inside the iteration with weight 1 (docs/contact.md's setting at dt = 1/30 s),
// dt = 1/30.
void drape_solver(FastMassSpring& fms, const System& s) {
  fms.options.iterations = 10;
  fms.options.initial_guess = massspring::InitialGuess::Inertial;
  fms.options.acceleration = massspring::Acceleration::Anderson;
  fms.options.contact_weight = 1;
  fms.precompute(s, 1.0 / 30);
}

// The state after `seconds` (1 or 5) of the full model.
const std::pair<massspring::Points<double>, massspring::Points<double>>& drape_state(int seconds) {
  static const auto state = [](int steps) {
    System s = large_drape(2);
    FastMassSpring fms;
    drape_solver(fms, s);
    for (int k = 0; k < steps; ++k) fms.step(s);
    return std::make_pair(s.positions(), s.velocities());
  };
  static const auto one = state(30), five = state(150);
  return seconds == 1 ? one : five;
}

void LargeDrape(benchmark::State& state) {
  System s = large_drape(int(state.range(0)));
  FastMassSpring fms;
  drape_solver(fms, s);
  const auto& start = drape_state(int(state.range(1)));
  long impulses = 0, zone_points = 0;
  int in_row = 0;
  for (auto _ : state) {
    if (in_row++ % 30 == 0) {
      state.PauseTiming();
      s.positions() = start.first;  // same sizes: copies, no allocation
      s.velocities() = start.second;
      state.ResumeTiming();
    }
    const massspring::StepReport r = fms.step(s);
    impulses += r.contact_impulses;
    zone_points += r.contact_zone_points;
  }
  state.counters["impulses"] =
      benchmark::Counter(double(impulses), benchmark::Counter::kAvgIterations);
  state.counters["zone_points"] =
      benchmark::Counter(double(zone_points), benchmark::Counter::kAvgIterations);
}
BENCHMARK(LargeDrape)
    ->ArgNames({"contact", "from"})
    ->Args({0, 1})
    ->Args({1, 1})
    ->Args({2, 1})
    ->Args({3, 1})
    ->Args({0, 5})
    ->Args({2, 5})
    ->Args({3, 5})
    ->Iterations(60)
    ->Unit(benchmark::kMillisecond);

// An n x n cloth of 1 m by 1 m, one diagonal per cell (two triangles), in the x-y plane.
massspring::SceneDescription<double> unit_cloth(int n) {
  massspring::ClothOptions o;
  o.columns = o.rows = n;
  o.width = o.height = 1.0;
  o.shear = massspring::ClothShear::One;
  return massspring::make_cloth(o);
}

// Moves every coordinate of x by its own uniform random step in [-spacing / 2, spacing / 2]
// (seed 1: the same steps at every call).
void jitter(massspring::Points<double>& x, double spacing) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> step(-spacing / 2, spacing / 2);
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    for (int c = 0; c < 3; ++c) x(i, c) += step(rng);
}

void BoxHash(benchmark::State& state) {
  const int n = int(state.range(0));
  const massspring::SceneDescription<double> cloth = unit_cloth(n);
  const double spacing = 1.0 / (n - 1);
  massspring::Points<double> x0 = cloth.vertices, x1 = cloth.vertices;
  jitter(x1, spacing);
  using Box = massspring::contact::AlignedBox3<double>;
  const auto swept = [&](std::initializer_list<int> points) {
    Box b{x0.row(*points.begin()).transpose(), x0.row(*points.begin()).transpose()};
    for (int p : points) {
      b.lo = b.lo.cwiseMin(x0.row(p).transpose()).cwiseMin(x1.row(p).transpose());
      b.hi = b.hi.cwiseMax(x0.row(p).transpose()).cwiseMax(x1.row(p).transpose());
    }
    return b;
  };
  std::vector<Box> triangles, points;
  for (const auto& f : cloth.faces) triangles.push_back(swept({f[0], f[1], f[2]}));
  for (Eigen::Index i = 0; i < x0.rows(); ++i) points.push_back(swept({int(i)}));
  massspring::contact::BoxHash<double> hash;
  long pairs = 0;
  for (auto _ : state) {
    hash.build(triangles, 1.5 * spacing);
    for (const Box& b : points) hash.query(b, [&](int) { ++pairs; });
  }
  state.counters["points"] = double(x0.rows());
  state.counters["pairs"] = benchmark::Counter(double(pairs), benchmark::Counter::kAvgIterations);
  state.counters["per_point"] =
      benchmark::Counter(double(x0.rows()), benchmark::Counter::kIsIterationInvariantRate |
                                                benchmark::Counter::kInvert);
}
BENCHMARK(BoxHash)->ArgName("grid")->RangeMultiplier(2)->Range(32, 256)->Unit(
    benchmark::kMicrosecond);

// The self-collision broad phase on an n x n cloth of 1 m: refit() and self_pairs() of
// contact/broad_phase/normal_cone_tree.hpp (built once, outside the timing), the boxes grown by
// a twelfth of the spacing (the drape's 2 mm on its 2.5 cm). motion 0: every point jumps by up to
// half a spacing (crumpled, few patches skipped); motion 1: the cloth, rolled into three quarters
// of a cylinder (its normals turn by 270 degrees), rolls 2% tighter and falls half a spacing (a
// few large patches skipped, pairs along their borders). Counters: triangle pairs listed and
// the time per triangle.
void ConeTree(benchmark::State& state) {
  const int n = int(state.range(0));
  const massspring::SceneDescription<double> cloth = unit_cloth(n);
  const double spacing = 1.0 / (n - 1);
  massspring::Points<double> x0 = cloth.vertices, x1 = cloth.vertices;
  const auto roll = [&](massspring::Points<double>& x, double radius, double fall) {
    for (Eigen::Index i = 0; i < x.rows(); ++i) {
      const double along = cloth.vertices(i, 0), angle = along / radius;
      x.row(i) << radius * std::sin(angle), cloth.vertices(i, 1) - fall,
          radius * (1 - std::cos(angle));
    }
  };
  if (state.range(1) == 0) {
    jitter(x1, spacing);
  } else {
    roll(x0, 1 / (1.5 * M_PI), 0);
    roll(x1, 0.98 / (1.5 * M_PI), spacing / 2);
  }
  std::vector<std::array<int, 3>> triangles;
  for (const auto& f : cloth.faces) triangles.push_back({f[0], f[1], f[2]});
  massspring::contact::NormalConeTree<double> tree;
  tree.build(x0, triangles);
  long pairs = 0;
  for (auto _ : state) {
    tree.refit(x0, x1, spacing / 12);
    tree.self_pairs(x0, x1, [&](int, int) { ++pairs; });
  }
  state.counters["pairs"] = benchmark::Counter(double(pairs), benchmark::Counter::kAvgIterations);
  state.counters["per_triangle"] =
      benchmark::Counter(double(triangles.size()), benchmark::Counter::kIsIterationInvariantRate |
                                                       benchmark::Counter::kInvert);
}
BENCHMARK(ConeTree)
    ->ArgNames({"grid", "motion"})
    ->ArgsProduct({{32, 64, 128, 256}, {0, 1}})
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
