// diagnostics/strain.hpp: |l/l0 - 1| per spring against hand-computed lengths, rest length 0, and
// a face's strain as the mean over the springs along its boundary.
#include <doctest/doctest.h>

#include <massspring/diagnostics/strain.hpp>
#include <vector>

TEST_CASE("strain: per spring |l/l0 - 1| (0 for a rest length of 0), per face the boundary mean") {
  massspring::Points<double> x(4, 3);
  x << 0, 0, 0,   //
      1.5, 0, 0,  // 0-1: length 1.5
      1.5, 2, 0,  // 1-2: length 2
      0, 2, 0;
  massspring::Edges springs(4, 2);
  springs << 0, 1, 1, 2, 2, 0, 2, 3;
  Eigen::VectorXd rest(4);
  rest << 1.0, 2.5, 2.5, 0.0;  // 2-0: length 2.5
  const Eigen::VectorXd s = massspring::spring_strain(x, springs, rest);
  CHECK(s(0) == doctest::Approx(0.5));
  CHECK(s(1) == doctest::Approx(0.2));
  CHECK(s(2) == doctest::Approx(0.0));
  CHECK(s(3) == 0.0);  // rest length 0: no strain

  // triangle 0 1 2: springs 0, 1, 2 along it; quad 0 1 2 3: springs 0, 1, 3 (3-0 is none);
  // triangle 0 3 1: only 1-0 (spring 0, either direction) along it
  const std::vector<std::vector<int>> faces = {{0, 1, 2}, {0, 1, 2, 3}, {0, 3, 1}};
  const auto boundary = massspring::face_boundary_springs(faces, springs);
  CHECK(boundary[0] == std::vector<int>{0, 1, 2});
  CHECK(boundary[1] == std::vector<int>{0, 1, 3});
  CHECK(boundary[2] == std::vector<int>{0});
  const Eigen::VectorXd f = massspring::face_strain(boundary, s);
  CHECK(f(0) == doctest::Approx((0.5 + 0.2 + 0.0) / 3));
  CHECK(f(1) == doctest::Approx((0.5 + 0.2 + 0.0) / 3));
  CHECK(f(2) == doctest::Approx(0.5));
  CHECK(massspring::face_strain({{}}, s)(0) == 0.0);
}
