// massspring_drape: the drape (support/drape_figures.hpp) in massspring, for the comparison with
// bullet_drape (docs/performance.md, "Against Bullet"). The same cloth on Bullet's own mesh:
// make_cloth's 81 x 81 horizontal grid (2 m x 2 m, 1.9 / 6561 kg a point, k = 1000 N/m, nothing
// pinned, centre at (0, 0.55, 0)) with its cells split as CreatePatch splits them; a sphere
// collider (r 0.5 m at the origin) and a floor plane (y = -1), friction 0.5 on both; gravity as a
// force term. FastMassSpring with 10 iterations (--iterations) from the inertial prediction
// (InitialGuess::Inertial), Anderson acceleration and the contact term inside the iteration
// (contact_weight = 1), one thread. Self-collision (thickness 4 mm, friction 0.5) with
// --self-collision.
//
// It drops the cloth, runs the frames (one step each) and prints the figures of
// support/drape_figures.hpp; the time is the step alone, CPU time.
//
//   massspring_drape [--fps 30 | 60 (default 30)] [--self-collision] [--seconds S (default 3)]
//                    [--crossings] [--contact-weight W (default 1; 0: contact only at the step's
//                    end, the library's default)] [--plain (no Anderson acceleration)]
//                    [--no-surface] [--iterations N (default 10)]
//
// --no-surface removes the surface make_system gives the cloth, and with it the end-of-step
// surface pass (contact/response/surface_contact.hpp: the cloth's edges and faces against the
// obstacles' thin parts, here the sphere's centre), leaving the points' contact with the colliders;
// the figures still use the triangles.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <massspring/contact/self_collision.hpp>
#include <massspring/forces/gravity.hpp>
#include <massspring/integrators/fast_mass_spring.hpp>
#include <massspring/scene/cloth.hpp>
#include <massspring/scene/make_system.hpp>
#include <string>

#include "support/drape_figures.hpp"

namespace {

using System = massspring::MassSpringSystem<double, massspring::Sparse>;
using V3 = massspring::Vector3<double>;
using Collider = massspring::contact::Collider<double>;

System drape_system(bool self_collision) {
  massspring::ClothOptions o;
  o.columns = o.rows = drape::kSide;
  o.width = o.height = drape::kWidth;
  o.stiffness = 1000;
  o.mass = drape::kMass / (drape::kSide * drape::kSide);
  o.shear = massspring::ClothShear::One;
  o.pins = massspring::ClothPins::None;
  o.plane = massspring::ClothPlane::Horizontal;
  o.center = V3(0, drape::kHeight, 0);
  massspring::SceneDescription<double> scene = massspring::make_cloth(o);
  // make_cloth's point (r, c) is CreatePatch's (ix, iy) = (c, r), at the same place; give every
  // cell CreatePatch's diagonal (the springs are the triangles' sides).
  const massspring::Triangles t = drape::patch_triangles();
  scene.faces.clear();
  for (Eigen::Index f = 0; f < t.rows(); ++f) scene.faces.push_back({t(f, 0), t(f, 1), t(f, 2)});
  System s = massspring::make_system<System>(scene);
  s.add_force(massspring::Gravity<double>(V3(0, -drape::kGravity, 0)));
  s.add_collider(Collider::sphere(V3::Zero(), drape::kRadius).set_friction(drape::kFriction));
  s.add_collider(
      Collider::plane(V3(0, drape::kFloor, 0), V3(0, 1, 0)).set_friction(drape::kFriction));
  if (self_collision) s.set_self_collision(massspring::contact::SelfCollision<double>{0.004, 0.5});
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 3;
  int fps = 30;
  bool self_collision = false;
  double contact_weight = 1;
  bool anderson = true;
  bool surface = true;
  int iterations = 10;
  drape::Watch watch;
  // The options of this program; drape::parse() takes --seconds and --crossings.
  const auto option = [&](const std::string& arg, const char* next, int& a) {
    if (arg == "--self-collision") {
      self_collision = true;
    } else if (arg == "--no-surface") {
      surface = false;
    } else if (arg == "--plain") {
      anderson = false;
    } else if (arg == "--contact-weight" && next) {
      contact_weight = std::atof(next);
      ++a;
      return contact_weight >= 0;
    } else if (arg == "--iterations" && next) {
      iterations = std::atoi(next);
      ++a;
      return iterations > 0;
    } else if (arg == "--fps" && next) {
      fps = std::atoi(next);
      ++a;
      return fps > 0;
    } else {
      return false;
    }
    return true;
  };
  const bool parsed = drape::parse(argc, argv, seconds, watch.count_crossings, option);
  if (!parsed || (self_collision && !surface)) {
    std::fprintf(stderr,
                 "usage: massspring_drape [--fps N > 0 (default 30)] [--self-collision] "
                 "[--seconds S > 0] [--crossings] [--contact-weight W >= 0 (default 1)] "
                 "[--plain] [--no-surface (not with --self-collision)] "
                 "[--iterations N > 0 (default 10)]\n");
    return 2;
  }
  const double dt = 1.0 / fps;
  const int frames = std::max(1, int(std::lround(seconds / dt)));

  System s = drape_system(self_collision);
  massspring::Triangles triangles = s.surface();
  if (!surface) s.set_surface(massspring::Triangles());
  massspring::FastMassSpring<System> fms;
  fms.options.iterations = iterations;
  fms.options.initial_guess = massspring::InitialGuess::Inertial;
  fms.options.contact_weight = contact_weight;
  fms.options.acceleration =
      anderson ? massspring::Acceleration::Anderson : massspring::Acceleration::None;
  fms.precompute(s, dt);

  drape::FrameTimer timer;
  bool ok = true;
  for (int k = 0; k < frames; ++k) {
    timer.start();
    const massspring::StepReport r = fms.step(s);
    timer.stop();
    ok = ok && r.ok();
    watch.frame_end(s.positions(), triangles);
  }
  ok = ok && s.positions().allFinite();
  char engine[160];
  std::snprintf(engine, sizeof engine,
                "massspring FastMassSpring, %d points, %d springs, %d triangles, %d iterations%s, "
                "contact_weight %g, %s",
                int(s.num_points()), s.num_springs(), int(triangles.rows()), iterations,
                anderson ? " (Anderson)" : "", contact_weight,
                self_collision ? "self-collision on (4 mm, 0.5)"
                : surface      ? "self-collision off"
                               : "no surface (point contact only)");
  drape::print(engine, dt, frames, timer,
               drape::figures(s.positions(), s.springs(), s.rest_lengths()), watch, ok);
  return ok ? 0 : 1;
}
