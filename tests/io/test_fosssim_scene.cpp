// io/fosssim_scene.hpp: every FOSSSim scene in ../shared loads as SOURCE.md's table lists it
// (VortexExample with its vortex force), the systems built from them, the
// writer's exact round trip, and every refusal with its file:line message.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <massspring/forces/gravitational_attraction.hpp>
#include <massspring/forces/gravity.hpp>
#include <massspring/forces/linear_drag.hpp>
#include <massspring/forces/vortex.hpp>
#include <massspring/io/fosssim_scene.hpp>
#include <massspring/io/load_scene.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "../../tools/fosssim_scenes.hpp"
#include "io/test_files.hpp"
#include "massspring/system/mass_spring_system.hpp"
#include "support/paths.hpp"

namespace {

namespace fs = std::filesystem;
using massspring::Dense;
using massspring::Error;
using massspring::MassSpringSystem;
using massspring::Sparse;
using massspring::io::FosssimIntegrator;
using massspring::io::FosssimScene;
using massspring::io::make_fosssim_system;
using massspring::io::read_fosssim_scene;
using massspring::io::write_fosssim_scene;
using massspring::test::contains;
using massspring::test::TempDir;
using SparseSystem = MassSpringSystem<double, Sparse>;
using DenseSystem = MassSpringSystem<double, Dense>;

fs::path fosssim_dir() { return massspring::test::shared_dir() / "scenes" / "fosssim"; }
bool have_fosssim() { return fs::is_directory(fosssim_dir()); }

// One row of SOURCE.md's per-file table.
struct Row {
  std::string file, integrator;
  double dt = 0, duration = 0;
  int particles = 0, fixed = 0, edges = 0, springs = 0;
  std::string other;
};

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(' ');
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(' ') - a + 1);
}

// Parses the table "| file | bytes | integrator | dt | duration | particles | fixed | edges |
// springforces | other forces |" of SOURCE.md: an oracle written independently of our reader.
std::vector<Row> source_table() {
  std::ifstream in(fosssim_dir() / "SOURCE.md");
  std::vector<Row> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("| t1m", 0) != 0) continue;
    std::vector<std::string> cells;
    std::stringstream ss(line.substr(1));
    std::string cell;
    while (std::getline(ss, cell, '|')) cells.push_back(trim(cell));
    REQUIRE(cells.size() >= 10);
    Row r;
    r.file = cells[0];
    r.integrator = cells[2];
    r.dt = std::stod(cells[3]);
    r.duration = std::stod(cells[4]);
    r.particles = std::stoi(cells[5]);
    r.fixed = std::stoi(cells[6]);
    r.edges = std::stoi(cells[7]);
    r.springs = std::stoi(cells[8]);  // "11 (b in {...})" -> 11
    r.other = cells[9];
    rows.push_back(r);
  }
  return rows;
}

// "simplegravity×1" -> {simplegravity: 1}
std::map<std::string, int> other_forces(const std::string& cell) {
  std::map<std::string, int> out;
  if (cell == "-") return out;
  std::stringstream ss(cell);
  std::string item;
  while (std::getline(ss, item, ',')) {
    item = trim(item);
    const auto x = item.find("\xC3\x97");  // U+00D7 MULTIPLICATION SIGN in UTF-8
    REQUIRE(x != std::string::npos);
    out[item.substr(0, x)] = std::stoi(item.substr(x + 2));
  }
  return out;
}

const char* const kHead =
    "<scene>\n"
    "  <duration time=\"1\"/>\n"
    "  <integrator type=\"symplectic-euler\" dt=\"0.1\"/>\n";  // lines 1-3; the body starts on 4

// Writes kHead + body + "</scene>" and checks that reading it throws "<path>:<line>: <what>".
void refuses(const std::string& body, int line, const std::string& what) {
  TempDir dir;
  const fs::path file = dir.write("scene.xml", std::string(kHead) + body + "</scene>\n");
  CAPTURE(body);
  CHECK_THROWS_WITH_AS(read_fosssim_scene(file),
                       contains(file.string() + ":" + std::to_string(line) + ": " + what), Error);
}

const char* const kTwo =
    "  <particle m=\"1\" px=\"0\" py=\"0\" vx=\"0\" vy=\"0\" fixed=\"0\"/>\n"
    "  <particle m=\"1\" px=\"1\" py=\"0\" vx=\"0\" vy=\"0\" fixed=\"0\"/>\n";  // lines 4, 5

}  // namespace

