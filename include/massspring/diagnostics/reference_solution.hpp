#pragma once
/// @file
/// @brief reference_solution(): a scene integrated to an end time with RK4, the step halved until
/// halving it changes the result by less than a tolerance; cached on disk.

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <type_traits>

#include "massspring/detail/validate.hpp"
#include "massspring/diagnostics/accuracy.hpp"
#include "massspring/diagnostics/energy.hpp"
#include "massspring/diagnostics/stable_time_step.hpp"
#include "massspring/error.hpp"
#include "massspring/integrators/rk4.hpp"

namespace massspring {

/// @brief Parameters of reference_solution().
struct ReferenceOptions {
  /// @brief Stop when halving the step changes the end positions by less than this, as a
  /// trajectory error (RMS distance over the bounding-box diagonal). Finite, > 0; default 1e-9.
  double tolerance = 1e-9;
  /// @brief The first step [s]; 0 (default) takes stable_time_step(system, RK4) (half the limit),
  /// at most end_time / 8.
  double initial_dt = 0;
  /// @brief At most this many halvings (>= 1; default 14); past them reference_solution() throws.
  int max_halvings = 14;
  /// @brief Where results are cached (created when missing); empty (default): no cache.
  std::string cache_directory;
  /// @brief Names the scene in the cache file name, and covers what the hash cannot see: the
  /// parameters of the force terms (the hash covers the state, masses, springs, pins, the number
  /// of terms, the end time and the tolerance). Required with a cache directory.
  std::string key;
  /// @brief Called now and then with (the step being tried [s], fraction of that run done).
  std::function<void(double, double)> progress;
};

/// @brief A reference end state.
struct ReferenceSolution {
  Points<double> positions = Points<double>(0, 3);   ///< at the end time [m]
  Points<double> velocities = Points<double>(0, 3);  ///< at the end time [m/s]
  double dt = 0;                                     ///< the step of the finest run [s]
  double change = 0;          ///< the trajectory error between the last two runs
  double kinetic_max = 0;     ///< the largest kinetic energy of the finest run [J]
  double initial_energy = 0;  ///< total energy at time 0 [J]
  double diagonal = 0;        ///< bounding-box diagonal of the initial positions [m]
  bool from_cache = false;    ///< read from the cache, not computed
};

namespace detail {

inline void fnv(std::uint64_t& h, const void* data, std::size_t bytes) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t k = 0; k < bytes; ++k) {
    h ^= p[k];
    h *= 1099511628211ull;
  }
}

template <class M>
void fnv_matrix(std::uint64_t& h, const M& m) {
  const Eigen::Index rows = m.rows(), cols = m.cols();
  fnv(h, &rows, sizeof rows);
  fnv(h, &cols, sizeof cols);
  for (Eigen::Index r = 0; r < rows; ++r)
    for (Eigen::Index c = 0; c < cols; ++c) {
      const auto value = m(r, c);
      fnv(h, &value, sizeof value);
    }
}

template <class System>
std::uint64_t reference_hash(const System& s, double end_time, const ReferenceOptions& o) {
  std::uint64_t h = 1469598103934665603ull;
  fnv_matrix(h, s.positions());
  fnv_matrix(h, s.velocities());
  fnv_matrix(h, s.masses());
  fnv_matrix(h, s.springs());
  fnv_matrix(h, s.stiffness());
  fnv_matrix(h, s.rest_lengths());
  fnv_matrix(h, s.damping());
  fnv_matrix(h, s.pin_targets());
  for (const int i : s.pinned()) fnv(h, &i, sizeof i);
  std::size_t terms = 0;
  for (const auto& t : s.forces()) {
    (void)t;
    ++terms;
  }
  fnv(h, &terms, sizeof terms);
  fnv(h, &end_time, sizeof end_time);
  fnv(h, &o.tolerance, sizeof o.tolerance);
  fnv(h, o.key.data(), o.key.size());
  return h;
}

constexpr char reference_magic[8] = {'M', 'S', 'R', 'E', 'F', '0', '0', '1'};

inline bool read_reference(const std::string& path, Eigen::Index n, ReferenceSolution& r) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  char magic[8];
  Eigen::Index rows = 0;
  in.read(magic, 8);
  in.read(reinterpret_cast<char*>(&rows), sizeof rows);
  if (!in || std::string(magic, 8) != std::string(reference_magic, 8) || rows != n) return false;
  double scalars[5];
  in.read(reinterpret_cast<char*>(scalars), sizeof scalars);
  r.positions.resize(n, 3);
  r.velocities.resize(n, 3);
  in.read(reinterpret_cast<char*>(r.positions.data()), std::streamsize(sizeof(double) * 3 * n));
  in.read(reinterpret_cast<char*>(r.velocities.data()), std::streamsize(sizeof(double) * 3 * n));
  if (!in || in.peek() != std::ifstream::traits_type::eof()) return false;
  r.dt = scalars[0];
  r.change = scalars[1];
  r.kinetic_max = scalars[2];
  r.initial_energy = scalars[3];
  r.diagonal = scalars[4];
  r.from_cache = true;
  return true;
}

