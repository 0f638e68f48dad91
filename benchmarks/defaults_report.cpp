// defaults_report: the contact scenes at dt = 1/30 s with the integrators' DEFAULT options and
// self-collision on (thickness 4 mm, friction 0.3), each run one trajectory. Per run: ms per step
// (mean), the springs' strain |l / l0 - 1| at the end (mean, max, how many past 15%) and the
// largest over every step end, the most edge-triangle crossings at a step end (the exact checker
// of tests/support/intersections.hpp, written apart from the library's detection; a capsule's
// axis counts as an edge), the deepest point inside an obstacle at a step end (signed distances
// computed here, apart from the colliders' code), and the steps that did not report ok. A plain
// program, not a Google Benchmark; docs/contact.md's table of defaults is its output.
//
//   defaults_report [--scene NAME|all] [--integrator fast-mass-spring|backward-euler|all]
//                   [--seconds S] [--no-self-collision] [--no-surface]
//                   [--contact-weight A] [--iterations N] [--acceleration none|chebyshev|anderson]
// (the last three replace a default, for comparisons; --no-surface, which needs
// --no-self-collision, removes the system's surface, so that no end-of-step pass tests the
// obstacles' edges and corners: crossings are still counted on the scene's triangles).
// With MS_TRACE=1 in the environment each step's report goes to stderr: ok, finite, blown up,
// contact resolved, impulses, zone points, iterations, the largest strain, the crossings and the
// energy the contact response added (StepReport::contact_work, "work", J).
//
// Scenes: drape31 (examples/scenes/drape.json, the README's drape), drape81 (the Bullet
// comparison's cloth), clothesline, ribbon_pile, two_cloths, five_cloths, tablecloth, twist,
// fast_ball. Default: every scene, both integrators, 5 s (twist 4 s: two turns; fast_ball 1 s).
#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <massspring/contact/self_collision.hpp>
#include <massspring/forces/gravity.hpp>
#include <massspring/integrators/backward_euler.hpp>
#include <massspring/integrators/fast_mass_spring.hpp>
#include <massspring/io/json_scene.hpp>
#include <massspring/scene/contact_recipes.hpp>
#include <massspring/scene/make_system.hpp>
#include <string>
#include <type_traits>
#include <vector>

#include "support/intersections.hpp"

