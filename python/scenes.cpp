// Generated scenes (scene/cloth.hpp, chain.hpp, net.hpp) and make_system (scene/make_system.hpp):
// the C++ generators' options with their field names, a SceneDescription to read or change, and
// the system made from it exactly as massspring-simulate --generate makes it.

#include <type_traits>

#include "bindings.hpp"

namespace massspring::python {

namespace {

using Scene = SceneDescription<double>;

// Options(**fields): a default T with the named fields set through their Python attributes (so
// each is converted and checked as an assignment is); an unknown name is a TypeError listing the
// fields.
template <class T>
T from_fields(const py::kwargs& fields, const char* type) {
  T value{};
  const py::object self = py::cast(&value, py::return_value_policy::reference);
  for (const auto& [key, field] : fields) {
    const std::string name = py::str(key);
    if (name.rfind('_', 0) == 0 || !py::hasattr(self, name.c_str())) {
      std::string known;
      for (const py::handle a : py::module_::import("builtins").attr("dir")(self)) {
        const std::string attribute = py::str(a);
        if (attribute.rfind('_', 0) != 0) known += (known.empty() ? "" : ", ") + attribute;
      }
      throw py::type_error(std::string(type) + "() has no field \"" + name +
                           "\" (fields: " + known + ")");
    }
    py::setattr(self, key, field);
  }
  return value;
}

// An optional point [m] of a generator's options: None or three numbers. `member` may be one of
// a base of T (ScenePlacement's origin and center).
template <class T, class Owner>
void optional_point(py::class_<T>& c, const char* name, std::optional<Vec3> Owner::*member,
                    const char* doc) {
  static_assert(std::is_base_of_v<Owner, T>, "member must be T's or a base's");
  c.def_property(
      name,
      [member](const T& o) -> py::object {
        if (!(o.*member)) return py::none();
        return copy_array(*(o.*member), true);
      },
      [member, name](T& o, const py::handle& v) {
        if (v.is_none())
          (o.*member).reset();
        else
          o.*member = vector3(v, name);
      },
      doc);
}

}  // namespace

void bind_scenes(py::module_& m) {
  py::class_<Scene>(m, "SceneDescription",
                    "A scene before it is a system: vertices [m], faces, edges, pinned points, "
                    "stiffness [N/m], mass [kg] (None: Voronoi areas), colliders, self-collision.")
      .def(py::init<>())
      .def_property(
          "vertices", [](const Scene& s) { return copy_array(s.vertices); },
          [](Scene& s, const py::handle& v) { s.vertices = real_matrix(v, "vertices", 3); },
          "(n, 3) rest positions [m] (a copy; assign a whole array).")
      .def_readwrite("faces", &Scene::faces, "Polygons, 0-based; their sides become springs.")
      .def_property(
          "edges", [](const Scene& s) { return copy_edges(s.edges); },
          [](Scene& s, const py::handle& e) { s.edges = index_matrix(e, "edges", 2); },
          "(k, 2) springs besides the faces' (a copy; assign a whole array).")
      .def_readwrite("pinned", &Scene::pinned, "Pinned points, 0-based.")
      .def_readwrite("stiffness", &Scene::stiffness, "Every spring's stiffness [N/m].")
      .def_readwrite("mass", &Scene::mass, "Every point's mass [kg], or None: Voronoi masses.")
      .def_readwrite("self_collision", &Scene::self_collision,
                     "A SelfCollision, or None (off); make_system applies it, after giving the "
                     "system its surface (the faces split into fans).")
      .def_property(
          "gravity",
          [](const Scene& s) -> py::object {
            if (!s.gravity) return py::none();
            return copy_array(*s.gravity, true);
          },
          [](Scene& s, const py::handle& g) {
            if (g.is_none())
              s.gravity.reset();
            else
              s.gravity = vector3(g, "gravity");
          },
          "Acceleration of gravity [m/s^2] (the JSON key \"gravity\"), or None; make_system adds "
          "it as a Gravity term.")
      .def_readwrite("dt", &Scene::dt,
                     "The step the scene is meant to run at [s] (the JSON key \"dt\"), or None.")
      .def_property_readonly(
          "num_colliders", [](const Scene& s) { return int(s.colliders.size()); },
          "Colliders the scene describes (made by make_system).");

  py::enum_<ClothShear>(m, "ClothShear")
      .value("None_", ClothShear::None)  // None is a Python keyword
      .value("One", ClothShear::One)
      .value("Both", ClothShear::Both);
  py::enum_<ClothPins>(m, "ClothPins")
      .value("None_", ClothPins::None)
      .value("TopCorners", ClothPins::TopCorners)
      .value("TopEdge", ClothPins::TopEdge);
  py::enum_<ClothPlane>(m, "ClothPlane")
      .value("Vertical", ClothPlane::Vertical)
      .value("Horizontal", ClothPlane::Horizontal);
  py::enum_<ChainPins>(m, "ChainPins")
      .value("None_", ChainPins::None)
      .value("First", ChainPins::First)
      .value("BothEnds", ChainPins::BothEnds);
  py::enum_<NetPins>(m, "NetPins")
      .value("None_", NetPins::None)
      .value("Corners", NetPins::Corners)
      .value("Border", NetPins::Border);

  py::class_<ClothOptions> cloth(m, "ClothOptions",
                                 "make_cloth's options (scene/cloth.hpp); ClothOptions(columns=30, "
                                 "rows=20, center=[0, 1, 0]) sets fields by name.");
  cloth
      .def(py::init(
          [](const py::kwargs& f) { return from_fields<ClothOptions>(f, "ClothOptions"); }))
      .def_readwrite("columns", &ClothOptions::columns)
      .def_readwrite("rows", &ClothOptions::rows)
      .def_readwrite("width", &ClothOptions::width, "[m]")
      .def_readwrite("height", &ClothOptions::height, "[m]")
      .def_readwrite("shear", &ClothOptions::shear)
      .def_readwrite("bending", &ClothOptions::bending)
      .def_readwrite("pins", &ClothOptions::pins)
      .def_readwrite("plane", &ClothOptions::plane)
      .def_readwrite("stiffness", &ClothOptions::stiffness, "[N/m]")
      .def_readwrite("mass", &ClothOptions::mass, "[kg] per point, or None: Voronoi masses");
  optional_point(cloth, "origin", &ClothOptions::origin,
                 "Where point (0, 0) lies [m], or None: the origin. Not with center.");
  optional_point(cloth, "center", &ClothOptions::center,
                 "Where the middle of the cloth lies [m], or None. Not with origin.");
  py::class_<ChainOptions> chain(m, "ChainOptions",
                                 "make_chain's options (scene/chain.hpp); fields by name as in "
                                 "ChainOptions(points=12).");
  chain
      .def(py::init(
          [](const py::kwargs& f) { return from_fields<ChainOptions>(f, "ChainOptions"); }))
      .def_readwrite("points", &ChainOptions::points)
      .def_readwrite("length", &ChainOptions::length, "[m]")
      .def_property(
          "direction", [](const ChainOptions& o) { return copy_array(o.direction, true); },
          [](ChainOptions& o, const py::handle& d) { o.direction = vector3(d, "direction"); },
          "(a copy: assign the whole vector)")
      .def_readwrite("pins", &ChainOptions::pins)
      .def_readwrite("stiffness", &ChainOptions::stiffness, "[N/m]")
      .def_readwrite("mass", &ChainOptions::mass, "[kg] per point");
  optional_point(chain, "origin", &ChainOptions::origin,
                 "Where point 0 lies [m], or None: the origin. Not with center.");
  optional_point(chain, "center", &ChainOptions::center,
                 "Where the middle of the chain lies [m], or None. Not with origin.");
  py::class_<NetOptions> net(m, "NetOptions",
                             "make_net's options (scene/net.hpp); fields by name as in "
                             "NetOptions(columns=6, rows=5).");
  net.def(py::init([](const py::kwargs& f) { return from_fields<NetOptions>(f, "NetOptions"); }))
      .def_readwrite("columns", &NetOptions::columns)
      .def_readwrite("rows", &NetOptions::rows)
      .def_readwrite("width", &NetOptions::width, "[m]")
      .def_readwrite("depth", &NetOptions::depth, "[m]")
      .def_readwrite("pins", &NetOptions::pins)
      .def_readwrite("stiffness", &NetOptions::stiffness, "[N/m]")
      .def_readwrite("mass", &NetOptions::mass, "[kg] per point");
  optional_point(net, "origin", &NetOptions::origin,
                 "Where point (0, 0) lies [m], or None: the origin. Not with center.");
  optional_point(net, "center", &NetOptions::center,
                 "Where the middle of the net lies [m], or None. Not with origin.");

  m.def("make_cloth", &make_cloth, py::arg("options") = ClothOptions{},
        "A rectangular cloth (a SceneDescription).");
  m.def("make_chain", &make_chain, py::arg("options") = ChainOptions{}, "A chain of points.");
  m.def("make_net", &make_net, py::arg("options") = NetOptions{}, "A horizontal net.");
  // The named recipes (scene/recipes.hpp), as options to change and pass to make_*.
  m.def("chain_recipe", &chain_recipe,
        "The JSON+OBJ scenes' chain: 10 points over 1 m, both ends pinned, k = 500 N/m, 1 kg "
        "each.");
  m.def("net_recipe", &net_recipe,
        "The JSON+OBJ scenes' net: 8 x 8 points over 1 m x 1 m, corners pinned, k = 300 N/m, 1 kg "
        "each.");
  m.def("hanging_cloth_recipe", &hanging_cloth_recipe, py::arg("n"),
        "An n x n cloth over 1 m x 1 m, vertical, both diagonals, top corners pinned, "
        "k = 1000 N/m, Voronoi masses (1 kg in all).");
  m.def(
      "make_system", [](const Scene& scene) { return make_system<System>(scene); },
      py::arg("scene"),
      "The MassSpringSystem of a scene (masses, springs from faces and edges, pins, colliders).");
}

}  // namespace massspring::python
