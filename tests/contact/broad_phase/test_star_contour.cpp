// contact/broad_phase/star_contour.hpp. Oracles: convex polygons about an inner point (star-
// shaped in closed form), their mirror images (clockwise) and spirals (not star-shaped); and the
// triple product a . ((p(t) - c(t)) x (q(t) - c(t))) computed directly at 1001 times of the step,
// positive throughout whenever the loop is accepted.
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <massspring/contact/broad_phase/star_contour.hpp>
#include <random>
#include <vector>

namespace {
using massspring::contact::loop_stays_star_shaped;
using Pts = massspring::Points<double>;
using V3 = Eigen::Vector3d;

// n points on a circle of radius r about the origin in the x-y plane, counterclockwise, as rows
// turned by the rotation q and shifted by s.
Pts polygon(int n, double r, const Eigen::Matrix3d& q, const V3& s) {
  Pts x(n, 3);
  for (int k = 0; k < n; ++k) {
    const double angle = 2 * M_PI * k / n;
    x.row(k) = (q * V3(r * std::cos(angle), r * std::sin(angle), 0) + s).transpose();
  }
  return x;
}

std::vector<int> in_order(int n) {
  std::vector<int> loop(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) loop[std::size_t(k)] = k;
  return loop;
}

// Whether the triple product stays positive at 1001 times: apart from the library's Bernstein
// test.
bool positive_throughout(const Pts& x0, const Pts& x1, const V3& a, const V3& c0, const V3& c1,
                         const std::vector<int>& loop) {
  for (int s = 0; s <= 1000; ++s) {
    const double t = s / 1000.0;
    const V3 c = (1 - t) * c0 + t * c1;
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const int i = loop[k], j = loop[(k + 1) % loop.size()];
      const V3 p = ((1 - t) * x0.row(i) + t * x1.row(i)).transpose() - c;
      const V3 q = ((1 - t) * x0.row(j) + t * x1.row(j)).transpose() - c;
      if (!(a.dot(p.cross(q)) > 0)) return false;
    }
  }
  return true;
}
}  // namespace

TEST_CASE("loop_stays_star_shaped: a convex polygon moving rigidly, seen from above and below") {
  const Eigen::Matrix3d q = Eigen::AngleAxisd(0.7, V3(1, 2, 3).normalized()).toRotationMatrix();
  const V3 up = q * V3(0, 0, 1);
  for (const int n : {3, 4, 9, 40}) {
    const Pts x0 = polygon(n, 0.05, q, V3(0.1, -0.2, 0.3));
    const Pts x1 = x0.rowwise() + Eigen::RowVector3d(0.01, 0.02, -0.01);
    const V3 c0 = q * V3(0.01, -0.005, 0) + V3(0.1, -0.2, 0.3);  // inside
    const V3 c1 = c0 + V3(0.01, 0.02, -0.01);
    std::vector<int> loop = in_order(n);
    CAPTURE(n);
    CHECK(loop_stays_star_shaped(x0, x1, up, c0, c1, loop.data(), n));
    CHECK_FALSE(loop_stays_star_shaped(x0, x1, V3(-up), c0, c1, loop.data(), n));
    // The centre outside the polygon: not star-shaped about it.
    const V3 out = q * V3(0.08, 0, 0) + V3(0.1, -0.2, 0.3);
    CHECK_FALSE(
        loop_stays_star_shaped(x0, x1, up, out, V3(out + V3(0.01, 0.02, -0.01)), loop.data(), n));
    // Traversed clockwise: refused.
    std::reverse(loop.begin(), loop.end());
    CHECK_FALSE(loop_stays_star_shaped(x0, x1, up, c0, c1, loop.data(), n));
  }
}

TEST_CASE("loop_stays_star_shaped: a half turn in the plane passes the centre mid-step") {
  // Each point moves straight to its opposite: star-shaped at both ends, every point at the
  // centre at t = 1/2.
  const Pts x0 = polygon(6, 0.05, Eigen::Matrix3d::Identity(), V3::Zero());
  const Pts x1 = -x0;
  const std::vector<int> loop = in_order(6);
  const V3 origin = V3::Zero();
  CHECK_FALSE(loop_stays_star_shaped(x0, x1, V3(0, 0, 1), origin, origin, loop.data(), 6));
  CHECK_FALSE(positive_throughout(x0, x1, V3(0, 0, 1), origin, origin, loop));
}

