// docs/errors.md, row by row: every refused input raises massspring::Error with the catalogue's
// message (exact, or the documented pattern with its file:line), and the accepted edge cases
// (the last 1-based pin, a zero-length spring at rest, repeated OBJ springs) are accepted. Test
// names start with the row's id (J = JSON scene, O = OBJ, X = FOSSSim XML, S = system, F = force
// terms, I = integrators). The last test replays the fuzzers' regression inputs (tests/data/fuzz).
#include <doctest/doctest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <massspring/io/fosssim_scene.hpp>
#include <massspring/io/json_scene.hpp>
#include <massspring/io/load_scene.hpp>
#include <massspring/io/obj.hpp>
#include <massspring/massspring.hpp>
#include <regex>
#include <string>
#include <utility>
#include <vector>

#include "../../fuzz/scene_targets.hpp"
#include "io/test_files.hpp"
#include "support/paths.hpp"

namespace {

namespace fs = std::filesystem;
using massspring::Edges;
using massspring::Error;
using massspring::Points;
using massspring::Vector;
using massspring::Vector3;
using massspring::test::TempDir;
using System = massspring::MassSpringSystem<double, massspring::Sparse>;

const double kInf = std::numeric_limits<double>::infinity();
const double kNaN = std::numeric_limits<double>::quiet_NaN();

// The message of the massspring::Error that f() throws; fails the test when it returns normally.
// Any other exception escapes and fails the test too (a bad input must raise Error, nothing else).
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  FAIL("no massspring::Error was thrown");
  return {};
}

// True when `text` matches the ECMAScript regular expression `pattern` as a whole.
bool matches(const std::string& text, const std::string& pattern) {
  return std::regex_match(text, std::regex(pattern));
}

// Escapes a path for use inside a regular expression.
std::string quote(const std::string& s) {
  static const std::regex special(R"([.^$|()\[\]{}*+?\\])");
  return std::regex_replace(s, special, R"(\$&)");
}

const char* const kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";  // 3 vertices

// A scene folder: scene.json and tri.obj.
struct JsonScene {
  TempDir dir;
  fs::path json, obj;
  JsonScene(const std::string& json_text, const std::string& obj_text = kTriangle) {
    obj = dir.write("tri.obj", obj_text);
    json = dir.write("scene.json", json_text);
  }
  [[nodiscard]] std::string name() const { return json.string(); }
  [[nodiscard]] std::string error() const {
    return error_of([&] { (void)massspring::io::load_scene<System>(json); });
  }
};

// Reads `text` as mesh.obj and checks that the error is "<path of mesh.obj><rest>".
void check_obj_error(const std::string& text, const std::string& rest) {
  TempDir dir;
  const fs::path obj = dir.write("mesh.obj", text);
  CAPTURE(text);
  CHECK(error_of([&] { (void)massspring::io::read_obj<double>(obj); }) == obj.string() + rest);
}

std::string xml_error(const std::string& text) {
  return error_of([&] { (void)massspring::io::parse_fosssim_scene(text, "s.xml"); });
}

// A valid FOSSSim scene around `body` (two particles, line 3 and 4; body from line 5 on).
std::string xml_scene(
    const std::string& body,
    const std::string& integrator = R"(<integrator type="symplectic-euler" dt="0.01"/>)") {
  return "<scene>\n<duration time=\"1\"/>" + integrator +
         "\n<particle m=\"1\" px=\"0\" py=\"0\" vx=\"0\" vy=\"0\" fixed=\"0\"/>\n"
         "<particle m=\"1\" px=\"1\" py=\"0\" vx=\"0\" vy=\"0\" fixed=\"0\"/>\n" +
         body + "</scene>\n";
}

// Three points in a row, springs (0,1), (1,2).
Points<double> row3() {
  Points<double> v(3, 3);
  v << 0, 0, 0, 1, 0, 0, 2, 0, 0;
  return v;
}
Edges edges(std::initializer_list<std::array<int, 2>> list) {
  Edges e(Eigen::Index(list.size()), 2);
  Eigen::Index r = 0;
  for (const auto& p : list) e.row(r++) << p[0], p[1];
  return e;
}
System chain3() { return System(row3(), edges({{0, 1}, {1, 2}}), 1.0, 10.0); }

}  // namespace

// ---- J: the JSON+OBJ scenes (load_scene, read_json_scene) -----------------------------------

TEST_CASE("J1 malformed JSON") {
  const JsonScene s(R"({"obj": "tri.obj", "b": [1], "k": })");
  CHECK(
      matches(s.error(), quote(s.name()) +
                             R"(: not valid JSON: parse error at line 1, column 35: syntax error )"
                             R"(while parsing value - unexpected '\}'.*)"));
}

TEST_CASE("J2 truncated JSON") {
  const JsonScene s("{\"obj\": \"tri.obj\",\n \"b\": [1");
  CHECK(matches(s.error(), quote(s.name()) +
                               R"(: not valid JSON: parse error at line 2, column 9: syntax error )"
                               R"(while parsing array - unexpected end of input.*)"));
  const JsonScene empty("");
  CHECK(matches(empty.error(),
                quote(empty.name()) + R"(: not valid JSON: parse error at line 1, column 1: .*)"));
}

TEST_CASE("J3 JSON that is not an object") {
  const JsonScene s("[1, 2]");
  CHECK(s.error() == s.name() +
                         ": expected a JSON object {\"obj\": ..., \"b\": [...], \"k\": ...}, got "
                         "array");
}

TEST_CASE("J4 missing required key") {
  for (const char* key : {"obj", "b", "k"}) {
    CAPTURE(key);
    nlohmann::json j = {{"obj", "tri.obj"}, {"b", {1}}, {"k", 10}};
    j.erase(key);
    const JsonScene s(j.dump());
    CHECK(s.error() == s.name() + ": missing key \"" + key + "\"");
  }
}

TEST_CASE("J5 unknown, repeated or unsupported key") {
  const JsonScene unknown(R"({"obj": "tri.obj", "b": [1], "k": 10, "wind": 1})");
  CHECK(unknown.error() ==
        unknown.name() +
            ": unknown key \"wind\" (expected obj, b, k, m, png, colliders, self_collision, "
            "gravity, dt)");
  const JsonScene twice(R"({"obj": "tri.obj", "b": [1], "k": 10, "k": 20})");
  CHECK(twice.error() == twice.name() + ": key \"k\" appears twice");
  const JsonScene bc(R"({"obj": "tri.obj", "b": [1], "k": 10, "bc": [[0, 0, 0]]})");
  CHECK(bc.error() == bc.name() +
                          ": key \"bc\" (pinned positions) is not supported: pinned vertices stay "
                          "at their rest positions");
}

