// diagnostics/accuracy.hpp and reference_solution.hpp: the error metrics against closed forms,
// the incremental potential against a converged Newton step (its stationary point), the
// reference solution against the oscillator's closed form, and its on-disk cache.
#include <doctest/doctest.h>

#include <Eigen/Core>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <massspring/diagnostics/accuracy.hpp>
#include <massspring/diagnostics/reference_solution.hpp>
#include <massspring/forces/gravity.hpp>
#include <massspring/forces/linear_drag.hpp>
#include <massspring/integrators/backward_euler.hpp>
#include <random>
#include <string>
#include <vector>

#include "support/small_systems.hpp"

namespace {

using massspring::Sparse;
using Pts = massspring::Points<double>;
using SystemS = massspring::MassSpringSystem<double, Sparse>;
namespace fs = std::filesystem;

// A fresh, empty directory under the system's temporary directory; removed on destruction.
struct ScratchDir {
  fs::path path;
  ScratchDir() {
    std::random_device rd;
    const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
    path = fs::temp_directory_path() /
           ("massspring-test-reference-" + std::to_string(stamp) + "-" + std::to_string(rd()));
    fs::remove_all(path);
  }
  ~ScratchDir() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  [[nodiscard]] std::vector<fs::path> files() const {
    std::vector<fs::path> out;
    if (fs::exists(path))
      for (const auto& entry : fs::directory_iterator(path)) out.push_back(entry.path());
    return out;
  }
};

// Checks that x_star is a stationary point and a local minimum of the incremental potential of
// the step from (x_start, v_start), and lower than the potential at x_start.
void check_minimiser(const SystemS& s, const Pts& x_star, const Pts& x_start, const Pts& v_start,
                     double h) {
  const auto e = [&](const Pts& x) {
    return massspring::incremental_potential(s, x, x_start, v_start, h);
  };
  const double eps = 1e-6;
  // The gradient at x_start over the free coordinates (central differences): the size a
  // directional derivative has when nothing was solved.
  double gradient_start = 0;
  for (int i = 0; i < s.num_points(); ++i) {
    if (s.is_pinned(i)) continue;
    for (int a = 0; a < 3; ++a) {
      Pts p = x_start, m = x_start;
      p(i, a) += eps;
      m(i, a) -= eps;
      gradient_start += std::pow((e(p) - e(m)) / (2 * eps), 2);
    }
  }
  gradient_start = std::sqrt(gradient_start);
  REQUIRE(gradient_start > 1e-3);
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  double worst = 0;
  for (int k = 0; k < 10; ++k) {
    Pts d(s.num_points(), 3);
    for (int i = 0; i < d.rows(); ++i)
      for (int a = 0; a < 3; ++a) d(i, a) = s.is_pinned(i) ? 0.0 : normal(rng);
    d /= d.norm();
    const double slope = (e(x_star + eps * d) - e(x_star - eps * d)) / (2 * eps);
    worst = std::max(worst, std::abs(slope));
    // A minimum, not just a stationary point: moving 1e-3 m either way raises it.
    CHECK(e(x_star + 1e-3 * d) > e(x_star));
    CHECK(e(x_star - 1e-3 * d) > e(x_star));
  }
  MESSAGE("accuracy: |directional derivative| at the Newton solution / |gradient| at the start = ",
          worst / gradient_start);
  CHECK(worst < 1e-6 * gradient_start);
  CHECK(e(x_star) < e(x_start));
}

}  // namespace

TEST_CASE("accuracy: bounding_box_diagonal is the box's diagonal") {
  Pts x(4, 3);
  x << -1, 0, -3,  //
      2, 1, -2,    //
      0, 4, -1,    //
      1, 2, -2.5;
  // Extent (3, 4, 2).
  CHECK(massspring::bounding_box_diagonal(x) == doctest::Approx(std::sqrt(29.0)).epsilon(1e-15));
  CHECK(massspring::bounding_box_diagonal(Pts(0, 3)) == 0);
  CHECK(massspring::bounding_box_diagonal(x.topRows(1)) == 0);
  const Eigen::MatrixX3f xf = x.cast<float>();
  CHECK(massspring::bounding_box_diagonal(xf) == doctest::Approx(std::sqrt(29.0)).epsilon(1e-6));
}

