// Determinism: the same cloth stepped 100 frames twice from the same start gives bit-identical
// positions and velocities (an FNV-1a hash of their bytes), with the same integrator reused and
// with a separately constructed system and integrator, for FastMassSpring, SymplecticEuler and
// BackwardEuler (Sparse, double).
//
// The library has no threading today (no OpenMP, no std::thread; Eigen's own parallelism is only
// for dense products, which these integrators do not use). When threading appears, this test must
// also run with 1 and 2 threads (e.g. OMP_NUM_THREADS / Eigen::setNbThreads) and compare hashes
// across thread counts.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <massspring/diagnostics/stable_time_step.hpp>
#include <massspring/forces/gravity.hpp>
#include <massspring/integrators/backward_euler.hpp>
#include <massspring/integrators/fast_mass_spring.hpp>
#include <massspring/integrators/symplectic_euler.hpp>
#include <massspring/scene/cloth.hpp>
#include <massspring/scene/make_system.hpp>
#include <sstream>
#include <string>

namespace {

using System = massspring::MassSpringSystem<double, massspring::Sparse>;
using Pts = massspring::Points<double>;

constexpr int kDeterminismFrames = 100;

/// FNV-1a (64 bit) over the bytes of a matrix's coefficients, continuing from h.
std::uint64_t fnv1a(const Pts& m, std::uint64_t h = 14695981039346656037ull) {
  const auto* bytes = reinterpret_cast<const unsigned char*>(m.data());
  const std::size_t n = std::size_t(m.size()) * sizeof(double);
  for (std::size_t b = 0; b < n; ++b) {
    h ^= bytes[b];
    h *= 1099511628211ull;
  }
  return h;
}

std::uint64_t state_hash(const System& s) { return fnv1a(s.velocities(), fnv1a(s.positions())); }

/// An n x n hanging cloth (1 m x 1 m), pinned at its top corners, with a small deterministic
/// out-of-plane perturbation so that the motion is three-dimensional. Gravity as a force term when
/// asked.
System make_cloth_system(bool gravity_term, int n) {
  massspring::ClothOptions o;
  o.columns = n;
  o.rows = n;
  o.width = 1.0;
  o.height = 1.0;
  o.stiffness = 200;
  o.mass = 0.01;
  System s = massspring::make_system<System>(massspring::make_cloth(o));
  Pts x = s.positions();
  for (int i = 0; i < x.rows(); ++i)
    if (!s.is_pinned(i)) x(i, 2) = 0.01 * std::sin(0.37 * i);
  s.set_positions(x);
  if (gravity_term) s.add_force(massspring::Gravity<double>(Eigen::Vector3d(0, -9.8, 0)));
  return s;
}

/// Steps kDeterminismFrames frames; every step must succeed. Returns the hash of the final state.
template <class Integrator>
std::uint64_t run(System& s, Integrator& integrator) {
  for (int f = 0; f < kDeterminismFrames; ++f) {
    const massspring::StepReport r = integrator.step(s);
    REQUIRE(r.finite);
  }
  return state_hash(s);
}

/// The three runs: (1) system A with integrator A; (2) A reset to its start, same integrator;
/// (3) a separately constructed system B with a separately constructed integrator B. The final
/// states must be bit-identical, and must differ from the start (the cloth moved).
template <class Integrator>
void check_deterministic(const char* name, bool gravity_term, int n, double dt,
                         const std::function<void(Integrator&)>& configure) {
  const std::string label = name;
  CAPTURE(label);
  System a = make_cloth_system(gravity_term, n);
  const Pts x0 = a.positions(), v0 = a.velocities();
  const std::uint64_t start = state_hash(a);

  Integrator ia;
  configure(ia);
  ia.precompute(a, dt);
  const std::uint64_t first = run(a, ia);
  const Pts x1 = a.positions();

  a.set_positions(x0);
  a.set_velocities(v0);
  REQUIRE(state_hash(a) == start);
  const std::uint64_t second = run(a, ia);

  System b = make_cloth_system(gravity_term, n);
  REQUIRE(state_hash(b) == start);
  Integrator ib;
  configure(ib);
  ib.precompute(b, dt);
  const std::uint64_t third = run(b, ib);

  std::ostringstream hex;
  hex << std::hex << first;
  MESSAGE(label, ": ", kDeterminismFrames, " frames, FNV-1a of positions and velocities 0x",
          hex.str());
  CHECK(first == second);
  CHECK(first == third);
  CHECK(a.positions() == b.positions());  // exact equality, coefficient by coefficient
  CHECK(first != start);
  // The cloth fell: the mean height dropped by a visible amount (not a no-op integrator).
  CHECK(x1.col(1).mean() < x0.col(1).mean() - 1e-3);
}

}  // namespace

TEST_CASE("FastMassSpring is deterministic: 100 frames of a 24x24 cloth hash the same") {
  check_deterministic<massspring::FastMassSpring<System>>(
      "FastMassSpring", true, 24, 1.0 / 30,
      [](massspring::FastMassSpring<System>& fms) { fms.options.iterations = 10; });
}

TEST_CASE("FastMassSpring with Chebyshev and Anderson acceleration is deterministic") {
  for (auto acc : {massspring::Acceleration::Chebyshev, massspring::Acceleration::Anderson}) {
    check_deterministic<massspring::FastMassSpring<System>>(
        acc == massspring::Acceleration::Chebyshev ? "FastMassSpring Chebyshev"
                                                   : "FastMassSpring Anderson",
        true, 24, 1.0 / 30, [acc](massspring::FastMassSpring<System>& fms) {
          fms.options.iterations = 10;
          fms.options.acceleration = acc;
        });
  }
}

TEST_CASE("SymplecticEuler is deterministic: 100 frames of a 24x24 cloth hash the same") {
  const double dt = massspring::stable_time_step(make_cloth_system(true, 24));
  check_deterministic<massspring::SymplecticEuler<System>>(
      "SymplecticEuler", true, 24, dt, [](massspring::SymplecticEuler<System>&) {});
}

// BackwardEuler on a 16 x 16 cloth: it factorizes every frame (SparseLU when the cloth's compressed
// springs make the matrix indefinite), and 6 runs of 100 frames on 24 x 24 took over 6 minutes
// under the sanitizers on a loaded 2-core machine.
TEST_CASE("BackwardEuler is deterministic: 100 frames of a 16x16 cloth hash the same") {
  for (auto mode :
       {massspring::BackwardEulerMode::Linearized, massspring::BackwardEulerMode::Newton})
    check_deterministic<massspring::BackwardEuler<System>>(
        mode == massspring::BackwardEulerMode::Newton ? "BackwardEuler Newton"
                                                      : "BackwardEuler Linearized",
        true, 16, 1.0 / 30,
        [mode](massspring::BackwardEuler<System>& be) { be.options.mode = mode; });
}