TEST_CASE("J6 key of the wrong type") {
  const JsonScene k(R"({"obj": "tri.obj", "b": [1], "k": "abc"})");
  CHECK(k.error() == k.name() + ": key \"k\": expected a number >= 0, got string \"abc\"");
  const JsonScene obj(R"({"obj": 3, "b": [1], "k": 10})");
  CHECK(obj.error() ==
        obj.name() + ": key \"obj\": expected the name of an OBJ file (a string), got number 3");
  const JsonScene b(R"({"obj": "tri.obj", "b": 1, "k": 10})");
  CHECK(b.error() ==
        b.name() + ": key \"b\": expected an array of 1-based vertex ids, got number 1");
  const JsonScene entry(R"({"obj": "tri.obj", "b": [1, 1.5], "k": 10})");
  CHECK(entry.error() == entry.name() +
                             ": key \"b\": entry 1 (counting from 0) is number 1.5, expected an "
                             "integer vertex id (1-based)");
  const JsonScene png(R"({"obj": "tri.obj", "b": [], "k": 10, "png": 7})");
  CHECK(png.error() ==
        png.name() +
            ": key \"png\": expected the name of a texture image (a string), got number 7");
}

TEST_CASE("J7 stiffness k < 0 or not finite") {
  const JsonScene negative(R"({"obj": "tri.obj", "b": [1], "k": -1})");
  CHECK(negative.error() == negative.name() + ": key \"k\": expected a finite number >= 0, got -1");
  // JSON has no infinity; 1e999 overflows double
  const JsonScene huge(R"({"obj": "tri.obj", "b": [1], "k": 1e999})");
  CHECK(huge.error() == huge.name() + ": not valid JSON: number overflow parsing '1e999'");
  // a stiffness a float cannot hold
  const JsonScene s(R"({"obj": "tri.obj", "b": [1], "k": 1e39})");
  CHECK(error_of([&] { (void)massspring::io::read_json_scene<float>(s.json); }) ==
        s.name() + ": key \"k\": expected a finite number >= 0 (in this Scalar type), got 1e+39");
}

TEST_CASE("J8 mass m <= 0") {
  const JsonScene zero(R"({"obj": "tri.obj", "b": [1], "k": 10, "m": 0})");
  CHECK(zero.error() == zero.name() + ": key \"m\": expected a finite number > 0, got 0");
  const JsonScene negative(R"({"obj": "tri.obj", "b": [1], "k": 10, "m": -2.5})");
  CHECK(negative.error() ==
        negative.name() + ": key \"m\": expected a finite number > 0, got -2.5");
}

TEST_CASE("J9 pin 0 refused (pins are 1-based)") {
  const JsonScene s(R"({"obj": "tri.obj", "b": [0], "k": 10})");
  CHECK(s.error() == s.name() +
                         ": key \"b\": entry 0 (counting from 0) is 0, out of range [1, 3]: "
                         "vertex ids are 1-based and " +
                         s.obj.string() + " has 3 vertices");
}

TEST_CASE("J10 pin n + 1 or negative refused") {
  const JsonScene over(R"({"obj": "tri.obj", "b": [1, 4], "k": 10})");
  CHECK(over.error() == over.name() +
                            ": key \"b\": entry 1 (counting from 0) is 4, out of range [1, 3]: "
                            "vertex ids are 1-based and " +
                            over.obj.string() + " has 3 vertices");
  const JsonScene negative(R"({"obj": "tri.obj", "b": [-1], "k": 10})");
  CHECK(negative.error() == negative.name() +
                                ": key \"b\": entry 0 (counting from 0) is -1, out of range [1, "
                                "3]: vertex ids are 1-based and " +
                                negative.obj.string() + " has 3 vertices");
}

TEST_CASE("J11 pin n accepted: the last point (accepted)") {
  const JsonScene s(R"({"obj": "tri.obj", "b": [3, 1], "k": 10})");
  const System system = massspring::io::load_scene<System>(s.json);
  CHECK(system.pinned() == std::vector<int>{0, 2});
  CHECK(system.pin_targets().row(1) == system.rest_positions().row(2));
}

TEST_CASE("J12 missing OBJ file") {
  const JsonScene s(R"({"obj": "none.obj", "b": [], "k": 10})");
  CHECK(s.error() ==
        s.name() + ": key \"obj\": OBJ file " + (s.dir / "none.obj").string() + " not found");
}

TEST_CASE("J13 unreadable OBJ file") {
  const JsonScene s(R"({"obj": "sub", "b": [], "k": 10})");
  fs::create_directory(s.dir / "sub");
  CHECK(s.error() == (s.dir / "sub").string() + ": cannot read OBJ file: it is a directory");
  if (::geteuid() != 0) {  // root reads a file whatever its mode
    const JsonScene t(R"({"obj": "tri.obj", "b": [], "k": 10})");
    fs::permissions(t.obj, fs::perms::none);
    CHECK(t.error() == t.obj.string() + ": cannot read OBJ file: Permission denied");
  }
}

TEST_CASE("J14 missing or unreadable scene file") {
  TempDir dir;
  const fs::path none = dir / "none.json";
  CHECK(error_of([&] { (void)massspring::io::load_scene<System>(none); }) ==
        none.string() + ": cannot read JSON scene: no such file");
  fs::create_directory(dir / "d.json");
  CHECK(error_of([&] { (void)massspring::io::load_scene<System>(dir / "d.json"); }) ==
        (dir / "d.json").string() + ": cannot read JSON scene: it is a directory");
  CHECK(error_of([&] { (void)massspring::io::load_scene<System>(dir / "scene.txt"); }) ==
        (dir / "scene.txt").string() +
            ": unsupported scene format \".txt\": supported are .json (JSON+OBJ scene), .xml "
            "(FOSSSim XML scene)");
}

TEST_CASE("J15 OBJ file with no vertices") {
  const JsonScene s(R"({"obj": "tri.obj", "b": [], "k": 10, "m": 1})", "# nothing\n");
  CHECK(s.error() == s.name() + ": key \"obj\": OBJ file " + s.obj.string() +
                         " has no vertices: a scene needs at least one point");
}

