// forces/vortex.hpp against FOSSSim's definition (VortexForce::addGradEToTotal, 2D):
// rhat = kbs (x_j - x_i) / r turned by (x, y) -> (-y, x), minus (v_j - v_i), times kvc / r^2;
// F_j = +that, F_i = -that. Internal, velocity-dependent, validated.
#include <doctest/doctest.h>

#include <massspring/forces/force_term.hpp>
#include <massspring/forces/vortex.hpp>
#include <random>

namespace {
using Pts = massspring::Points<double>;
using Vec = massspring::Vector<double>;
}  // namespace

TEST_CASE("VortexForce: FOSSSim Theme 1's 2D formula, internal, velocity-dependent") {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-2, 2);
  Pts x(3, 3), v(3, 3);
  for (int i = 0; i < 3; ++i) {
    x.row(i) << u(rng), u(rng), 0;
    v.row(i) << u(rng), u(rng), 0;
  }
  const double kbs = 0.8, kvc = 1000;
  massspring::VortexForce<double> f({{0, 1, kbs, kvc}, {2, 1, -0.3, 5}});
  Vec m = Vec::Ones(3), k, l0, b;
  massspring::Edges e(0, 2);
  const massspring::ForceContext<double> c{x, v, m, e, k, l0, b, false};
  Pts out = Pts::Zero(3, 3);
  f.add_force(c, out);
  // FOSSSim's computation, transcribed for pairs (0, 1) and (2, 1)
  Pts expected = Pts::Zero(3, 3);
  for (auto [i, j, s, w] :
       {std::tuple<int, int, double, double>{0, 1, kbs, kvc}, {2, 1, -0.3, 5}}) {
    Eigen::Vector2d rhat = (x.row(j) - x.row(i)).head<2>().transpose();
    const double r = rhat.norm();
    rhat /= r;
    rhat *= s;
    const double t = rhat.x();
    rhat.x() = -rhat.y();
    rhat.y() = t;
    rhat -= (v.row(j) - v.row(i)).head<2>().transpose();
    rhat /= r * r;
    rhat *= w;
    expected.row(i).head<2>() -= rhat.transpose();  // gradE_i += rhat: F_i = -rhat
    expected.row(j).head<2>() += rhat.transpose();
  }
  CHECK((out - expected).cwiseAbs().maxCoeff() < 1e-12 * (1 + expected.cwiseAbs().maxCoeff()));
  CHECK(out.colwise().sum().norm() < 1e-10);
  CHECK(out.col(2).isZero());
  static_assert(massspring::VortexForce<double>::velocity_dependent);
  static_assert(!massspring::detail::has_energy<massspring::VortexForce<double>, double>::value);
  static_assert(!massspring::detail::has_dfdx<massspring::VortexForce<double>, double>::value);
  CHECK(f.max_index() == 2);
  CHECK_THROWS_WITH_AS(massspring::VortexForce<double>({{1, 1, 1, 1}}),
                       "vortex force 0 acts between point 1 and itself", massspring::Error);
}
