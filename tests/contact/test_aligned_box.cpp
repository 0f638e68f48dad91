// contact/aligned_box.hpp against closed forms: growth from empty, union, overlap (touching
// counts) and the squared distance from a point (to a face, an edge, a corner; 0 inside).
#include <doctest/doctest.h>

#include <Eigen/Core>
#include <massspring/contact/aligned_box.hpp>

TEST_CASE("AlignedBox3: extend, merged, overlaps and squared_distance") {
  using Box3 = massspring::contact::AlignedBox3<double>;
  using Point = Eigen::Vector3d;
  Box3 b = Box3::empty();
  CHECK_FALSE(b.overlaps(Box3{Point(-1e300, -1e300, -1e300), Point(1e300, 1e300, 1e300)}));
  b.extend(Point(0, 0, 0));
  b.extend(Point(1, 2, -1));
  CHECK(b.lo == Point(0, 0, -1));
  CHECK(b.hi == Point(1, 2, 0));
  const Box3 far{Point(3, 0, 0), Point(4, 1, 1)};
  CHECK_FALSE(b.overlaps(far));
  CHECK_FALSE(far.overlaps(b));
  CHECK(b.overlaps(Box3{Point(1, 2, 0), Point(5, 5, 5)}));  // a shared corner
  const Box3 both = b.merged(far);
  CHECK(both.lo == Point(0, 0, -1));
  CHECK(both.hi == Point(4, 2, 1));
  CHECK(b.squared_distance(Point(0.5, 1, -0.5)) == 0);  // inside
  CHECK(b.squared_distance(Point(0.5, 3, -0.5)) == 1);  // 1 above the face y = 2
  CHECK(b.squared_distance(Point(2, 3, -0.5)) == 2);    // off the edge x = 1, y = 2
  CHECK(b.squared_distance(Point(2, 3, 1)) == 3);       // off the corner (1, 2, 0)
}
