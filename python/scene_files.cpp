// Scene files (io/load_scene.hpp, io/obj.hpp, io/state_scene.hpp): load_scene(path) for JSON+OBJ,
// FOSSSim XML and saved states; load_scene_file(path) with what the file holds besides the system
// (faces and edges to draw, an XML scene's time step, duration and integrator); write_obj and
// write_state. Errors (a missing file, a bad key, a line of an OBJ) raise massspring.Error with
// the library's message, which names the file and the item.

#include <pybind11/stl/filesystem.h>

#include <massspring/io.hpp>
#include <massspring/io/state_scene.hpp>
#include <optional>

#include "bindings.hpp"

namespace massspring::python {

namespace {

using Loaded = io::LoadedScene<System>;

// What an XML scene says about how to run it.
struct XmlRun {
  double dt = 0, duration = 0;
  long long steps = 0;
  std::string integrator;  // FOSSSim's name, e.g. "symplectic-euler"
  std::string description;
};

std::vector<std::vector<int>> faces_from(const py::handle& faces) {
  if (faces.is_none()) return {};
  try {
    return faces.cast<std::vector<std::vector<int>>>();
  } catch (const py::cast_error&) {
    throw Error("faces: expected a list of lists of point indices (0-based)");
  }
}

}  // namespace

void bind_scene_files(py::module_& m) {
  py::class_<XmlRun>(m, "FosssimRun", "How a FOSSSim XML scene asks to be run.")
      .def_readonly("dt", &XmlRun::dt, "Time step [s].")
      .def_readonly("duration", &XmlRun::duration, "Simulated time [s].")
      .def_readonly("steps", &XmlRun::steps, "ceil(duration / dt) steps.")
      .def_readonly("integrator", &XmlRun::integrator, "FOSSSim's integrator name.")
      .def_readonly("description", &XmlRun::description);

  py::class_<Loaded>(m, "LoadedScene", "A scene file's system and what else the file holds.")
      .def_property_readonly(
          "system", [](Loaded& s) -> System& { return s.system; },
          py::return_value_policy::reference_internal,
          "The system (part of this object: it lives as long as the scene does).")
      .def_readonly("faces", &Loaded::faces, "Polygons to draw (0-based point indices).")
      .def_property_readonly(
          "edges", [](const Loaded& s) { return copy_edges(s.edges); }, "(k, 2) segments to draw.")
      .def_readonly("files", &Loaded::files, "Every file read.")
      .def_readonly("state", &Loaded::state, "True for a state saved by write_state.")
      .def_readonly("dt", &Loaded::dt,
                    "A JSON+OBJ scene's \"dt\": the step it is meant to run at [s], or None.")
      .def_property_readonly(
          "fosssim",
          [](const Loaded& s) -> std::optional<XmlRun> {
            if (!s.fosssim) return std::nullopt;
            return XmlRun{s.fosssim->dt, s.fosssim->duration, s.fosssim->steps(),
                          io::to_string(s.fosssim->integrator), s.fosssim->description};
          },
          "An XML scene's time step, duration and integrator; None for other files.");

  m.def(
      "load_scene", [](const std::filesystem::path& path) { return io::load_scene<System>(path); },
      py::arg("path"),
      "The system of a scene file: .json (JSON+OBJ, or a saved state) or .xml (FOSSSim). An XML "
      "scene or a saved state brings its force terms; a JSON+OBJ scene has none (add Gravity).");
  m.def(
      "load_scene_file",
      [](const std::filesystem::path& path) { return io::load_scene_file<System>(path); },
      py::arg("path"), "The system and the rest of a scene file (a LoadedScene).");
  m.def(
      "write_obj",
      [](const std::filesystem::path& path, const py::handle& positions, const py::handle& faces,
         const py::handle& edges) {
        const Points x = real_matrix(positions, "write_obj: positions", 3);
        const Edges e = edges.is_none() ? Edges(0, 2) : Edges(index_matrix(edges, "edges", 2));
        io::write_obj(path, x, faces_from(faces), e);
      },
      py::arg("path"), py::arg("positions"), py::arg("faces") = py::none(),
      py::arg("edges") = py::none(), "Writes an OBJ: vertices, faces (polygons) and edges.");
  m.def(
      "write_state",
      [](const System& system, const std::filesystem::path& path, const py::handle& faces,
         const py::handle& edges) {
        io::StateSceneExtras extras;
        extras.faces = faces_from(faces);
        if (!edges.is_none()) extras.edges = index_matrix(edges, "edges", 2);
        io::write_state(system, path, extras);
      },
      py::arg("system"), py::arg("path"), py::arg("faces") = py::none(),
      py::arg("edges") = py::none(),
      "Saves the system's model and state as a .json state scene that load_scene reads back "
      "exactly.");
}

}  // namespace massspring::python
