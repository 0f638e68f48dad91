// io/json_scene.hpp: the JSON+OBJ scene format as SOURCE.md describes it, its refusals
// (file and key named) and the writer's exact round trip.
#include <doctest/doctest.h>

#include <cstring>
#include <limits>
#include <massspring/io/json_scene.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/test_files.hpp"
#include "massspring/scene/chain.hpp"
#include "massspring/scene/cloth.hpp"
#include "support/paths.hpp"

namespace {

using massspring::Edges;
using massspring::Error;
using massspring::SceneDescription;
using massspring::io::read_json_scene;
using massspring::io::write_json_scene;
using massspring::test::TempDir;

template <class Scalar>
using Points = massspring::Points<Scalar>;

const char* const kTriangleObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

// The same description, vertices compared bit for bit.
template <class Scalar>
void check_same(const SceneDescription<Scalar>& a, const SceneDescription<Scalar>& b) {
  REQUIRE(a.vertices.rows() == b.vertices.rows());
  CHECK(std::memcmp(a.vertices.data(), b.vertices.data(),
                    sizeof(Scalar) * std::size_t(a.vertices.size())) == 0);
  CHECK(a.faces == b.faces);
  CHECK(a.edges == b.edges);
  CHECK(a.pinned == b.pinned);
  CHECK(a.stiffness == b.stiffness);
  CHECK(a.mass.has_value() == b.mass.has_value());
  if (a.mass && b.mass) CHECK(*a.mass == *b.mass);
  REQUIRE(a.self_collision.has_value() == b.self_collision.has_value());
  if (a.self_collision) {
    CHECK(a.self_collision->thickness == b.self_collision->thickness);
    CHECK(a.self_collision->friction == b.self_collision->friction);
  }
  CHECK(a.gravity == b.gravity);
  CHECK(a.dt == b.dt);
}

template <class Scalar>
SceneDescription<Scalar> cast(const SceneDescription<double>& s) {
  SceneDescription<Scalar> r;
  r.vertices = s.vertices.cast<Scalar>();
  r.faces = s.faces;
  r.edges = s.edges;
  r.pinned = s.pinned;
  r.stiffness = Scalar(s.stiffness);
  if (s.mass) r.mass = Scalar(*s.mass);
  if (s.self_collision)
    r.self_collision = massspring::contact::SelfCollision<Scalar>{
        Scalar(s.self_collision->thickness), Scalar(s.self_collision->friction)};
  if (s.gravity) r.gravity = s.gravity->cast<Scalar>();
  if (s.dt) r.dt = Scalar(*s.dt);
  return r;
}

}  // namespace

TEST_CASE("read_json_scene reads the JSON+OBJ scenes as SOURCE.md lists them" *
          doctest::skip(!massspring::test::have_jacobson())) {
  const auto dir = massspring::test::jacobson_dir();
  struct Expected {
    const char* file;
    Eigen::Index vertices;
    std::size_t faces;
    Eigen::Index edges;
    std::size_t pins;
    double k;
    bool has_mass;
  };
  for (const Expected& e : {Expected{"flag.json", 3200, 3081, 0, 40, 100000, false},
                            Expected{"horizontal-chain.json", 10, 0, 9, 2, 500, true},
                            Expected{"net.json", 61, 0, 156, 6, 300, true},
                            Expected{"single-spring-horizontal.json", 2, 0, 1, 1, 500, true},
                            Expected{"skirt.json", 9840, 9600, 0, 240, 100000, false}}) {
    CAPTURE(e.file);
    const auto s = read_json_scene(dir / e.file);
    CHECK(s.vertices.rows() == e.vertices);
    CHECK(s.faces.size() == e.faces);
    CHECK(s.edges.rows() == e.edges);
    CHECK(s.pinned.size() == e.pins);
    CHECK(s.stiffness == e.k);
    CHECK(s.mass.has_value() == e.has_mass);
    if (s.mass) CHECK(*s.mass == 1.0);
  }
  // "b" is 1-based in the files; the description is 0-based
  CHECK(read_json_scene(dir / "single-spring-horizontal.json").pinned == std::vector<int>{0});
  CHECK(read_json_scene(dir / "horizontal-chain.json").pinned == std::vector<int>{0, 9});
  CHECK(read_json_scene(dir / "net.json").pinned == std::vector<int>{0, 4, 34, 60, 56, 26});
  std::vector<int> flag_pins(40), skirt_pins(240);
  for (int i = 0; i < 40; ++i) flag_pins[std::size_t(i)] = i;        // 1..40
  for (int i = 0; i < 240; ++i) skirt_pins[std::size_t(i)] = 2 * i;  // 1, 3, ..., 479
  CHECK(read_json_scene(dir / "flag.json").pinned == flag_pins);
  CHECK(read_json_scene(dir / "skirt.json").pinned == skirt_pins);
}

