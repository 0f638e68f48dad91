// The JSON scene's "colliders" key (io/json_colliders.hpp) and colliders in state scenes
// (io/detail/state_colliders.hpp): every key reaches the system's colliders with the value the
// file gives, every refusal names the file and the entry, a mesh's OBJ is relative to the JSON
// file, write_json_scene() gives back the description bit for bit, and a state scene resumes a
// run with moving colliders bit for bit (the oracle: the same run, not interrupted).
#include <doctest/doctest.h>

#include <cmath>
#include <massspring/integrators/fast_mass_spring.hpp>
#include <massspring/integrators/symplectic_euler.hpp>
#include <massspring/io/json_scene.hpp>
#include <massspring/io/load_scene.hpp>
#include <massspring/io/state_scene.hpp>
#include <massspring/scene/cloth.hpp>
#include <massspring/scene/make_system.hpp>
#include <random>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "io/test_files.hpp"

namespace {

namespace fs = std::filesystem;
using massspring::Error;
using massspring::test::TempDir;
using System = massspring::MassSpringSystem<double, massspring::Sparse>;
using Collider = massspring::contact::Collider<double>;
using Shape = massspring::contact::ColliderShape;
using V3 = massspring::Vector3<double>;
using M3 = Eigen::Matrix3d;

// A 2 x 2 m pyramid over the x-z square, apex (1, 1, 1); its base a quad (two triangles).
const char* const kBump =
    "v 0 0 0\nv 2 0 0\nv 2 0 2\nv 0 0 2\nv 1 1 1\n"
    "f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\nf 1 2 3 4\n";

// scene.json (a 2 x 2 quad cloth at y = 1) with the given "colliders" value, beside
// meshes/bump.obj.
struct Scene {
  TempDir dir;
  fs::path json;
  explicit Scene(const std::string& colliders, const std::string& bump = kBump) {
    dir.write("cloth.obj", "v 0 1 0\nv 1 1 0\nv 1 1 1\nv 0 1 1\nf 1 2 3 4\n");
    dir.write("meshes/bump.obj", bump);
    json =
        dir.write("scene.json", R"({"obj": "cloth.obj", "b": [], "k": 10, "m": 1, "colliders": )" +
                                    colliders + "}");
  }
  [[nodiscard]] std::string error() const {
    try {
      (void)massspring::io::load_scene<System>(json);
    } catch (const Error& e) {
      return e.what();
    }
    return "(no error)";
  }
};

const char* const kAllKeys = R"([
  {"type": "plane", "point": [0, -1, 0], "normal": [0, 2, 0], "friction": 0.3},
  {"type": "sphere", "center": [1, 2, 3], "radius": 0.5,
   "friction": {"static": 0.6, "kinetic": 0.4}, "restitution": 0.25, "thickness": 0.01},
  {"type": "capsule", "a": [0, 0, 0], "b": [2, 0, 0], "radius": 0.1,
   "velocity": [1, 0, -2], "angular_velocity": [0, 0, 3]},
  {"type": "box", "center": [0, 1, 0], "half_extents": [1, 0.5, 0.25],
   "rotation": [0.5, 0.5, 0.5, 0.5]},
  {"type": "box", "center": [0, 1, 0], "half_extents": [1, 0.5, 0.25]},
  {"type": "mesh", "obj": "meshes/bump.obj", "thickness": 0.002}
])";

void check_material(const Collider& c, double mu_s, double mu_k, double e, double h,
                    const V3& v = V3::Zero(), const V3& w = V3::Zero()) {
  CHECK(c.static_friction() == mu_s);
  CHECK(c.kinetic_friction() == mu_k);
  CHECK(c.restitution() == e);
  CHECK(c.thickness() == h);
  CHECK(c.velocity() == v);
  CHECK(c.angular_velocity() == w);
}

// Every field of two colliders, bit for bit.
void check_same(const Collider& a, const Collider& b) {
  CHECK(a.shape() == b.shape());
  CHECK(a.axis() == b.axis());
  CHECK(a.radius() == b.radius());
  CHECK(a.rotation() == b.rotation());
  CHECK(a.translation() == b.translation());
  check_material(b, a.static_friction(), a.kinetic_friction(), a.restitution(), a.thickness(),
                 a.velocity(), a.angular_velocity());
  CHECK((a.triangle_mesh() == nullptr) == (b.triangle_mesh() == nullptr));
  if (a.triangle_mesh() && b.triangle_mesh()) {
    const auto& va = a.triangle_mesh()->vertices();
    const auto& vb = b.triangle_mesh()->vertices();
    REQUIRE(vb.rows() >= va.rows());  // the writer may add two unused corners
    CHECK(vb.topRows(va.rows()) == va);
    CHECK(a.triangle_mesh()->triangles() == b.triangle_mesh()->triangles());
  }
}

