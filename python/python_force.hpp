#pragma once
/// @file
/// @brief massspring.PythonForce (python_force.cpp): a force term whose force, and optionally
/// whose Jacobians, come from Python callables. What the other binding files ask of it.

#include <string>

#include "bindings.hpp"

namespace massspring::python {

/// @brief Adds PythonForce and its MassSpringSystem.add_force overload, then the add_force
/// overload that refuses any other object with a TypeError naming the terms there are. Called
/// after bind_forces (every other add_force overload must come first).
void bind_python_force(py::module_& m);

/// @brief "" when every force term of `system` has a Jacobian where it is a PythonForce; else the
/// message refusing `integrator` (which needs dF/dx and dF/dv of every term), naming the first
/// PythonForce given without a jacobian.
std::string python_terms_without_jacobian(const System& system, const char* integrator);

}  // namespace massspring::python