TEST_CASE("J16 no mass and no faces to take Voronoi masses from") {
  const JsonScene s(R"({"obj": "tri.obj", "b": [], "k": 10})", "v 0 0 0\nv 1 0 0\nf 1 2\n");
  CHECK(s.error() == s.name() + ": scene has no faces to take masses from: give a mass (\"m\")");
  // vertex 4, on line 6 (after a comment), is on a spring only: named by its file, line and
  // 1-based index
  const JsonScene lone(R"({"obj": "tri.obj", "b": [], "k": 10})",
                       std::string(kTriangle) + "# a tail\nv 5 5 5\nf 3 4\n");
  CHECK(lone.error() == lone.name() + ": " + lone.obj.string() +
                            ":6: vertex 4: lies on no face of nonzero area, so its "
                            "Voronoi mass is 0; give a mass (\"m\")");
}

TEST_CASE("J17 repeated springs in an OBJ are merged (accepted)") {
  // adjacent polygons share sides, so a pair that occurs more than once is one spring
  const JsonScene s(R"({"obj": "tri.obj", "b": [], "k": 10, "m": 1})",
                    std::string(kTriangle) + "v 1 1 0\nf 2 4 3\nf 1 2\nf 2 1\nl 1 2 3\n");
  const System system = massspring::io::load_scene<System>(s.json);
  CHECK(system.num_springs() == 5);  // (0,1) (0,2) (1,2) (1,3) (2,3)
}

TEST_CASE("J18 colliders not a list, an entry not an object, a missing or unknown type") {
  const std::string head = R"({"obj": "tri.obj", "b": [], "k": 10, "colliders": )";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"{}", "key \"colliders\": expected an array of collider objects, got object {}"},
      {"[3]",
       "colliders[0]: expected an object with a \"type\" (plane, sphere, capsule, box or mesh), "
       "got number 3"},
      {"[{}]", "colliders[0]: missing key \"type\" (plane, sphere, capsule, box or mesh)"},
      {R"([{"type": "cone"}])",
       "colliders[0]: unknown type \"cone\" (expected plane, sphere, capsule, box or mesh)"}};
  for (const auto& [colliders, message] : cases) {
    const JsonScene s(head + colliders + "}");
    CHECK(s.error() == s.name() + ": " + message);
  }
}

TEST_CASE("J19 unknown, missing or repeated collider key") {
  const std::string head =
      R"({"obj": "tri.obj", "b": [], "k": 10, "colliders": [{"type": "sphere", "center": [0, 0, 0])";
  const JsonScene unknown(head + R"(, "radius": 1, "radiu": 2}]})");
  CHECK(unknown.error() == unknown.name() +
                               ": colliders[0] (sphere): unknown key \"radiu\" (a sphere takes "
                               "center, radius; friction, restitution, thickness, velocity, "
                               "angular_velocity)");
  const JsonScene missing(head + "}]}");
  CHECK(missing.error() == missing.name() + ": colliders[0] (sphere): missing key \"radius\"");
  const JsonScene twice(head + R"(, "radius": 1, "radius": 2}]})");
  CHECK(twice.error() == twice.name() + ": colliders[0]: key \"radius\" appears twice");
}

TEST_CASE("J20 collider value of the wrong type or out of range") {
  const std::string head = R"({"obj": "tri.obj", "b": [], "k": 10, "colliders": [)";
  const std::string sphere = R"({"type": "sphere", "center": [0, 0, 0], )";
  const std::string box = R"({"type": "box", "center": [0, 0, 0], )";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {sphere + R"("radius": -1})", "(sphere): \"radius\" must be finite and > 0, got -1"},
      {sphere + R"("radius": "a"})", "(sphere): \"radius\" must be a number > 0, got string \"a\""},
      {R"({"type": "sphere", "center": [0, 0], "radius": 1})",
       "(sphere): \"center\" must be [x, y, z] (3 numbers), got array [0,0]"},
      {R"({"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 0]})",
       "(plane): \"normal\" must not be zero, got [0,0,0]"},
      {box + R"("half_extents": [1, 0, 1]})",
       "(box): \"half_extents\" must be 3 numbers > 0, got [1,0,1]"},
      {box + R"("half_extents": [1, 1, 1], "rotation": [0, 0, 0, 0]})",
       "(box): \"rotation\" must be a quaternion [w, x, y, z], not zero, got [0,0,0,0]"},
      {sphere + R"("radius": 1, "friction": {"static": 0.3, "kinetic": 0.5}})",
       "(sphere): \"friction\": kinetic 0.5 exceeds static 0.3 (Coulomb: kinetic <= static)"},
      {sphere + R"("radius": 1, "restitution": 2})",
       "(sphere): \"restitution\" must be finite and in [0, 1], got 2"},
      {sphere + R"("radius": 1, "thickness": -1})",
       "(sphere): \"thickness\" must be finite and >= 0, got -1"}};
  for (const auto& [collider, message] : cases) {
    const JsonScene s(head + collider + "]}");
    CHECK(s.error() == s.name() + ": colliders[0] " + message);
  }
  const JsonScene huge(head + sphere + R"("radius": 1e39}]})");
  CHECK(error_of([&] { (void)massspring::io::read_json_scene<float>(huge.json); }) ==
        huge.name() +
            ": colliders[0] (sphere): \"radius\" must be finite and > 0 (in this Scalar type), got "
            "1e+39");
}

TEST_CASE("J21 a mesh collider's OBJ missing, not polygons, or degenerate") {
  const std::string head =
      R"({"obj": "tri.obj", "b": [], "k": 10, "colliders": [{"type": "mesh", "obj": )";
  const JsonScene none(head + R"("none.obj"}]})");
  CHECK(none.error() == none.name() + ": colliders[0] (mesh): \"obj\": OBJ file " +
                            (none.dir.path() / "none.obj").string() + " not found");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"v 0 0 0\nv 1 0 0\nf 1 2\n",
       " has 2-vertex faces or lines: a collider mesh takes polygons only"},
      {"v 0 0 0\n", " has no polygons: a collider mesh needs some"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\n",
       ":6: face (1, 2, 4) has zero area"},
      // a quad's second fan triangle (1, 2, 4) is flat; the file's line and 1-based indices
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\n\n# flat\nf 1 3 2 4\n",
       ":7: face (1, 3, 2, 4): fan triangle (1, 2, 4) has zero area"}};
  for (const auto& [obj, message] : cases) {
    const JsonScene s(head + R"("m.obj"}]})");
    const fs::path m = s.dir.write("m.obj", obj);
    const std::string key = message[0] == ':' ? "" : "\"obj\": ";
    CHECK(s.error() == s.name() + ": colliders[0] (mesh): " + key + m.string() + message);
  }
}

