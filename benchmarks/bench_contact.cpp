// What contact with obstacles costs (contact/colliders/colliders.hpp).
//
// - Drape/<integrator>/colliders:{0,1}: one step of the drape (scene/recipes.hpp: an 81 x 81
//   cloth over a sphere onto a floor) with and without the two colliders, from the same state: the
//   cloth after 1.2 s of falling with the colliders (resting on the sphere, its edges on the
//   floor), restored before every step. FastMassSpring with 10 plain iterations, the same with
//   the contact term inside the iteration (ContactTerm: options.contact_weight = 1), Chebyshev,
//   and symplectic Euler at its stable step, all at dt = 1/60 s; and the step users take,
//   dt = 1/30 s (LargeStep: 10 iterations from the inertial prediction with Anderson
//   acceleration, contact_weight 1, as benchmarks/massspring_drape.cpp runs it).
// - MeshQuery/<triangles>: the mesh collider's queries (the bounding-volume hierarchy, then the
//   closest point within the thickness and the segment's first crossing) for 4096 points
//   against a closed mesh (a subdivided icosahedron) of 80 .. 81920 triangles: time per point
//   grows like log(triangles) (broad phase O(n log m)), where testing all triangles would grow
//   like the triangles. MeshQuery/brute/<triangles> does that for the smaller meshes.
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <map>
#include <massspring/contact/colliders/colliders.hpp>
#include <massspring/diagnostics/stable_time_step.hpp>
#include <massspring/forces/gravity.hpp>
#include <massspring/integrators/fast_mass_spring.hpp>
#include <massspring/integrators/symplectic_euler.hpp>
#include <massspring/scene/cloth.hpp>
#include <massspring/scene/make_system.hpp>
#include <massspring/scene/recipes.hpp>
#include <random>
#include <utility>
#include <vector>

namespace {

using System = massspring::MassSpringSystem<double, massspring::Sparse>;
using V3 = massspring::Vector3<double>;
using Collider = massspring::contact::Collider<double>;

System drape_system(bool colliders) {
  System s = massspring::make_system<System>(massspring::make_cloth(massspring::drape_recipe()));
  s.add_force(massspring::Gravity<double>(V3(0, -9.81, 0)));
  if (colliders) {
    const massspring::DrapeObstacles o;
    s.add_collider(Collider::sphere(V3(o.sphere_center[0], o.sphere_center[1], o.sphere_center[2]),
                                    o.sphere_radius)
                       .set_friction(o.friction));
    s.add_collider(Collider::plane(V3(o.floor_point[0], o.floor_point[1], o.floor_point[2]),
                                   V3(o.floor_normal[0], o.floor_normal[1], o.floor_normal[2]))
                       .set_friction(o.friction));
  }
  return s;
}

// The draped state: 1.2 s of FastMassSpring (10 iterations, dt = 1/60) with the colliders.
const std::pair<massspring::Points<double>, massspring::Points<double>>& draped_state() {
  static const auto state = [] {
    System s = drape_system(true);
    massspring::FastMassSpring<System> fms;
    fms.options = massspring::FastMassSpringOptions<double>::reference();
    fms.options.iterations = 10;
    fms.precompute(s, 1.0 / 60);
    for (int k = 0; k < 72; ++k) fms.step(s);
    return std::make_pair(s.positions(), s.velocities());
  }();
  return state;
}

template <class Integrator, class Setup>
void run_drape(benchmark::State& state, Setup setup, double dt) {
  System s = drape_system(state.range(0) != 0);
  Integrator integrator;
  setup(integrator);
  integrator.precompute(s, dt);
  const auto& start = draped_state();
  for (auto _ : state) {
    s.positions() = start.first;  // same sizes: copies, no allocation
    s.velocities() = start.second;
    benchmark::DoNotOptimize(integrator.step(s));
  }
}

using FastMassSpring = massspring::FastMassSpring<System>;

void Drape_FastMassSpring(benchmark::State& state) {
  run_drape<FastMassSpring>(
      state,
      [](FastMassSpring& fms) {
        fms.options = massspring::FastMassSpringOptions<double>::reference();
        fms.options.iterations = 10;
      },
      1.0 / 60);
}
void Drape_Chebyshev(benchmark::State& state) {
  run_drape<FastMassSpring>(
      state,
      [](FastMassSpring& fms) {
        fms.options = massspring::FastMassSpringOptions<double>::reference();
        fms.options.iterations = 10;
        fms.options.acceleration = massspring::Acceleration::Chebyshev;
      },
      1.0 / 60);
}
// The opt-in contact term inside the iteration (options.contact_weight = 1,
// local_global/contact_projection.hpp): each iteration projects every point through the colliders.
void Drape_ContactTerm(benchmark::State& state) {
  run_drape<FastMassSpring>(
      state,
      [](FastMassSpring& fms) {
        fms.options = massspring::FastMassSpringOptions<double>::reference();
        fms.options.iterations = 10;
        fms.options.contact_weight = 1;
      },
      1.0 / 60);
}
void Drape_LargeStep(benchmark::State& state) {
  run_drape<FastMassSpring>(
      state,
      [](FastMassSpring& fms) {
        fms.options = massspring::FastMassSpringOptions<double>::reference();
        fms.options.iterations = 10;
        fms.options.initial_guess = massspring::InitialGuess::Inertial;
        fms.options.acceleration = massspring::Acceleration::Anderson;
        fms.options.contact_weight = 1;
      },
      1.0 / 30);
}
void Drape_SymplecticEuler(benchmark::State& state) {
  run_drape<massspring::SymplecticEuler<System>>(
      state, [](auto&) {}, massspring::stable_time_step(drape_system(false)));
}
BENCHMARK(Drape_FastMassSpring)
    ->ArgName("colliders")
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(Drape_ContactTerm)->ArgName("colliders")->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(Drape_Chebyshev)->ArgName("colliders")->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(Drape_LargeStep)->ArgName("colliders")->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(Drape_SymplecticEuler)
    ->ArgName("colliders")
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMicrosecond);

