#pragma once
/// @file
/// @brief Every 3D collider: the set and its response (contact/colliders/collider_set.hpp), the
/// collider (collider.hpp) and the geometry of boxes and meshes (box_shape.hpp, mesh_shape.hpp),
/// which Collider::box() and Collider::mesh() need.

#include "massspring/contact/colliders/box_shape.hpp"
#include "massspring/contact/colliders/collider.hpp"
#include "massspring/contact/colliders/collider_set.hpp"
#include "massspring/contact/colliders/mesh_shape.hpp"
