// contact/fosssim/penalty.hpp: the force is minus the gradient of the energy (central differences) for
// particle-particle, particle-edge and particle-plane contacts; closed form of one overlap;
// internal forces sum to zero; the grid broad phase gives the same force as all pairs.
#include <doctest/doctest.h>

#include <massspring/contact/fosssim/penalty.hpp>
#include <random>

#include "contact/support.hpp"

namespace contact = massspring::contact;
using massspring::test::Pts;
using massspring::test::v3;
using Vec = massspring::Vector<double>;

namespace {

struct Ctx {
  Vec m, k, l0, b;
  massspring::Edges e = massspring::Edges(0, 2);
  explicit Ctx(int n) : m(Vec::Ones(n)) {}
  massspring::ForceContext<double> operator()(const Pts& x, const Pts& v) const {
    return {x, v, m, e, k, l0, b, false};
  }
};

Pts force(const contact::PenaltyForce<double>& p, const Ctx& c, const Pts& x) {
  Pts f = Pts::Zero(x.rows(), 3);
  p.add_force(c(x, x), f);
  return f;
}

}  // namespace

TEST_CASE("PenaltyForce: one overlap in closed form, k (s - d) along the line of centres") {
  contact::PenaltyForce<double> p(massspring::test::particles(2, 0.2), 100, 0.05);
  Ctx c(2);
  Pts x(2, 3);
  x << 0, 0, 0, 0.3, 0.4, 0;  // d = 0.5, s = 0.45: apart
  CHECK(force(p, c, x).isZero());
  x << 0, 0, 0, 0.24, 0.32, 0;  // d = 0.4: overlap 0.05
  const Pts f = force(p, c, x);
  CHECK((f.row(0) - 100 * 0.05 * v3(-0.6, -0.8).transpose()).norm() < 1e-12);
  CHECK((f.row(0) + f.row(1)).norm() < 1e-15);
  CHECK(p.energy(c(x, x)) == doctest::Approx(0.5 * 100 * 0.05 * 0.05));
}

TEST_CASE("PenaltyForce: F = -dE/dx (central differences), every pair kind; internal forces") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  const int n = 12;
  contact::ContactGeometry<double> g;
  g.radii = Vec::NullaryExpr(n, [&] { return 0.25 + 0.1 * u(rng); });
  g.edges.resize(4, 2);
  g.edges << 0, 1, 2, 3, 4, 5, 6, 7;
  g.edge_radii = Vec::Constant(4, 0.1);
  for (const bool planes : {false, true}) {
    CAPTURE(planes);
    contact::ContactGeometry<double> gg = g;
    if (planes) gg.planes.push_back({v3(0, -0.6), v3(0.5, 2)});
    Pts x(n, 3);
    for (int i = 0; i < n; ++i) x.row(i) << u(rng), u(rng), 0.3 * u(rng);
    contact::PenaltyForce<double> p(gg, 50, 0.05);
    Ctx c(n);
    const Pts f = force(p, c, x);
    CHECK(p.energy(c(x, x)) > 0);
    const double h = 1e-6;
    double worst = 0;
    for (int i = 0; i < n; ++i)
      for (int a = 0; a < 3; ++a) {
        Pts xp = x, xm = x;
        xp(i, a) += h;
        xm(i, a) -= h;
        const double fd = -(p.energy(c(xp, xp)) - p.energy(c(xm, xm))) / (2 * h);
        worst = std::max(worst, std::abs(fd - f(i, a)));
      }
    CHECK(worst < 1e-6 * std::max(1.0, f.cwiseAbs().maxCoeff()));
    if (!planes) CHECK(f.colwise().sum().norm() < 1e-12);  // internal
    // the grid gives the same force
    contact::PenaltyForce<double> q(gg, 50, 0.05, contact::BroadPhaseKind::Grid);
    CHECK((force(q, c, x) - f).cwiseAbs().maxCoeff() < 1e-12);
  }
}