TEST_CASE("accuracy: trajectory_error of a translation by d is |d| / diagonal") {
  const auto s = massspring::test::perturbed_cloth<SystemS>();
  const Pts& x = s.positions();
  const Eigen::RowVector3d d(0.03, -0.04, 0.12);  // |d| = 0.13
  const Pts moved = x.rowwise() + d;
  for (const double diagonal : {1.0, 0.64, 2.5})
    CHECK(massspring::trajectory_error(moved, x, diagonal) ==
          doctest::Approx(0.13 / diagonal).epsilon(1e-13));
  CHECK(massspring::trajectory_error(x, x, 1.0) == 0);
  // RMS, not max: one point off by 1 among n gives 1 / sqrt(n).
  Pts one = x;
  one(3, 1) += 1;
  CHECK(massspring::trajectory_error(one, x, 1.0) ==
        doctest::Approx(1 / std::sqrt(double(x.rows()))).epsilon(1e-13));
  // Float against a double reference.
  const Eigen::MatrixX3f movedf = moved.cast<float>();
  CHECK(massspring::trajectory_error(movedf, x, 1.0) == doctest::Approx(0.13).epsilon(1e-5));

  CHECK_THROWS_AS(massspring::trajectory_error(x.topRows(5), x, 1.0), massspring::Error);
  CHECK_THROWS_AS(massspring::trajectory_error(x.leftCols(2), x.leftCols(3), 1.0),
                  massspring::Error);
  for (const double bad : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(),
                           std::numeric_limits<double>::infinity()})
    CHECK_THROWS_AS(massspring::trajectory_error(x, x, bad), massspring::Error);
}

TEST_CASE("accuracy: a converged BackwardEuler step minimises incremental_potential") {
  for (const double beta : {0.0, 0.5}) {
    CAPTURE(beta);
    auto s = massspring::test::perturbed_cloth<SystemS>(5);
    s.add_force(massspring::Gravity<double>(Eigen::Vector3d(0, -9.81, 0)));
    if (beta > 0) s.add_force(massspring::LinearDrag<double>(beta));
    Pts v = Pts::Zero(s.num_points(), 3);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-0.5, 0.5);
    for (int i = 0; i < s.num_points(); ++i)
      if (!s.is_pinned(i)) v.row(i) << u(rng), u(rng), u(rng);
    s.set_velocities(v);
    const Pts x_start = s.positions(), v_start = s.velocities();
    const double h = 1.0 / 30;
    massspring::BackwardEulerOptions<double> o;
    o.tolerance = 1e-13;
    o.iterations = 50;
    massspring::BackwardEuler<SystemS> be(o);
    be.precompute(s, h);
    const auto r = be.step(s);
    REQUIRE(r.ok());
    REQUIRE(r.converged);
    check_minimiser(s, s.positions(), x_start, v_start, h);
    // The step's own report of its objective is the same function (up to its rounding).
    CHECK(r.energy ==
          doctest::Approx(massspring::incremental_potential(s, s.positions(), x_start, v_start, h))
              .epsilon(1e-12));
  }
  const auto s = massspring::test::oscillator<SystemS>(1, 1, 1.0, 0.1);
  CHECK_THROWS_AS(
      massspring::incremental_potential(s, s.positions(), s.positions(), s.velocities(), 0.0),
      massspring::Error);
}

TEST_CASE("accuracy: step_error is 0 at E*, 1 at E(x_0); energy_drift") {
  CHECK(massspring::step_error(-2.5, 4.0, -2.5) == 0);
  CHECK(massspring::step_error(4.0, 4.0, -2.5) == 1);
  CHECK(massspring::step_error(0.75, 4.0, -2.5) == doctest::Approx(0.5).epsilon(1e-15));
  CHECK(std::isnan(massspring::step_error(1.0, 2.0, 2.0)));
  CHECK(massspring::energy_drift(3.0, 1.0, 4.0) == 0.5);
  CHECK(massspring::energy_drift(1.0, 3.0, 4.0) == -0.5);
  CHECK_THROWS_AS(massspring::energy_drift(1.0, 1.0, 0.0), massspring::Error);
  CHECK_THROWS_AS(massspring::energy_drift(1.0, 1.0, std::numeric_limits<double>::quiet_NaN()),
                  massspring::Error);
}

