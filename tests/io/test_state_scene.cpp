// io/state_scene.hpp: write_state() then read_state() (and load_scene()) gives a system equal
// in every field, bit for bit, in double and float; one FastMassSpring step from each gives the
// same state; what cannot be written or read is refused, naming the file.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <massspring/forces/gravitational_attraction.hpp>
#include <massspring/forces/vortex.hpp>
#include <massspring/integrators/fast_mass_spring.hpp>
#include <massspring/io/load_scene.hpp>
#include <massspring/io/state_scene.hpp>
#include <massspring/scene/cloth.hpp>
#include <massspring/scene/make_system.hpp>
#include <random>
#include <string>
#include <vector>

#include "io/test_files.hpp"

namespace {

using massspring::Error;
using massspring::test::TempDir;

// Every field of a and b, exactly (== on floating point: bit for bit for finite values).
template <class System>
void check_equal(const System& a, const System& b) {
  REQUIRE(a.num_points() == b.num_points());
  REQUIRE(a.num_springs() == b.num_springs());
  CHECK((a.rest_positions().array() == b.rest_positions().array()).all());
  CHECK((a.springs().array() == b.springs().array()).all());
  CHECK((a.masses().array() == b.masses().array()).all());
  CHECK((a.stiffness().array() == b.stiffness().array()).all());
  CHECK((a.rest_lengths().array() == b.rest_lengths().array()).all());
  CHECK((a.damping().array() == b.damping().array()).all());
  CHECK(a.pinned() == b.pinned());
  CHECK((a.pin_targets().array() == b.pin_targets().array()).all());
  CHECK((a.positions().array() == b.positions().array()).all());
  CHECK((a.velocities().array() == b.velocities().array()).all());
  CHECK(a.has_spring_damping() == b.has_spring_damping());
  CHECK(a.surface() == b.surface());
  CHECK(a.surface_edges() == b.surface_edges());
  REQUIRE(a.self_collision().has_value() == b.self_collision().has_value());
  if (a.self_collision()) {
    CHECK(a.self_collision()->thickness == b.self_collision()->thickness);
    CHECK(a.self_collision()->friction == b.self_collision()->friction);
  }
  REQUIRE(a.forces().size() == b.forces().size());
  using Scalar = typename System::Scalar;
  for (int k = 0; k < a.forces().size(); ++k) {
    CAPTURE(k);
    CHECK(std::string(a.forces()[k].name) == b.forces()[k].name);
    if (const auto* g = a.forces().template find<massspring::Gravity<Scalar>>())
      CHECK(g->g == b.forces().template find<massspring::Gravity<Scalar>>()->g);
    if (const auto* f = a.forces().template find<massspring::ConstantForce<Scalar>>())
      CHECK(f->force == b.forces().template find<massspring::ConstantForce<Scalar>>()->force);
    if (const auto* d = a.forces().template find<massspring::LinearDrag<Scalar>>())
      CHECK(d->beta == b.forces().template find<massspring::LinearDrag<Scalar>>()->beta);
    using Attraction = massspring::GravitationalAttraction<Scalar>;
    if (const auto* g = a.forces().template find<Attraction>()) {
      const auto* h = b.forces().template find<Attraction>();
      REQUIRE(h != nullptr);
      CHECK(g->softening() == h->softening());
      REQUIRE(g->pairs().size() == h->pairs().size());
      for (std::size_t p = 0; p < g->pairs().size(); ++p) {
        CHECK(g->pairs()[p].i == h->pairs()[p].i);
        CHECK(g->pairs()[p].j == h->pairs()[p].j);
        CHECK(g->pairs()[p].G == h->pairs()[p].G);
      }
    }
    using Vortex = massspring::VortexForce<Scalar>;
    if (const auto* v = a.forces().template find<Vortex>()) {
      const auto* w = b.forces().template find<Vortex>();
      REQUIRE(w != nullptr);
      REQUIRE(v->pairs().size() == w->pairs().size());
      for (std::size_t p = 0; p < v->pairs().size(); ++p) {
        CHECK(v->pairs()[p].i == w->pairs()[p].i);
        CHECK(v->pairs()[p].j == w->pairs()[p].j);
        CHECK(v->pairs()[p].kbs == w->pairs()[p].kbs);
        CHECK(v->pairs()[p].kvc == w->pairs()[p].kvc);
      }
    }
  }
}

// A cloth whose every field differs from point to point or spring to spring, mid-motion.
template <class System>
System scrambled_cloth() {
  using Scalar = typename System::Scalar;
  massspring::ClothOptions o;
  o.columns = 7;
  o.rows = 5;
  System s = massspring::make_system<System>(massspring::make_cloth(o));
  std::mt19937 random(42);
  std::uniform_real_distribution<double> u(0.1, 3.0);
  massspring::Vector<Scalar> m(s.num_points()), k(s.num_springs()), r(s.num_springs()),
      b(s.num_springs());
  for (int i = 0; i < s.num_points(); ++i) m(i) = Scalar(u(random) / 7);  // not short decimals
  for (int e = 0; e < s.num_springs(); ++e) {
    k(e) = Scalar(u(random) * 1000 / 3);
    r(e) = Scalar(s.rest_lengths()(e) * u(random) / 1.7);
    b(e) = e % 3 ? Scalar(0) : Scalar(u(random) / 11);
  }
  s.set_masses(m);
  s.set_stiffness(k);
  s.set_rest_lengths(r);
  s.set_damping(b);
  s.pin(3, massspring::Vector3<Scalar>(Scalar(0.1) / 3, Scalar(-2) / 7, Scalar(1e-17)));
  s.set_pin_target(s.pinned().front(), massspring::Vector3<Scalar>(Scalar(1) / 3, 0, 0));
  massspring::Points<Scalar> x = s.positions(), v(s.num_points(), 3);
  for (int i = 0; i < x.rows(); ++i)
    for (int c = 0; c < 3; ++c) {
      x(i, c) += Scalar(u(random) / 97);
      v(i, c) = Scalar(u(random) - 1.5);
    }
  v(1, 0) = Scalar(-0.0);  // a negative zero survives too
  v(2, 1) = Scalar(1e-300 > 0 && sizeof(Scalar) == 8 ? 1e-300 : 1e-38);
  s.set_positions(x);
  s.set_velocities(v);
  s.add_force(massspring::Gravity<Scalar>({0, Scalar(-9.8), Scalar(0.1) / 3}));
  s.add_force(massspring::LinearDrag<Scalar>(Scalar(0.3) / 7));
  s.add_force(massspring::ConstantForce<Scalar>({Scalar(1e-3) / 3, 0, 0}));
  return s;
}

// scrambled_cloth() with a gravitational attraction and a vortex term too (the terms an XML
// scene adds).
template <class System>
System scrambled_cloth_all_terms() {
  using Scalar = typename System::Scalar;
  System s = scrambled_cloth<System>();
  s.add_force(massspring::GravitationalAttraction<Scalar>(
      {{0, 5, Scalar(1) / 3}, {7, 2, Scalar(6.674e-3) / 7}}, Scalar(0.01) / 3));
  s.add_force(massspring::VortexForce<Scalar>({{1, 4, Scalar(0.2) / 3, Scalar(-1) / 7}}));
  return s;
}

template <class System>
void round_trip() {
  TempDir dir;
  const System a = scrambled_cloth_all_terms<System>();
  massspring::io::StateSceneExtras extras;
  extras.faces = {{0, 1, 8}, {1, 2, 9, 8}};
  extras.edges = massspring::Edges(1, 2);
  extras.edges << 3, 4;
  extras.run = {{"frame", 12}, {"integrator", "fast-mass-spring"}};
  massspring::io::write_state(a, dir / "state.json", extras);
  CHECK_FALSE(std::filesystem::exists(dir / "state.json.tmp"));

  const auto read = massspring::io::read_state<System>(dir / "state.json");
  check_equal(a, read.system);
  CHECK(std::signbit(read.system.velocities()(1, 0)));  // == does not see the sign of a zero
  CHECK(read.extras.faces == extras.faces);
  CHECK(read.extras.edges == extras.edges);
  CHECK(read.extras.run == extras.run);

  // load_scene() recognises it, and says which files it read.
  const auto loaded = massspring::io::load_scene_file<System>(dir / "state.json");
  CHECK(loaded.state);
  CHECK(loaded.files.size() == 1);
  check_equal(a, loaded.system);

  // Written again from the loaded system: the same bytes.
  massspring::io::write_state(read.system, dir / "again.json", extras);
  CHECK(massspring::test::read_bytes(dir / "state.json") ==
        massspring::test::read_bytes(dir / "again.json"));

  // The same step from each: the same state, bit for bit.
  System x = a, y = read.system;
  massspring::FastMassSpring<System> sx, sy;
  sx.precompute(x, typename System::Scalar(1.0 / 30));
  sy.precompute(y, typename System::Scalar(1.0 / 30));
  for (int step = 0; step < 3; ++step) {
    REQUIRE(sx.step(x).ok());
    REQUIRE(sy.step(y).ok());
  }
  CHECK((x.positions().array() == y.positions().array()).all());
  CHECK((x.velocities().array() == y.velocities().array()).all());
}

}  // namespace