// A unit sphere as an icosahedron subdivided `levels` times: 20 * 4^levels triangles.
std::pair<massspring::Points<double>, massspring::contact::Triangles> icosphere(int levels) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::vector<V3> v = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                       {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (V3& p : v) p.normalize();
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto middle = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back((v[std::size_t(a)] + v[std::size_t(b)]).normalized());
      return mid[key] = int(v.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& tri : f) {
      const int a = middle(tri[0], tri[1]), b = middle(tri[1], tri[2]), c = middle(tri[2], tri[0]);
      next.push_back({tri[0], a, c});
      next.push_back({tri[1], b, a});
      next.push_back({tri[2], c, b});
      next.push_back({a, b, c});
    }
    f.swap(next);
  }
  massspring::Points<double> vertices(Eigen::Index(v.size()), 3);
  for (std::size_t i = 0; i < v.size(); ++i) vertices.row(Eigen::Index(i)) = v[i].transpose();
  massspring::contact::Triangles triangles(Eigen::Index(f.size()), 3);
  for (std::size_t i = 0; i < f.size(); ++i)
    triangles.row(Eigen::Index(i)) << f[i][0], f[i][1], f[i][2];
  return {vertices, triangles};
}

// 4096 points, each moving 1 cm over a step, within 5 cm of the unit sphere's surface.
struct Paths {
  std::vector<V3> start, end;
};
const Paths& query_paths() {
  static const Paths paths = [] {
    Paths p;
    std::mt19937 rng(7);
    std::normal_distribution<double> normal;
    std::uniform_real_distribution<double> radius(0.95, 1.05);
    for (int i = 0; i < 4096; ++i) {
      const V3 dir = V3(normal(rng), normal(rng), normal(rng)).normalized();
      const V3 step = V3(normal(rng), normal(rng), normal(rng)).normalized() * 0.01;
      p.start.push_back(radius(rng) * dir);
      p.end.push_back(p.start.back() + step);
    }
    return p;
  }();
  return paths;
}

// The mesh queries' counters: the triangle count and the time per queried point.
void set_query_counters(benchmark::State& state, const massspring::contact::Triangles& triangles,
                        const Paths& paths) {
  state.counters["triangles"] = double(triangles.rows());
  state.counters["time_per_point"] =
      benchmark::Counter(double(paths.start.size()), benchmark::Counter::kIsIterationInvariantRate |
                                                         benchmark::Counter::kInvert);
}

void MeshQuery(benchmark::State& state) {
  auto [vertices, triangles] = icosphere(int(state.range(0)));
  const Collider mesh = Collider::mesh(vertices, triangles).set_thickness(0.02);
  const Paths& paths = query_paths();
  massspring::contact::ColliderContact<double> c;
  for (auto _ : state) {
    int contacts = 0;
    for (std::size_t i = 0; i < paths.start.size(); ++i)
      contacts += mesh.contact(paths.start[i], paths.end[i], 0.0, c) ? 1 : 0;
    benchmark::DoNotOptimize(contacts);
  }
  set_query_counters(state, triangles, paths);
}
BENCHMARK(MeshQuery)->ArgName("levels")->DenseRange(1, 7)->Unit(benchmark::kMicrosecond);

// All triangles tested for every point: what the hierarchy saves.
void MeshQueryBrute(benchmark::State& state) {
  auto [vertices, triangles] = icosphere(int(state.range(0)));
  const massspring::contact::TriangleMesh<double> mesh(vertices, triangles);
  const Paths& paths = query_paths();
  for (auto _ : state) {
    int contacts = 0;
    for (std::size_t i = 0; i < paths.start.size(); ++i) {
      double best = 0.02 * 0.02, t = 0;
      for (int k = 0; k < mesh.num_triangles(); ++k) {
        const V3 q = massspring::contact::closest_point_on_triangle(
            paths.end[i], mesh.vertex(k, 0), mesh.vertex(k, 1), mesh.vertex(k, 2));
        best = std::min(best, (q - paths.end[i]).squaredNorm());
        contacts += massspring::contact::segment_crosses_triangle(
                        paths.start[i], paths.end[i], mesh.vertex(k, 0), mesh.vertex(k, 1),
                        mesh.vertex(k, 2), t)
                        ? 1
                        : 0;
      }
      contacts += best < 0.02 * 0.02 ? 1 : 0;
    }
    benchmark::DoNotOptimize(contacts);
  }
  set_query_counters(state, triangles, paths);
}
BENCHMARK(MeshQueryBrute)->ArgName("levels")->DenseRange(1, 4)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
