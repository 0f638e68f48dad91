// contact/collision_handler.hpp and the integrators: every integrator calls the system's handler
// once per step with the start-of-step state and its own end-of-step state, and commits what the
// handler leaves; pinned points stay at their targets; copies of a system get their own handler;
// a step with the simple handler allocates nothing after the first.
#include <doctest/doctest.h>

#include <massspring/contact/fosssim/simple_impulse.hpp>
#include <massspring/forces/gravity.hpp>
#include <massspring/integrators/backward_euler.hpp>
#include <massspring/integrators/fast_mass_spring.hpp>
#include <massspring/integrators/forward_euler.hpp>
#include <massspring/integrators/rk4.hpp>
#include <massspring/integrators/symplectic_euler.hpp>
#include <massspring/system/mass_spring_system.hpp>

#include "contact/support.hpp"
#include "support/alloc_counter.hpp"

namespace contact = massspring::contact;
using System = massspring::MassSpringSystem<double, massspring::Sparse>;
using Pts = massspring::Points<double>;

namespace {

// Records what it sees; stops point 1 (sets its end velocity to zero and its end position to
// its start position).
struct Recorder final : contact::CollisionHandler<double> {
  int* calls;
  Pts* seen_start;
  Pts* seen_end;
  Recorder(int* c, Pts* s, Pts* e) : calls(c), seen_start(s), seen_end(e) {}
  std::unique_ptr<contact::CollisionHandler<double>> clone() const override {
    return std::make_unique<Recorder>(*this);
  }
  const char* name() const override { return "recorder"; }
  void handle(const contact::CollisionStep<double>& s) override {
    ++*calls;
    *seen_start = s.x_start;
    *seen_end = s.x_end;
    s.x_end.row(1) = s.x_start.row(1);
    s.v_end.row(1).setZero();
  }
};

System chain() {
  Pts x(3, 3);
  x << 0, 0, 0, 1, 0, 0, 2, 0, 0;
  massspring::Edges e(2, 2);
  e << 0, 1, 1, 2;
  System s(x, e, 1.0, 10.0);
  s.add_force(massspring::Gravity<double>(massspring::test::v3(0, -9.8)));
  s.pin(0);
  return s;
}

template <class Integrator>
void check_hook(Integrator& integrator) {
  System sys = chain();
  int calls = 0;
  Pts start, end;
  sys.set_collision_handler(Recorder(&calls, &start, &end));
  integrator.precompute(sys, 0.01);
  for (int k = 0; k < 3; ++k) {
    const Pts before = sys.positions();
    integrator.step(sys);
    CHECK(calls == k + 1);
    CHECK(start == before);
    CHECK(end.row(2) == sys.positions().row(2));  // committed as the handler left it
    CHECK(sys.positions().row(1) == before.row(1));
    CHECK(sys.velocities().row(1).isZero());
    CHECK(sys.positions().row(0) == sys.pin_targets().row(0));
  }
  System copy = sys;  // its own handler, still calling the same counters
  copy.clear_collision_handler();
  integrator.step(copy);
  CHECK(calls == 3);
  CHECK(sys.collision_handler() != nullptr);
}

}  // namespace

TEST_CASE("collision hook: every integrator calls the handler once per step and commits it") {
  massspring::ForwardEuler<System> forward;
  check_hook(forward);
  massspring::SymplecticEuler<System> symplectic;
  check_hook(symplectic);
  massspring::RK4<System> rk4;
  check_hook(rk4);
  massspring::BackwardEuler<System> newton;
  check_hook(newton);
  massspring::BackwardEuler<System> linearized;
  linearized.options.mode = massspring::BackwardEulerMode::Linearized;
  check_hook(linearized);
  massspring::FastMassSpring<System> local_global;
  check_hook(local_global);
}

TEST_CASE("collision hook: a step with the simple handler allocates nothing after the first") {
  System sys = chain();
  contact::ContactGeometry<double> g = massspring::test::particles(3, 0.3);
  g.edges = sys.springs();
  g.edge_radii = massspring::Vector<double>::Constant(2, 0.1);
  g.planes.push_back({massspring::test::v3(0, -0.05), massspring::test::v3(0, 1)});
  sys.set_collision_handler(contact::SimpleCollisionHandler<double>(g, 0.5));
  massspring::SymplecticEuler<System> se;
  se.precompute(sys, 0.01);
  se.step(sys);
  massspring::test::CountAllocations count;
  for (int k = 0; k < 20; ++k) se.step(sys);
  CHECK(count.count() == 0);
  CHECK(sys.positions().allFinite());
}