// 30 steps, a state scene, 30 more steps from it and from the system that wrote it: the same
// positions, velocities and collider poses, bit for bit.
template <class Solver>
void check_resume(const massspring::SceneDescription<double>& scene, const TempDir& dir) {
  const double dt = 1.0 / 60;
  auto configured = [](Solver& solver) {
    if constexpr (std::is_same_v<Solver, massspring::FastMassSpring<System>>)
      solver.options.iterations = 5;
  };
  System whole = massspring::make_system<System>(scene);
  whole.add_force(massspring::Gravity<double>({0, -9.8, 0}));
  Solver solver;
  configured(solver);
  solver.precompute(whole, dt);
  for (int n = 0; n < 30; ++n) REQUIRE(solver.step(whole).ok());
  const fs::path state = dir / "state.json";
  massspring::io::write_state(whole, state);
  System resumed = massspring::io::read_state<System>(state).system;
  REQUIRE(resumed.colliders().size() == 5);
  for (int i = 0; i < 5; ++i) {
    CAPTURE(i);
    check_same(whole.colliders()[i], resumed.colliders()[i]);
  }
  Solver resumed_solver;
  configured(resumed_solver);
  resumed_solver.precompute(resumed, dt);
  // The contact term's dual variables go on from step to step: a resumed run takes them over
  // (massspring-simulate saves them in the state's "run").
  if constexpr (std::is_same_v<Solver, massspring::FastMassSpring<System>>)
    resumed_solver.set_contact_duals(solver.contact_duals());
  for (int n = 0; n < 30; ++n) {
    REQUIRE(solver.step(whole).ok());
    REQUIRE(resumed_solver.step(resumed).ok());
  }
  CHECK(resumed.positions() == whole.positions());
  CHECK(resumed.velocities() == whole.velocities());
  for (int i = 0; i < 5; ++i) {
    CAPTURE(i);
    CHECK(resumed.colliders()[i].rotation() == whole.colliders()[i].rotation());
    CHECK(resumed.colliders()[i].translation() == whole.colliders()[i].translation());
  }
  // The colliders caught the cloth (free fall would take it 4.9 m down in the second).
  CHECK(whole.positions().col(1).minCoeff() > -1);
}

}  // namespace

TEST_CASE("colliders: every key reaches the system's colliders, in file order") {
  const Scene s(kAllKeys);
  const System sys = massspring::io::load_scene<System>(s.json);
  REQUIRE(sys.colliders().size() == 6);
  const auto& c = sys.colliders();

  CHECK(c[0].shape() == Shape::Plane);
  CHECK(c[0].translation() == V3(0, -1, 0));
  CHECK(c[0].axis() == V3(0, 1, 0));  // the normal, unit
  check_material(c[0], 0.3, 0.3, 0, 0);

  CHECK(c[1].shape() == Shape::Sphere);
  CHECK(c[1].translation() == V3(1, 2, 3));
  CHECK(c[1].radius() == 0.5);
  check_material(c[1], 0.6, 0.4, 0.25, 0.01);

  CHECK(c[2].shape() == Shape::Capsule);
  CHECK(c[2].translation() == V3(1, 0, 0));  // the midpoint
  CHECK(c[2].axis() == V3(1, 0, 0));         // half the segment
  CHECK(c[2].radius() == 0.1);
  check_material(c[2], 0, 0, 0, 0, V3(1, 0, -2), V3(0, 0, 3));

  // (0.5, 0.5, 0.5, 0.5): 120 degrees about (1, 1, 1), which takes x to y, y to z, z to x.
  CHECK(c[3].shape() == Shape::Box);
  CHECK(c[3].translation() == V3(0, 1, 0));
  CHECK(c[3].axis() == V3(1, 0.5, 0.25));
  M3 cycle;
  cycle << 0, 0, 1, 1, 0, 0, 0, 1, 0;
  CHECK(c[3].rotation() == cycle);
  CHECK(c[4].rotation() == M3::Identity());  // no "rotation": the identity
  check_material(c[4], 0, 0, 0, 0);

  // The mesh: its frame's origin the centre of its bounding box; the quad fan-triangulated.
  CHECK(c[5].shape() == Shape::Mesh);
  CHECK(c[5].translation() == V3(1, 0.5, 1));
  const auto& mesh = *c[5].triangle_mesh();
  REQUIRE(mesh.num_triangles() == 6);
  massspring::contact::Triangles expected(6, 3);
  expected << 0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4, 0, 1, 2, 0, 2, 3;
  CHECK(mesh.triangles() == expected);
  CHECK(V3(mesh.vertices().row(4).transpose()) == V3(0, 0.5, 0));  // the apex, local
  check_material(c[5], 0, 0, 0, 0.002);

  // The description holds the file's values as given.
  const auto scene = massspring::io::read_json_scene<double>(s.json);
  REQUIRE(scene.colliders.size() == 6);
  CHECK(scene.colliders[0].normal == V3(0, 2, 0));
  CHECK(scene.colliders[3].rotation == Eigen::Vector4d(0.5, 0.5, 0.5, 0.5));
  CHECK(scene.colliders[5].vertices.rows() == 5);
}