TEST_CASE("J22 self_collision not an object, an unknown, repeated or bad field") {
  const std::string head = R"({"obj": "tri.obj", "b": [], "k": 10, "self_collision": )";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"true", R"(key "self_collision": expected an object {"thickness": T, "friction": MU}, )"
               R"(got boolean true)"},
      {R"({"stiffness": 1})",
       R"(key "self_collision": unknown key "stiffness" (expected thickness, friction))"},
      {R"({"thickness": 0})",
       R"(key "self_collision": "thickness": expected a finite number > 0, got 0)"},
      {R"({"friction": -0.2})",
       R"(key "self_collision": "friction": expected a finite number >= 0, got -0.2)"},
      {R"({"thickness": "4mm"})",
       R"(key "self_collision": "thickness": expected a number > 0, got string "4mm")"},
      {R"({"thickness": 0.1, "thickness": 0.2})",
       R"(key "self_collision": key "thickness" appears twice)"}};
  for (const auto& [value, message] : cases) {
    CAPTURE(value);
    const JsonScene s(head + value + "}");
    CHECK(s.error() == s.name() + ": " + message);
  }
}

TEST_CASE("J23 a surface make_system cannot build") {
  // the quad on line 6 (after a comment) has the flat fan triangle (1, 2, 3): the file's line and
  // 1-based indices
  const JsonScene flat(R"({"obj": "tri.obj", "b": [], "k": 10, "m": 1})",
                       "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\n# a quad\nf 1 2 3 4\n");
  CHECK(flat.error() == flat.name() + ": " + flat.obj.string() +
                            ":6: face (1, 2, 3, 4): fan triangle (1, 2, 3): zero area at the rest "
                            "positions");
  // a flat triangle face after a good one: named without "fan triangle"
  const JsonScene second(R"({"obj": "tri.obj", "b": [], "k": 10, "m": 1})",
                         std::string(kTriangle) + "v 2 0 0\nf 1 2 4\n");
  CHECK(second.error() == second.name() + ": " + second.obj.string() +
                              ":6: face (1, 2, 4): zero area at the rest positions");
  const JsonScene chain(R"({"obj": "tri.obj", "b": [], "k": 10, "m": 1, "self_collision": {}})",
                        "v 0 0 0\nv 1 0 0\nf 1 2\n");
  CHECK(chain.error() == chain.name() +
                             ": self_collision: the scene has no faces, so no surface to collide "
                             "(chains and nets have none)");
}

// ---- O: OBJ files (read_obj), messages "<file>:<line>: ..." ---------------------------------

TEST_CASE("O1 malformed number") {
  check_obj_error("v 0 0 0\nv 1 x 0\n", ":2: vertex coordinate 2 is not a number: \"x\"");
  check_obj_error("v 1,5 0 0\n", ":1: vertex coordinate 1 is not a number: \"1,5\"");
}

TEST_CASE("O2 truncated OBJ") {
  // cut in the middle of a vertex line, of a number, of a face
  check_obj_error(
      "v 0 0 0\nv 1 0",
      ":2: a vertex needs 3 coordinates and an optional weight (v x y z [w]), got 2 values");
  check_obj_error("v 0 0 0\nv 1 0 1e", ":2: vertex coordinate 3 is not a number: \"1e\"");
  check_obj_error(
      "v 0 0 0\nv 1 0 0\nf 1",
      ":3: a face needs at least 2 vertices (f i j for a spring, 3 or more for a polygon), "
      "got 1");
  check_obj_error("v 0 0 0\nv 1 0 0\nf 1 2/",
                  ":3: face vertex 2 is malformed: \"2/\" (expected i, i/t, i//n or i/t/n)");
}

TEST_CASE("O3 non-finite or out-of-range coordinate") {
  check_obj_error("v nan 0 0\n", ":1: vertex coordinate 1 is not finite: \"nan\"");
  check_obj_error("v 0 inf 0\n", ":1: vertex coordinate 2 is not finite: \"inf\"");
  check_obj_error("v 0 0 1e999\n", ":1: vertex coordinate 3 is out of range for double: \"1e999\"");
}

TEST_CASE("O4 unsupported statement") {
  check_obj_error(
      "v 0 0 0\ncurv 1 2\n",
      ":2: unsupported OBJ statement \"curv\" (expected v, f or l; vt, vn, vp, o, g, s, "
      "usemtl and mtllib are ignored)");
}

TEST_CASE("O5 vertex index 0, out of range, or not an integer") {
  check_obj_error(std::string(kTriangle) + "f 0 1\n",
                  ":5: face vertex 1: vertex index 0 is invalid (OBJ indices start at 1)");
  check_obj_error("v 0 0 0\nf 1 5\nv 1 0 0\n",
                  ":2: vertex index 5 is out of range: the file has 2 vertices");
  check_obj_error(
      std::string(kTriangle) + "f 1 -4\n",
      ":5: face vertex 2: vertex index -4 refers before the first vertex (3 vertices are "
      "defined above it)");
  check_obj_error(std::string(kTriangle) + "f 1 a\n",
                  ":5: face vertex 2: vertex index is not an integer: \"a\"");
  check_obj_error(std::string(kTriangle) + "f 1 99999999999999999999\n",
                  ":5: face vertex 2: vertex index is out of range: \"99999999999999999999\"");
  check_obj_error(std::string(kTriangle) + "f 1/0 2\n",
                  ":5: face vertex 1: texture index is not a nonzero integer: \"1/0\"");
}

TEST_CASE("O6 face or segment from a vertex to itself") {
  check_obj_error(
      std::string(kTriangle) + "f 1 2 1\n",
      ":5: face vertices 1 and 3 are the same vertex 1: a face may not repeat a vertex");
  check_obj_error(
      std::string(kTriangle) + "f 2 2\n",
      ":5: face vertices 1 and 2 are the same vertex 2: a face may not repeat a vertex");
  check_obj_error(
      std::string(kTriangle) + "l 1 2 2\n",
      ":5: polyline vertices 2 and 3 are the same vertex: a segment must join two vertices");
}

TEST_CASE("O7 missing OBJ file") {
  TempDir dir;
  CHECK(error_of([&] { (void)massspring::io::read_obj<double>(dir / "none.obj"); }) ==
        (dir / "none.obj").string() + ": cannot read OBJ file: no such file");
}

// ---- X: FOSSSim XML scenes (parse_fosssim_scene, read_fosssim_scene), "<file>:<line>: ..." ---

TEST_CASE("X1 malformed XML") {
  CHECK(matches(xml_error("<scene>\n<duration time=\"1\"/>\n<particle m=1/>\n</scene>\n"),
                R"(s\.xml:3: not well-formed XML: .+)"));
}

