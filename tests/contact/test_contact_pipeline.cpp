// contact/contact_pipeline.hpp: respond() applies the handler, then the colliders, then the
// surface pass, to one CollisionStep; the pipeline is active only with something to apply;
// copies are deep (a copy's handler and surface pass are its own). The oracles are closed forms:
// a plane y = 0 puts a point below it back on it; a handler that moves a point is seen by the
// colliders after it, never the other way round.
#include <doctest/doctest.h>

#include <massspring/contact/colliders/colliders.hpp>
#include <massspring/contact/contact_pipeline.hpp>
#include <massspring/contact/response/surface_contact.hpp>
#include <memory>
#include <string>

using Pts = massspring::Points<double>;

namespace {

// Moves point 0 to y = -0.5 and records the end position of point 0 it was given.
struct SinkPointZero final : massspring::contact::CollisionHandler<double> {
  double* seen_y;
  explicit SinkPointZero(double* y) : seen_y(y) {}
  std::unique_ptr<massspring::contact::CollisionHandler<double>> clone() const override {
    return std::make_unique<SinkPointZero>(*this);
  }
  const char* name() const override { return "sink"; }
  void handle(const massspring::contact::CollisionStep<double>& s) override {
    *seen_y = s.x_end(0, 1);
    s.x_end(0, 1) = -0.5;
  }
};

}  // namespace

TEST_CASE("ContactPipeline: handler, then colliders, then the surface pass, on one step") {
  using massspring::contact::Collider;
  massspring::contact::ContactPipeline<double> pipeline;
  CHECK_FALSE(pipeline.active());
  double seen_y = 0;
  pipeline.set_collision_handler(SinkPointZero(&seen_y));
  CHECK(pipeline.active());
  pipeline.colliders().add(Collider<double>::plane({0, 0, 0}, {0, 1, 0}));

  Pts x0(3, 3), v0 = Pts::Zero(3, 3);
  x0 << 0, 0.2, 0, 1, 0.2, 0, 0, 0.2, 1;
  Pts x1 = x0, v1 = v0;
  x1(0, 1) = 0.1;  // the integrator's end: still above the plane
  const massspring::Vector<double> m = massspring::Vector<double>::Ones(3), w = m;
  const std::vector<int> pinned;
  const massspring::contact::CollisionStep<double> step{x0, v0, x1, v1, 1.0 / 30, m, w, pinned};
  const auto report = pipeline.respond(step);
  CHECK(seen_y == 0.1);                                  // the handler saw the integrator's end
  CHECK(x1(0, 1) == doctest::Approx(0).epsilon(1e-12));  // then the plane put the point back
  CHECK(x1(1, 1) == 0.2);                                // the others untouched
  CHECK(report.rounds == 0);                             // no surface: no pass
}

TEST_CASE("ContactPipeline: self-collision needs a surface; copies are deep") {
  massspring::contact::ContactPipeline<double> pipeline;
  massspring::contact::SelfCollision<double> self;
  CHECK_THROWS_WITH_AS(pipeline.set_self_collision(self),
                       doctest::Contains("self-collision: the system has no surface"),
                       massspring::Error);
  Pts rest(3, 3);
  rest << 0, 0, 0, 1, 0, 0, 0, 0, 1;
  massspring::Triangles t(1, 3);
  t << 0, 1, 2;
  pipeline.set_surface(t, rest);
  CHECK(pipeline.surface_edges().rows() == 3);
  pipeline.set_self_collision(self);
  CHECK(pipeline.active());
  pipeline.surface_contact().set_max_rounds(5);
  double seen_y = 0;
  pipeline.set_collision_handler(SinkPointZero(&seen_y));

  massspring::contact::ContactPipeline<double> copy = pipeline;
  copy.surface_contact().set_max_rounds(7);
  CHECK(pipeline.surface_contact().max_rounds() == 5);
  CHECK(&copy.surface_contact() != &pipeline.surface_contact());
  CHECK(copy.collision_handler() != pipeline.collision_handler());
  CHECK(std::string(copy.collision_handler()->name()) == "sink");
  pipeline.clear_self_collision();
  pipeline.clear_collision_handler();
  CHECK_FALSE(pipeline.active());
  CHECK(copy.active());
}