TEST_CASE("fosssim: every scene in ../shared loads as SOURCE.md's table lists it" *
          doctest::skip(!have_fosssim())) {
  const std::vector<Row> rows = source_table();
  REQUIRE(rows.size() == 70);  // the table lists the 70 files, VortexExample among them
  int loaded = 0;
  for (const Row& row : rows) {
    CAPTURE(row.file);
    const fs::path file = fosssim_dir() / row.file;
    if (row.file.find("VortexExample") != std::string::npos) continue;  // its own test
    const FosssimScene s = read_fosssim_scene(file);
    CHECK(massspring::io::to_string(s.integrator) == row.integrator);
    CHECK(s.dt == row.dt);
    CHECK(s.duration == row.duration);
    CHECK(s.num_particles() == row.particles);
    CHECK(int(s.fixed.size()) == row.fixed);
    CHECK(s.edges.rows() == row.edges);
    CHECK(int(s.springs.size()) == row.springs);
    const auto other = other_forces(row.other);
    CHECK(s.gravity.has_value() == (other.count("simplegravity") > 0));
    CHECK(s.drag.has_value() == (other.count("dragdamping") > 0));
    const int pairs = other.count("gravitationalforce") ? other.at("gravitationalforce") : 0;
    CHECK(int(s.attractions.size()) == pairs);
    CHECK((s.positions.col(2).array() == 0).all());
    CHECK((s.velocities.col(2).array() == 0).all());
    // the system: one spring per springforce, the fixed particles pinned, one term per force kind
    const auto system = make_fosssim_system<SparseSystem>(s);
    CHECK(system.num_points() == row.particles);
    CHECK(system.num_springs() == row.springs);
    CHECK(system.num_pinned() == row.fixed);
    CHECK(system.forces().size() == int(other.size()));
    ++loaded;
  }
  CHECK(loaded == 69);
  MESSAGE("fosssim: " << loaded << " of 70 Theme-1 scenes checked here (VortexExample below)");
}

TEST_CASE("fosssim: VortexExample loads: six vortex pairs as the file lists them" *
          doctest::skip(!have_fosssim())) {
  const fs::path file = fosssim_dir() / "t1m3" / "VortexExample.xml";
  const FosssimScene s = read_fosssim_scene(file);
  REQUIRE(s.vortices.size() == 6);
  const int pairs[6][2] = {{0, 1}, {0, 2}, {0, 3}, {4, 1}, {4, 2}, {4, 3}};
  for (int k = 0; k < 6; ++k) {
    CHECK(s.vortices[std::size_t(k)].i == pairs[k][0]);
    CHECK(s.vortices[std::size_t(k)].j == pairs[k][1]);
    CHECK(s.vortices[std::size_t(k)].kbs == 0.8);
    CHECK(s.vortices[std::size_t(k)].kvc == 1000.0);
  }
  const auto system = massspring::io::load_scene<SparseSystem>(file);
  CHECK(system.forces().size() == 1);
  CHECK(system.forces().find<massspring::VortexForce<double>>() != nullptr);
}