TEST_CASE("colliders: a mesh's obj is relative to the JSON file's folder, wherever the run is") {
  TempDir dir;
  dir.write("shared/bump.obj", kBump);
  dir.write("scenes/cloth.obj", "v 0 1 0\nv 1 1 0\nv 0 1 1\nf 1 2 3\n");
  const fs::path json = dir.write("scenes/scene.json",
                                  R"({"obj": "cloth.obj", "b": [], "k": 10, "colliders": [
          {"type": "mesh", "obj": "../shared/bump.obj"}]})");
  const fs::path cwd = fs::current_path();
  fs::current_path(dir.path() / "shared");  // not the JSON file's folder
  massspring::io::LoadedScene<System> loaded;
  try {
    loaded = massspring::io::load_scene_file<System>(json);
  } catch (...) {
    fs::current_path(cwd);
    throw;
  }
  fs::current_path(cwd);
  REQUIRE(loaded.system.colliders().size() == 1);
  CHECK(loaded.system.colliders()[0].triangle_mesh()->num_triangles() == 6);
  // The mesh is one of the files the scene reads (massspring-simulate will not overwrite it).
  REQUIRE(loaded.files.size() == 3);
  CHECK(loaded.files[2] == json.parent_path() / "../shared/bump.obj");
}

TEST_CASE("colliders: every refusal names the file and the entry") {
  const std::string plane = R"({"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0]})";
  const std::string sphere = R"("type": "sphere", "center": [0, 0, 0])";
  const std::string keys = "; friction, restitution, thickness, velocity, angular_velocity)";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"{}", "key \"colliders\": expected an array of collider objects, got object {}"},
      {"[3]",
       "colliders[0]: expected an object with a \"type\" (plane, sphere, capsule, box or mesh), "
       "got number 3"},
      {"[" + plane + ", {}]",
       "colliders[1]: missing key \"type\" (plane, sphere, capsule, box or mesh)"},
      {R"([{"type": 1}])",
       "colliders[0]: \"type\" must be a string (plane, sphere, capsule, box or mesh), got number "
       "1"},
      {R"([{"type": "cone"}])",
       "colliders[0]: unknown type \"cone\" (expected plane, sphere, capsule, box or mesh)"},
      {"[" + plane + ", {" + sphere + R"(, "radius": 1, "radiu": 2}])",
       "colliders[1] (sphere): unknown key \"radiu\" (a sphere takes center, radius" + keys},
      {R"([{"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "center": [0, 0, 0]}])",
       "colliders[0] (plane): unknown key \"center\" (a plane takes point, normal" + keys},
      {"[" + plane + ", " + plane + ", {" + sphere + R"(, "radius": 1, "radius": 2}])",
       "colliders[2]: key \"radius\" appears twice"},
      {R"([{"type": "box", "center": [0, 0, 0], "half_extents": [1, 1, 1],
            "friction": {"static": 1, "static": 2}}])",
       "colliders[0]: key \"static\" appears twice"},
      {"[{" + sphere + "}]", "colliders[0] (sphere): missing key \"radius\""},
      {R"([{"type": "plane", "normal": [0, 1, 0]}])",
       "colliders[0] (plane): missing key \"point\""},
      {"[{" + sphere + R"(, "radius": -1}])",
       "colliders[0] (sphere): \"radius\" must be finite and > 0, got -1"},
      {"[{" + sphere + R"(, "radius": 0}])",
       "colliders[0] (sphere): \"radius\" must be finite and > 0, got 0"},
      {"[{" + sphere + R"(, "radius": "a"}])",
       "colliders[0] (sphere): \"radius\" must be a number > 0, got string \"a\""},
      {R"([{"type": "capsule", "a": [0, 0, 0], "b": [1, 0, 0], "radius": -0.5}])",
       "colliders[0] (capsule): \"radius\" must be finite and > 0, got -0.5"},
      {R"([{"type": "sphere", "center": [0, 0], "radius": 1}])",
       "colliders[0] (sphere): \"center\" must be [x, y, z] (3 numbers), got array [0,0]"},
      {R"([{"type": "sphere", "center": [0, "x", 0], "radius": 1}])",
       "colliders[0] (sphere): \"center\" must be [x, y, z] (3 numbers), got array [0,\"x\",0]"},
      {R"([{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 0]}])",
       "colliders[0] (plane): \"normal\" must not be zero, got [0,0,0]"},
      {R"([{"type": "box", "center": [0, 0, 0], "half_extents": [1, 0, 1]}])",
       "colliders[0] (box): \"half_extents\" must be 3 numbers > 0, got [1,0,1]"},
      {R"([{"type": "box", "center": [0, 0, 0], "half_extents": [1, 1, 1],
            "rotation": [0, 0, 0, 0]}])",
       "colliders[0] (box): \"rotation\" must be a quaternion [w, x, y, z], not zero, got "
       "[0,0,0,0]"},
      {R"([{"type": "box", "center": [0, 0, 0], "half_extents": [1, 1, 1],
            "rotation": [1, 0, 0]}])",
       "colliders[0] (box): \"rotation\" must be a quaternion [w, x, y, z] (4 numbers), got "
       "array [1,0,0]"},
      {"[{" + sphere + R"(, "radius": 1, "friction": -0.1}])",
       "colliders[0] (sphere): \"friction\" must be finite and >= 0 (or {\"static\": a, "
       "\"kinetic\": b}), got -0.1"},
      {"[{" + sphere + R"(, "radius": 1, "friction": {"static": 0.3}}])",
       "colliders[0] (sphere): \"friction\" must be a number >= 0 or {\"static\": a, "
       "\"kinetic\": b}, got object {\"static\":0.3}"},
      {"[{" + sphere + R"(, "radius": 1, "friction": {"static": 0.3, "kinetic": 0.5}}])",
       "colliders[0] (sphere): \"friction\": kinetic 0.5 exceeds static 0.3 (Coulomb: kinetic "
       "<= static)"},
      {"[{" + sphere + R"(, "radius": 1, "friction": {"static": -1, "kinetic": 0}}])",
       "colliders[0] (sphere): \"friction\": \"static\" must be finite and >= 0, got -1"},
      {"[{" + sphere + R"(, "radius": 1, "restitution": 2}])",
       "colliders[0] (sphere): \"restitution\" must be finite and in [0, 1], got 2"},
      {"[{" + sphere + R"(, "radius": 1, "thickness": -1}])",
       "colliders[0] (sphere): \"thickness\" must be finite and >= 0, got -1"},
      {"[{" + sphere + R"(, "radius": 1, "velocity": [1, 2]}])",
       "colliders[0] (sphere): \"velocity\" must be [x, y, z] (3 numbers), got array [1,2]"},
      {"[{" + sphere + R"(, "radius": 1, "angular_velocity": true}])",
       "colliders[0] (sphere): \"angular_velocity\" must be [x, y, z] (3 numbers), got boolean "
       "true"},
      {R"([{"type": "mesh"}])", "colliders[0] (mesh): missing key \"obj\""},
      {R"([{"type": "mesh", "obj": 3}])",
       "colliders[0] (mesh): \"obj\" must be the name of an OBJ file (a string), got number 3"},
  };
  for (const auto& [colliders, expected] : cases) {
    CAPTURE(colliders);
    const Scene s(colliders);
    CHECK(s.error() == s.json.string() + ": " + expected);
  }
}

