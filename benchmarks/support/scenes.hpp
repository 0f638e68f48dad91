#pragma once
/// @file
/// @brief The scenes and the set-up the local-global benchmarks (bench_step, bench_options,
/// bench_acceleration, bench_threads) share: the JSON+OBJ scenes' settings, the cloth grids, Liu
/// 2013's curtain and the JSON+OBJ scenes' flag and skirt, and FastMassSpring's options for them.
///
/// Settings throughout are the JSON+OBJ scenes' and the reference solver's: dt = 1/30 s, a force
/// (0, -9.8, 0) N on every point, penalty pins w = 1e10 N/m, 50 local-global iterations per step
/// starting from the current positions. The curtain falls under gravity m g instead (as in Liu's
/// paper: 9.8 N on each of its 1.5e-4 kg points would pull it ~70 m in one frame).
///
/// Scenes: `cloth<N>`, make_cloth() with N x N points (1 m x 1 m, quads with both diagonals, top
/// corners pinned, k = 1000 N/m, Voronoi masses); `curtain` (massspring::curtain_recipe(): 6561
/// points, 32158 springs); `flag` and `skirt`, read from
/// shared_dir()/scenes/jacobson when it is there and the program links
/// massspring::io (MASSSPRING_BENCH_WITH_IO=1).

#include <Eigen/Core>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <massspring/forces/gravity.hpp>
#include <massspring/integrators/fast_mass_spring.hpp>
#include <massspring/scene/cloth.hpp>
#include <massspring/scene/make_system.hpp>
#include <massspring/scene/recipes.hpp>
#include <massspring/storage/storage.hpp>
#include <massspring/system/mass_spring_system.hpp>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#if MASSSPRING_BENCH_WITH_IO
#include <massspring/io/load_scene.hpp>
#endif

#include "seed/seed_reference.hpp"