TEST_CASE("state scene: write_state then read_state gives every field back, double") {
  round_trip<massspring::MassSpringSystem<double, massspring::Sparse>>();
}

TEST_CASE("state scene: write_state then read_state gives every field back, float") {
  round_trip<massspring::MassSpringSystem<float, massspring::Dense>>();
}

// A force term of the user's own (forces/force_term.hpp), which a state scene cannot hold.
struct UserTerm {
  static constexpr bool velocity_dependent = false;
  [[nodiscard]] const char* name() const { return "a user's term"; }
  void add_force(const massspring::ForceContext<double>&, massspring::Points<double>&) const {}
};

TEST_CASE("state scene: a term it cannot hold is refused and nothing is written") {
  TempDir dir;
  using System = massspring::MassSpringSystem<double, massspring::Sparse>;
  System s = scrambled_cloth<System>();
  s.add_force(UserTerm{});
  const auto path = dir / "s.json";
  CHECK_THROWS_WITH_AS(
      massspring::io::write_state(s, path),
      (path.string() + ": force term 3 (a user's term) cannot be written: a state scene holds "
                       "gravity, constant force, linear drag, gravitational attraction and vortex "
                       "force terms")
          .c_str(),
      Error);
  CHECK_FALSE(std::filesystem::exists(path));
  CHECK_FALSE(std::filesystem::exists(dir / "s.json.tmp"));
}