TEST_CASE("X2 truncated or empty XML") {
  CHECK(matches(xml_error("<scene>\n<duration time=\"1\"/>\n<particle m=\"1\""),
                R"(s\.xml:3: not well-formed XML: .+)"));
  CHECK(matches(xml_error("<scene>\n<duration time=\"1\"/>\n"),
                R"(s\.xml:[23]: not well-formed XML: .+)"));
  CHECK(xml_error("") == "s.xml:1: not well-formed XML: No document element found");
  CHECK(xml_error("<!-- only a comment -->\n") ==
        "s.xml:2: not well-formed XML: No document element found");
}

TEST_CASE("X3 wrong or second root element") {
  CHECK(xml_error("\n<scenes/>\n") == "s.xml:2: the root element is <scenes>, expected <scene>");
  CHECK(xml_error(xml_scene("") + "<scene/>\n") ==
        "s.xml:6: a second root element <scene> (a scene file holds one <scene>)");
}

TEST_CASE("X4 unknown element or attribute") {
  CHECK(xml_error(xml_scene("<rigidbody i=\"0\"/>\n")) ==
        "s.xml:5: unknown element <rigidbody> (massspring reads particle, edge, halfplane, "
        "springforce, simplegravity, gravitationalforce, dragdamping, vortexforce, collision, "
        "collisiondetection, integrator, duration, and ignores the rendering elements)");
  CHECK(xml_error(xml_scene("<edge i=\"0\" j=\"1\" colour=\"red\"/>\n")) ==
        "s.xml:5: <edge> 0: unknown attribute \"colour\" (expected i, j, radius)");
}

TEST_CASE("X5 missing required element or attribute") {
  CHECK(xml_error("<scene>\n<integrator type=\"symplectic-euler\" dt=\"0.1\"/>\n</scene>") ==
        "s.xml:1: <scene> has no <duration time=\"...\"/>");
  CHECK(xml_error("<scene>\n<duration time=\"1\"/>\n</scene>") ==
        "s.xml:1: <scene> has no <integrator type=\"...\" dt=\"...\"/>");
  CHECK(xml_error(xml_scene("<particle px=\"0\" py=\"0\" vx=\"0\" vy=\"0\" fixed=\"0\"/>\n")) ==
        "s.xml:5: <particle> 2: missing required attribute \"m\"");
  CHECK(xml_error(xml_scene("<edge i=\"0\" j=\"1\"/>\n<springforce edge=\"0\" k=\"1\"/>\n")) ==
        "s.xml:6: <springforce> 0: missing required attribute \"l0\"");
  CHECK(xml_error("<scene>\n<duration time=\"1\"/>\n<integrator type=\"symplectic-euler\" "
                  "dt=\"0.1\"/>\n</scene>") ==
        "s.xml:1: <scene> has no <particle>: a scene needs at least one particle");
}

TEST_CASE("X6 repeated duration or integrator") {
  CHECK(xml_error(xml_scene("<duration time=\"2\"/>\n")) ==
        "s.xml:5: <duration> appears twice (first on line 2)");
}

TEST_CASE("X7 unknown integrator type") {
  CHECK(xml_error(xml_scene("", R"(<integrator type="rk4" dt="0.01"/>)")) ==
        "s.xml:2: <integrator>: unknown type \"rk4\" (expected explicit-euler, symplectic-euler, "
        "forward-backward-euler, linearized-implicit-euler or implicit-euler)");
}

TEST_CASE("X8 value that is not a number, not finite or out of range") {
  const std::string p = "<particle m=\"1\" px=\"0\" py=\"0\" vx=\"0\" vy=\"0\" fixed=\"0\"/>\n";
  auto with = [&](const std::string& attribute, const std::string& value) {
    std::string q = p;
    const auto at = q.find(attribute + "=\"") + attribute.size() + 2;
    q.replace(at, q.find('"', at) - at, value);
    return xml_error(xml_scene(q));
  };
  CHECK(with("px", "abc") == "s.xml:5: <particle> 2: px = \"abc\" is not a number");
  CHECK(with("py", "nan") == "s.xml:5: <particle> 2: py = \"nan\" must be finite");
  CHECK(with("vx", "inf") == "s.xml:5: <particle> 2: vx = \"inf\" must be finite");
  CHECK(with("vy", "1e999") ==
        "s.xml:5: <particle> 2: vy = \"1e999\" is out of the range of double");
  CHECK(with("fixed", "yes") == "s.xml:5: <particle> 2: fixed = \"yes\" must be 0 or 1");
  CHECK(xml_error(xml_scene("<simplegravity fx=\"0\" fy=\"-inf\"/>\n")) ==
        "s.xml:5: <simplegravity>: fy = \"-inf\" must be finite");
}

TEST_CASE("X9 mass m <= 0") {
  for (const char* m : {"0", "-1"}) {
    CAPTURE(m);
    CHECK(xml_error(xml_scene(std::string("<particle m=\"") + m +
                              "\" px=\"0\" py=\"0\" vx=\"0\" vy=\"0\" fixed=\"0\"/>\n")) ==
          std::string("s.xml:5: <particle> 2: m = ") + m + " must be > 0");
  }
}

TEST_CASE("X10 negative k, l0, b, G, drag, radius or duration") {
  const std::string edge = "<edge i=\"0\" j=\"1\"/>\n";
  CHECK(xml_error(xml_scene(edge + "<springforce edge=\"0\" k=\"-1\" l0=\"1\"/>\n")) ==
        "s.xml:6: <springforce> 0: k = -1 must be >= 0");
  CHECK(xml_error(xml_scene(edge + "<springforce edge=\"0\" k=\"1\" l0=\"-0.5\"/>\n")) ==
        "s.xml:6: <springforce> 0: l0 = -0.5 must be >= 0");
  CHECK(xml_error(xml_scene(edge + "<springforce edge=\"0\" k=\"1\" l0=\"1\" b=\"-2\"/>\n")) ==
        "s.xml:6: <springforce> 0: b = -2 must be >= 0");
  CHECK(xml_error(xml_scene("<gravitationalforce i=\"0\" j=\"1\" G=\"-1\"/>\n")) ==
        "s.xml:5: <gravitationalforce> 0: G = -1 must be >= 0");
  CHECK(xml_error(xml_scene("<dragdamping b=\"-1\"/>\n")) ==
        "s.xml:5: <dragdamping>: b = -1 must be >= 0");
  CHECK(xml_error(xml_scene("<edge i=\"0\" j=\"1\" radius=\"-1\"/>\n")) ==
        "s.xml:5: <edge> 0: radius = -1 must be >= 0");
  CHECK(xml_error("<scene>\n<duration time=\"-1\"/>\n</scene>") ==
        "s.xml:1: <scene> has no <integrator type=\"...\" dt=\"...\"/>");
  CHECK(xml_error("<scene>\n<duration time=\"-1\"/>\n<integrator type=\"explicit-euler\" "
                  "dt=\"1\"/>\n</scene>") == "s.xml:2: <duration>: time = -1 must be >= 0");
}