TEST_CASE("colliders: a mesh's OBJ is refused when missing, not polygons, or degenerate") {
  const std::string mesh = R"([{"type": "mesh", "obj": "meshes/bump.obj"}])";
  auto error = [&](const std::string& bump) {
    const Scene s(mesh, bump);
    return std::make_pair(s.error(), (s.dir.path() / "meshes/bump.obj").string());
  };
  {
    const Scene s(R"([{"type": "mesh", "obj": "none.obj"}])");
    CHECK(s.error() == s.json.string() + ": colliders[0] (mesh): \"obj\": OBJ file " +
                           (s.dir.path() / "none.obj").string() + " not found");
  }
  const std::string prefix = ": colliders[0] (mesh): ";
  {
    const auto [what, obj] = error("v 0 0 0\nv 1 0 0\nf 1 2\n");
    CHECK(what.substr(what.find(prefix)) ==
          prefix + "\"obj\": " + obj +
              " has 2-vertex faces or lines: a collider mesh takes polygons only");
  }
  {
    const auto [what, obj] = error("v 0 0 0\n");
    CHECK(what.substr(what.find(prefix)) ==
          prefix + "\"obj\": " + obj + " has no polygons: a collider mesh needs some");
  }
  {  // the OBJ's line and 1-based indices
    const auto [what, obj] = error("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\n");
    CHECK(what.substr(what.find(prefix)) == prefix + obj + ":6: face (1, 2, 4) has zero area");
  }
  {  // a polygon: its fan triangle (1, 2, 4) is the flat one
    const auto [what, obj] = error("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 3 2 4\n");
    CHECK(what.substr(what.find(prefix)) ==
          prefix + obj + ":5: face (1, 3, 2, 4): fan triangle (1, 2, 4) has zero area");
  }
  {
    const auto [what, obj] = error("v 0 0 0\nv x 0 0\n");
    CHECK(what.substr(what.find(prefix)) ==
          prefix + obj + ":2: vertex coordinate 1 is not a number: \"x\"");
  }
}

