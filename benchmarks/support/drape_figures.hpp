#pragma once
// The drape against Bullet (bullet_drape.cpp, massspring_drape.cpp): the scene both programs
// build and the figures both print, computed here by the same code from plain arrays, so neither
// engine's own measures are trusted.
//
// Scene: an 81 x 81 cloth, 2 m x 2 m, 1.9 kg (equal point masses), lying flat in the x-z plane
// 5 cm above a sphere of radius 0.5 m at the origin, over a floor at y = -1; gravity 9.81 m/s^2
// along -y; Coulomb friction 0.5 on the sphere and the floor. The cells are split as
// btSoftBodyHelpers::CreatePatch splits them (gendiags): cell (ix, iy) with ix + iy odd by the
// diagonal (ix, iy)-(ix + 1, iy + 1), the others by (ix + 1, iy)-(ix, iy + 1); point (ix, iy) has
// index iy * 81 + ix and lies at (-1 + ix dx, 0.55, -1 + iy dx), dx = 2 / 80.
//
// Figures (of positions x, the links and their rest lengths):
//   strain    |l / l0 - 1| over the links at the end, mean and max, and how many links exceed
//             kStrainBound (the largest strain the comparison accepts at rest);
//   gap       min over the points of |x_i| - r (signed: negative = a point inside the sphere);
//   rest      the cloth's highest point above the sphere's top, max_i y_i - r;
//   crossings edge-triangle crossings of the cloth's own surface (tests/support/intersections.hpp,
//             the tests' exact checker, written apart from the library's contact code).
#include <time.h>

#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <massspring/types.hpp>
#include <string>

#include "support/intersections.hpp"

namespace drape {

constexpr int kSide = 81;              // points along each side
constexpr double kWidth = 2.0;         // m
constexpr double kMass = 1.9;          // kg, the whole cloth
constexpr double kHeight = 0.55;       // m, the cloth's plane at the start
constexpr double kRadius = 0.5;        // m, the sphere's (centre at the origin)
constexpr double kFloor = -1.0;        // m, the floor's top
constexpr double kFriction = 0.5;      // Coulomb, sphere and floor
constexpr double kGravity = 9.81;      // m/s^2
constexpr double kStrainBound = 0.15;  // the largest |l / l0 - 1| a link may have at rest

inline int index(int ix, int iy) { return iy * kSide + ix; }

// CreatePatch's triangles (see the file's comment), two per cell.
inline massspring::Triangles patch_triangles() {
  massspring::Triangles t((kSide - 1) * (kSide - 1) * 2, 3);
  Eigen::Index row = 0;
  for (int iy = 0; iy + 1 < kSide; ++iy)
    for (int ix = 0; ix + 1 < kSide; ++ix) {
      const int a = index(ix, iy), b = index(ix + 1, iy), c = index(ix + 1, iy + 1),
                d = index(ix, iy + 1);
      if ((ix + iy) & 1) {
        t.row(row++) << a, b, c;
        t.row(row++) << a, c, d;
      } else {
        t.row(row++) << d, a, b;
        t.row(row++) << d, b, c;
      }
    }
  return t;
}

struct Figures {
  double strain_mean = 0, strain_max = 0, gap = 0, rest = 0;
  int past_bound = 0;  // links with strain > kStrainBound
};

inline Figures figures(const massspring::Points<double>& x, const massspring::Edges& links,
                       const Eigen::VectorXd& rest_lengths) {
  Figures f;
  for (Eigen::Index e = 0; e < links.rows(); ++e) {
    const double l = (x.row(links(e, 0)) - x.row(links(e, 1))).norm();
    const double strain = std::abs(l / rest_lengths(e) - 1);
    f.strain_mean += strain;
    f.strain_max = std::max(f.strain_max, strain);
    f.past_bound += strain > kStrainBound;
  }
  f.strain_mean /= double(links.rows());
  f.gap = std::numeric_limits<double>::infinity();
  f.rest = -std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    f.gap = std::min(f.gap, x.row(i).norm() - kRadius);
    f.rest = std::max(f.rest, x(i, 1) - kRadius);
  }
  return f;
}

// The frames' time: CPU time of the process (both programs run one thread, so this is the time
// the frames held a core, not what other processes on a shared machine took of it) and the wall
// clock beside it.
struct FrameTimer {
  double cpu_ms = 0, wall_ms = 0;
  double cpu0 = 0;
  std::chrono::steady_clock::time_point wall0;

  static double cpu_now() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
  }
  void start() {
    wall0 = std::chrono::steady_clock::now();
    cpu0 = cpu_now();
  }
  void stop() {
    cpu_ms += cpu_now() - cpu0;
    wall_ms +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wall0).count();
  }
};

// The lowest gap over the frame ends, and the crossings at the frame ends (counted only when
// asked: the checker is brute force, far slower than a frame). Kept out of the timed frames.
struct Watch {
  bool count_crossings = false;
  double lowest_gap = std::numeric_limits<double>::infinity();
  int max_crossings = 0, end_crossings = 0;
  massspring::Edges edges;

  void frame_end(const massspring::Points<double>& x, const massspring::Triangles& surface) {
    for (Eigen::Index i = 0; i < x.rows(); ++i)
      lowest_gap = std::min(lowest_gap, x.row(i).norm() - kRadius);
    if (!count_crossings) return;
    if (edges.rows() == 0) edges = massspring::test::triangle_edges(surface);
    end_crossings = massspring::test::count_crossings(x, surface, edges);
    max_crossings = std::max(max_crossings, end_crossings);
  }
};

// The figures, one per line, "name: value", the same for both programs.
inline void print(const char* engine, double dt, int frames, const FrameTimer& time,
                  const Figures& f, const Watch& w, bool ok) {
  const double per_frame = time.cpu_ms / frames;
  std::printf("engine: %s\n", engine);
  std::printf("dt: 1/%.0f s, frames: %d (%.2f s)\n", 1 / dt, frames, frames * dt);
  std::printf("ms per frame (CPU): %.3f (wall clock: %.3f)\n", per_frame, time.wall_ms / frames);
  std::printf("ms per simulated second (CPU): %.1f\n", per_frame / dt);
  std::printf("strain at the end, mean: %.4f, max: %.4f\n", f.strain_mean, f.strain_max);
  std::printf("links past %.0f%% strain at the end: %d\n", 100 * kStrainBound, f.past_bound);
  std::printf("gap to the sphere at the end: %.3f mm (lowest at a frame end: %.3f mm)\n",
              1e3 * f.gap, 1e3 * w.lowest_gap);
  std::printf("rests above the sphere (highest point - r): %.3f mm\n", 1e3 * f.rest);
  if (w.count_crossings)
    std::printf("crossings at frame ends, max: %d, at the end: %d\n", w.max_crossings,
                w.end_crossings);
  else
    std::printf("crossings: not counted (--crossings)\n");
  std::printf("finite: %s\n", ok ? "yes" : "NO");
}

// Options both programs take: --seconds S (default 3), --crossings; the rest go to `extra`, which
// returns false for an argument it does not know.
template <class Extra>
bool parse(int argc, char** argv, double& seconds, bool& crossings, Extra extra) {
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--seconds" && a + 1 < argc) {
      seconds = std::atof(argv[++a]);
      if (!(seconds > 0)) return false;
    } else if (arg == "--crossings") {
      crossings = true;
    } else if (!extra(arg, a + 1 < argc ? argv[a + 1] : nullptr, a)) {
      return false;
    }
  }
  return true;
}

}  // namespace drape