TEST_CASE("X11 dt <= 0 or not finite") {
  for (const char* dt : {"0", "-0.01"}) {
    CAPTURE(dt);
    CHECK(xml_error(xml_scene(
              "", std::string(R"(<integrator type="explicit-euler" dt=")") + dt + "\"/>")) ==
          std::string("s.xml:2: <integrator>: dt = ") + dt + " must be > 0");
  }
  CHECK(xml_error(xml_scene("", R"(<integrator type="explicit-euler" dt="inf"/>)")) ==
        "s.xml:2: <integrator>: dt = \"inf\" must be finite");
}

TEST_CASE("X12 index not a whole number or out of range") {
  CHECK(xml_error(xml_scene("<edge i=\"0\" j=\"1.5\"/>\n")) ==
        "s.xml:5: <edge> 0: j = \"1.5\" is not a whole number");
  CHECK(xml_error(xml_scene("<edge i=\"0\" j=\"2\"/>\n")) ==
        "s.xml:5: <edge> 0: j = 2 is out of range: the scene has 2 particles");
  CHECK(xml_error(xml_scene("<edge i=\"-1\" j=\"1\"/>\n")) ==
        "s.xml:5: <edge> 0: i = -1 is out of range: the scene has 2 particles");
  CHECK(xml_error(
            xml_scene("<edge i=\"0\" j=\"1\"/>\n<springforce edge=\"1\" k=\"1\" l0=\"1\"/>\n")) ==
        "s.xml:6: <springforce> 0: edge = 1 is out of range: the scene has 1 edge");
  CHECK(xml_error(xml_scene("<gravitationalforce i=\"0\" j=\"7\" G=\"1\"/>\n")) ==
        "s.xml:5: <gravitationalforce> 0: j = 7 is out of range: the scene has 2 particles");
}

TEST_CASE("X13 edge or attraction from a particle to itself") {
  CHECK(xml_error(xml_scene("<edge i=\"1\" j=\"1\"/>\n")) ==
        "s.xml:5: <edge> 0 joins particle 1 to itself");
  CHECK(xml_error(xml_scene("<gravitationalforce i=\"0\" j=\"0\" G=\"1\"/>\n")) ==
        "s.xml:5: <gravitationalforce> 0 attracts particle 0 to itself");
}

TEST_CASE("X14 duplicate springs refused") {
  const std::string edges = "<edge i=\"0\" j=\"1\"/>\n<edge i=\"1\" j=\"0\"/>\n";
  CHECK(xml_error(xml_scene(edges + "<springforce edge=\"0\" k=\"1\" l0=\"1\"/>\n"
                                    "<springforce edge=\"0\" k=\"1\" l0=\"1\"/>\n")) ==
        "s.xml:8: <springforce> 1: edge 0 already has a spring (<springforce> 0 on line 7); one "
        "<springforce> per edge");
  CHECK(xml_error(xml_scene(edges + "<springforce edge=\"0\" k=\"1\" l0=\"1\"/>\n"
                                    "<springforce edge=\"1\" k=\"1\" l0=\"1\"/>\n")) ==
        "s.xml:8: <springforce> 1: particles 0 and 1 are already joined by <springforce> 0 on "
        "line 7 (through another edge); one spring per pair");
}

TEST_CASE("X15 forces that add up to a non-finite value") {
  CHECK(xml_error(xml_scene("<simplegravity fx=\"1e308\" fy=\"0\"/>\n"
                            "<simplegravity fx=\"1e308\" fy=\"0\"/>\n")) ==
        "s.xml:6: <simplegravity>: the accelerations so far add up to (inf, 0, 0), which is not "
        "finite");
  CHECK(xml_error(xml_scene("<dragdamping b=\"1e308\"/>\n<dragdamping b=\"1e308\"/>\n")) ==
        "s.xml:6: <dragdamping>: the coefficients so far add up to inf, which is not finite");
}

TEST_CASE("X17 collision, collisiondetection, halfplane and vortexforce (Theme 2)") {
  CHECK(xml_error(xml_scene("<collision/>\n")) ==
        "s.xml:5: <collision>: missing required attribute \"type\"");
  CHECK(xml_error(xml_scene("<collision type=\"soft\"/>\n")) ==
        "s.xml:5: <collision>: unknown type \"soft\" (expected none, simple, penalty, "
        "continuous-time or hybrid)");
  CHECK(xml_error(xml_scene("<collision type=\"simple\" k=\"3\"/>\n")) ==
        "s.xml:5: <collision>: attribute \"k\" does not apply to type \"simple\" (it reads COR)");
  CHECK(xml_error(xml_scene("<collision type=\"penalty\" mu=\"3\"/>\n")) ==
        "s.xml:5: <collision>: unknown attribute \"mu\" (type \"penalty\" reads k and "
        "thickness)");
  CHECK(xml_error(xml_scene("<collision type=\"simple\" COR=\"1.5\"/>\n")) ==
        "s.xml:5: <collision>: COR = 1.5 must be in [0, 1]");
  CHECK(xml_error(xml_scene("<collision type=\"penalty\" k=\"-1\"/>\n")) ==
        "s.xml:5: <collision>: k = -1 must be >= 0");
  CHECK(xml_error(xml_scene("<collision type=\"hybrid\" maxiters=\"2.5\"/>\n")) ==
        "s.xml:5: <collision>: maxiters = \"2.5\" must be a whole number >= 0");
  CHECK(xml_error(xml_scene("<collision type=\"none\"/>\n<collision type=\"none\"/>\n")) ==
        "s.xml:6: <collision> appears twice (first on line 5)");
  CHECK(xml_error(xml_scene("<collisiondetection type=\"octree\"/>\n")) ==
        "s.xml:5: <collisiondetection>: unknown type \"octree\" (expected allpairs or contest)");
  CHECK(xml_error(xml_scene("<halfplane px=\"0\" py=\"0\" nx=\"0\" ny=\"0\"/>\n")) ==
        "s.xml:5: <halfplane> 0: the normal (nx, ny) = (0, 0) must be non-zero (and its square "
        "finite)");
  CHECK(xml_error(xml_scene("<vortexforce i=\"1\" j=\"1\" kbs=\"1\" kvc=\"1\"/>\n")) ==
        "s.xml:5: <vortexforce> 0 acts between particle 1 and itself");
  CHECK(xml_error(xml_scene("<vortexforce i=\"0\" j=\"1\"/>\n")) ==
        "s.xml:5: <vortexforce> 0: missing required attribute \"kbs\"");
  // A number that is not one, inside the half-plane's point (once an unfinished Eigen comma
  // initializer: tests/data/fuzz/fuzz_fosssim_scene/halfplane-not-a-number.xml).
  CHECK(xml_error(xml_scene("<halfplane px=\"0\" py=\"m1.0\" nx=\"0\" ny=\"1\"/>\n")) ==
        "s.xml:5: <halfplane> 0: py = \"m1.0\" is not a number");
}