TEST_CASE("colliders: a value a float cannot hold is refused in float") {
  const Scene radius(R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1e39}])");
  auto error = [](const fs::path& json) -> std::string {
    try {
      (void)massspring::io::read_json_scene<float>(json);
    } catch (const Error& e) {
      return e.what();
    }
    return "(no error)";
  };
  CHECK(error(radius.json) ==
        radius.json.string() +
            ": colliders[0] (sphere): \"radius\" must be finite and > 0 (in this Scalar type), "
            "got 1e+39");
  const Scene center(R"([{"type": "sphere", "center": [1e39, 0, 0], "radius": 1}])");
  CHECK(error(center.json) ==
        center.json.string() +
            ": colliders[0] (sphere): \"center\" must be finite (in this Scalar type), got "
            "[1e+39,0,0]");
}

TEST_CASE("colliders: write_json_scene then read_json_scene gives them back bit for bit") {
  const Scene s(kAllKeys);
  auto scene = massspring::io::read_json_scene<double>(s.json);
  // Values with no short decimal, and a negative zero.
  scene.colliders[1].center = V3(0.1, 1.0 / 3, -0.0);
  scene.colliders[2].angular_velocity = V3(std::sqrt(2.0), 0, 1e-300);
  scene.colliders[3].rotation = Eigen::Vector4d(std::cos(0.3), 0, std::sin(0.3), 0);
  TempDir out;
  massspring::io::write_json_scene(out / "copy.json", scene);
  CHECK(fs::exists(out / "copy_collider5.obj"));  // the mesh, beside it
  const auto back = massspring::io::read_json_scene<double>(out / "copy.json");
  REQUIRE(back.colliders.size() == scene.colliders.size());
  for (std::size_t i = 0; i < back.colliders.size(); ++i) {
    CAPTURE(i);
    const auto &a = scene.colliders[i], &b = back.colliders[i];
    CHECK(a.shape == b.shape);
    CHECK(a.point == b.point);
    CHECK(a.normal == b.normal);
    CHECK(a.center == b.center);
    CHECK(a.a == b.a);
    CHECK(a.b == b.b);
    CHECK(a.radius == b.radius);
    CHECK(a.half_extents == b.half_extents);
    CHECK(a.rotation == b.rotation);
    CHECK(a.vertices == b.vertices);
    CHECK(a.triangles == b.triangles);
    CHECK(a.static_friction == b.static_friction);
    CHECK(a.kinetic_friction == b.kinetic_friction);
    CHECK(a.restitution == b.restitution);
    CHECK(a.thickness == b.thickness);
    CHECK(a.velocity == b.velocity);
    CHECK(a.angular_velocity == b.angular_velocity);
  }
  CHECK(std::signbit(back.colliders[1].center(2)));
  // An invalid collider is refused before anything is written.
  scene.colliders[1].radius = -1;
  TempDir none;
  CHECK_THROWS_WITH_AS(
      massspring::io::write_json_scene(none / "bad.json", scene),
      massspring::test::contains((none / "bad.json").string() + ": colliders[1] (sphere): "),
      Error);
  CHECK(fs::is_empty(none.path()));
}