TEST_CASE("state scene: state_force_terms() names exactly the terms write_state holds") {
  // a system with one term of every kind write_state() writes: their names, in the system's
  // order, are the list; each is held, a user's term is not, and the phrase joins the list
  using System = massspring::MassSpringSystem<double, massspring::Sparse>;
  const System s = scrambled_cloth_all_terms<System>();
  std::vector<std::string> names;
  for (int k = 0; k < s.forces().size(); ++k) names.emplace_back(s.forces()[k].name);
  std::vector<std::string> listed = massspring::io::state_force_terms();
  CHECK(listed.size() == names.size());
  for (const std::string& name : names) {
    CAPTURE(name);
    CHECK(std::count(listed.begin(), listed.end(), name) == 1);
    CHECK(massspring::io::state_holds_force_term(name));
  }
  CHECK_FALSE(massspring::io::state_holds_force_term(UserTerm{}.name()));
  CHECK_FALSE(massspring::io::state_holds_force_term(""));
  CHECK(massspring::io::state_force_terms_text() ==
        "gravity, constant force, linear drag, gravitational attraction and vortex force");
  TempDir dir;
  CHECK_NOTHROW(massspring::io::write_state(s, dir / "all.json"));
}

TEST_CASE("state scene: bad files are refused, naming the file") {
  TempDir dir;
  using System = massspring::MassSpringSystem<double, massspring::Dense>;
  massspring::io::write_state(scrambled_cloth<System>(), dir / "good.json");
  std::string text = massspring::test::read_bytes(dir / "good.json");
  auto with = [&](const std::string& from, const std::string& to) {
    std::string t = text;
    const auto at = t.find(from);
    REQUIRE(at != std::string::npos);
    return dir.write("bad.json", t.replace(at, from.size(), to));
  };
  const std::string bad = (dir / "bad.json").string();
  CHECK_THROWS_WITH_AS(
      massspring::io::load_scene<System>(
          with("\"massspring_state\": 1", "\"massspring_state\": 2")),
      (bad + ": key \"massspring_state\": this reader knows version 1, got 2").c_str(), Error);
  CHECK_THROWS_WITH_AS(
      massspring::io::load_scene<System>(with("\"masses\": [", "\"masses\": [0, ")),
      (bad + ": key \"masses\": expected 35 values, got 36").c_str(), Error);
  // an error of the system's constructor or setters gets the file's name
  auto first_value = [&](const std::string& key, const std::string& value) {
    const std::string from = "\"" + key + "\": [";
    const auto at = text.find(from);
    REQUIRE(at != std::string::npos);
    const auto begin = at + from.size();
    const auto end = text.find_first_of(",]", begin);
    std::string t = text;
    return dir.write("bad.json", t.replace(begin, end - begin, value));
  };
  CHECK_THROWS_WITH_AS(massspring::io::load_scene<System>(first_value("damping", "-1")),
                       (bad + ": spring 0: damping must be finite and >= 0, got -1").c_str(),
                       Error);
  CHECK_THROWS_WITH_AS(massspring::io::load_scene<System>(first_value("pinned", "99")),
                       (bad + ": pin: point index 99 out of range [0, 35)").c_str(), Error);
  CHECK_THROWS_WITH_AS(
      massspring::io::load_scene<System>(with("\"pinned\": [", "\"pinned\": [9, ")),
      (bad + ": key \"pin_targets\": expected 4 rows, got 3").c_str(), Error);
  CHECK_THROWS_WITH_AS(massspring::io::load_scene<System>(
                           with("\"massspring_state\": 1", "\"massspring_state\": 1, \"x\": 0")),
                       (bad + ": unknown key \"x\"").c_str(), Error);
  // read_json_scene (the JSON+OBJ reader) says what the file is
  CHECK_THROWS_WITH_AS(massspring::io::read_json_scene(dir / "good.json"),
                       ((dir / "good.json").string() +
                        ": a state scene (written by io::write_state), not a JSON+OBJ scene: load "
                        "it with io::load_scene or io::read_state")
                           .c_str(),
                       Error);
}