TEST_CASE_TEMPLATE("read_json_scene: obj relative to the JSON's folder, pins 1-based, png ignored",
                   Scalar, float, double) {
  TempDir dir;
  dir.write("meshes/quad.obj", "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\nf 1 2 3 4\nf 1 3\n");
  const auto json = dir.write(
      "scenes/quad.json",
      R"({"obj": "../meshes/quad.obj", "png": "missing.png", "b": [4, 2], "k": 2.5e3, "m": 0.25})");
  const auto s = read_json_scene<Scalar>(json);
  Points<Scalar> v(4, 3);
  v << 0, 0, 0, 2, 0, 0, 2, 1, 0, 0, 1, 0;
  CHECK(s.vertices == v);
  CHECK(s.faces == std::vector<std::vector<int>>{{0, 1, 2, 3}});
  REQUIRE(s.edges.rows() == 1);  // mixed arity: a polygon and a 2-vertex face in one file
  CHECK(s.edges(0, 0) == 0);
  CHECK(s.edges(0, 1) == 2);
  CHECK(s.pinned == std::vector<int>{3, 1});
  CHECK(s.stiffness == Scalar(2500));
  REQUIRE(s.mass.has_value());
  CHECK(*s.mass == Scalar(0.25));

  const auto no_mass = read_json_scene<Scalar>(
      dir.write("scenes/b.json", R"({"obj":"../meshes/quad.obj","b":[],"k":0})"));
  CHECK_FALSE(no_mass.mass.has_value());
  CHECK(no_mass.pinned.empty());
  CHECK(no_mass.stiffness == Scalar(0));
}