inline void write_reference(const std::string& path, const ReferenceSolution& r) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    const Eigen::Index rows = r.positions.rows();
    const double scalars[5] = {r.dt, r.change, r.kinetic_max, r.initial_energy, r.diagonal};
    out.write(reference_magic, 8);
    out.write(reinterpret_cast<const char*>(&rows), sizeof rows);
    out.write(reinterpret_cast<const char*>(scalars), sizeof scalars);
    out.write(reinterpret_cast<const char*>(r.positions.data()),
              std::streamsize(sizeof(double) * 3 * rows));
    out.write(reinterpret_cast<const char*>(r.velocities.data()),
              std::streamsize(sizeof(double) * 3 * rows));
    if (!out) throw Error(message("reference_solution: cannot write the cache file ", tmp));
  }
  std::filesystem::rename(tmp, path);
}

/// @brief Runs a copy of `system` with RK4 at step end_time / steps; returns the copy.
template <class System>
System run_rk4(const System& system, double end_time, long steps, double& kinetic_max,
               const ReferenceOptions& o) {
  System s = system;
  RK4<System> rk4;
  const double h = end_time / double(steps);
  rk4.precompute(s, h);
  kinetic_max = double(kinetic_energy(s));
  const long report_every = std::max(1L, steps / 20);
  for (long k = 0; k < steps; ++k) {
    if (!rk4.step(s).ok())
      throw Error(message("reference_solution: RK4 at dt = ", h,
                          " s produced a non-finite value at step ", k + 1,
                          "; give a smaller initial_dt"));
    kinetic_max = std::max(kinetic_max, double(kinetic_energy(s)));
    if (o.progress && (k + 1) % report_every == 0) o.progress(h, double(k + 1) / double(steps));
  }
  return s;
}

}  // namespace detail

/// @brief The state of `system` (double precision) after `end_time` seconds, integrated with RK4
/// at steps h, h/2, h/4, ... until two successive results differ by less than
/// `options.tolerance` (trajectory error); the finer one is returned. With a cache directory, a
/// result computed before for the same scene, end time and tolerance is read instead.
/// @throws Error for invalid options, a non-finite run, or no convergence within max_halvings.
template <class System>
ReferenceSolution reference_solution(const System& system, double end_time,
                                     const ReferenceOptions& options = {}) {
  static_assert(std::is_same_v<typename System::Scalar, double>,
                "reference_solution needs a double-precision system");
  using detail::message;
  detail::require_number("reference_solution", "end_time", end_time, true);
  detail::require_number("reference_solution", "tolerance", options.tolerance, true);
  if (!(options.initial_dt >= 0) || !std::isfinite(options.initial_dt))
    throw Error(message("reference_solution: initial_dt must be finite and >= 0, got ",
                        options.initial_dt));
  if (options.max_halvings < 1)
    throw Error(
        message("reference_solution: max_halvings must be >= 1, got ", options.max_halvings));
  std::string path;
  if (!options.cache_directory.empty()) {
    if (options.key.empty())
      throw Error("reference_solution: a cache directory needs a key naming the scene");
    std::filesystem::create_directories(options.cache_directory);
    char hash[17];
    std::snprintf(
        hash, sizeof hash, "%016llx",
        static_cast<unsigned long long>(detail::reference_hash(system, end_time, options)));
    path = (std::filesystem::path(options.cache_directory) / (options.key + "-" + hash + ".ref"))
               .string();
    ReferenceSolution cached;
    if (detail::read_reference(path, system.num_points(), cached)) return cached;
  }

  double h = options.initial_dt;
  if (h == 0) h = std::min(stable_time_step(system, ExplicitMethod::RK4), end_time / 8);
  long steps = std::max(1L, long(std::ceil(end_time / h)));
  ReferenceSolution r;
  r.diagonal = bounding_box_diagonal(system.positions());
  if (!(r.diagonal > 0)) r.diagonal = 1;  // a single point: distances in metres
  r.initial_energy = double(total_energy(system));
  double kinetic = 0;
  System coarse = detail::run_rk4(system, end_time, steps, kinetic, options);
  for (int halving = 1; halving <= options.max_halvings; ++halving) {
    steps *= 2;
    System fine = detail::run_rk4(system, end_time, steps, kinetic, options);
    r.change = trajectory_error(coarse.positions(), fine.positions(), r.diagonal);
    if (r.change < options.tolerance) {
      r.positions = fine.positions();
      r.velocities = fine.velocities();
      r.dt = end_time / double(steps);
      r.kinetic_max = kinetic;
      if (!path.empty()) detail::write_reference(path, r);
      return r;
    }
    coarse = std::move(fine);
  }
  throw Error(message("reference_solution: halving the step ", options.max_halvings,
                      " times still changed the result by ", r.change, " (tolerance ",
                      options.tolerance, ")"));
}

}  // namespace massspring