TEST_CASE("state scene: the writer's inputs make Collider's factories give its colliders back") {
  std::mt19937_64 random(7);
  std::normal_distribution<double> normal;
  int unit_kept = 0, exact = 0;
  for (int k = 0; k < 2000; ++k) {
    const V3 n(normal(random), normal(random), normal(random));
    const V3 axis = Collider::plane(V3::Zero(), n).axis();
    const V3 back =
        Collider::plane(V3::Zero(), massspring::io::detail::plane_normal_for(axis)).axis();
    exact += back == axis;
    CHECK((back - axis).cwiseAbs().maxCoeff() <= 2.3e-16);  // at worst a rounding unit
    unit_kept += Collider::plane(V3::Zero(), axis).axis() == axis;
  }
  MESSAGE(unit_kept, " of 2000 unit normals survive normalising again as they are; ", exact,
          " are written so that they do");
  CHECK(exact >= 1995);  // about 3 in 10^5 cannot be
  // A mesh whose bounding box is not centred to the last bit (0.1 and 0.7: centre 0.4 rounds).
  massspring::Points<double> v(3, 3);
  v << 0.1, 0, 0, 0.7, 0, 0.3, 0.1, 0.9, 0.1;
  massspring::contact::Triangles f(1, 3);
  f << 0, 1, 2;
  const Collider mesh = Collider::mesh(v, f);
  const auto& local = mesh.triangle_mesh()->vertices();
  const Collider again = Collider::mesh(massspring::io::detail::mesh_vertices_for(local), f);
  CHECK(again.triangle_mesh()->vertices().topRows(3) == local);
}

TEST_CASE("state scene: moving colliders resume bit for bit, symplectic Euler and FastMassSpring") {
  // A falling cloth over colliders of every kind, every one moving, with normals and bounds that
  // do not survive normalising and re-centring as they are.
  massspring::ClothOptions o;
  o.columns = 6;
  o.rows = 5;
  o.plane = massspring::ClothPlane::Horizontal;
  o.pins = massspring::ClothPins::None;
  o.mass = 1;  // symplectic Euler is stable at dt = 1/60 (omega dt = 0.53)
  o.stiffness = 100;
  auto scene = massspring::make_cloth(o);
  TempDir dir;
  dir.write("cloth.obj", "v 0 0 0\n");  // unused: the scene is built in memory
  dir.write("bump.obj", "v 0.1 -0.5 0.1\nv 0.7 -0.5 0.3\nv 0.1 -0.4 0.9\nf 1 2 3\n");
  const fs::path colliders = dir.write("c.json", R"({"obj": "cloth.obj", "b": [], "k": 1,
    "colliders": [
      {"type": "plane", "point": [0, -0.6, 0], "normal": [0.1, 3, 0.7], "friction": 0.3,
       "velocity": [0, 0.01, 0]},
      {"type": "sphere", "center": [0.6, -0.3, 0.5], "radius": 0.25, "friction": 0.5,
       "velocity": [0, 0, 0.1], "angular_velocity": [0.3, 0.2, 1]},
      {"type": "capsule", "a": [0, -0.2, 0.2], "b": [1.2, -0.2, 0.7], "radius": 0.05,
       "friction": {"static": 0.4, "kinetic": 0.2}, "angular_velocity": [2, 0, 0]},
      {"type": "box", "center": [0.3, -0.4, 0.3], "half_extents": [0.2, 0.1, 0.3],
       "rotation": [0.9, 0.1, 0.3, 0.2], "restitution": 0.5, "thickness": 0.01,
       "velocity": [0.05, 0, 0], "angular_velocity": [0, 1, 0]},
      {"type": "mesh", "obj": "bump.obj", "velocity": [0.01, 0.02, 0],
       "angular_velocity": [0, 0, 0.5], "thickness": 0.005}]})");
  scene.colliders = massspring::io::read_json_scene<double>(colliders).colliders;
  REQUIRE(scene.colliders.size() == 5);

  SUBCASE("symplectic Euler") { check_resume<massspring::SymplecticEuler<System>>(scene, dir); }
  SUBCASE("FastMassSpring") { check_resume<massspring::FastMassSpring<System>>(scene, dir); }
}