TEST_CASE("X16 missing or unreadable XML file") {
  TempDir dir;
  CHECK(error_of([&] { (void)massspring::io::read_fosssim_scene(dir / "none.xml"); }) ==
        (dir / "none.xml").string() + ": cannot read FOSSSim scene: no such file");
  CHECK(error_of([&] { (void)massspring::io::load_scene<System>(dir / "none.xml"); }) ==
        (dir / "none.xml").string() + ": cannot read FOSSSim scene: no such file");
  CHECK(error_of([&] { (void)massspring::io::read_fosssim_scene(dir.path()); }) ==
        dir.path().string() + ": cannot read FOSSSim scene: it is a directory");
}

// ---- S: MassSpringSystem (constructor and setters) ------------------------------------------

TEST_CASE("S1 spring point index out of range") {
  CHECK(error_of([] {
          System s(row3(), edges({{0, 1}, {1, 3}}), 1.0, 1.0);
        }) == "spring 1 = (1, 3): point index 3 out of range [0, 3)");
  CHECK(error_of([] {
          System s(row3(), edges({{-1, 1}}), 1.0, 1.0);
        }) == "spring 0 = (-1, 1): point index -1 out of range [0, 3)");
}

TEST_CASE("S2 spring from a point to itself") {
  CHECK(error_of([] {
          System s(row3(), edges({{0, 1}, {2, 2}}), 1.0, 1.0);
        }) == "spring 1 connects point 2 to itself");
}

TEST_CASE("S3 duplicate springs refused") {
  CHECK(error_of([] {
          System s(row3(), edges({{0, 1}, {1, 2}, {1, 0}}), 1.0, 1.0);
        }) == "spring 2 duplicates spring 0: both join points 0 and 1");
}

TEST_CASE("S4 mass m <= 0 or not finite") {
  CHECK(error_of([] {
          System s(row3(), edges({{0, 1}}), 0.0, 1.0);
        }) == "point 0: mass must be finite and > 0, got 0");
  System s = chain3();
  CHECK(error_of([&] {
          s.set_masses(Vector<double>::Constant(3, 1.0).eval().cwiseProduct(
              (Vector<double>(3) << 1, -1, 1).finished()));
        }) == "point 1: mass must be finite and > 0, got -1");
  CHECK(error_of([&] { s.set_masses((Vector<double>(3) << 1, 1, kNaN).finished()); }) ==
        "point 2: mass must be finite and > 0, got nan");
  CHECK(error_of([&] { s.set_masses(Vector<double>::Ones(2)); }) ==
        "masses: expected one value per point (3), got 2");
}

TEST_CASE("S5 stiffness k < 0 or not finite") {
  CHECK(error_of([] {
          System s(row3(), edges({{0, 1}}), 1.0, -1.0);
        }) == "spring 0: stiffness must be finite and >= 0, got -1");
  System s = chain3();
  CHECK(error_of([&] { s.set_stiffness((Vector<double>(2) << 1, kInf).finished()); }) ==
        "spring 1: stiffness must be finite and >= 0, got inf");
}

TEST_CASE("S6 non-finite position, velocity, rest length or damping") {
  Points<double> v = row3();
  v(1, 0) = kNaN;
  CHECK(error_of([&] {
          System s(v, edges({{0, 1}}), 1.0, 1.0);
        }) == "point 1: rest position must be finite, got (nan, 0, 0)");
  System s = chain3();
  CHECK(error_of([&] { s.set_positions(v); }) ==
        "point 1: positions must be finite, got (nan, 0, 0)");
  CHECK(error_of([&] { s.set_velocities(v); }) ==
        "point 1: velocities must be finite, got (nan, 0, 0)");
  CHECK(error_of([&] { s.set_rest_lengths((Vector<double>(2) << 1, -1).finished()); }) ==
        "spring 1: rest length must be finite and >= 0, got -1");
  CHECK(error_of([&] { s.set_damping((Vector<double>(2) << kNaN, 0).finished()); }) ==
        "spring 0: damping must be finite and >= 0, got nan");
}

TEST_CASE("S7 pin index out of range or target not finite") {
  System s = chain3();
  CHECK(error_of([&] { s.pin(3); }) == "pin: point index 3 out of range [0, 3)");
  CHECK(error_of([&] { s.pin(-1); }) == "pin: point index -1 out of range [0, 3)");
  CHECK(error_of([&] {
          s.pin(std::vector<int>{0, 5});
        }) == "pin: point index 5 out of range [0, 3)");
  CHECK(error_of([&] { s.pin(0, Vector3<double>(0, kInf, 0)); }) ==
        "pin 0: target must be finite, got (0, inf, 0)");
  CHECK(error_of([&] { s.set_pin_target(1, Vector3<double>::Zero()); }) ==
        "pin target: point 1 is not pinned");
}

TEST_CASE("S8 zero-length spring at rest (accepted)") {
  // two points at the same place joined by a spring of rest length 0: the spring has no
  // direction; every integrator steps it (FastMassSpring keeps the last direction, the force
  // terms take a zero force) and the state stays finite
  Points<double> v(3, 3);
  v << 0, 0, 0, 0, 0, 0, 1, 0, 0;
  auto make = [&] {
    System s(v, edges({{0, 1}, {1, 2}}), 1.0, 10.0);
    s.pin(2);
    s.add_force(massspring::Gravity<double>({0, -9.8, 0}));
    return s;
  };
  CHECK(make().rest_lengths()(0) == 0);
  auto run = [&](auto integrator) {
    System s = make();
    integrator.precompute(s, 0.01);
    for (int k = 0; k < 20; ++k) REQUIRE(integrator.step(s).ok());
    CHECK(s.positions().allFinite());
    CHECK(s.positions()(0, 1) < 0);  // it fell
  };
  run(massspring::FastMassSpring<System>{});
  run(massspring::ForwardEuler<System>{});
  run(massspring::SymplecticEuler<System>{});
  run(massspring::BackwardEuler<System>{});
}

