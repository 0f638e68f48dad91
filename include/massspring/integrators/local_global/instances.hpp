#pragma once
/// @file
/// @brief The explicit instantiations that MASSSPRING_EXTERN_TEMPLATES declares (see the end of
/// local_global/fast_mass_spring.hpp): FastMassSpring of MassSpringSystem<double, Sparse>,
/// <float, Sparse>, <double, Dense> and <float, Dense>, every member.
///
/// Include this header in exactly one translation unit of a program whose other translation units
/// define MASSSPRING_EXTERN_TEMPLATES, and compile that unit with the same compiler, flags and
/// configuration macros as the others (NDEBUG, EIGEN_*, MASSSPRING_NO_SIMD, -fopenmp): the program
/// then holds one copy of the solver, compiled once. Including it in two units of one program, or
/// compiling it differently from the units that use it, breaks the one-definition rule (C++17
/// [basic.def.odr], [temp.explicit]). A program without MASSSPRING_EXTERN_TEMPLATES needs nothing
/// of this: every unit instantiates what it uses, as with any header-only template.

#include "massspring/integrators/local_global/fast_mass_spring.hpp"

namespace massspring {

template class FastMassSpring<MassSpringSystem<double, Sparse>>;
template class FastMassSpring<MassSpringSystem<float, Sparse>>;
template class FastMassSpring<MassSpringSystem<double, Dense>>;
template class FastMassSpring<MassSpringSystem<float, Dense>>;

}  // namespace massspring