TEST_CASE("fosssim: the systems carry the scenes' numbers" * doctest::skip(!have_fosssim())) {
  SUBCASE("SpringTests/test00: two unit masses 1.2 m apart on a spring k = 1, l0 = 1") {
    const auto s = massspring::io::load_scene<DenseSystem>(fosssim_dir() /
                                                           "t1m2/SpringTests/test00symplectic.xml");
    REQUIRE(s.num_springs() == 1);
    CHECK(s.stiffness()(0) == 1.0);
    CHECK(s.rest_lengths()(0) == 1.0);
    CHECK(s.damping()(0) == 0.0);
    CHECK_FALSE(s.has_spring_damping());
    CHECK(s.positions().row(0) == Eigen::RowVector3d(0, 0.6, 0));  // py=" 0.6": blanks allowed
    CHECK(s.positions().row(1) == Eigen::RowVector3d(0, -0.6, 0));
    CHECK(s.forces().empty());
  }
  SUBCASE("SpringDampingTests/test03: b = 0, 0.1, ..., 1 on springs 0..10") {
    const auto s = massspring::io::load_scene<SparseSystem>(
        fosssim_dir() / "t1m2/SpringDampingTests/test03symplectic.xml");
    REQUIRE(s.num_springs() == 11);
    for (int e = 0; e < 11; ++e) CHECK(s.damping()(e) == doctest::Approx(0.1 * e).epsilon(1e-15));
    CHECK(s.has_spring_damping());
  }
  SUBCASE("LinearDragTests/test00: the edge between the fixed posts is drawing only") {
    const fs::path file = fosssim_dir() / "t1m2/LinearDragTests/test00explicit.xml";
    const FosssimScene scene = read_fosssim_scene(file);
    CHECK(scene.edges.rows() == 1);
    CHECK(scene.fixed == std::vector<int>{1, 2});
    const auto s = massspring::io::load_scene<SparseSystem>(file);
    CHECK(s.num_springs() == 0);
    CHECK(s.pinned() == std::vector<int>{1, 2});
    const auto* drag = s.forces().find<massspring::LinearDrag<double>>();
    REQUIRE(drag != nullptr);
    CHECK(drag->beta == 1.0);
    CHECK(s.velocities().row(0) == Eigen::RowVector3d(1, 0, 0));
  }
  SUBCASE("SimpleGravityTests/test00: gravity is an acceleration (0, -9.81, 0)") {
    const auto s = massspring::io::load_scene<MassSpringSystem<float, Dense>>(
        fosssim_dir() / "t1m1/SimpleGravityTests/test00explicit.xml");
    const auto* g = s.forces().find<massspring::Gravity<float>>();
    REQUIRE(g != nullptr);
    CHECK(g->g == Eigen::Vector3f(0, -9.81f, 0));
  }
  SUBCASE("GravityTests/test01: one pair (0, 1) with G = 4") {
    const auto s = massspring::io::load_scene<SparseSystem>(
        fosssim_dir() / "t1m2/GravityTests/test01symplectic.xml");
    const auto* g = s.forces().find<massspring::GravitationalAttraction<double>>();
    REQUIRE(g != nullptr);
    REQUIRE(g->pairs().size() == 1);
    CHECK(g->pairs()[0].i == 0);
    CHECK(g->pairs()[0].j == 1);
    CHECK(g->pairs()[0].G == 4.0);
  }
  SUBCASE("CantileverSemiImplicit: 30 particles, 71 springs, 4 fixed, gravity") {
    const FosssimScene scene =
        read_fosssim_scene(fosssim_dir() / "t1m2/SystemTests/CantileverSemiImplicit.xml");
    CHECK(scene.steps() == 5000);
    const auto s = make_fosssim_system<DenseSystem>(scene);
    CHECK(s.num_springs() == 71);
    CHECK(s.num_pinned() == 4);
    for (int r = 0; r < s.num_pinned(); ++r)
      CHECK(s.pin_targets().row(r) == s.rest_positions().row(s.pinned()[std::size_t(r)]));
  }
}

TEST_CASE("fosssim: steps() is ceil(duration / dt) with whole quotients exact") {
  FosssimScene s;
  s.duration = 4.0;
  s.dt = 0.01;
  CHECK(s.steps() == 400);
  s.duration = 500;
  s.dt = 0.1;
  CHECK(s.steps() == 5000);
  s.duration = 1.0;
  s.dt = 0.3;
  CHECK(s.steps() == 4);  // 3.33 -> 4: the last step overshoots, as FOSSSim's does
  CHECK(s.steps_for(0.5) == 2);
  s.duration = 0;
  CHECK(s.steps() == 0);
}