TEST_CASE("read_json_scene refuses bad scenes, naming the file and the key") {
  TempDir dir;
  dir.write("tri.obj", kTriangleObj);
  const std::string path = (dir / "bad.json").string();
  // Each case: the JSON text, what the message must contain after "<path>: ".
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"({"obj": "tri.obj", "b": [1], "k": "abc"})",
       "key \"k\": expected a number >= 0, got string \"abc\""},
      {R"({"obj": "tri.obj", "b": [1], "k": true})",
       "key \"k\": expected a number >= 0, got boolean"},
      {R"({"obj": "tri.obj", "b": [1], "k": -1})",
       "key \"k\": expected a finite number >= 0, got -1"},
      {R"({"obj": "tri.obj", "b": [1], "k": 1, "m": 0})",
       "key \"m\": expected a finite number > 0, got 0"},
      {R"({"obj": "tri.obj", "b": [1], "k": 1, "m": -2.5})",
       "key \"m\": expected a finite number > 0"},
      {R"({"obj": "tri.obj", "b": [1], "k": 1, "m": "1"})",
       "key \"m\": expected a number > 0, got string"},
      {R"({"obj": "tri.obj", "b": [1], "k": 1, "m": null})",
       "key \"m\": expected a number > 0, got null"},
      {R"({"obj": "tri.obj", "b": [1], "k": 1, "bc": [[0,0,0]]})",
       "key \"bc\" (pinned positions) is not supported"},
      {R"({"obj": "tri.obj", "b": [1], "k": 1, "wind": true})",
       "unknown key \"wind\" (expected obj, b, k, m, png, colliders, self_collision, gravity, "
       "dt)"},
      {R"({"obj": "tri.obj", "b": [1], "k": 1, "dt": 0})",
       "key \"dt\": expected a finite number > 0, got 0"},
      {R"({"obj": "tri.obj", "b": [1], "k": 1, "dt": "1/30"})",
       "key \"dt\": expected a number > 0, got string \"1/30\""},
      {R"({"obj": "tri.obj", "b": [1], "k": 1, "dt": 1e999})", "not valid JSON"},
      {R"({"obj": "tri.obj", "b": [1], "k": 1, "gravity": [0, -9.8]})",
       "key \"gravity\": expected [gx, gy, gz] (three numbers, m/s^2), got [0,-9.8]"},
      {R"({"obj": "tri.obj", "b": [1], "k": 1, "gravity": -9.8})",
       "key \"gravity\": expected [gx, gy, gz] (three numbers, m/s^2), got -9.8"},
      {R"({"obj": "tri.obj", "b": [1], "k": 1, "gravity": [0, null, 0]})",
       "key \"gravity\": expected [gx, gy, gz] (three finite numbers, m/s^2), got [0,null,0]"},
      {R"({"obj": "tri.obj", "b": [1], "k": 1, "gravity": [0, 1e308, 1e309]})", "not valid JSON"},
      {R"({"b": [1], "k": 1})", "missing key \"obj\""},
      {R"({"obj": "tri.obj", "k": 1})", "missing key \"b\""},
      {R"({"obj": "tri.obj", "b": [1]})", "missing key \"k\""},
      {R"({"obj": 42, "b": [1], "k": 1})",
       "key \"obj\": expected the name of an OBJ file (a string), got number 42"},
      {R"({"obj": "", "b": [1], "k": 1})", "key \"obj\": expected the name of an OBJ file"},
      {R"({"obj": "none.obj", "b": [1], "k": 1})", "key \"obj\": OBJ file "},
      {R"({"obj": "tri.obj", "b": 1, "k": 1})",
       "key \"b\": expected an array of 1-based vertex ids, got number 1"},
      {R"({"obj": "tri.obj", "b": [1, 1.5], "k": 1})",
       "key \"b\": entry 1 (counting from 0) is number 1.5, expected an integer vertex id "
       "(1-based)"},
      {R"({"obj": "tri.obj", "b": ["1"], "k": 1})",
       "key \"b\": entry 0 (counting from 0) is string"},
      {R"({"obj": "tri.obj", "b": [0], "k": 1})",
       "key \"b\": entry 0 (counting from 0) is 0, out of range [1, 3]: vertex ids are 1-based"},
      {R"({"obj": "tri.obj", "b": [1, 2, 4], "k": 1})",
       "key \"b\": entry 2 (counting from 0) is 4, out of range [1, 3]"},
      {R"({"obj": "tri.obj", "b": [-1], "k": 1})",
       "key \"b\": entry 0 (counting from 0) is -1, out of range"},
      {R"({"obj": "tri.obj", "b": [18446744073709551615], "k": 1})",
       "key \"b\": entry 0 (counting from 0) is 18446744073709551615, out of range"},
      {R"({"obj": "tri.obj", "b": [1], "k": 1, "png": 3})",
       "key \"png\": expected the name of a texture image"},
      {R"({"obj": "tri.obj", "b": [1], "k": 1, "k": 2})", "key \"k\" appears twice"},
      {R"(["tri.obj", [1], 1])", "expected a JSON object"},
      {"{\"obj\": \"tri.obj\",\n \"b\": [1],\n \"k\": }",
       "not valid JSON: parse error at line 3, column 7"},
      {"{\"obj\": \"tri.obj\", \"b\": [1], \"k\": 1e999}", "not valid JSON: number overflow"},
      {"", "not valid JSON: parse error at line 1, column 1"},
  };
  for (const auto& [text, expected] : cases) {
    CAPTURE(text);
    const auto json = dir.write("bad.json", text);
    CHECK_THROWS_WITH_AS(read_json_scene(json), massspring::test::contains(path + ": " + expected),
                         Error);
  }
}

