// A fixture of tests.unity_group_clash (tests/cmake/unity_groups_test.cmake), never compiled:
// the names second.cpp may repeat and third.cpp, fourth.cpp and fifth.cpp clash on, among decoys
// the scan must not take for file-scope declarations.
#include <string>

#define TOLERANCE 1e-12

namespace {
using Real = double;
namespace chrono = std::chrono;

struct Fixture {
  int size = 0;
  void grow() { ++size; }
};

double helper(int n) { return n; }

const char* kText = R"(struct Decoy { int x; };)";
/* struct Hidden { int y; }; */
// struct AlsoHidden {
}  // namespace

namespace first_only {
double in_named = 1;
}  // namespace first_only

TEST_CASE("a test") {
  struct Local {};
  double local_value = 2;
}
