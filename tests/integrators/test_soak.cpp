// Long-run soak: a 64 x 64 cloth (two top corners pinned, gravity) stepped for 10,000 frames with
// each stable integrator: FastMassSpring and BackwardEuler (Linearized) at 1/30 s, SymplecticEuler
// and RK4 at their stable_time_step (half their stability limit). Checks
// that every value stays finite, that the cloth stays bounded, and that memory does not grow: the
// heap bytes in use (glibc mallinfo2) after the run equal those after a short warm-up, and the
// integrators that promise an allocation-free step() (FastMassSpring, SymplecticEuler, RK4) make no
// allocation at all (CountAllocations).
//
// These cases are in the doctest suite "soak" and skipped by default: plain `massspring_tests`
// and the discovered ctest cases do not run them; tests/CMakeLists.txt adds one ctest test per
// integrator (`massspring_tests --no-skip --test-suite=soak --test-case=...`) labelled `soak`, so
// scripts/test.sh runs them and the sanitizer run excludes them (`ctest -LE soak`).
#include <doctest/doctest.h>
#include <malloc.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <massspring/diagnostics/stable_time_step.hpp>
#include <massspring/forces/gravity.hpp>
#include <massspring/integrators/backward_euler.hpp>
#include <massspring/integrators/fast_mass_spring.hpp>
#include <massspring/integrators/rk4.hpp>
#include <massspring/integrators/symplectic_euler.hpp>
#include <massspring/scene/cloth.hpp>
#include <massspring/scene/make_system.hpp>
#include <optional>
#include <string>

#include "support/alloc_counter.hpp"

namespace {

using System = massspring::MassSpringSystem<double, massspring::Sparse>;

/// Heap bytes in use: small blocks (uordblks) plus mmapped ones (hblkhd).
long long heap_in_use() {
  const struct mallinfo2 mi = mallinfo2();
  return static_cast<long long>(mi.uordblks) + static_cast<long long>(mi.hblkhd);
}

/// A "VmRSS:" or "VmHWM:" field of /proc/self/status [kB], -1 when absent.
long long proc_status_kb(const std::string& field) {
  std::ifstream in("/proc/self/status");
  std::string key;
  long long value = -1;
  while (in >> key) {
    if (key == field) {
      in >> value;
      return value;
    }
    in.ignore(4096, '\n');
  }
  return -1;
}

/// 64 x 64 points over 1 m x 1 m, total mass 1 kg, k = 1000 N/m, both diagonals, top corners
/// pinned, hanging in the x-y plane under gravity (a force term).
System soak_cloth(int size = 64) {
  massspring::ClothOptions o;
  o.columns = size;
  o.rows = size;
  o.width = 1.0;
  o.height = 1.0;
  o.stiffness = 1000;
  o.mass = 1.0 / (size * size);
  System s = massspring::make_system<System>(massspring::make_cloth(o));
  s.add_force(massspring::Gravity<double>(Eigen::Vector3d(0, -9.8, 0)));
  return s;
}

/// The explicit stability bound of DESIGN.md: 2 / omega_max with

constexpr int kWarmup = 20;

/// Steps `frames` frames after a warm-up and checks finiteness, boundedness and memory.
template <class Integrator>
void soak(const char* name, System& s, Integrator& integrator, int frames, bool allocation_free) {
  const std::string label = name;
  CAPTURE(label);
  for (int f = 0; f < kWarmup; ++f) REQUIRE(integrator.step(s).finite);

  // /proc is read outside the heap measurements: the first std::ifstream may leave a one-time
  // allocation (locale facets) behind.
  const long long rss0 = proc_status_kb("VmRSS:");
  const long long heap0 = heap_in_use();
  int first_bad = -1;
  double farthest = 0;  // largest |x_i| seen at the sampled frames [m]
  std::size_t allocations = 0;
  const auto t0 = std::chrono::steady_clock::now();
  {
    // No doctest macro (they allocate) inside the loop.
    std::optional<massspring::test::CountAllocations> count;
    if (allocation_free) count.emplace();
    for (int f = 0; f < frames; ++f) {
      const massspring::StepReport r = integrator.step(s);
      if (!r.finite || !s.positions().allFinite() || !s.velocities().allFinite()) {
        first_bad = f;
        break;
      }
      if (f % 100 == 0) farthest = std::max(farthest, s.positions().rowwise().norm().maxCoeff());
    }
    if (count) allocations = count->count();
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const long long heap1 = heap_in_use();
  const long long rss1 = proc_status_kb("VmRSS:");
  farthest = std::max(farthest, s.positions().rowwise().norm().maxCoeff());

  MESSAGE(label, ": ", frames, " frames in ", seconds, " s; heap in use ", heap0, " -> ", heap1,
          " bytes; VmRSS ", rss0, " -> ", rss1, " kB, VmHWM ", proc_status_kb("VmHWM:"),
          " kB; farthest point ", farthest, " m");
  CHECK(first_bad == -1);
  // Memory does not grow: a leak of even one byte per frame would show here.
  CHECK(heap1 - heap0 <= 4096);
  if (allocation_free) CHECK(allocations == 0);
  // Bounded: the cloth hangs from (0, 0, 0) and (1, 0, 0); its springs are ~1 m long in all, so
  // even stretched by gravity no point gets farther than a few metres from the origin.
  CHECK(farthest < 5.0);
  // It moved (the integrator did something): the cloth sagged from its rest plane.
  CHECK(s.positions().col(1).minCoeff() < -1.0 - 1e-3);
}

}  // namespace

TEST_SUITE("soak" * doctest::skip()) {
  TEST_CASE("soak: FastMassSpring, 64x64 cloth, 10000 frames at dt = 1/30, 10 iterations") {
    System s = soak_cloth();
    massspring::FastMassSpring<System> fms;
    fms.options.iterations = 10;
    fms.precompute(s, 1.0 / 30);
    soak("FastMassSpring", s, fms, 10000, true);
  }

  TEST_CASE("soak: SymplecticEuler, 64x64 cloth, 10000 frames at half the explicit limit") {
    System s = soak_cloth();
    const double dt = massspring::stable_time_step(s);  // half the limit
    MESSAGE("SymplecticEuler dt = ", dt, " s (limit ", massspring::stability_limit(s), " s)");
    massspring::SymplecticEuler<System> se;
    se.precompute(s, dt);
    soak("SymplecticEuler", s, se, 10000, true);
  }

  TEST_CASE("soak: RK4, 64x64 cloth, 10000 frames at half the explicit limit") {
    System s = soak_cloth();
    const double dt = massspring::stable_time_step(s, massspring::ExplicitMethod::RK4);
    massspring::RK4<System> rk4;
    rk4.precompute(s, dt);
    soak("RK4", s, rk4, 10000, true);
  }

  // The most expensive soak: BackwardEuler factorizes the 3n x 3n matrix every frame, with LDLT
  // when compressed springs make it indefinite. The 32x32 cloth (3,072 unknowns) keeps the 10,000
  // frames, the indefinite solves and the heap check without making this test the suite's
  // critical path.
  TEST_CASE("soak: BackwardEuler Linearized, 32x32 cloth, 10000 frames at dt = 1/30") {
    System s = soak_cloth(32);
    massspring::BackwardEuler<System> be;
    be.options.mode = massspring::BackwardEulerMode::Linearized;
    be.precompute(s, 1.0 / 30);
    // Sparse storage allocates in Eigen's numeric factorization: heap growth is the oracle.
    soak("BackwardEuler Linearized", s, be, 10000, false);
  }
}