TEST_CASE("read_json_scene refuses a stiffness a float cannot hold") {
  TempDir dir;
  dir.write("tri.obj", kTriangleObj);
  const auto json = dir.write("big.json", R"({"obj": "tri.obj", "b": [], "k": 1e39})");
  CHECK_THROWS_WITH_AS(
      read_json_scene<float>(json),
      doctest::Contains("key \"k\": expected a finite number >= 0 (in this Scalar type)"), Error);
  CHECK(read_json_scene<double>(json).stiffness == 1e39);
}

TEST_CASE("read_json_scene passes on the OBJ reader's errors, which name the OBJ file and line") {
  TempDir dir;
  const auto obj = dir.write("broken.obj", "v 0 0 0\nv 1 x 0\n");
  const auto json = dir.write("scene.json", R"({"obj": "broken.obj", "b": [], "k": 1})");
  CHECK_THROWS_WITH_AS(
      read_json_scene(json),
      massspring::test::contains(obj.string() + ":2: vertex coordinate 2 is not a number"), Error);
  const auto missing = dir / "missing.json";
  CHECK_THROWS_WITH_AS(
      read_json_scene(missing),
      massspring::test::contains(missing.string() + ": cannot read JSON scene: no such file"),
      Error);
}

TEST_CASE_TEMPLATE("write_json_scene then read_json_scene gives the same description", Scalar,
                   float, double) {
  TempDir dir;
  massspring::ClothOptions mixed;  // quads and 2-vertex bending springs in one OBJ
  mixed.columns = 7;
  mixed.rows = 5;
  mixed.bending = true;
  massspring::ClothOptions triangles;  // triangles, pins along the top edge, a given mass
  triangles.columns = 4;
  triangles.rows = 6;
  triangles.shear = massspring::ClothShear::One;
  triangles.pins = massspring::ClothPins::TopEdge;
  triangles.mass = 0.1;
  triangles.stiffness = 1.0 / 3.0;
  SceneDescription<double> folded = massspring::make_cloth(triangles);  // self-collision on
  folded.self_collision = massspring::contact::SelfCollision<double>{0.01 / 3, 0.7 / 3};
  folded.gravity = Eigen::Vector3d(0.1 / 3, -9.8, -0.0);  // its own gravity and step
  folded.dt = 1.0 / 300;
  massspring::ChainOptions chain;  // edges only
  chain.points = 7;
  chain.direction = Eigen::Vector3d(1, 2, 3);
  chain.mass = 0.3;
  const std::vector<SceneDescription<double>> scenes = {massspring::make_cloth(mixed),
                                                        massspring::make_cloth(triangles),
                                                        massspring::make_chain(chain), folded};
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    CAPTURE(i);
    const SceneDescription<Scalar> scene = cast<Scalar>(scenes[i]);
    const auto json = dir / ("scene" + std::to_string(i) + ".json");
    write_json_scene(json, scene);
    CHECK(std::filesystem::exists(dir / ("scene" + std::to_string(i) + ".obj")));
    check_same(read_json_scene<Scalar>(json), scene);
  }
}

