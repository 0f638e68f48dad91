// integrators/local_global/instances.hpp: the explicit instantiations MASSSPRING_EXTERN_TEMPLATES
// declares. The test program defines MASSSPRING_EXTERN_TEMPLATES (tests/CMakeLists.txt), so every
// other test file steps the four common systems through the instantiations in this file, which
// compiles on its own (no unity group). Here they are checked against an implicit instantiation of
// the same solver: a factorization type the declarations do not name (SparseCholesky under another
// name) makes FastMassSpring instantiate in this file, from the same header and flags, and both
// must give the same trajectory bit for bit. That a consumer with the macro instantiates neither
// precompute() nor step() is checked on its object file by the test
// integrators.extern_templates_not_instantiated
// (tests/integrators/local_global/extern_templates.cmake).
#include <doctest/doctest.h>

#include <massspring/forces/gravity.hpp>
#include <massspring/integrators/local_global/instances.hpp>
#include <massspring/scene/cloth.hpp>
#include <massspring/scene/make_system.hpp>

namespace {

// The default factorization of Sparse storage, as a type of its own.
template <class Scalar>
struct RenamedCholesky : massspring::SparseCholesky<Scalar> {};

template <class Scalar>
massspring::MassSpringSystem<Scalar, massspring::Sparse> hanging_cloth() {
  using System = massspring::MassSpringSystem<Scalar, massspring::Sparse>;
  massspring::ClothOptions o;
  o.columns = 9;
  o.rows = 7;
  o.stiffness = 300;
  System s = massspring::make_system<System>(massspring::make_cloth(o));
  s.add_force(massspring::Gravity<Scalar>({0, Scalar(-9.8), 0}));
  return s;
}

}  // namespace

TEST_CASE_TEMPLATE(
    "instances.hpp: the explicitly instantiated solver steps as an implicit instantiation, bit for "
    "bit",
    Scalar, double, float) {
  using System = massspring::MassSpringSystem<Scalar, massspring::Sparse>;
  System a = hanging_cloth<Scalar>(), b = hanging_cloth<Scalar>();
  massspring::FastMassSpring<System> instantiated;                           // instances.hpp's
  massspring::FastMassSpring<System, RenamedCholesky<Scalar>> implicit_one;  // this file's
  for (auto acceleration : {massspring::Acceleration::None, massspring::Acceleration::Chebyshev,
                            massspring::Acceleration::Anderson}) {
    CAPTURE(int(acceleration));
    instantiated.options.acceleration = implicit_one.options.acceleration = acceleration;
    instantiated.options.iterations = implicit_one.options.iterations = 20;
    instantiated.precompute(a, Scalar(1) / 30);
    implicit_one.precompute(b, Scalar(1) / 30);
    for (int step = 0; step < 10; ++step) {
      REQUIRE(instantiated.step(a).ok());
      REQUIRE(implicit_one.step(b).ok());
    }
    CHECK(a.positions() == b.positions());
    CHECK(a.velocities() == b.velocities());
    CHECK(instantiated.rejections() == implicit_one.rejections());
  }
  // The cloth moved: equal trajectories are not two unmoved ones.
  CHECK((a.positions() - hanging_cloth<Scalar>().positions()).norm() > Scalar(1e-3));
}