namespace massspring::bench {

/// @brief The folder holding scenes/jacobson (MASSSPRING_SHARED_DIR at configure time; defined in
/// the generated shared_dir.cpp, so no other unit holds an absolute path).
std::filesystem::path shared_dir();

using SparseSystem = MassSpringSystem<double, Sparse>;
using DenseSystem = MassSpringSystem<double, Dense>;
using FloatSystem = MassSpringSystem<float, Sparse>;
using test::SeedFastMassSpring;

/// @brief Time step [s].
inline constexpr double kDt = 1.0 / 30;
/// @brief Local-global iterations per step (the reference solver's 50).
inline constexpr int kIterations = 50;
/// @brief Penalty weight of the pins [N/m] (the reference solver's).
inline constexpr double kPenaltyWeight = 1e10;

/// @brief One scene, in the storages and precisions a program asks for (null: not built).
struct Scene {
  std::string name;
  bool gravity = false;  ///< m g (the curtain) instead of (0, -9.8, 0) N per point
  std::shared_ptr<const SparseSystem> sparse;
  std::shared_ptr<const DenseSystem> dense;
  std::shared_ptr<const FloatSystem> single;
};

/// @brief `system` with the scene's force added as a term: Gravity m g when `gravity`, else the
/// JSON+OBJ scenes' ConstantForce of (0, -9.8, 0) N on every point.
template <class System>
System with_force(System system, bool gravity) {
  using Scalar = typename System::Scalar;
  const Vector3<Scalar> down(0, Scalar(-9.8), 0);
  if (gravity)
    system.add_force(Gravity<Scalar>(down));
  else
    system.add_force(ConstantForce<Scalar>(down));
  return system;
}

/// @brief What to build besides the double, Sparse system.
struct Build {
  bool dense = false;
  bool single = false;
};

/// @brief cloth<n>: n x n points, both diagonals, top corners pinned, k = 1000 N/m.
inline Scene cloth_scene(int n, Build build = {}) {
  ClothOptions o;
  o.columns = o.rows = n;
  o.shear = ClothShear::Both;
  o.pins = ClothPins::TopCorners;
  o.stiffness = 1000;
  const auto description = make_cloth(o);
  Scene s;
  s.name = "cloth" + std::to_string(n);
  s.sparse = std::make_shared<const SparseSystem>(
      with_force(make_system<SparseSystem>(description), s.gravity));
  if (build.dense)
    s.dense = std::make_shared<const DenseSystem>(
        with_force(make_system<DenseSystem>(description), s.gravity));
  if (build.single)
    s.single = std::make_shared<const FloatSystem>(
        with_force(make_system<FloatSystem>(description), s.gravity));
  return s;
}

/// @brief Liu 2013's curtain, under gravity m g.
inline Scene curtain_scene(Build build = {}) {
  const auto description = make_cloth(curtain_recipe());
  Scene s;
  s.name = "curtain";
  s.gravity = true;
  s.sparse = std::make_shared<const SparseSystem>(
      with_force(make_system<SparseSystem>(description), s.gravity));
  if (build.single)
    s.single = std::make_shared<const FloatSystem>(
        with_force(make_system<FloatSystem>(description), s.gravity));
  return s;
}

/// @brief The JSON+OBJ scene `name` (flag, skirt), or nothing (with a note on stderr) when
/// its file or massspring::io is missing.
inline std::vector<Scene> jacobson_scene(const std::string& name, Build build = {}) {
  const std::filesystem::path file = shared_dir() / "scenes" / "jacobson" / (name + ".json");
  if (!std::filesystem::exists(file)) {
    std::fprintf(stderr, "note: %s not found; the %s benchmarks are not registered\n",
                 file.string().c_str(), name.c_str());
    return {};
  }
#if MASSSPRING_BENCH_WITH_IO
  try {
    Scene s;
    s.name = name;
    s.sparse = std::make_shared<const SparseSystem>(
        with_force(io::load_scene<SparseSystem>(file), s.gravity));
    if (build.single)
      s.single = std::make_shared<const FloatSystem>(
          with_force(io::load_scene<FloatSystem>(file), s.gravity));
    return {std::move(s)};
  } catch (const std::exception& e) {
    std::fprintf(stderr, "WARNING: loading %s failed (%s); its benchmarks are not registered\n",
                 file.string().c_str(), e.what());
  }
#else
  std::fprintf(stderr, "note: built without massspring::io; the %s benchmarks are not registered\n",
               name.c_str());
#endif
  return {};
}

/// @brief The scenes most programs run: cloth32, cloth64, cloth128, the curtain, flag, skirt.
inline std::vector<Scene> standard_scenes(Build build = {}) {
  std::vector<Scene> scenes;
  for (const int n : {32, 64, 128}) scenes.push_back(cloth_scene(n, build));
  scenes.push_back(curtain_scene(build));
  for (const char* name : {"flag", "skirt"})
    for (Scene& s : jacobson_scene(name, build)) scenes.push_back(std::move(s));
  return scenes;
}

/// @brief FastMassSpring's options for `scene`, set up as the reference solver: kIterations
/// iterations from the current positions, penalty pins of weight kPenaltyWeight (the scene's
/// systems carry its force).
template <class Scalar>
FastMassSpringOptions<Scalar> options_for(const Scene&) {
  FastMassSpringOptions<Scalar> o = FastMassSpringOptions<Scalar>::reference();
  o.iterations = kIterations;
  o.pins = PinMode::Penalty;
  o.penalty_weight = Scalar(kPenaltyWeight);
  o.initial_guess = InitialGuess::Current;
  return o;
}

/// @brief The reference solver's options for `scene` (the same step as options_for).
inline SeedFastMassSpring::Options seed_options(const Scene& scene) {
  SeedFastMassSpring::Options o;
  o.iterations = kIterations;
  o.penalty_weight = kPenaltyWeight;
  o.external_force = scene.gravity ? Eigen::RowVector3d::Zero() : Eigen::RowVector3d(0, -9.8, 0);
  o.gravity = scene.gravity ? Eigen::RowVector3d(0, -9.8, 0) : Eigen::RowVector3d::Zero();
  return o;
}

}  // namespace massspring::bench
