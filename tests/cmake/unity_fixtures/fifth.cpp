// A fixture of tests.unity_group_clash: defines first.cpp's function again.
namespace {
double helper(int n) { return 2 * n; }
}  // namespace