TEST_CASE("loop_stays_star_shaped: accepted loops stay positive at every time checked") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  int accepted = 0, refused = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    // A wobbly star-shaped polygon about the origin, each point moved at random; sizes from
    // small to a jump past the centre.
    const int n = 3 + trial % 12;
    Pts x0(n, 3), x1(n, 3);
    const double reach = 0.002 * (1 + trial % 30);
    for (int k = 0; k < n; ++k) {
      const double angle = 2 * M_PI * (k + 0.3 * u(rng)) / n, r = 0.05 * (1 + 0.5 * u(rng));
      x0.row(k) << r * std::cos(angle), r * std::sin(angle), 0.01 * u(rng);
      x1.row(k) = x0.row(k) + reach * Eigen::RowVector3d(u(rng), u(rng), u(rng));
    }
    const V3 c0(0.005 * u(rng), 0.005 * u(rng), 0), c1 = c0 + reach * V3(u(rng), u(rng), 0);
    const V3 a = V3(0.2 * u(rng), 0.2 * u(rng), 1).normalized();
    const std::vector<int> loop = in_order(n);
    if (loop_stays_star_shaped(x0, x1, a, c0, c1, loop.data(), n)) {
      ++accepted;
      CAPTURE(trial);
      CHECK(positive_throughout(x0, x1, a, c0, c1, loop));
    } else {
      ++refused;
    }
  }
  CHECK(accepted > 300);
  CHECK(refused > 300);
}

// The loop's turns about c at t = 0, from the angles of its edges (apart from the library's
// count of crossings of a ray).
double turns_about(const Pts& x, const V3& c, const std::vector<int>& loop) {
  double angle = 0;
  for (std::size_t k = 0; k < loop.size(); ++k) {
    const V3 p = x.row(loop[k]).transpose() - c;
    const V3 q = x.row(loop[(k + 1) % loop.size()]).transpose() - c;
    angle += std::atan2(p.cross(q).z(), p.head<2>().dot(q.head<2>()));
  }
  return angle / (2 * M_PI);
}

TEST_CASE("loop_stays_star_shaped: a loop that turns twice about the centre is refused") {
  // Points on a circle visited twice around (a pentagram: 144 degrees per edge; eight points at
  // 90 degrees per edge, two circles of radii 0.05 and 0.06): every edge turns counterclockwise
  // by less than a half turn, as a star-shaped loop's do, but the loop winds twice, as the
  // boundary of a fan folded over itself in a spiral does.
  for (const int n : {5, 8}) {
    Pts x0(n, 3);
    for (int k = 0; k < n; ++k) {
      const double angle = (n == 5 ? 4 * M_PI / 5 : M_PI / 2) * k;
      const double r = n == 5 ? 0.05 : 0.05 + 0.01 * (k / 4);
      x0.row(k) << r * std::cos(angle), r * std::sin(angle), 0.001 * k;
    }
    const Pts x1 = x0.rowwise() + Eigen::RowVector3d(0.003, -0.002, 0.001);
    const V3 c0 = V3::Zero(), c1(0.003, -0.002, 0.001);
    const std::vector<int> loop = in_order(n);
    CAPTURE(n);
    REQUIRE(positive_throughout(x0, x1, V3(0, 0, 1), c0, c1, loop));
    REQUIRE(std::abs(turns_about(x0, c0, loop) - 2) < 1e-9);
    CHECK_FALSE(loop_stays_star_shaped(x0, x1, V3(0, 0, 1), c0, c1, loop.data(), n));
  }
  // The same circle visited once: accepted.
  const Pts once = polygon(5, 0.05, Eigen::Matrix3d::Identity(), V3::Zero());
  const std::vector<int> loop = in_order(5);
  const V3 origin = V3::Zero();
  REQUIRE(std::abs(turns_about(once, origin, loop) - 1) < 1e-9);
  CHECK(loop_stays_star_shaped(once, once, V3(0, 0, 1), origin, origin, loop.data(), 5));
}
