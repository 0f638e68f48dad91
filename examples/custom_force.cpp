// A force term of your own: a steady wind whose drag grows with the air speed relative to each
// point, F_i = c (w - v_i). Any integrator honours it; implicit ones use its Jacobian.
// Run: prints how far the wind has pushed a hanging cloth out of its plane (+z) in 2 s.
#include <cstdio>
#include <massspring/forces/force_term.hpp>
#include <massspring/forces/gravity.hpp>
#include <massspring/integrators/backward_euler.hpp>
#include <massspring/scene/cloth.hpp>
#include <massspring/scene/make_system.hpp>

using System = massspring::MassSpringSystem<double, massspring::Sparse>;

struct Wind {
  massspring::Vector3<double> air{2, 0, 1};  // wind velocity [m/s]
  double c = 0.01;                           // drag coefficient [N s/m] per point

  const char* name() const { return "wind"; }  // for messages
  // f += F(x, v): every term adds its force to f, an #points by 3 array [N].
  void add_force(const massspring::ForceContext<double>& ctx, massspring::Points<double>& f) const {
    for (Eigen::Index i = 0; i < f.rows(); ++i) f.row(i) += c * (air.transpose() - ctx.v.row(i));
  }
  // dF/dv = -c I: entries at coordinates (3 i + k, 3 i + k), the same sequence at every call.
  void add_dfdv(const massspring::ForceContext<double>& ctx,
                massspring::JacobianSink<double>& j) const {
    for (int i = 0; i < int(ctx.x.rows()); ++i)
      for (int k = 0; k < 3; ++k) j.add(3 * i + k, 3 * i + k, -c);
  }
};

int main() {
  massspring::ClothOptions cloth;
  cloth.columns = cloth.rows = 15;
  System system = massspring::make_system<System>(massspring::make_cloth(cloth));
  system.add_force(massspring::Gravity<double>({0, -9.8, 0}));
  system.add_force(Wind{});
  const double z0 = system.positions().col(2).mean();

  massspring::BackwardEuler<System> solver;  // Newton's method on the implicit step
  solver.precompute(system, 1.0 / 30);
  for (int step = 0; step < 60; ++step)
    if (!solver.step(system).ok()) return 2;
  const double pushed = system.positions().col(2).mean() - z0;
  std::printf("the wind pushed the cloth %.3f m along +z in 2 s\n", pushed);
  return pushed > 0 ? 0 : 1;
}
