// surface_contact_report: the contact scenes at dt = 1/30 s under each integrator, with
// self-collision on (thickness 4 mm, friction 0.2): per run, ms per step (mean and max), the
// strain |l / l0 - 1| of the springs at the end (mean and max), the smallest distance between
// non-adjacent elements of the surface over the step ends, and the most edge-triangle crossings
// at a step end (the exact checker of tests/support/intersections.hpp, written apart from the
// library's detection; a capsule's axis counts as an edge). A plain program, not a Google
// Benchmark: each run is one trajectory.
//
//   surface_contact_report [steps]      (default 45, i.e. 1.5 s)
#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <massspring/contact/self_collision.hpp>
#include <massspring/forces/gravity.hpp>
#include <massspring/integrators/backward_euler.hpp>
#include <massspring/integrators/fast_mass_spring.hpp>
#include <massspring/scene/contact_recipes.hpp>
#include <massspring/scene/make_system.hpp>
#include <string>
#include <vector>

#include "support/intersections.hpp"

namespace {

using System = massspring::MassSpringSystem<double, massspring::Sparse>;
using FastMassSpring = massspring::FastMassSpring<System>;
using BackwardEuler = massspring::BackwardEuler<System>;

template <class Stepper, class Setup>
void report(const char* scene_name, const massspring::SceneDescription<double>& scene,
            const char* integrator, Setup setup, int steps) {
  System s = massspring::make_system<System>(scene);
  s.add_force(massspring::Gravity<double>({0, -9.81, 0}));
  s.set_self_collision(massspring::contact::SelfCollision<double>{});
  Stepper stepper;
  setup(stepper);
  stepper.precompute(s, 1.0 / 30);
  const massspring::Edges edges = massspring::test::triangle_edges(s.surface());
  double total = 0, slowest = 0, separation = 1e300;
  int crossings = 0;
  bool ok = true;
  for (int k = 0; k < steps; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    const massspring::StepReport r = stepper.step(s);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    total += ms;
    slowest = std::max(slowest, ms);
    ok = ok && r.ok();
    int c = massspring::test::count_crossings(s.positions(), s.surface(), edges);
    for (const auto& collider : scene.colliders)
      if (collider.shape == massspring::contact::ColliderShape::Capsule)
        c += massspring::test::count_segment_crossings(s.positions(), s.surface(), collider.a,
                                                       collider.b);
    crossings = std::max(crossings, c);
    separation =
        std::min(separation, massspring::test::min_separation(s.positions(), s.surface(), edges));
  }
  double strain_sum = 0, strain_max = 0;
  for (Eigen::Index e = 0; e < s.springs().rows(); ++e) {
    const double l =
        (s.positions().row(s.springs()(e, 0)) - s.positions().row(s.springs()(e, 1))).norm();
    const double strain = std::abs(l / s.rest_lengths()(e) - 1);
    strain_sum += strain;
    strain_max = std::max(strain_max, strain);
  }
  std::printf("%-12s %-22s %5d %9.2f %9.2f %8.4f %8.4f %11.2e %9d %s\n", scene_name, integrator,
              int(s.num_points()), total / steps, slowest, strain_sum / double(s.springs().rows()),
              strain_max, separation, crossings, ok ? "ok" : "FAILED");
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const int steps = argc > 1 ? std::atoi(argv[1]) : 45;
  if (steps <= 0) {
    std::fprintf(stderr, "usage: surface_contact_report [steps > 0]\n");
    return 2;
  }
  std::printf("%-12s %-22s %5s %9s %9s %8s %8s %11s %9s\n", "scene", "integrator", "n", "ms/step",
              "max ms", "strain", "max", "min dist m", "crossings");
  const std::vector<std::pair<std::string, massspring::SceneDescription<double>>> scenes = {
      {"clothesline", massspring::clothesline_scene()},
      {"ribbon_pile", massspring::ribbon_pile_scene()},
      {"two_cloths", massspring::two_cloths_on_ball_scene()},
      {"large_drape", massspring::large_drape_scene()}};
  for (const auto& [name, scene] : scenes) {
    report<FastMassSpring>(
        name.c_str(), scene, "FastMassSpring 10",
        [](FastMassSpring& f) {
          f.options = massspring::FastMassSpringOptions<double>::reference();
          f.options.iterations = 10;
        },
        steps);
    report<FastMassSpring>(
        name.c_str(), scene, "Chebyshev 10",
        [](FastMassSpring& f) {
          f.options = massspring::FastMassSpringOptions<double>::reference();
          f.options.iterations = 10;
          f.options.acceleration = massspring::Acceleration::Chebyshev;
        },
        steps);
    report<BackwardEuler>(
        name.c_str(), scene, "BackwardEuler Newton", [](BackwardEuler&) {}, steps);
    report<BackwardEuler>(
        name.c_str(), scene, "BackwardEuler linear",
        [](BackwardEuler& b) { b.options.mode = massspring::BackwardEulerMode::Linearized; },
        steps);
  }
  return 0;
}