TEST_CASE("fosssim: a comment before <scene>, rendering elements, sums of gravity and drag") {
  TempDir dir;
  const fs::path file =
      dir.write("s.xml",
                "<!-- a comment -->\n<?xml-stylesheet x?>\n"
                "<scene>\n"
                "  <description text=\"two &amp; one\"/>\n"
                "  <scenetag tag=\"AccuracyTestScene\"/>\n"
                "  <duration time=\" 2.5 \"/>\n"
                "  <integrator type=\"implicit-euler\" dt=\"1e-3\"/>\n"
                "  <maxsimfreq max=\"500\"/>\n"
                "  <particle m=\"2\" px=\"+1\" py=\"-.5\" vx=\"3\" vy=\"4\" "
                "fixed=\"1\" radius=\"0.1\" tag=\"x\"/>\n"
                "  <particle m=\"1\" px=\"0\" py=\"0\" vx=\"0\" vy=\"1\" fixed=\"0\"/>\n"
                "  <edge i=\"0\" j=\"1\" radius=\"0.01\"/>\n"
                "  <simplegravity fx=\"1\" fy=\"-2\"/>\n"
                "  <simplegravity fx=\"0.5\" fy=\"-8\"/>\n"
                "  <dragdamping b=\"0.25\"/>\n"
                "  <dragdamping b=\"0.5\"/>\n"
                "  <particlecolor i=\"0\" r=\"1\" g=\"0\" b=\"0\"/>\n"
                "  <edgecolor i=\"0\" r=\"1\" g=\"0\" b=\"0\"/>\n"
                "  <particlepath i=\"0\" duration=\"2\" r=\"1\" g=\"0\" b=\"0\"/>\n"
                "  <backgroundcolor r=\"0\" g=\"0\" b=\"0\"/>\n"
                "  <viewport cx=\"0\" cy=\"0\" size=\"3\"/>\n"
                "</scene>\n");
  const FosssimScene s = read_fosssim_scene(file);
  CHECK(s.description == "two & one");
  CHECK(s.tags == std::vector<std::string>{"AccuracyTestScene"});
  CHECK(s.duration == 2.5);
  CHECK(s.dt == 1e-3);
  CHECK(s.integrator == FosssimIntegrator::ImplicitEuler);
  CHECK(s.positions.row(0) == Eigen::RowVector3d(1, -0.5, 0));
  CHECK(s.masses(0) == 2);
  REQUIRE(s.gravity.has_value());
  CHECK(*s.gravity == Eigen::Vector3d(1.5, -10, 0));
  REQUIRE(s.drag.has_value());
  CHECK(*s.drag == 0.75);
  CHECK(s.springs.empty());
  // the fixed particle starts at rest whatever its vx, vy
  const auto system = make_fosssim_system<DenseSystem>(s);
  CHECK(system.velocities().row(0) == Eigen::RowVector3d(0, 0, 0));
  CHECK(system.velocities().row(1) == Eigen::RowVector3d(0, 1, 0));
  CHECK(system.pinned() == std::vector<int>{0});
  CHECK(system.num_springs() == 0);
  CHECK(system.forces().size() == 2);  // gravity, drag
}

TEST_CASE("fosssim: write_fosssim_scene round-trips exactly") {
  FosssimScene s;
  s.description = "a \"quoted\" <scene> & more";
  s.tags = {"t1", "t2"};
  s.integrator = FosssimIntegrator::LinearizedImplicitEuler;
  s.dt = 0.1;  // not exact in binary: must come back bit for bit
  s.duration = 1.0 / 3.0;
  s.positions.resize(3, 3);
  s.positions << 0.1, 0.2, 0, 1.0 / 3, -2e-300, 0, 5, 6, 0;
  s.velocities.resize(3, 3);
  s.velocities << 1e-17, 0, 0, 0, 7, 0, -1, 1, 0;
  s.masses.resize(3);
  s.masses << 1, 0.3, 7e5;
  s.fixed = {2};
  s.edges.resize(3, 2);
  s.edges << 0, 1, 1, 2, 2, 0;
  s.springs = {{0, 10.0, 0.7, 0.1}, {2, 0.0, 0.0, 0.0}};
  s.gravity = Eigen::Vector3d(0, -9.81, 0);
  s.attractions = {{0, 2, 6.674e-11}};
  s.drag = 0.05;
  TempDir dir;
  write_fosssim_scene(dir / "s.xml", s);
  const FosssimScene r = read_fosssim_scene(dir / "s.xml");
  CHECK(r.description == s.description);
  CHECK(r.tags == s.tags);
  CHECK(r.integrator == s.integrator);
  CHECK(r.dt == s.dt);
  CHECK(r.duration == s.duration);
  CHECK(r.positions == s.positions);
  CHECK(r.velocities == s.velocities);
  CHECK(r.masses == s.masses);
  CHECK(r.fixed == s.fixed);
  CHECK(r.edges == s.edges);
  REQUIRE(r.springs.size() == 2);
  for (std::size_t k = 0; k < 2; ++k) {
    CHECK(r.springs[k].edge == s.springs[k].edge);
    CHECK(r.springs[k].k == s.springs[k].k);
    CHECK(r.springs[k].l0 == s.springs[k].l0);
    CHECK(r.springs[k].b == s.springs[k].b);
  }
  CHECK(*r.gravity == *s.gravity);
  REQUIRE(r.attractions.size() == 1);
  CHECK(r.attractions[0].G == s.attractions[0].G);
  CHECK(*r.drag == *s.drag);

  FosssimScene bad = s;
  bad.positions(1, 2) = 1;
  CHECK_THROWS_WITH_AS(write_fosssim_scene(dir / "bad.xml", bad),
                       doctest::Contains("particle 1 has z != 0: FOSSSim scenes are 2D"), Error);
}

