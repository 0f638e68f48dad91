// A fixture of tests.unity_group_clash: every name here may share a unity group with first.cpp.
#define TOLERANCE 1e-12

namespace {
using Real = double;  // the same alias
namespace chrono = std::chrono;
double helper(double x) { return x; }  // an overload
struct Local {};                       // first.cpp's is inside a TEST_CASE
struct Decoy {};                       // first.cpp's is inside a string
struct Hidden {};                      // first.cpp's is inside comments
struct AlsoHidden {};
double local_value = 3;
}  // namespace

namespace second_only {
double in_named = 2;  // another namespace than first.cpp's
}  // namespace second_only
