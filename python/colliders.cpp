// massspring.Collider (contact/colliders/collider.hpp): plane, sphere, capsule, box, mesh;
// friction, restitution, thickness, pose, velocity, angular velocity; and the system's colliders.
// system.add_collider(c) stores a copy: change a collider in the system with
// system.set_collider(i, c) (system.collider(i) returns a copy), never through a reference that
// a later add_collider could invalidate.

#include "bindings.hpp"

namespace massspring::python {

namespace {

using Collider = contact::Collider<double>;

int check_collider(const System& s, int i) {
  if (i < 0 || i >= s.colliders().size())
    throw Error(
        detail::message("collider index ", i, " out of range [0, ", s.colliders().size(), ")"));
  return i;
}

}  // namespace

void bind_colliders(py::module_& m) {
  py::enum_<contact::ColliderShape>(m, "ColliderShape")
      .value("Plane", contact::ColliderShape::Plane)
      .value("Sphere", contact::ColliderShape::Sphere)
      .value("Capsule", contact::ColliderShape::Capsule)
      .value("Box", contact::ColliderShape::Box)
      .value("Mesh", contact::ColliderShape::Mesh);

  py::class_<Collider> c(m, "Collider", R"doc(
An obstacle the integrators keep the points out of (contact/colliders/collider.hpp). Lengths in m,
velocities in m/s, angular velocities in rad/s. Made by the static methods plane, sphere, capsule,
box and mesh; the set_* methods validate, change the collider and return it (chainable).)doc");
  c.def_static(
       "plane",
       [](const ArrayLike& point, const ArrayLike& normal) {
         return Collider::plane(vector3(point, "plane: point"), vector3(normal, "plane: normal"));
       },
       py::arg("point"), py::arg("normal"), "The half-space on the normal's side is free.")
      .def_static(
          "sphere",
          [](const ArrayLike& center, double radius) {
            return Collider::sphere(vector3(center, "sphere: center"), radius);
          },
          py::arg("center"), py::arg("radius"))
      .def_static(
          "capsule",
          [](const ArrayLike& a, const ArrayLike& b, double radius) {
            return Collider::capsule(vector3(a, "capsule: a"), vector3(b, "capsule: b"), radius);
          },
          py::arg("a"), py::arg("b"), py::arg("radius"))
      .def_static(
          "box",
          [](const ArrayLike& center, const ArrayLike& half_extents, const ArrayLike& wxyz) {
            const Vec q = real_vector(wxyz, "box: rotation (w, x, y, z)", 4);
            return Collider::box(vector3(center, "box: center"),
                                 vector3(half_extents, "box: half_extents"),
                                 Eigen::Vector4d(q(0), q(1), q(2), q(3)));
          },
          py::arg("center"), py::arg("half_extents"),
          py::arg("rotation") = py::make_tuple(1.0, 0.0, 0.0, 0.0),
          "A box; rotation a quaternion (w, x, y, z), normalised.")
      .def_static(
          "mesh",
          [](const ArrayLike& vertices, const ArrayLike& triangles) {
            const AnyMatrix v = real_matrix(vertices, "mesh collider: vertices", 3);
            const IndexMatrix t = index_matrix(triangles, "mesh collider: triangles", 3);
            return Collider::mesh(v, t);
          },
          py::arg("vertices"), py::arg("triangles"),
          "A closed triangle mesh: vertices (v, 3), triangles (t, 3) 0-based.");

  c.def_property_readonly("shape", &Collider::shape);
  c.def(
       "set_friction", [](Collider& k, double mu) -> Collider& { return k.set_friction(mu); },
       py::arg("mu"), py::return_value_policy::reference_internal,
       "Coulomb friction, static = kinetic.")
      .def(
          "set_friction",
          [](Collider& k, double mu_static, double mu_kinetic) -> Collider& {
            return k.set_friction(mu_static, mu_kinetic);
          },
          py::arg("mu_static"), py::arg("mu_kinetic"), py::return_value_policy::reference_internal)
      .def("set_restitution", &Collider::set_restitution, py::arg("e"),
           py::return_value_policy::reference_internal, "Coefficient of restitution in [0, 1].")
      .def("set_thickness", &Collider::set_thickness, py::arg("thickness"),
           py::return_value_policy::reference_internal,
           "Contact distance added to the surface [m].")
      .def(
          "set_pose",
          [](Collider& k, const ArrayLike& rotation, const ArrayLike& translation) -> Collider& {
            return k.set_pose(matrix3(rotation, "pose: rotation"),
                              vector3(translation, "pose: translation"));
          },
          py::arg("rotation"), py::arg("translation"), py::return_value_policy::reference_internal,
          "Rotation (3, 3) and translation [m] of the collider's frame.")
      .def(
          "set_velocity",
          [](Collider& k, const ArrayLike& v) -> Collider& {
            return k.set_velocity(vector3(v, "velocity"));
          },
          py::arg("velocity"), py::return_value_policy::reference_internal)
      .def(
          "set_angular_velocity",
          [](Collider& k, const ArrayLike& w) -> Collider& {
            return k.set_angular_velocity(vector3(w, "angular_velocity"));
          },
          py::arg("angular_velocity"), py::return_value_policy::reference_internal);
  c.def_property_readonly("static_friction", &Collider::static_friction)
      .def_property_readonly("kinetic_friction", &Collider::kinetic_friction)
      .def_property_readonly("restitution", &Collider::restitution)
      .def_property_readonly("thickness", &Collider::thickness)
      .def_property_readonly("radius", &Collider::radius)
      .def_property_readonly("rotation", [](const Collider& k) { return copy_array(k.rotation()); })
      .def_property_readonly("translation",
                             [](const Collider& k) { return copy_array(k.translation(), true); })
      .def_property_readonly("velocity",
                             [](const Collider& k) { return copy_array(k.velocity(), true); })
      .def_property_readonly("angular_velocity", [](const Collider& k) {
        return copy_array(k.angular_velocity(), true);
      });
  c.def("__repr__", [](const Collider& k) {
    return detail::message("Collider.", contact::to_string(k.shape()), "(translation ",
                           detail::format_row(k.translation()), ", friction ", k.static_friction(),
                           "/", k.kinetic_friction(), ", restitution ", k.restitution(),
                           ", thickness ", k.thickness(), ")");
  });

  py::class_<System> system = system_class(m);
  system
      .def(
          "add_collider",
          [](System& s, const Collider& k) {
            check_idle(&s, "add_collider");
            return s.add_collider(k);
          },
          py::arg("collider"), "Adds a copy of the collider; returns its index.")
      .def_property_readonly("num_colliders", [](const System& s) { return s.colliders().size(); })
      .def(
          "collider", [](const System& s, int i) { return s.colliders()[check_collider(s, i)]; },
          py::arg("i"), "A copy of collider i.")
      .def(
          "set_collider",
          [](System& s, int i, const Collider& k) {
            check_idle(&s, "set_collider");
            s.colliders()[check_collider(s, i)] = k;
          },
          py::arg("i"), py::arg("collider"),
          "Replaces collider i (e.g. a copy given a new pose or velocity between steps).")
      .def(
          "collider_impulse",
          [](const System& s, int i) {
            return copy_array(s.colliders().impulse(check_collider(s, i)), true);
          },
          py::arg("i"), "The impulse [N s] collider i gave the points in the last step.")
      .def(
          "clear_colliders",
          [](System& s) {
            check_idle(&s, "clear_colliders");
            s.colliders().clear();
          },
          "Removes every collider.");
}

}  // namespace massspring::python
