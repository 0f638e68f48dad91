// A program that uses massspring as a consumer would: core and io (and CHOLMOD where
// massspring::cholmod is linked), through the package's targets.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <massspring/io.hpp>
#include <massspring/massspring.hpp>
#ifdef MASSSPRING_HAS_CHOLMOD  // linked with massspring::cholmod
#include <massspring/storage/cholmod.hpp>
#endif

int main(int argc, char** argv) {
  using System = massspring::MassSpringSystem<double, massspring::Sparse>;
  massspring::ChainOptions chain;
  const auto scene = massspring::make_chain(chain);
  const std::filesystem::path dir = argc > 1 ? argv[1] : ".";
  massspring::io::write_json_scene(dir / "consumer-chain.json", scene);
  System system = massspring::io::load_scene<System>(dir / "consumer-chain.json");

  // The plain iteration (FastMassSpringOptions::reference()): the CHOLMOD check below bounds its
  // rounding, which Anderson's mixing would amplify.
  massspring::FastMassSpring<System> solver(massspring::FastMassSpringOptions<double>::reference());
  system.add_force(massspring::Gravity<double>(massspring::Vector3<double>(0, -9.8, 0)));
  solver.precompute(system, 1.0 / 30);
  for (int frame = 0; frame < 30; ++frame)
    if (!solver.step(system).ok()) return 1;
  const double sag = -system.positions().col(1).minCoeff();
  std::printf("massspring %s: %d points, sag %.4f m\n", massspring::version_string,
              system.num_points(), sag);
  if (!(sag > 0 && std::isfinite(sag))) return 1;
#ifdef MASSSPRING_HAS_CHOLMOD
  // The same 30 frames with CHOLMOD's factorization: the same sag, to rounding (measured 2.7e-15
  // relative; the bound leaves about ten times that).
  System other = massspring::io::load_scene<System>(dir / "consumer-chain.json");
  massspring::FastMassSpring<System, massspring::CholmodCholesky<double>> cholmod(
      massspring::FastMassSpringOptions<double>::reference());
  other.add_force(massspring::Gravity<double>(massspring::Vector3<double>(0, -9.8, 0)));
  cholmod.precompute(other, 1.0 / 30);
  for (int frame = 0; frame < 30; ++frame)
    if (!cholmod.step(other).ok()) return 1;
  const double cholmod_sag = -other.positions().col(1).minCoeff();
  std::printf("with CHOLMOD: sag %.4f m\n", cholmod_sag);
  if (!(std::abs(cholmod_sag - sag) <= 3e-14 * sag)) return 1;
#endif
  return 0;
}