TEST_CASE("write_json_scene writes pins 1-based, omits an absent mass, names the OBJ beside it") {
  TempDir dir;
  SceneDescription<double> s;
  s.vertices.resize(3, 3);
  s.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  s.faces = {{0, 1, 2}};
  s.pinned = {0, 2};
  s.stiffness = 12.5;
  write_json_scene(dir / "tri.json", s);
  const auto j = nlohmann::json::parse(massspring::test::read_bytes(dir / "tri.json"));
  CHECK(j.at("obj") == "tri.obj");
  CHECK(j.at("b") == nlohmann::json::array({1, 3}));
  CHECK(j.at("k") == 12.5);
  CHECK_FALSE(j.contains("m"));
  CHECK(j.size() == 3);
  CHECK(massspring::test::read_bytes(dir / "tri.obj").find("\nf 1 2 3\n") != std::string::npos);

  s.mass = 2;
  write_json_scene(dir / "tri.json", s);
  CHECK(nlohmann::json::parse(massspring::test::read_bytes(dir / "tri.json")).at("m") == 2);
  CHECK_FALSE(std::filesystem::exists(dir / "tri.json.tmp"));
  CHECK_FALSE(std::filesystem::exists(dir / "tri.obj.tmp"));
}

TEST_CASE("write_json_scene refuses a scene it could not read back, and writes nothing") {
  TempDir dir;
  SceneDescription<double> good;
  good.vertices.resize(3, 3);
  good.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  good.faces = {{0, 1, 2}};
  good.stiffness = 1;
  const auto json = dir / "s.json";
  const std::string name = json.string();

  auto s = good;
  s.pinned = {3};
  CHECK_THROWS_WITH_AS(
      write_json_scene(json, s),
      massspring::test::contains(name + ": pin 0: vertex index 3 out of range [0, 3)"), Error);
  s = good;
  s.stiffness = -1;
  CHECK_THROWS_WITH_AS(write_json_scene(json, s),
                       massspring::test::contains(name + ": stiffness must be finite and >= 0"),
                       Error);
  s = good;
  s.mass = 0.0;
  CHECK_THROWS_WITH_AS(write_json_scene(json, s),
                       massspring::test::contains(name + ": mass must be finite and > 0"), Error);
  s = good;
  s.faces = {{0, 1}};
  CHECK_THROWS_WITH_AS(write_json_scene(json, s), doctest::Contains("s.obj: face 0 has 2 vertices"),
                       Error);
  CHECK_THROWS_WITH_AS(write_json_scene(dir / "s.obj", good),
                       doctest::Contains("a JSON scene must not be named .obj"), Error);
  CHECK(std::filesystem::is_empty(dir.path()));
}

TEST_CASE_TEMPLATE("read_json_scene: \"self_collision\" turns it on, its fields default", Scalar,
                   float, double) {
  TempDir dir;
  dir.write("tri.obj", kTriangleObj);
  const auto read = [&](const std::string& extra) {
    return read_json_scene<Scalar>(
        dir.write("s.json", R"({"obj": "tri.obj", "b": [], "k": 1)" + extra + "}"));
  };
  CHECK_FALSE(read("").self_collision.has_value());  // absent: off

  const auto both = read(R"(, "self_collision": {"thickness": 0.01, "friction": 0.5})");
  REQUIRE(both.self_collision.has_value());
  CHECK(both.self_collision->thickness == Scalar(0.01));
  CHECK(both.self_collision->friction == Scalar(0.5));

  const massspring::contact::SelfCollision<Scalar> defaults;
  const auto empty = read(R"(, "self_collision": {})");
  REQUIRE(empty.self_collision.has_value());
  CHECK(empty.self_collision->thickness == defaults.thickness);
  CHECK(empty.self_collision->friction == defaults.friction);

  const auto thickness_only = read(R"(, "self_collision": {"thickness": 0.002})");
  REQUIRE(thickness_only.self_collision.has_value());
  CHECK(thickness_only.self_collision->thickness == Scalar(0.002));
  CHECK(thickness_only.self_collision->friction == defaults.friction);

  const auto frictionless = read(R"(, "self_collision": {"friction": 0})");
  REQUIRE(frictionless.self_collision.has_value());
  CHECK(frictionless.self_collision->thickness == defaults.thickness);
  CHECK(frictionless.self_collision->friction == Scalar(0));
}

