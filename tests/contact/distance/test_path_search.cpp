// contact/distance/path_search.hpp: golden-section search finds the minimiser of smooth, kinked
// and monotone functions on [0, 1], and a path's nearest point to a sphere's centre as the closed
// form of path_sphere.hpp gives it; bisection finds the last point where a predicate holds.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <massspring/contact/distance/path_search.hpp>
#include <massspring/contact/distance/path_sphere.hpp>
#include <random>

using massspring::contact::bisect_last;
using massspring::contact::golden_section_minimum;

TEST_CASE("golden-section search finds the minimiser of unimodal functions on [0, 1]") {
  // A smooth minimum is flat: f is known to rounding, s to about sqrt(eps).
  const auto [s_q, f_q] =
      golden_section_minimum<double>([](double s) { return (s - 0.3) * (s - 0.3) + 1; });
  CHECK(std::abs(s_q - 0.3) < 1e-7);
  CHECK(std::abs(f_q - 1) < 1e-14);
  // A kink is sharp: 60 steps of 0.618 leave a bracket of 3e-13.
  const auto [s_v, f_v] =
      golden_section_minimum<double>([](double s) { return std::abs(s - 0.7); });
  CHECK(std::abs(s_v - 0.7) < 1e-12);
  CHECK(f_v < 1e-12);
  // Monotone: the minimum is at an end.
  CHECK(golden_section_minimum<double>([](double s) { return s; }).first < 1e-12);
  CHECK(golden_section_minimum<double>([](double s) { return -s; }).first > 1 - 1e-12);
  // Fewer steps, a wider bracket: 10 steps leave 0.618^10 = 8e-3.
  const double s10 =
      golden_section_minimum<double>([](double s) { return std::abs(s - 0.7); }, 10).first;
  CHECK(std::abs(s10 - 0.7) < 0.0082);
  CHECK(std::abs(s10 - 0.7) > 1e-6);
}

TEST_CASE("golden-section search on a path past a sphere agrees with the closed form") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-2, 2);
  for (int trial = 0; trial < 200; ++trial) {
    const massspring::Vector3<double> a(u(rng), u(rng), u(rng)), d(u(rng), u(rng), u(rng));
    const double s = massspring::contact::path_nearest_to_origin<double>(a, d);
    const auto [s_g, f_g] =
        golden_section_minimum<double>([&](double t) { return (a + t * d).norm() - 0.5; });
    CAPTURE(trial);
    CHECK(std::abs(f_g - ((a + s * d).norm() - 0.5)) < 1e-12);
    CHECK(std::abs(s_g - s) < 1e-6);
  }
}

TEST_CASE("bisection finds the last point where a predicate holds") {
  int calls = 0;
  const auto below_half = [&](double s) {
    ++calls;
    return s * s <= 0.5;
  };
  const double s = bisect_last<double>(below_half, 0.0, 1.0);
  CHECK(s * s <= 0.5);
  CHECK(std::abs(s - std::sqrt(0.5)) < 1e-14);
  CHECK(calls == 48);
  // An empty bracket is returned as it is, with no evaluation.
  calls = 0;
  CHECK(bisect_last<double>(below_half, 0.25, 0.25) == 0.25);
  CHECK(calls == 0);
  // The bracket stops at machine epsilon: a change near 1e-3 takes about 52 halvings, not 480.
  calls = 0;
  const double t = bisect_last<double>(
      [&](double x) {
        ++calls;
        return x < 1e-3;
      },
      0.0, 1.0, 480);
  CHECK(t < 1e-3);
  CHECK(1e-3 - t <= 4 * std::numeric_limits<double>::epsilon());
  CHECK(calls <= 53);
}
