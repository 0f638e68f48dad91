// massspring.MassSpringSystem: MassSpringSystem<double, Sparse> with the C++ names. A C++ getter
// `x()` is the property `x`; a C++ setter `set_x(v)` is both the method and the assignment
// `x = v`. Positions and velocities read as views (no copy); the rest read as copies.

#include <algorithm>
#include <vector>

#include "bindings.hpp"

namespace massspring::python {

namespace {

// The system, after checking that no step in another thread is using it (bindings.hpp, InUse).
System& idle(System& s, const char* what) {
  check_idle(&s, what);
  return s;
}

// sys.positions = x and sys.set_positions(x): any (rows, 3) real array; the library checks the
// row count and finiteness and names the point.
void set_positions(System& s, const py::handle& x) {
  idle(s, "set_positions").set_positions(real_matrix(x, "positions", 3));
}
void set_velocities(System& s, const py::handle& v) {
  idle(s, "set_velocities").set_velocities(real_matrix(v, "velocities", 3));
}

// A new (k, 3) int32 numpy array holding a copy of `triangles` (row-major, as numpy's).
py::array_t<int> copy_triangles(const Triangles& triangles) {
  py::array_t<int> out({triangles.rows(), Eigen::Index(3)});
  std::copy(triangles.data(), triangles.data() + triangles.size(), out.mutable_data());
  return out;
}

// sys.set_surface(triangles): an (n, 3) integer array; the library names a bad triangle.
void set_surface(System& s, const py::handle& t) {
  const IndexMatrix triangles = index_matrix(t, "surface", 3);
  idle(s, "set_surface").set_surface(Triangles(triangles));
}

using SystemClass = py::class_<System>;

// MassSpringSystem(rest_positions, springs, mass, stiffness, rest_lengths=None, damping=None).
void bind_construction(SystemClass& c) {
  c.def(py::init([](const py::handle& v, const py::handle& e, const py::handle& mass,
                    const py::handle& stiffness, const py::handle& rest_lengths,
                    const py::handle& damping) {
          const AnyMatrix points = real_matrix(v, "rest positions", 3);
          const IndexMatrix springs = index_matrix(e, "springs", 2);
          const Vec masses = real_vector(mass, "masses", points.rows(), true);
          const Vec k = real_vector(stiffness, "stiffness", springs.rows(), true);
          System s(points, springs, masses, k);
          if (!rest_lengths.is_none())
            s.set_rest_lengths(real_vector(rest_lengths, "rest lengths", springs.rows()));
          if (!damping.is_none()) s.set_damping(real_vector(damping, "damping", springs.rows()));
          return s;
        }),
        py::arg("rest_positions"), py::arg("springs"), py::arg("mass"), py::arg("stiffness"),
        py::arg("rest_lengths") = py::none(), py::arg("damping") = py::none());
}

// num_points, num_springs, num_pinned.
void bind_sizes(SystemClass& c) {
  c.def_property_readonly("num_points", &System::num_points, "Number of points n.");
  c.def_property_readonly("num_springs", &System::num_springs, "Number of springs m.");
  c.def_property_readonly("num_pinned", &System::num_pinned, "Number of pinned points.");
}

// The model: rest positions and springs (read only), masses, stiffness, rest lengths and damping
// (properties and set_* methods); copies, as the library may reallocate them.
void bind_model(SystemClass& c) {
  c.def_property_readonly(
      "rest_positions", [](const System& s) { return copy_array(s.rest_positions()); },
      "(n, 3) rest positions [m] (a copy).");
  c.def_property_readonly(
      "springs", [](const System& s) { return copy_edges(s.springs()); },
      "(m, 2) point indices (a copy).");
  c.def_property(
      "masses", [](const System& s) { return copy_array(s.masses(), true); },
      [](System& s, const py::handle& x) {
        idle(s, "set_masses").set_masses(real_vector(x, "masses", s.num_points(), true));
      },
      "(n,) masses [kg] (a copy); assigning refactorizes at the next implicit step.");
  c.def_property_readonly(
      "inverse_masses", [](const System& s) { return copy_array(s.inverse_masses(), true); },
      "(n,) inverse masses [1/kg] (a copy): 1 / m, and 0 at a pinned point (immobile).");
  c.def_property(
      "stiffness", [](const System& s) { return copy_array(s.stiffness(), true); },
      [](System& s, const py::handle& x) {
        idle(s, "set_stiffness").set_stiffness(real_vector(x, "stiffness", s.num_springs(), true));
      },
      "(m,) stiffness [N/m] (a copy).");
  c.def_property(
      "rest_lengths", [](const System& s) { return copy_array(s.rest_lengths(), true); },
      [](System& s, const py::handle& x) {
        idle(s, "set_rest_lengths")
            .set_rest_lengths(real_vector(x, "rest lengths", s.num_springs(), true));
      },
      "(m,) rest lengths [m] (a copy); free to change between steps.");
  c.def_property(
      "damping", [](const System& s) { return copy_array(s.damping(), true); },
      [](System& s, const py::handle& x) {
        idle(s, "set_damping").set_damping(real_vector(x, "damping", s.num_springs(), true));
      },
      "(m,) damping along each spring [N s/m] (a copy).");
  c.def(
      "set_masses",
      [](System& s, const py::handle& x) {
        idle(s, "set_masses").set_masses(real_vector(x, "masses", s.num_points(), true));
      },
      py::arg("masses"));
  c.def(
      "set_stiffness",
      [](System& s, const py::handle& x) {
        idle(s, "set_stiffness").set_stiffness(real_vector(x, "stiffness", s.num_springs(), true));
      },
      py::arg("stiffness"));
  c.def(
      "set_rest_lengths",
      [](System& s, const py::handle& x) {
        idle(s, "set_rest_lengths")
            .set_rest_lengths(real_vector(x, "rest lengths", s.num_springs(), true));
      },
      py::arg("rest_lengths"));
  c.def(
      "set_damping",
      [](System& s, const py::handle& x) {
        idle(s, "set_damping").set_damping(real_vector(x, "damping", s.num_springs(), true));
      },
      py::arg("damping"));
}

// pin (a point, a point and its target, a list), unpin, set_pin_target, and the pins read back.
void bind_pins(SystemClass& c) {
  c.def(
      "pin", [](System& s, int i) { idle(s, "pin").pin(i); }, py::arg("i"),
      "Pins point i at its rest position.");
  c.def(
      "pin",
      [](System& s, int i, const py::handle& t) {
        idle(s, "pin").pin(i, vector3(t, "pin target"));
      },
      py::arg("i"), py::arg("target"), "Pins point i at target [m] (or moves its target).");
  c.def(
      "pin",
      [](System& s, const py::handle& points) {
        // a lone number that is not an int (1.0, numpy's float64): say what pin takes
        if (py::isinstance<py::float_>(points) ||
            (py::hasattr(points, "ndim") && py::int_(points.attr("ndim")).cast<int>() == 0 &&
             !py::isinstance<py::int_>(points)))
          throw Error("pin: expected a point index (an int) or a list of them, got " +
                      std::string(py::repr(points)) + " (" +
                      std::string(py::str(points.get_type().attr("__name__"))) + ")");
        idle(s, "pin").pin(index_vector(points, "pin"));
      },
      py::arg("points"), "Pins each listed point at its rest position.");
  c.def(
      "unpin", [](System& s, int i) { idle(s, "unpin").unpin(i); }, py::arg("i"),
      "Releases point i (no-op when not pinned).");
  c.def(
      "set_pin_target",
      [](System& s, int i, const py::handle& t) {
        idle(s, "set_pin_target").set_pin_target(i, vector3(t, "pin target"));
      },
      py::arg("i"), py::arg("target"), "Moves the target of pinned point i [m]; free.");
  c.def_property_readonly(
      "pinned", [](const System& s) { return s.pinned(); }, "Pinned point indices, ascending.");
  c.def_property_readonly(
      "pin_targets", [](const System& s) { return copy_array(s.pin_targets()); },
      "(p, 3) targets [m], row r for point pinned[r] (a copy).");
  c.def("is_pinned", &System::is_pinned, py::arg("i"));
  c.def("pin_row", &System::pin_row, py::arg("i"));
}

// positions and velocities: views of the system's own buffers; assigned whole (checked).
void bind_state(SystemClass& c) {
  c.def_property(
      "positions",
      [](const py::object& self) {
        check_idle(&self.cast<const System&>(), "positions");  // a step may run elsewhere
        return points_view(self.cast<const System&>().positions(), self);
      },
      &set_positions,
      "(n, 3) positions [m]: a read-only view (no copy) that follows the state; "
      "assign a whole array to set them (checked).");
  c.def_property(
      "velocities",
      [](const py::object& self) {
        check_idle(&self.cast<const System&>(), "velocities");
        return points_view(self.cast<const System&>().velocities(), self);
      },
      &set_velocities,
      "(n, 3) velocities [m/s]: a read-only view (no copy) that follows the state; "
      "assign a whole array to set them (checked).");
  c.def("set_positions", &set_positions, py::arg("positions"));
  c.def("set_velocities", &set_velocities, py::arg("velocities"));
}

// The force terms' names and clear_forces (add_force is added by forces.cpp); has_spring_damping
// and revision.
void bind_force_list(SystemClass& c) {
  c.def_property_readonly(
      "forces",
      [](const System& s) {
        std::vector<std::string> names;
        for (int k = 0; k < s.forces().size(); ++k) names.emplace_back(s.forces()[k].name);
        return names;
      },
      "The names of the force terms added with add_force, in order.");
  c.def(
      "clear_forces", [](System& s) { idle(s, "clear_forces").clear_forces(); },
      "Removes every added force term.");
  c.def_property_readonly("has_spring_damping", &System::has_spring_damping);
  c.def_property_readonly("revision", &System::revision,
                          "Changes whenever masses, stiffness, springs, pins or forces change.");
}

// massspring.SelfCollision: the parameters of self-collision (contact/self_collision.hpp).
void bind_self_collision_parameters(py::module_& m) {
  using SelfCollision = contact::SelfCollision<double>;
  py::class_<SelfCollision>(m, "SelfCollision", R"doc(
Self-collision parameters (contact/self_collision.hpp).

SelfCollision(thickness=0.004, friction=0.2)
  thickness  the distance at which layers of the surface repel [m], > 0
  friction   Coulomb's coefficient between layers, >= 0
Out-of-range values raise massspring.Error.)doc")
      .def(py::init([](double thickness, double friction) {
             SelfCollision p;
             p.thickness = thickness;
             p.friction = friction;
             p.validate();
             return p;
           }),
           py::arg("thickness") = SelfCollision{}.thickness,
           py::arg("friction") = SelfCollision{}.friction)
      .def_readonly("thickness", &SelfCollision::thickness, "[m]")
      .def_readonly("friction", &SelfCollision::friction, "Coulomb's coefficient")
      .def("__eq__",
           [](const SelfCollision& a, const SelfCollision& b) {
             return a.thickness == b.thickness && a.friction == b.friction;
           })
      .def("__repr__", [](const SelfCollision& p) {
        return detail::message("SelfCollision(thickness=", p.thickness, ", friction=", p.friction,
                               ")");
      });
}

// The surface (set_surface, surface, surface_edges) and self-collision on it.
void bind_surface(SystemClass& c) {
  using SelfCollision = contact::SelfCollision<double>;
  c.def("set_surface", &set_surface, py::arg("triangles"),
        "Sets the surface: an (n, 3) integer array of point indices, 0-based (an empty array "
        "removes it). A triangle out of range, with a repeated point or of zero area raises "
        "massspring.Error naming it; nothing changes then.");
  c.def_property_readonly(
      "surface", [](const System& s) { return copy_triangles(s.surface()); },
      "(k, 3) surface triangles, 0-based (a copy; empty when none was set).");
  c.def_property_readonly(
      "surface_edges", [](const System& s) { return copy_edges(s.surface_edges()); },
      "(e, 2) the surface's edges, each once as (i, j) with i < j, ascending (a copy).");
  c.def(
      "set_self_collision",
      [](System& s, double thickness, double friction) {
        SelfCollision p;
        p.thickness = thickness;
        p.friction = friction;
        idle(s, "set_self_collision").set_self_collision(p);
      },
      py::arg("thickness") = SelfCollision{}.thickness,
      py::arg("friction") = SelfCollision{}.friction,
      "Turns self-collision of the surface on: thickness [m] > 0, friction >= 0. Needs a "
      "surface (set_surface, or a scene's faces); raises massspring.Error otherwise.");
  c.def(
      "clear_self_collision",
      [](System& s) { idle(s, "clear_self_collision").clear_self_collision(); },
      "Turns self-collision off.");
  c.def_property_readonly(
      "self_collision", [](const System& s) { return s.self_collision(); },
      "The SelfCollision parameters, or None when it is off.");
}

// copy, __copy__, __deepcopy__ (the model, the state, the force terms, the colliders: not shared
// with the original) and __repr__.
void bind_copies(SystemClass& c) {
  c.def(
      "copy",
      [](const System& s) {
        check_idle(&s, "copy");
        return System(s);
      },
      "An independent copy (model, state, force terms, colliders), e.g. to run two solvers from "
      "one state.");
  c.def("__copy__", [](const System& s) {
    check_idle(&s, "copy");
    return System(s);
  });
  c.def(
      "__deepcopy__",
      [](const System& s, const py::dict&) {
        check_idle(&s, "copy");
        return System(s);
      },
      py::arg("memo"));
  c.def("__repr__", [](const System& s) {
    return detail::message("MassSpringSystem(", s.num_points(), " points, ", s.num_springs(),
                           " springs, ", s.num_pinned(), " pinned, ", s.forces().size(),
                           " force terms, ", s.colliders().size(), " colliders",
                           s.surface().rows()
                               ? detail::message(", ", s.surface().rows(), " surface triangles")
                               : std::string(),
                           s.self_collision() ? ", self-collision" : "", ")");
  });
}

}  // namespace

void bind_system(py::module_& m) {
  py::class_<System> c(m, "MassSpringSystem", R"doc(
A network of point masses joined by springs (MassSpringSystem<double, Sparse>).

MassSpringSystem(rest_positions, springs, mass, stiffness, rest_lengths=None, damping=None)
  rest_positions  (n, 3) float64 [m]; positions start here, at rest
  springs         (m, 2) integer point indices, 0-based; no self or duplicate springs
  mass            one mass for every point, or (n,) masses [kg], each > 0
  stiffness       one stiffness for every spring, or (m,) [N/m], each >= 0
  rest_lengths    (m,) [m], default: the distances between the rest positions
  damping         (m,) damping along each spring [N s/m], default 0
Invalid input raises massspring.Error and builds nothing.)doc");
  bind_construction(c);
  bind_sizes(c);
  bind_model(c);
  bind_pins(c);
  bind_state(c);
  bind_force_list(c);
  bind_self_collision_parameters(m);  // before the methods that take or return it
  bind_surface(c);
  bind_copies(c);
}

}  // namespace massspring::python