TEST_CASE("fosssim: refusals name the file, the line and the item") {
  SUBCASE("XML and structure") {
    TempDir dir;
    const fs::path broken = dir.write("b.xml", "<scene>\n  <particle m=\"1\"\n</scene>\n");
    CHECK_THROWS_WITH_AS(read_fosssim_scene(broken),
                         contains(broken.string() + ":3: not well-formed XML"), Error);
    const fs::path root = dir.write("r.xml", "<!-- x -->\n<scenes/>\n");
    CHECK_THROWS_WITH_AS(
        read_fosssim_scene(root),
        contains(root.string() + ":2: the root element is <scenes>, expected <scene>"), Error);
    const fs::path empty = dir.write("e.xml", "<!-- nothing -->\n");
    CHECK_THROWS_WITH_AS(
        read_fosssim_scene(empty),
        contains(empty.string() + ":2: not well-formed XML: No document element found"), Error);
    const fs::path two = dir.write("t.xml", std::string(kHead) + "</scene>\n<scene/>\n");
    CHECK_THROWS_WITH_AS(read_fosssim_scene(two),
                         contains(two.string() + ":5: a second root element <scene>"), Error);
    const fs::path no_duration =
        dir.write("d.xml", "<scene>\n  <integrator type=\"explicit-euler\" dt=\"1\"/>\n</scene>\n");
    CHECK_THROWS_WITH_AS(read_fosssim_scene(no_duration),
                         contains(no_duration.string() + ":1: <scene> has no <duration"), Error);
    const fs::path no_integrator =
        dir.write("i.xml", "<scene>\n  <duration time=\"1\"/>\n</scene>\n");
    CHECK_THROWS_WITH_AS(read_fosssim_scene(no_integrator),
                         contains(no_integrator.string() + ":1: <scene> has no <integrator"),
                         Error);
    CHECK_THROWS_WITH_AS(read_fosssim_scene(dir / "missing.xml"),
                         contains((dir / "missing.xml").string() + ": cannot read FOSSSim scene"),
                         Error);
  }
  SUBCASE("elements and attributes") {
    refuses(std::string(kTwo) + "  <vortexforce i=\"0\" j=\"1\" kbs=\"1\"/>\n", 6,
            "<vortexforce> 0: missing required attribute \"kvc\"");
    refuses("  <rigidbody/>\n", 4, "unknown element <rigidbody>");
    refuses("\n  <Particle/>\n", 5, "unknown element <Particle>");
    refuses("  <duration time=\"2\"/>\n", 4, "<duration> appears twice (first on line 2)");
    refuses("  <integrator type=\"explicit-euler\" dt=\"2\"/>\n", 4,
            "<integrator> appears twice (first on line 3)");
    refuses(std::string(kTwo) + "  <particle m=\"1\" px=\"0\" py=\"0\" vx=\"0\" vy=\"0\"/>\n", 6,
            "<particle> 2: missing required attribute \"fixed\"");
    refuses(
        "  <particle m=\"1\" px=\"0\" py=\"0\" pz=\"0\" vx=\"0\" vy=\"0\" fixed=\"0\"/>\n", 4,
        "<particle> 0: unknown attribute \"pz\" (expected m, px, py, vx, vy, fixed, radius, tag)");
    refuses("  <simplegravity fx=\"0\"/>\n", 4,
            "<simplegravity>: missing required attribute \"fy\"");
    refuses("  <dragdamping beta=\"1\"/>\n", 4, "<dragdamping>: unknown attribute \"beta\"");
  }
  SUBCASE("numbers") {
    refuses("  <particle m=\"one\" px=\"0\" py=\"0\" vx=\"0\" vy=\"0\" fixed=\"0\"/>\n", 4,
            "<particle> 0: m = \"one\" is not a number");
    refuses("  <particle m=\"1\" px=\"1,5\" py=\"0\" vx=\"0\" vy=\"0\" fixed=\"0\"/>\n", 4,
            "<particle> 0: px = \"1,5\" is not a number");
    refuses("  <particle m=\"1\" px=\"0\" py=\"\" vx=\"0\" vy=\"0\" fixed=\"0\"/>\n", 4,
            "<particle> 0: py = \"\" is not a number");
    refuses("  <particle m=\"1\" px=\"0\" py=\"0\" vx=\"inf\" vy=\"0\" fixed=\"0\"/>\n", 4,
            "<particle> 0: vx = \"inf\" must be finite");
    refuses("  <particle m=\"1\" px=\"0\" py=\"0\" vx=\"0\" vy=\"nan\" fixed=\"0\"/>\n", 4,
            "<particle> 0: vy = \"nan\" must be finite");
    refuses("  <particle m=\"1\" px=\"1e999\" py=\"0\" vx=\"0\" vy=\"0\" fixed=\"0\"/>\n", 4,
            "<particle> 0: px = \"1e999\" is out of the range of double");
    refuses(std::string(kTwo) +
                "  <particle m=\"0\" px=\"0\" py=\"0\" vx=\"0\" vy=\"0\" fixed=\"0\"/>\n",
            6, "<particle> 2: m = 0 must be > 0");
    refuses("  <particle m=\"-1\" px=\"0\" py=\"0\" vx=\"0\" vy=\"0\" fixed=\"0\"/>\n", 4,
            "<particle> 0: m = -1 must be > 0");
    refuses("  <particle m=\"1\" px=\"0\" py=\"0\" vx=\"0\" vy=\"0\" fixed=\"yes\"/>\n", 4,
            "<particle> 0: fixed = \"yes\" must be 0 or 1");
    refuses("  <particle m=\"1\" px=\"0\" py=\"0\" vx=\"0\" vy=\"0\" fixed=\"0\" radius=\"-1\"/>\n",
            4, "<particle> 0: radius = -1 must be >= 0");
    refuses(std::string(kTwo) +
                "  <edge i=\"0\" j=\"1\"/>\n  <springforce edge=\"0\" k=\"-1\" l0=\"1\"/>\n",
            7, "<springforce> 0: k = -1 must be >= 0");
    refuses(std::string(kTwo) +
                "  <edge i=\"0\" j=\"1\"/>\n  <springforce edge=\"0\" k=\"1\" l0=\"-0.5\"/>\n",
            7, "<springforce> 0: l0 = -0.5 must be >= 0");
    refuses(
        std::string(kTwo) +
            "  <edge i=\"0\" j=\"1\"/>\n  <springforce edge=\"0\" k=\"1\" l0=\"1\" b=\"-2\"/>\n",
        7, "<springforce> 0: b = -2 must be >= 0");
    refuses(std::string(kTwo) + "  <gravitationalforce i=\"0\" j=\"1\" G=\"-1\"/>\n", 6,
            "<gravitationalforce> 0: G = -1 must be >= 0");
    refuses("  <dragdamping b=\"-0.1\"/>\n", 4, "<dragdamping>: b = -0.1 must be >= 0");
    refuses("  <simplegravity fx=\"0\" fy=\"x\"/>\n", 4,
            "<simplegravity>: fy = \"x\" is not a number");
    TempDir dir;
    const fs::path dt = dir.write("dt.xml",
                                  "<scene>\n<duration time=\"1\"/>\n<integrator "
                                  "type=\"explicit-euler\" dt=\"0\"/>\n</scene>\n");
    CHECK_THROWS_WITH_AS(read_fosssim_scene(dt),
                         contains(dt.string() + ":3: <integrator>: dt = 0 must be > 0"), Error);
    const fs::path t = dir.write("t.xml",
                                 "<scene>\n<duration time=\"-1\"/>\n<integrator "
                                 "type=\"explicit-euler\" dt=\"1\"/>\n</scene>\n");
    CHECK_THROWS_WITH_AS(read_fosssim_scene(t),
                         contains(t.string() + ":2: <duration>: time = -1 must be >= 0"), Error);
    const fs::path type = dir.write(
        "ty.xml",
        "<scene>\n<duration time=\"1\"/>\n<integrator type=\"rk4\" dt=\"1\"/>\n</scene>\n");
    CHECK_THROWS_WITH_AS(
        read_fosssim_scene(type),
        contains(type.string() + ":3: <integrator>: unknown type \"rk4\" (expected "
                                 "explicit-euler, symplectic-euler, forward-backward-euler, "
                                 "linearized-implicit-euler or implicit-euler)"),
        Error);
  }
  SUBCASE("indices") {
    refuses(std::string(kTwo) + "  <edge i=\"0\" j=\"2\"/>\n", 6,
            "<edge> 0: j = 2 is out of range: the scene has 2 particles");
    refuses(std::string(kTwo) + "  <edge i=\"-1\" j=\"1\"/>\n", 6,
            "<edge> 0: i = -1 is out of range: the scene has 2 particles");
    refuses(std::string(kTwo) + "  <edge i=\"0.5\" j=\"1\"/>\n", 6,
            "<edge> 0: i = \"0.5\" is not a whole number");
    refuses(std::string(kTwo) + "  <edge i=\"1\" j=\"1\"/>\n", 6,
            "<edge> 0 joins particle 1 to itself");
    refuses(std::string(kTwo) +
                "  <edge i=\"0\" j=\"1\"/>\n  <springforce edge=\"1\" k=\"1\" l0=\"1\"/>\n",
            7, "<springforce> 0: edge = 1 is out of range: the scene has 1 edge");
    refuses(std::string(kTwo) + "  <gravitationalforce i=\"0\" j=\"5\" G=\"1\"/>\n", 6,
            "<gravitationalforce> 0: j = 5 is out of range: the scene has 2 particles");
    refuses(std::string(kTwo) + "  <gravitationalforce i=\"1\" j=\"1\" G=\"1\"/>\n", 6,
            "<gravitationalforce> 0 attracts particle 1 to itself");
    // particles may come after the edges that use them (FOSSSim reads particles first)
    TempDir dir;
    const fs::path later = dir.write(
        "l.xml", std::string(kHead) + "  <edge i=\"0\" j=\"1\"/>\n" + kTwo + "</scene>\n");
    CHECK(read_fosssim_scene(later).edges.rows() == 1);
  }
  SUBCASE("two springs on one edge or on one pair") {
    refuses(std::string(kTwo) +
                "  <edge i=\"0\" j=\"1\"/>\n"
                "  <springforce edge=\"0\" k=\"1\" l0=\"1\"/>\n"
                "  <springforce edge=\"0\" k=\"2\" l0=\"1\"/>\n",
            8, "<springforce> 1: edge 0 already has a spring (<springforce> 0 on line 7)");
    refuses(std::string(kTwo) +
                "  <edge i=\"0\" j=\"1\"/>\n"
                "  <edge i=\"1\" j=\"0\"/>\n"
                "  <springforce edge=\"0\" k=\"1\" l0=\"1\"/>\n"
                "  <springforce edge=\"1\" k=\"2\" l0=\"1\"/>\n",
            9,
            "<springforce> 1: particles 0 and 1 are already joined by <springforce> 0 on line 8");
    // two edges on one pair without two springs: fine (drawing only)
    TempDir dir;
    const fs::path ok =
        dir.write("ok.xml", std::string(kHead) + kTwo +
                                "  <edge i=\"0\" j=\"1\"/>\n  <edge i=\"1\" j=\"0\"/>\n"
                                "  <springforce edge=\"1\" k=\"1\" l0=\"1\"/>\n"
                                "</scene>\n");
    const auto s = massspring::io::load_scene<DenseSystem>(ok);
    CHECK(s.num_springs() == 1);
    CHECK(s.springs().row(0) == Eigen::RowVector2i(1, 0));
  }
}

TEST_CASE(
    "fosssim: the committed examples/scenes_xml/*.xml are exactly what massspring-make-scenes "
    "writes") {
  TempDir dir;
  for (const auto& [stem, scene] : massspring::examples::project_fosssim_scenes()) {
    CAPTURE(stem);
    write_fosssim_scene(dir / (stem + ".xml"), scene);
    const fs::path committed =
        massspring::test::source_dir() / "examples" / "scenes_xml" / (stem + ".xml");
    CHECK(massspring::test::read_bytes(committed) ==
          massspring::test::read_bytes(dir / (stem + ".xml")));
    // and each loads into a system with one spring per springforce
    const auto system = massspring::io::load_scene<SparseSystem>(committed);
    CHECK(system.num_springs() == int(scene.springs.size()));
  }
}