TEST_CASE("reference_solution: the oscillator at T = 1 matches 1 + u0 cos(w t)") {
  // m = 1, k = 4: w = 2; u0 = 0.5: x(t) = 1 + 0.5 cos 2t, v(t) = -sin 2t.
  const auto s = massspring::test::oscillator<SystemS>(1, 4, 1.0, 0.5);
  const auto r = massspring::reference_solution(s, 1.0);
  CHECK_FALSE(r.from_cache);
  CHECK(r.change < 1e-9);
  CHECK(r.change > 0);
  CHECK(r.dt > 0);
  CHECK(r.dt <= 1.0 / 8);
  CHECK(std::abs(r.positions(1, 0) - (1 + 0.5 * std::cos(2.0))) < 1e-8 * 0.5);
  CHECK(std::abs(r.velocities(1, 0) + std::sin(2.0)) < 1e-8 * 1.0);
  CHECK(r.positions.row(0).isZero(0));
  CHECK(r.positions.rightCols(2).isZero(0));
  CHECK(r.diagonal == 1.5);  // the initial box: x from 0 to 1.5
  CHECK(r.initial_energy == doctest::Approx(0.5).epsilon(1e-15));  // k u0^2 / 2
  // The kinetic energy peaks at u = 0 (t = pi/4 < 1): all of the energy, less the steps' miss.
  CHECK(r.kinetic_max == doctest::Approx(0.5).epsilon(1e-3));
  CHECK(r.kinetic_max <= 0.5 * (1 + 1e-12));
}

TEST_CASE("reference_solution: on-disk cache: reused, keyed by end time, truncation ignored") {
  const ScratchDir dir;
  const auto s = massspring::test::oscillator<SystemS>(1, 4, 1.0, 0.5);
  massspring::ReferenceOptions o;
  o.cache_directory = dir.path.string();
  o.key = "oscillator";
  const auto first = massspring::reference_solution(s, 1.0, o);
  CHECK_FALSE(first.from_cache);
  const auto files = dir.files();
  REQUIRE(files.size() == 1);  // the result, no temporary left
  CHECK(files[0].extension() == ".ref");
  CHECK(files[0].filename().string().rfind("oscillator-", 0) == 0);

  const auto second = massspring::reference_solution(s, 1.0, o);
  CHECK(second.from_cache);
  CHECK(second.positions == first.positions);
  CHECK(second.velocities == first.velocities);
  CHECK(second.dt == first.dt);
  CHECK(second.change == first.change);
  CHECK(second.kinetic_max == first.kinetic_max);
  CHECK(second.initial_energy == first.initial_energy);
  CHECK(second.diagonal == first.diagonal);

  // Another end time is another result.
  const auto other = massspring::reference_solution(s, 0.5, o);
  CHECK_FALSE(other.from_cache);
  CHECK(std::abs(other.positions(1, 0) - (1 + 0.5 * std::cos(1.0))) < 1e-8 * 0.5);
  CHECK(dir.files().size() == 2);
  // Another state is another result too.
  auto moved = massspring::test::oscillator<SystemS>(1, 4, 1.0, 0.25);
  CHECK_FALSE(massspring::reference_solution(moved, 1.0, o).from_cache);
  CHECK(dir.files().size() == 3);

  // A truncated file is ignored: computed again (the same numbers) and rewritten whole.
  const auto size = fs::file_size(files[0]);
  fs::resize_file(files[0], size / 2);
  const auto third = massspring::reference_solution(s, 1.0, o);
  CHECK_FALSE(third.from_cache);
  CHECK(third.positions == first.positions);
  CHECK(fs::file_size(files[0]) == size);
  CHECK(massspring::reference_solution(s, 1.0, o).from_cache);
  // So is a file with trailing bytes.
  {
    std::ofstream out(files[0], std::ios::binary | std::ios::app);
    out << 'x';
  }
  CHECK_FALSE(massspring::reference_solution(s, 1.0, o).from_cache);
  CHECK(fs::file_size(files[0]) == size);
}

TEST_CASE("reference_solution: refuses invalid arguments") {
  const auto s = massspring::test::oscillator<SystemS>(1, 4, 1.0, 0.5);
  for (const double bad : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(),
                           std::numeric_limits<double>::infinity()})
    CHECK_THROWS_AS(massspring::reference_solution(s, bad), massspring::Error);
  {
    const ScratchDir dir;
    massspring::ReferenceOptions o;
    o.cache_directory = dir.path.string();  // no key
    CHECK_THROWS_AS(massspring::reference_solution(s, 1.0, o), massspring::Error);
  }
  massspring::ReferenceOptions o;
  o.tolerance = 0;
  CHECK_THROWS_AS(massspring::reference_solution(s, 1.0, o), massspring::Error);
  o = {};
  o.initial_dt = -0.1;
  CHECK_THROWS_AS(massspring::reference_solution(s, 1.0, o), massspring::Error);
  o = {};
  o.max_halvings = 0;
  CHECK_THROWS_AS(massspring::reference_solution(s, 1.0, o), massspring::Error);
  // One halving from h = 1/8 changes the result by ~1e-4, far above 1e-9: no convergence.
  o.max_halvings = 1;
  CHECK_THROWS_AS(massspring::reference_solution(s, 1.0, o), massspring::Error);
}
