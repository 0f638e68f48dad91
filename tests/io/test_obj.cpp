// io/obj.hpp: what the strict reader accepts, what it refuses (file and line named), and the
// writer's exact round trip.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <massspring/io/obj.hpp>
#include <random>
#include <string>
#include <vector>

#include "io/test_files.hpp"
#include "support/paths.hpp"

namespace {

using massspring::Edges;
using massspring::Error;
using massspring::io::read_obj;
using massspring::io::write_obj;
using massspring::test::TempDir;

template <class Scalar>
using Points = massspring::Points<Scalar>;

template <class Scalar>
bool bit_identical(const Points<Scalar>& a, const Points<Scalar>& b) {
  return a.rows() == b.rows() &&
         std::memcmp(a.data(), b.data(), sizeof(Scalar) * std::size_t(a.size())) == 0;
}

// Reads `text` as <dir>/bad.obj and returns the error message ("" when it was accepted).
template <class Scalar = double>
std::string refusal(const TempDir& dir, const std::string& text) {
  const auto file = dir.write("bad.obj", text);
  try {
    (void)read_obj<Scalar>(file);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE_TEMPLATE("read_obj reads vertices, polygons, 2-vertex faces and polylines", Scalar, float,
                   double) {
  TempDir dir;
  const auto file = dir.write("mesh.obj",
                              "# a comment\n"
                              "mtllib mesh.mtl\n"
                              "o mesh\n"
                              "\n"
                              "v 0 0 0\n"
                              "v 1 0 0 1.0\n"
                              "v\t1\t1  0   # trailing comment\n"
                              "v 0 1 0\n"
                              "vt 0 0\n"
                              "vn 0 0 1\n"
                              "vp 0.5\n"
                              "g group\n"
                              "s off\n"
                              "usemtl red\n"
                              "f 1 2 3 4\n"
                              "f 1/1 2/1 3/1\n"
                              "f 1//1 3//1 4//1\n"
                              "f 1/1/1 2/1/1 4/1/1\n"
                              "f -4 -2\n"
                              "l 1 2 3\n"
                              "l 4/1 1/1\n");
  const auto mesh = read_obj<Scalar>(file);
  Points<Scalar> expected(4, 3);
  expected << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
  CHECK(mesh.vertices == expected);
  REQUIRE(mesh.faces.size() == 4);
  CHECK(mesh.faces[0] == std::vector<int>{0, 1, 2, 3});
  CHECK(mesh.faces[1] == std::vector<int>{0, 1, 2});
  CHECK(mesh.faces[2] == std::vector<int>{0, 2, 3});
  CHECK(mesh.faces[3] == std::vector<int>{0, 1, 3});
  Edges edges(4, 2);
  edges << 0, 2,  // f -4 -2 with 4 vertices defined
      0, 1, 1, 2, 3, 0;
  CHECK(mesh.edges == edges);
}

TEST_CASE("read_obj: negative indices count back from the last vertex defined above the line") {
  TempDir dir;
  const auto mesh = read_obj(dir.write("relative.obj",
                                       "v 0 0 0\nv 1 0 0\nv 2 0 0\n"
                                       "f -3 -2 -1\n"  // 0 1 2
                                       "v 3 0 0\n"
                                       "f -1 -2\n"));  // 3 2
  REQUIRE(mesh.faces.size() == 1);
  CHECK(mesh.faces[0] == std::vector<int>{0, 1, 2});
  REQUIRE(mesh.edges.rows() == 1);
  CHECK(mesh.edges(0, 0) == 3);
  CHECK(mesh.edges(0, 1) == 2);
}

TEST_CASE("read_obj: the line of each vertex and polygon, for messages that point into the file") {
  TempDir dir;
  // comments, a blank line, a spring and a polyline between them; CRLF on one line
  const auto mesh = read_obj(dir.write("lines.obj",
                                       "# header\n"          // 1
                                       "v 0 0 0\n"           // 2: vertex 1
                                       "\n"                  // 3
                                       "v 1 0 0\r\n"         // 4: vertex 2
                                       "v 0 1 0 1\n"         // 5: vertex 3
                                       "f 1 2\n"             // 6: a spring, not a polygon
                                       "f 1 2 3\n"           // 7: polygon 1
                                       "l 1 2 3\n"           // 8
                                       "v 1 1 0 # corner\n"  // 9: vertex 4
                                       "f 2 4 3\n"));        // 10: polygon 2
  CHECK(mesh.vertex_lines == std::vector<std::size_t>{2, 4, 5, 9});
  CHECK(mesh.face_lines == std::vector<std::size_t>{7, 10});
  CHECK(mesh.edges.rows() == 3);
}

TEST_CASE("read_obj: positive indices may refer to vertices defined further down") {
  TempDir dir;
  const auto mesh = read_obj(dir.write("forward.obj", "f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"));
  CHECK(mesh.vertices.rows() == 3);
  REQUIRE(mesh.faces.size() == 1);
  CHECK(mesh.faces[0] == std::vector<int>{0, 1, 2});
}

TEST_CASE("read_obj: CRLF line ends, a byte order mark and no final newline are fine") {
  TempDir dir;
  const auto mesh =
      read_obj(dir.write("crlf.obj", "\xEF\xBB\xBFv 0 0 0\r\nv 1 2 3\r\n\r\nf 1 2\r\nv 4 5 6"));
  REQUIRE(mesh.vertices.rows() == 3);
  CHECK(mesh.vertices(1, 2) == 3.0);
  CHECK(mesh.vertices(2, 0) == 4.0);
  CHECK(mesh.vertices(2, 2) == 6.0);
  CHECK(mesh.edges.rows() == 1);
}

TEST_CASE("read_obj: numbers in every decimal form, parsed exactly whatever the locale") {
  TempDir dir;
  const auto mesh =
      read_obj(dir.write("numbers.obj", "v 1e-3 +2.5 .5\nv -0 1E2 -7.25e+1\nv 0.1 3. -.125\n"));
  CHECK(mesh.vertices(0, 0) == 1e-3);
  CHECK(mesh.vertices(0, 1) == 2.5);
  CHECK(mesh.vertices(0, 2) == 0.5);
  CHECK(mesh.vertices(1, 0) == 0.0);
  CHECK(std::signbit(mesh.vertices(1, 0)));
  CHECK(mesh.vertices(1, 1) == 100.0);
  CHECK(mesh.vertices(1, 2) == -72.5);
  CHECK(mesh.vertices(2, 0) == 0.1);  // the double nearest to 1/10, as the compiler reads it
  CHECK(mesh.vertices(2, 1) == 3.0);
  CHECK(mesh.vertices(2, 2) == -0.125);
  const auto single = read_obj<float>(dir.path() / "numbers.obj");
  CHECK(single.vertices(2, 0) == 0.1f);  // rounded once, to the nearest float
}

TEST_CASE("read_obj: an empty file is an empty mesh") {
  TempDir dir;
  const auto mesh = read_obj(dir.write("empty.obj", "# nothing\n\n"));
  CHECK(mesh.vertices.rows() == 0);
  CHECK(mesh.faces.empty());
  CHECK(mesh.edges.rows() == 0);
}

TEST_CASE("read_obj refuses malformed lines, naming the file and the line") {
  TempDir dir;
  const std::string bad = (dir.path() / "bad.obj").string();
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  // Each case: the file's text, what the message must contain after "<path>:".
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"v 0 0 0\nv 1 x 3\n", ":2: vertex coordinate 2 is not a number: \"x\""},
      {"v 1,5 0 0\n", ":1: vertex coordinate 1 is not a number: \"1,5\""},
      {"v 1 2\n", ":1: a vertex needs 3 coordinates and an optional weight"},
      {"v 1 2 3 4 5\n", ":1: a vertex needs 3 coordinates"},
      {"v\n", ":1: a vertex needs 3 coordinates"},
      {"v nan 0 0\n", ":1: vertex coordinate 1 is not finite: \"nan\""},
      {"v 0 inf 0\n", ":1: vertex coordinate 2 is not finite: \"inf\""},
      {"v 0 0 -infinity\n", ":1: vertex coordinate 3 is not finite"},
      {"v 0 0 1e999\n", ":1: vertex coordinate 3 is out of range for double: \"1e999\""},
      {"v 0 0 0x1p3\n", ":1: vertex coordinate 3 is not a number"},
      {"v 0 0 1e\n", ":1: vertex coordinate 3 is not a number"},
      {"v 0 0 --1\n", ":1: vertex coordinate 3 is not a number"},
      {"v 0 0 +-1\n", ":1: vertex coordinate 3 is not a number"},
      {"v 0 0 0 w\n", ":1: vertex coordinate 4 is not a number: \"w\""},
      {"V 0 0 0\n", ":1: unsupported OBJ statement \"V\""},
      {tri + "curv 0 1 1 2\n", ":4: unsupported OBJ statement \"curv\""},
      {"v1 0 0\n", ":1: unsupported OBJ statement \"v1\""},
      {tri + "f 0 1 2\n", ":4: face vertex 1: vertex index 0 is invalid (OBJ indices start at 1)"},
      {tri + "f 1 2 5\n", ":4: vertex index 5 is out of range: the file has 3 vertices"},
      {tri + "\n# comment\nf 1 2 3\r\nf 2 3 4\r\n",
       ":7: vertex index 4 is out of range: the file has 3 vertices"},
      {tri + "f 1 2 -4\n", ":4: face vertex 3: vertex index -4 refers before the first vertex"},
      {tri + "f 1\n", ":4: a face needs at least 2 vertices"},
      {tri + "f\n", ":4: a face needs at least 2 vertices"},
      {tri + "f 1 2 1\n",
       ":4: face vertices 1 and 3 are the same vertex 1: a face may not repeat a vertex"},
      {tri + "f 1 -3\n", ":4: face vertices 1 and 2 are the same vertex 1"},
      {tri + "f 1/ 2 3\n", ":4: face vertex 1 is malformed: \"1/\""},
      {tri + "f 1 2/1/ 3\n", ":4: face vertex 2 is malformed: \"2/1/\""},
      {tri + "f 1 2 3/1/1/1\n", ":4: face vertex 3 is malformed: \"3/1/1/1\""},
      {tri + "f /1 2 3\n", ":4: face vertex 1 is malformed"},
      {tri + "f a b c\n", ":4: face vertex 1: vertex index is not an integer: \"a\""},
      {tri + "f 1.0 2 3\n", ":4: face vertex 1: vertex index is not an integer: \"1.0\""},
      {tri + "f 1/x 2 3\n", ":4: face vertex 1: texture index is not a nonzero integer"},
      {tri + "f 1//0 2 3\n", ":4: face vertex 1: normal index is not a nonzero integer"},
      {tri + "f 99999999999999999999 2 3\n", ":4: face vertex 1: vertex index is out of range"},
      {tri + "l 1\n", ":4: a polyline needs at least 2 vertices"},
      {tri + "l 1 2 2\n", ":4: polyline vertices 2 and 3 are the same vertex"},
      {tri + "l 1//1 2\n", ":4: polyline vertex 1 is malformed: \"1//1\" (expected i or i/t)"},
      {tri + "l 1 7\n", ":4: vertex index 7 is out of range: the file has 3 vertices"},
  };
  for (const auto& [text, expected] : cases) {
    CAPTURE(text);
    const std::string message = refusal(dir, text);
    CHECK_MESSAGE(message.rfind(bad + expected, 0) == 0, message);
  }
}

TEST_CASE("read_obj refuses a float coordinate a float cannot hold") {
  TempDir dir;
  const std::string message = refusal<float>(dir, "v 0 1e39 0\n");
  CHECK(message.find("bad.obj:1: vertex coordinate 2 is out of range for float: \"1e39\"") !=
        std::string::npos);
  CHECK(refusal<double>(dir, "v 0 1e39 0\n").empty());
}

TEST_CASE("read_obj refuses a missing file or a folder, naming the path") {
  TempDir dir;
  const auto missing = dir / "missing.obj";
  CHECK_THROWS_WITH_AS(
      read_obj(missing),
      massspring::test::contains(missing.string() + ": cannot read OBJ file: no such file"), Error);
  CHECK_THROWS_WITH_AS(
      read_obj(dir.path()),
      massspring::test::contains(dir.path().string() + ": cannot read OBJ file: it is a directory"),
      Error);
}

TEST_CASE_TEMPLATE("write_obj then read_obj gives bit-identical vertices, faces and edges", Scalar,
                   float, double) {
  std::mt19937 random(42);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::uniform_int_distribution<int> exponent(-30, 30);  // within float's range
  Points<Scalar> v(200, 3);
  for (Eigen::Index i = 0; i < v.rows(); ++i)
    for (int c = 0; c < 3; ++c)
      v(i, c) = static_cast<Scalar>(unit(random) * std::pow(10.0, exponent(random)));
  // awkward values: signed zero, the extremes, a subnormal, values with long expansions
  v.row(0) << Scalar(-0.0), std::numeric_limits<Scalar>::max(),
      std::numeric_limits<Scalar>::lowest();
  v.row(1) << std::numeric_limits<Scalar>::min(), std::numeric_limits<Scalar>::denorm_min(),
      std::numeric_limits<Scalar>::epsilon();
  v.row(2) << Scalar(0.1), Scalar(1) / Scalar(3), Scalar(2) / Scalar(3);
  std::vector<std::vector<int>> faces = {{0, 1, 2}, {3, 4, 5, 6}, {7, 8, 9, 10, 11}};
  Edges edges(3, 2);
  edges << 0, 199, 12, 13, 5, 4;

  TempDir dir;
  const auto file = dir / "round.obj";
  write_obj(file, v, faces, edges);
  const auto mesh = read_obj<Scalar>(file);
  CHECK(bit_identical(mesh.vertices, v));
  CHECK(mesh.faces == faces);
  CHECK(mesh.edges == edges);
  CHECK_FALSE(std::filesystem::exists(dir / "round.obj.tmp"));
}

TEST_CASE("write_obj writes 1-based indices and springs as 2-vertex faces, replacing the file") {
  TempDir dir;
  const auto file =
      dir.write("out.obj", "old content that is longer than the new file ...........\n");
  Points<double> v(3, 3);
  v << 0, 0, 0, 0.5, 0, 0, 0, 0.25, 0;
  Edges edges(1, 2);
  edges << 2, 0;
  write_obj(file, v, {{0, 1, 2}}, edges);
  const std::string text = massspring::test::read_bytes(file);
  CHECK(text.find("v 0.5 0 0\n") != std::string::npos);
  CHECK(text.find("\nf 1 2 3\nf 3 1\n") != std::string::npos);
  CHECK(text.find("old content") == std::string::npos);
  // and the ObjMesh overload writes the same bytes
  write_obj(dir / "again.obj", read_obj(file));
  CHECK(massspring::test::read_bytes(dir / "again.obj") == text);
}

TEST_CASE("write_obj refuses what read_obj would refuse, and writes nothing") {
  TempDir dir;
  const auto file = dir / "refused.obj";
  const std::string name = file.string();
  Points<double> v(3, 3);
  v << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  Edges none(0, 2), self(1, 2), far(1, 2);
  self << 1, 1;
  far << 0, 3;
  CHECK_THROWS_WITH_AS(write_obj(file, v, {{0, 1}}, none),
                       massspring::test::contains(name + ": face 0 has 2 vertices"), Error);
  CHECK_THROWS_WITH_AS(
      write_obj(file, v, {{0, 1, 3}}, none),
      massspring::test::contains(name + ": face 0: vertex index 3 out of range [0, 3)"), Error);
  CHECK_THROWS_WITH_AS(write_obj(file, v, {{0, 1, 0}}, none),
                       massspring::test::contains(name + ": face 0: vertex 0 appears twice"),
                       Error);
  CHECK_THROWS_WITH_AS(write_obj(file, v, {}, self),
                       massspring::test::contains(name + ": edge 0 joins vertex 1 to itself"),
                       Error);
  CHECK_THROWS_WITH_AS(write_obj(file, v, {}, far),
                       massspring::test::contains(name + ": edge 0: vertex index 3 out of range"),
                       Error);
  v(1, 2) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH_AS(write_obj(file, v, {}, none),
                       massspring::test::contains(name + ": vertex 1: position must be finite"),
                       Error);
  CHECK_FALSE(std::filesystem::exists(file));
  CHECK_FALSE(std::filesystem::exists(dir / "refused.obj.tmp"));
}

TEST_CASE("write_obj into a missing folder raises an Error naming the path") {
  TempDir dir;
  const auto file = dir / "no" / "such" / "folder.obj";
  Points<double> v = Points<double>::Zero(1, 3);
  CHECK_THROWS_WITH_AS(write_obj(file, v, {}, Edges(0, 2)),
                       massspring::test::contains(file.string() + ": cannot write"), Error);
}

TEST_CASE("read_obj reads the JSON+OBJ scenes' OBJ files with the counts SOURCE.md lists" *
          doctest::skip(!massspring::test::have_jacobson())) {
  struct Expected {
    const char* file;
    Eigen::Index vertices;
    std::size_t quads;
    Eigen::Index edges;
  };
  for (const Expected& e :
       {Expected{"flag.obj", 3200, 3081, 0}, Expected{"horizontal-chain.obj", 10, 0, 9},
        Expected{"net.obj", 61, 0, 156}, Expected{"single-spring-horizontal.obj", 2, 0, 1},
        Expected{"skirt.obj", 9840, 9600, 0}}) {
    CAPTURE(e.file);
    const auto mesh = read_obj(massspring::test::jacobson_dir() / e.file);
    CHECK(mesh.vertices.rows() == e.vertices);
    CHECK(mesh.faces.size() == e.quads);
    for (const auto& f : mesh.faces) CHECK(f.size() == 4);
    CHECK(mesh.edges.rows() == e.edges);
    CHECK(mesh.vertices.allFinite());
  }
  // the chain's text, read by hand: "v 0.111111 0 0" is the second line, "f 1 2" the 11th
  const auto chain = read_obj(massspring::test::jacobson_dir() / "horizontal-chain.obj");
  CHECK(chain.vertices(1, 0) == 0.111111);
  CHECK(chain.vertices(9, 0) == 1.0);
  CHECK(chain.edges(0, 0) == 0);
  CHECK(chain.edges(0, 1) == 1);
  CHECK(chain.edges(8, 1) == 9);
}

TEST_CASE("the flag's vertices survive write_obj and read_obj bit for bit" *
          doctest::skip(!massspring::test::have_jacobson())) {
  const auto flag = read_obj(massspring::test::jacobson_dir() / "flag.obj");
  TempDir dir;
  write_obj(dir / "flag.obj", flag);
  const auto again = read_obj(dir / "flag.obj");
  CHECK(bit_identical(again.vertices, flag.vertices));
  CHECK(again.faces == flag.faces);
}
