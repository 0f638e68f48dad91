// contact/distance/barycentric.hpp against closed forms: on the right triangle (0,0,0),
// (2,0,0), (0,0,4), the point (x, h, z) projects to coordinates (1 - x/2 - z/4, x/2, z/4)
// whatever its height h; clamped_barycentric() clamps s to [0, 1] and then t to [0, 1 - s].
#include <doctest/doctest.h>

#include <Eigen/Core>
#include <massspring/contact/distance/barycentric.hpp>

namespace barycentric_test {

using V3 = Eigen::Vector3d;
const V3 kA(0, 0, 0), kB(2, 0, 0), kC(0, 0, 4);

TEST_CASE("plane_barycentric: the projection's coordinates, unclamped") {
  for (const V3& p : {V3(0.5, 0.3, 1.0), V3(0.5, -7.0, 1.0), V3(3.0, 0.1, 2.0), V3(-1, 0, -2)}) {
    CAPTURE(p.transpose());
    const auto b = massspring::contact::plane_barycentric<double>(p, kA, kB, kC);
    CHECK(b[1] == doctest::Approx(p.x() / 2));
    CHECK(b[2] == doctest::Approx(p.z() / 4));
    CHECK(b[0] == doctest::Approx(1 - p.x() / 2 - p.z() / 4));
  }
  // A degenerate triangle (three points on a line).
  const auto d = massspring::contact::plane_barycentric<double>(V3(1, 1, 1), kA, kB, V3(4, 0, 0));
  CHECK(d == std::array<double, 3>{1, 0, 0});
}

TEST_CASE("clamped_barycentric: s into [0, 1], then t into [0, 1 - s]") {
  using massspring::contact::clamped_barycentric;
  auto b = clamped_barycentric<double>(V3(0.5, 0, 1.0), kA, kB, kC);  // inside: unchanged
  CHECK(b[1] == doctest::Approx(0.25));
  CHECK(b[2] == doctest::Approx(0.25));
  b = clamped_barycentric<double>(V3(3.0, 0, 2.0), kA, kB, kC);  // s = 1.5 -> 1, t -> 0
  CHECK(b == std::array<double, 3>{0, 1, 0});
  b = clamped_barycentric<double>(V3(1.0, 0, 4.0), kA, kB, kC);  // s = 0.5, t = 1 -> 0.5
  CHECK(b[0] == 0.0);
  CHECK(b[1] == 0.5);
  CHECK(b[2] == 0.5);
  b = clamped_barycentric<double>(V3(-1, 0, -2), kA, kB, kC);  // both negative -> corner a
  CHECK(b == std::array<double, 3>{1, 0, 0});
}

}  // namespace barycentric_test
