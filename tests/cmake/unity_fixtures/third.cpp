// A fixture of tests.unity_group_clash: clashes with first.cpp's struct Fixture.
namespace {

int Fixture = 3;
}  // namespace