TEST_CASE_TEMPLATE("state scene: the surface and self-collision are written and read back", System,
                   massspring::MassSpringSystem<double, massspring::Sparse>,
                   massspring::MassSpringSystem<float, massspring::Dense>) {
  using Scalar = typename System::Scalar;
  TempDir dir;
  System a = scrambled_cloth<System>();
  REQUIRE(a.surface().rows() == 2 * 6 * 4);  // make_system: 2 triangles per cell
  massspring::contact::SelfCollision<Scalar> parameters;
  parameters.thickness = Scalar(0.01) / 3;  // not short decimals
  parameters.friction = Scalar(0.7) / 3;
  a.set_self_collision(parameters);
  massspring::io::write_state(a, dir / "state.json");
  const auto j = nlohmann::json::parse(massspring::test::read_bytes(dir / "state.json"));
  CHECK(j.at("surface").size() == 48);
  CHECK(j.at("self_collision").size() == 2);

  const System b = massspring::io::read_state<System>(dir / "state.json").system;
  check_equal(a, b);
  massspring::io::write_state(b, dir / "again.json");
  CHECK(massspring::test::read_bytes(dir / "state.json") ==
        massspring::test::read_bytes(dir / "again.json"));

  // Off and without a surface: neither key is written, and the system read back has neither.
  System c = a;
  c.clear_self_collision();
  c.set_surface(massspring::Triangles(0, 3));
  massspring::io::write_state(c, dir / "plain.json");
  const auto plain = nlohmann::json::parse(massspring::test::read_bytes(dir / "plain.json"));
  CHECK_FALSE(plain.contains("surface"));
  CHECK_FALSE(plain.contains("self_collision"));
  const System d = massspring::io::load_scene<System>(dir / "plain.json");
  check_equal(c, d);
  CHECK(d.surface().rows() == 0);
  CHECK_FALSE(d.self_collision().has_value());
}

