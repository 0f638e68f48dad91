// A fixture of tests.unity_group_clash: clashes with first.cpp's macro.
#define TOLERANCE 1e-9