TEST_CASE("read_json_scene refuses a bad \"self_collision\", naming the file and the key") {
  TempDir dir;
  dir.write("tri.obj", kTriangleObj);
  const std::string path = (dir / "bad.json").string();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"true",
       "key \"self_collision\": expected an object {\"thickness\": T, \"friction\": MU}, "
       "got boolean"},
      {"0.004", "key \"self_collision\": expected an object"},
      {"[0.004, 0.2]", "key \"self_collision\": expected an object"},
      {"null", "key \"self_collision\": expected an object"},
      {R"({"thickness": 0.004, "stiffness": 1})",
       "key \"self_collision\": unknown key \"stiffness\" (expected thickness, friction)"},
      {R"({"thickness": 0})",
       "key \"self_collision\": \"thickness\": expected a finite number > 0, got 0"},
      {R"({"thickness": -0.001})",
       "key \"self_collision\": \"thickness\": expected a finite number > 0, got -0.001"},
      {R"({"thickness": "4mm"})",
       "key \"self_collision\": \"thickness\": expected a number > 0, got string \"4mm\""},
      {R"({"thickness": null})", "key \"self_collision\": \"thickness\": expected a number > 0"},
      {R"({"friction": -0.2})",
       "key \"self_collision\": \"friction\": expected a finite number >= 0, got -0.2"},
      {R"({"friction": [0.2]})",
       "key \"self_collision\": \"friction\": expected a number >= 0, got array"},
      {R"({"thickness": 0.004, "thickness": 0.005})",
       "key \"self_collision\": key \"thickness\" appears twice"},
  };
  for (const auto& [value, expected] : cases) {
    CAPTURE(value);
    const auto json = dir.write(
        "bad.json", R"({"obj": "tri.obj", "b": [1], "k": 1, "self_collision": )" + value + "}");
    CHECK_THROWS_WITH_AS(read_json_scene(json), massspring::test::contains(path + ": " + expected),
                         Error);
  }
  // The same key twice at the top level, as for every key.
  const auto twice = dir.write("bad.json", R"({"obj": "tri.obj", "b": [1], "k": 1,
      "self_collision": {}, "self_collision": {}})");
  CHECK_THROWS_WITH_AS(read_json_scene(twice),
                       massspring::test::contains(path + ": key \"self_collision\" appears twice"),
                       Error);
  // A thickness a float cannot hold is refused in float.
  const auto tiny =
      dir.write("bad.json",
                R"({"obj": "tri.obj", "b": [1], "k": 1, "self_collision": {"thickness": 1e-50}})");
  CHECK_THROWS_WITH_AS(read_json_scene<float>(tiny),
                       doctest::Contains("key \"self_collision\": \"thickness\""), Error);
  CHECK(read_json_scene<double>(tiny).self_collision->thickness == 1e-50);
}

TEST_CASE("write_json_scene writes \"self_collision\" when given, and refuses a bad one") {
  TempDir dir;
  SceneDescription<double> s;
  s.vertices.resize(3, 3);
  s.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  s.faces = {{0, 1, 2}};
  s.stiffness = 1;
  s.self_collision = massspring::contact::SelfCollision<double>{};
  write_json_scene(dir / "tri.json", s);
  const auto j = nlohmann::json::parse(massspring::test::read_bytes(dir / "tri.json"));
  CHECK(j.at("self_collision") == nlohmann::json({{"thickness", 0.004}, {"friction", 0.2}}));

  s.self_collision->friction = -1;
  const auto json = dir / "other.json";
  CHECK_THROWS_WITH_AS(
      write_json_scene(json, s),
      massspring::test::contains(json.string() +
                                 ": self-collision: friction must be finite and >= 0, got -1"),
      Error);
  CHECK_FALSE(std::filesystem::exists(json));
  CHECK_FALSE(std::filesystem::exists(dir / "other.obj"));
}