TEST_CASE("state scene: a bad surface or self-collision is refused, naming the file and the key") {
  TempDir dir;
  using System = massspring::MassSpringSystem<double, massspring::Sparse>;
  System good = scrambled_cloth<System>();
  good.set_self_collision({});
  massspring::io::write_state(good, dir / "good.json");
  const auto root = nlohmann::json::parse(massspring::test::read_bytes(dir / "good.json"));
  const std::string bad = (dir / "bad.json").string();
  auto refused = [&](const char* key, const nlohmann::json& value, const std::string& message) {
    nlohmann::json j = root;
    j[key] = value;
    CAPTURE(j.dump());
    dir.write("bad.json", j.dump());
    CHECK_THROWS_WITH_AS(massspring::io::load_scene<System>(dir / "bad.json"),
                         (bad + ": " + message).c_str(), Error);
  };
  using J = nlohmann::json;
  refused("surface", J::array({J::array({0, 1, 99})}),
          "key \"surface\": surface triangle 0 = (0, 1, 99): point index 99 out of range [0, 35)");
  refused("surface", J::array({J::array({0, 1, 1})}),
          "key \"surface\": surface triangle 0 = (0, 1, 1): repeats a point");
  refused("surface", J::array({J::array({0, 1, 2})}),  // three points of row 0
          "key \"surface\": surface triangle 0 = (0, 1, 2): zero area at the rest positions");
  refused("surface", J::array({J::array({0, 1})}),
          "key \"surface\": entry 0 (counting from 0): expected [a, b, c], got [0,1]");
  refused("surface", J::array({J::array({0, 1, -8})}),
          "key \"surface\": entry 0 (counting from 0): expected a point index (an integer >= 0), "
          "got -8");
  refused("surface", J::object(), "key \"surface\": expected an array of [a, b, c], got object");
  refused("self_collision", J::array({0.004, 0.2}),
          "key \"self_collision\": expected {\"thickness\": h, \"friction\": mu}, got array");
  refused("self_collision", J{{"thickness", 0.0}, {"friction", 0.2}},
          "key \"self_collision\": self-collision: thickness must be finite and > 0, got 0");
  refused("self_collision", J{{"thickness", 0.004}, {"friction", -1}},
          "key \"self_collision\": self-collision: friction must be finite and >= 0, got -1");
  refused("self_collision", J{{"thickness", 0.004}},
          "key \"self_collision\": expected both \"thickness\" and \"friction\"");
  refused("self_collision", J{{"thickness", 0.004}, {"friction", 0.2}, {"x", 1}},
          "key \"self_collision\": unknown key \"x\" (expected thickness, friction)");
  refused("self_collision", J{{"thickness", "thin"}, {"friction", 0.2}},
          "key \"self_collision\": \"thickness\": expected a number, got \"thin\"");
  // Self-collision without a surface.
  nlohmann::json j = root;
  j.erase("surface");
  dir.write("bad.json", j.dump());
  CHECK_THROWS_WITH_AS(massspring::io::load_scene<System>(dir / "bad.json"),
                       (bad + ": key \"self_collision\": self-collision: the system has no surface "
                              "(set_surface(), or a scene's faces)")
                           .c_str(),
                       Error);
}