namespace {

using System = massspring::MassSpringSystem<double, massspring::Sparse>;
using Scene = massspring::SceneDescription<double>;
using V3 = Eigen::Vector3d;
constexpr double kDt = 1.0 / 30;

// Pins that move: target of pinned point r at time t.
using PinMotion = V3 (*)(const V3& start, double t);

struct Case {
  std::string name;
  Scene scene;
  double seconds = 5;
  PinMotion motion = nullptr;
};

// ---- scenes ---------------------------------------------------------------------------------

Scene drape31() {
  Scene s = massspring::io::read_json_scene<double>(std::string(MASSSPRING_EXAMPLES_DIR) +
                                                    "/scenes/drape.json");
  s.gravity.reset();  // run() adds the same gravity to every scene
  return s;
}

// Five 31 x 31 cloths of 1 m x 1 m, 5 cm apart (y = 0.8 ... 1.0), over the ball of two_cloths.
Scene five_cloths() {
  Scene s = massspring::detail::contact_cloth(31, 31, 1.0, 1.0, 0.8);
  for (int k = 1; k < 5; ++k)
    s = massspring::detail::disjoint_union(
        s, massspring::detail::contact_cloth(31, 31, 1.0, 1.0, 0.8 + 0.05 * k));
  s.colliders = {massspring::detail::contact_floor(),
                 massspring::detail::contact_sphere({0.0, 0.3, 0.0}, 0.3)};
  return s;
}

// A 41 x 41 cloth of 1.6 m x 1.6 m at y = 0.85 over a table: a box 0.8 m x 0.75 m x 0.8 m on the
// floor (top at y = 0.75).
Scene tablecloth() {
  Scene s = massspring::detail::contact_cloth(41, 41, 1.6, 1.6, 0.85);
  massspring::ColliderDescription<double> table;
  table.shape = massspring::contact::ColliderShape::Box;
  table.center = {0, 0.375, 0};
  table.half_extents = {0.4, 0.375, 0.4};
  table.static_friction = table.kinetic_friction = 0.3;
  s.colliders = {massspring::detail::contact_floor(), table};
  return s;
}

// A 21 x 21 cloth of 1 m x 1 m at y = 1, its edges x = -0.5 and x = 0.5 pinned; they turn about
// the x axis in opposite directions at half a turn per second and move 15 cm each towards the
// middle over 4 s (30% closer).
Scene twist() {
  Scene s = massspring::detail::contact_cloth(21, 21, 1.0, 1.0, 1.0);
  s.pinned.clear();
  for (int i = 0; i < int(s.vertices.rows()); ++i)
    if (std::abs(std::abs(s.vertices(i, 0)) - 0.5) < 1e-9) s.pinned.push_back(i);
  s.colliders.clear();
  return s;
}
V3 twist_motion(const V3& start, double t) {
  const double side = start.x() < 0 ? 1 : -1;  // left turns +, right turns -
  const double angle = side * M_PI * t;        // 0.5 turn/s
  const double y = start.y() - 1, z = start.z();
  const double inward = 0.15 * std::min(t / 4, 1.0);
  return {start.x() + side * inward, 1 + std::cos(angle) * y - std::sin(angle) * z,
          std::sin(angle) * y + std::cos(angle) * z};
}

// A 21 x 21 cloth of 1 m x 1 m hanging in the plane z = 0 from its top row (y = 1.5), and a
// ball of radius 0.1 m that starts 0.5 m in front of it (at y = 1) and flies through it at
// 15 m/s along +z.
Scene fast_ball() {
  massspring::ClothOptions o = massspring::detail::contact_cloth_options(21, 21, 1.0, 1.0);
  o.plane = massspring::ClothPlane::Vertical;
  Scene s = massspring::make_cloth(o);
  s.vertices.col(0).array() -= 0.5;
  s.vertices.col(1).array() += 1.5;
  s.pinned.clear();
  for (int i = 0; i < int(s.vertices.rows()); ++i)
    if (std::abs(s.vertices(i, 1) - 1.5) < 1e-9) s.pinned.push_back(i);
  massspring::ColliderDescription<double> ball =
      massspring::detail::contact_sphere({0, 1, -0.5}, 0.1);
  ball.velocity = {0, 0, 15};
  s.colliders = {ball};
  return s;
}

std::vector<Case> cases(const std::string& which, double seconds) {
  std::vector<Case> all;
  const auto add = [&](const char* name, auto make, double default_seconds, PinMotion m = nullptr) {
    if (which != "all" && which != name) return;
    all.push_back({name, make(), seconds > 0 ? seconds : default_seconds, m});
  };
  add("drape31", drape31, 5);
  add("drape81", massspring::large_drape_scene, 5);
  add("clothesline", massspring::clothesline_scene, 5);
  add("ribbon_pile", massspring::ribbon_pile_scene, 5);
  add("two_cloths", massspring::two_cloths_on_ball_scene, 5);
  add("five_cloths", five_cloths, 5);
  add("tablecloth", tablecloth, 5);
  add("twist", twist, 4, twist_motion);
  add("fast_ball", fast_ball, 1);
  if (all.empty()) {
    std::fprintf(stderr, "defaults_report: unknown scene '%s'\n", which.c_str());
    std::exit(1);
  }
  return all;
}

// ---- figures, computed apart from the library's contact code --------------------------------

// Signed distance of x to an obstacle at time t (its centre moved by velocity t): > 0 outside.
double signed_distance(const massspring::ColliderDescription<double>& c, const V3& x, double t) {
  using Shape = massspring::contact::ColliderShape;
  switch (c.shape) {
    case Shape::Plane:
      return (x - (c.point + t * c.velocity)).dot(c.normal.normalized());
    case Shape::Sphere:
      return (x - (c.center + t * c.velocity)).norm() - c.radius;
    case Shape::Capsule: {
      const V3 a = c.a + t * c.velocity, b = c.b + t * c.velocity, ab = b - a;
      const double s = std::clamp((x - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
      return (x - (a + s * ab)).norm() - c.radius;
    }
    case Shape::Box: {  // axis-aligned (the scenes here leave the rotation at the identity)
      const V3 q = (x - (c.center + t * c.velocity)).cwiseAbs() - c.half_extents;
      return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
    }
    default:
      return 1e300;
  }
}

struct Strain {
  double mean = 0, max = 0;
  int over = 0;  // past 15%
};
Strain strain(const System& s) {
  Strain r;
  for (Eigen::Index e = 0; e < s.springs().rows(); ++e) {
    const double l =
        (s.positions().row(s.springs()(e, 0)) - s.positions().row(s.springs()(e, 1))).norm();
    const double v = std::abs(l / s.rest_lengths()(e) - 1);
    r.mean += v;
    r.max = std::max(r.max, v);
    r.over += v > 0.15;
  }
  if (s.springs().rows() > 0) r.mean /= double(s.springs().rows());
  return r;
}

// Options other than the defaults, for comparisons (negative: the default).
struct Overrides {
  double contact_weight = -1;
  int iterations = -1;
  std::string acceleration;
  bool no_surface = false;  // --no-surface: not an option, the system's surface removed
};

template <class Integrator>
void configure(Integrator& integrator, const Overrides& o) {
  if (o.contact_weight >= 0) integrator.options.contact_weight = o.contact_weight;
  if (o.iterations > 0) integrator.options.iterations = o.iterations;
  if constexpr (std::is_same_v<Integrator, massspring::FastMassSpring<System>>)
    if (!o.acceleration.empty())
      integrator.options.acceleration = o.acceleration == "none" ? massspring::Acceleration::None
                                        : o.acceleration == "chebyshev"
                                            ? massspring::Acceleration::Chebyshev
                                            : massspring::Acceleration::Anderson;
}

template <class Integrator>
void run(const Case& c, const char* integrator_name, bool self_collision, const Overrides& o) {
  System s = massspring::make_system<System>(c.scene);
  s.add_force(massspring::Gravity<double>({0, -9.8, 0}));
  if (self_collision) {  // replaces a scene's own
    massspring::contact::SelfCollision<double> self;
    self.thickness = 0.004;
    self.friction = 0.3;
    s.set_self_collision(self);
  }
  const massspring::Triangles surface = s.surface();  // the crossings' triangles
  if (o.no_surface) s.set_surface(massspring::Triangles(0, 3));
  const massspring::Points<double> start = s.positions();
  Integrator integrator;  // the defaults
  configure(integrator, o);
  integrator.precompute(s, kDt);
  const massspring::Edges edges = massspring::test::triangle_edges(surface);
  const int steps = int(std::lround(c.seconds / kDt));
  double seconds = 0, worst_strain = 0, deepest = 0;
  int crossings = 0, failed = 0, first_failure = 0;
  for (int k = 1; k <= steps; ++k) {
    if (c.motion)
      for (int r = 0; r < s.num_pinned(); ++r) {
        const int i = s.pinned()[std::size_t(r)];
        s.set_pin_target(i, c.motion(start.row(i).transpose(), k * kDt));
      }
    const auto t0 = std::chrono::steady_clock::now();
    const massspring::StepReport report = integrator.step(s);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!report.ok()) {
      ++failed;
      if (first_failure == 0) first_failure = k;
    }
    int n = massspring::test::count_crossings(s.positions(), surface, edges);
    for (const auto& collider : c.scene.colliders)
      if (collider.shape == massspring::contact::ColliderShape::Capsule)
        n += massspring::test::count_segment_crossings(s.positions(), surface, collider.a,
                                                       collider.b);
    crossings = std::max(crossings, n);
    for (int i = 0; i < s.num_points(); ++i)
      for (const auto& collider : c.scene.colliders)
        deepest =
            std::min(deepest, signed_distance(collider, s.positions().row(i).transpose(), k * kDt));
    worst_strain = std::max(worst_strain, strain(s).max);
    if (std::getenv("MS_TRACE"))
      std::fprintf(stderr,
                   "step %d ok %d finite %d blew %d resolved %d imp %d zone %d it %d strain %.3f "
                   "crossings %d work %.4g\n",
                   k, int(report.ok()), int(report.finite), int(report.blew_up),
                   int(report.contact_resolved), report.contact_impulses,
                   report.contact_zone_points, report.iterations, strain(s).max, n,
                   report.contact_work);
  }
  const Strain end = strain(s);
  std::printf(
      "| %s | %s | %s | %d | %.2f | %.2f%% | %.1f%% | %d | %.1f%% | %d | %.2f | %d (first %d) |\n",
      c.name.c_str(), integrator_name,
      self_collision ? "on"
      : o.no_surface ? "off, no surface"
                     : "off",
      s.num_points(), 1e3 * seconds / steps, 100 * end.mean, 100 * end.max, end.over,
      100 * worst_strain, crossings, -1e3 * deepest, failed, first_failure);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::string scene = "all", integrator = "all";
  double seconds = 0;
  bool self_collision = true;
  Overrides overrides;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    const bool has_value = a + 1 < argc;
    if (arg == "--scene" && has_value) {
      scene = argv[++a];
    } else if (arg == "--integrator" && has_value) {
      integrator = argv[++a];
    } else if (arg == "--seconds" && has_value) {
      seconds = std::atof(argv[++a]);
      if (!(seconds > 0)) {
        std::fprintf(stderr, "defaults_report: --seconds must be > 0\n");
        return 1;
      }
    } else if (arg == "--contact-weight" && has_value) {
      overrides.contact_weight = std::atof(argv[++a]);
    } else if (arg == "--iterations" && has_value) {
      overrides.iterations = std::atoi(argv[++a]);
    } else if (arg == "--acceleration" && has_value) {
      overrides.acceleration = argv[++a];
    } else if (arg == "--no-self-collision") {
      self_collision = false;
    } else if (arg == "--no-surface") {
      overrides.no_surface = true;
    } else {
      std::fprintf(stderr,
                   "usage: defaults_report [--scene NAME|all] [--integrator "
                   "fast-mass-spring|backward-euler|all] [--seconds S] [--no-self-collision] "
                   "[--no-surface] [--contact-weight A] [--iterations N] [--acceleration "
                   "none|chebyshev|anderson]\n");
      return 1;
    }
  }
  if (overrides.no_surface && self_collision) {
    std::fprintf(stderr, "defaults_report: --no-surface needs --no-self-collision\n");
    return 1;
  }
  if (integrator != "all" && integrator != "fast-mass-spring" && integrator != "backward-euler") {
    std::fprintf(stderr, "defaults_report: unknown integrator '%s'\n", integrator.c_str());
    return 1;
  }
  std::printf(
      "| scene | integrator | self-collision | points | ms/step | strain mean | max | links > 15%% "
      "| max over steps | crossings | deepest [mm] | steps not ok |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Case& c : cases(scene, seconds)) {
    if (integrator != "backward-euler")
      run<massspring::FastMassSpring<System>>(c, "fast-mass-spring", self_collision, overrides);
    if (integrator != "fast-mass-spring")
      run<massspring::BackwardEuler<System>>(c, "backward-euler", self_collision, overrides);
  }
  return 0;
}