// ---- F: force terms ------------------------------------------------------------------------

TEST_CASE("F1 non-finite or negative force parameters") {
  CHECK(error_of([] {
          massspring::Gravity<double> g({0, kNaN, 0});
        }) == "gravity: acceleration must be finite, got (0, nan, 0)");
  CHECK(error_of([] {
          massspring::ConstantForce<double> f({kInf, 0, 0});
        }) == "constant force: must be finite, got (inf, 0, 0)");
  CHECK(error_of([] { massspring::LinearDrag<double> d(-1); }) ==
        "linear drag: beta must be finite and >= 0, got -1");
  using Attraction = massspring::GravitationalAttraction<double>;
  CHECK(error_of([] {
          Attraction a({{0, 1, -1.0}});
        }) == "gravitational attraction pair 0: G must be finite and >= 0, got -1");
  CHECK(error_of([] {
          Attraction a({{0, 1, 1.0}, {2, 2, 1.0}});
        }) == "gravitational attraction pair 1 attracts point 2 to itself");
  CHECK(error_of([] {
          Attraction a({{0, -1, 1.0}});
        }) == "gravitational attraction pair 0 = (0, -1): negative point index");
}

TEST_CASE("F2 force term point index out of range") {
  System s = chain3();
  CHECK(matches(error_of([&] {
                  s.add_force(massspring::GravitationalAttraction<double>({{0, 3, 1.0}}));
                }),
                R"(.*: point index 3 out of range \[0, 3\))"));
}

// ---- I: integrators ------------------------------------------------------------------------

TEST_CASE("I1 dt <= 0 or not finite, every integrator") {
  for (const double dt : {0.0, -0.1, kInf, kNaN}) {
    CAPTURE(dt);
    System s = chain3();
    const std::string got = massspring::detail::message(dt);
    CHECK(error_of([&] { massspring::ForwardEuler<System>{}.precompute(s, dt); }) ==
          "ForwardEuler: dt must be finite and > 0, got " + got);
    CHECK(error_of([&] { massspring::SymplecticEuler<System>{}.precompute(s, dt); }) ==
          "SymplecticEuler: dt must be finite and > 0, got " + got);
    CHECK(error_of([&] { massspring::BackwardEuler<System>{}.precompute(s, dt); }) ==
          "BackwardEuler: dt must be finite and > 0, got " + got);
    CHECK(error_of([&] { massspring::FastMassSpring<System>{}.precompute(s, dt); }) ==
          "FastMassSpring: dt must be finite and > 0, got " + got);
  }
}

TEST_CASE("I2 step before precompute") {
  System s = chain3();
  CHECK(error_of([&] { (void)massspring::ForwardEuler<System>{}.step(s); }) ==
        "ForwardEuler: step() before precompute()");
  CHECK(error_of([&] { (void)massspring::SymplecticEuler<System>{}.step(s); }) ==
        "SymplecticEuler: step() before precompute()");
  CHECK(error_of([&] { (void)massspring::BackwardEuler<System>{}.step(s); }) ==
        "BackwardEuler: step() before precompute()");
  CHECK(error_of([&] { (void)massspring::FastMassSpring<System>{}.step(s); }) ==
        "FastMassSpring: step() before precompute()");
}

TEST_CASE("I3 an elimination order that cannot be used") {
  // FastMassSpring's options.ordering on a Cholesky that takes no order; SparseCholesky given a
  // non-permutation; nested_dissection given coordinates that do not fit.
  massspring::MassSpringSystem<double, massspring::Dense> dense(row3(), edges({{0, 1}, {1, 2}}),
                                                                1.0, 10.0);
  massspring::FastMassSpring<decltype(dense)> solver;
  solver.options.ordering = massspring::FillOrdering::NestedDissection;
  CHECK(error_of([&] { solver.precompute(dense, 0.1); }) ==
        "FastMassSpring: options.ordering = NestedDissection: this storage's Cholesky takes no "
        "given elimination order (use Sparse storage)");
  System s = chain3();
  massspring::FastMassSpring<System> sparse;
  sparse.precompute(s, 0.1);
  massspring::SparseCholesky<double> llt;
  CHECK(error_of([&] {
          llt.compute(sparse.system_matrix(), {0, 2, 2});
        }) == "SparseCholesky: the order is not a permutation of 0 .. 2 (entry 2 is 2)");
  CHECK(error_of([&] {
          llt.compute(sparse.system_matrix(), {0, 1});
        }) == "SparseCholesky: the order has 2 entries for 3 unknowns");
  const massspring::Graph g = massspring::graph_of(sparse.system_matrix());
  Eigen::Matrix<double, Eigen::Dynamic, 3> xyz = s.rest_positions().topRows(2);
  CHECK(error_of([&] { (void)massspring::nested_dissection(xyz, g); }) ==
        "nested_dissection: coordinates are 2 x 3 for a graph of 3 vertices (need 3 x 3)");
  xyz = s.rest_positions();
  xyz(1, 0) = kNaN;
  CHECK(error_of([&] { (void)massspring::nested_dissection(xyz, g); }) ==
        "nested_dissection: coordinate (1, 0) is not finite: nan");
}

// ---- the fuzzers' regression inputs ---------------------------------------------------------

// Every file in tests/data/fuzz/<target>/ once crashed a fuzz target (fuzz/) or made it time out;
// each must now end normally or with massspring::Error, in the normal build as under the
// sanitizers. (What a timeout did wrong is checked by a test of its own: the far point over a
// rod, tests/integrators/detail/test_contact_dual.cpp.)
TEST_CASE("fuzz regressions: tests/data/fuzz replays without a crash") {
  const fs::path root = massspring::test::source_dir() / "tests" / "data" / "fuzz";
  int replayed = 0;
  for (const char* target : {"fuzz_json_scene", "fuzz_fosssim_scene"}) {
    if (!fs::is_directory(root / target)) continue;
    for (const auto& entry : fs::directory_iterator(root / target)) {
      CAPTURE(entry.path().string());
      const std::string input = massspring::test::read_bytes(entry.path());
      try {
        if (std::string(target) == "fuzz_json_scene")
          massspring::fuzz::run_json_scene_input(input);
        else
          massspring::fuzz::run_fosssim_scene_input(input);
      } catch (const Error&) {
        // refused clearly
      }
      ++replayed;
    }
  }
  CHECK(replayed >= 1);
}
