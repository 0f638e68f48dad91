// A square cloth dropped on a ball over a floor: colliders with friction, and the cloth's own
// surface kept from passing through itself (self-collision).
// Run: prints where the cloth rests after 2 s: on the ball's top, its edges down to the floor.
#include <cstdio>
#include <massspring/contact/colliders/collider.hpp>
#include <massspring/contact/self_collision.hpp>
#include <massspring/forces/gravity.hpp>
#include <massspring/integrators/fast_mass_spring.hpp>
#include <massspring/scene/cloth.hpp>
#include <massspring/scene/make_system.hpp>

using System = massspring::MassSpringSystem<double, massspring::Sparse>;
using Collider = massspring::contact::Collider<double>;

int main() {
  massspring::ClothOptions cloth;
  cloth.columns = cloth.rows = 25;
  cloth.width = cloth.height = 1.2;                  // [m]
  cloth.plane = massspring::ClothPlane::Horizontal;  // lying flat
  cloth.pins = massspring::ClothPins::None;
  cloth.center = massspring::Vector3<double>(0, 0.6, 0);  // 0.3 m above the ball's top
  System system = massspring::make_system<System>(massspring::make_cloth(cloth));
  system.add_force(massspring::Gravity<double>({0, -9.8, 0}));
  system.add_collider(Collider::sphere({0, 0, 0}, 0.3).set_friction(0.5));  // radius 0.3 m
  system.add_collider(Collider::plane({0, -0.5, 0}, {0, 1, 0}));            // the floor
  massspring::contact::SelfCollision<double> self;
  self.thickness = 0.005;  // [m]: layers of cloth stay this far apart
  system.set_self_collision(self);

  massspring::FastMassSpring<System> solver;  // the defaults: contact inside the iteration
  solver.precompute(system, 1.0 / 30);
  for (int step = 0; step < 60; ++step)
    if (!solver.step(system).ok()) return 2;
  const double highest = system.positions().col(1).maxCoeff();
  const double lowest = system.positions().col(1).minCoeff();
  std::printf("after 2 s the cloth spans y = %.3f .. %.3f m (ball top 0.3 m, floor -0.5 m)\n",
              lowest, highest);
  // Held by the ball (its top point rests on the ball's top, to 1 um), nothing under the floor.
  return highest > 0.3 - 1e-6 && lowest >= -0.5 ? 0 : 1;
}
