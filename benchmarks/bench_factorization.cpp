// Factorisations of FastMassSpring's Q compared: Eigen's SimplicialLLT with AMD, geometric nested
// dissection of the rest positions (massspring::nested_dissection; its time counted in the
// factorisation's), COLAMD and the natural ordering (SparseCholesky<Scalar, Ordering>), and, when
// built with CHOLMOD
// (MASSSPRING_HAS_CHOLMOD), CHOLMOD's supernodal factorisation with its own choice, AMD, METIS and
// NESDIS (CholmodCholesky). For each: nnz(L), factorisation time (compute(): ordering, symbolic,
// numeric; median of 3) and the time of one fused n x 3 solve with that factor (median of 21), on
// the curtain and on cloth grids (exact pins, dt = 1/30, k = 1000). Prints a Markdown table.
// A plain program with wall-clock medians (std::chrono::steady_clock).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <massspring/integrators/fast_mass_spring.hpp>
#include <massspring/scene/cloth.hpp>
#include <massspring/scene/make_system.hpp>
#include <massspring/scene/recipes.hpp>
#include <massspring/storage/storage.hpp>
#include <string>
#include <vector>
#if MASSSPRING_HAS_CHOLMOD
#include <massspring/storage/cholmod.hpp>
#endif

namespace {

using System = massspring::MassSpringSystem<double, massspring::Sparse>;
using Matrix = System::Matrix;
using Clock = std::chrono::steady_clock;

double median_ms(int repetitions, const std::function<void()>& f) {
  std::vector<double> t;
  for (int r = 0; r < repetitions; ++r) {
    const auto t0 = Clock::now();
    f();
    t.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

template <class Cholesky, class Compute>
void measure(const std::string& scene, const char* name, const Matrix& q, Cholesky& llt,
             int solve_repetitions, Compute compute) {
  bool ok = true;
  const double factor_ms = median_ms(3, [&] { ok = compute() && ok; });
  if (!ok) {
    std::printf("| %s | %s | failed | | |\n", scene.c_str(), name);
    return;
  }
  massspring::Points<double> w = massspring::Points<double>::Random(q.rows(), 3);
  const double solve_ms = median_ms(solve_repetitions, [&] { llt.solve_in_place(w.data()); });
  std::printf("| %s | %s | %ld | %.2f | %.4f |\n", scene.c_str(), name, long(llt.factor_nonzeros()),
              factor_ms, solve_ms);
  std::fflush(stdout);
}

template <class Cholesky>
void measure(const std::string& scene, const char* name, const Matrix& q, Cholesky& llt,
             int solve_repetitions) {
  measure(scene, name, q, llt, solve_repetitions, [&] { return llt.compute(q); });
}

void compare(const std::string& scene, const massspring::ClothOptions& o) {
  const System system = massspring::make_system<System>(massspring::make_cloth(o));
  massspring::FastMassSpring<System> solver;
  solver.options.ordering = massspring::FillOrdering::Solver;
  solver.precompute(system, 1.0 / 30);
  const Matrix& q = solver.system_matrix();
  const int reps = q.rows() > 100000 ? 5 : 21;
  {
    massspring::SparseCholesky<double, Eigen::AMDOrdering<int>> llt;
    measure(scene, "Eigen SimplicialLLT, AMD", q, llt, reps);
  }
  {
    Eigen::Matrix<double, Eigen::Dynamic, 3> xyz(q.rows(), 3);
    for (Eigen::Index r = 0; r < q.rows(); ++r)
      xyz.row(r) = system.rest_positions().row(solver.free_points()[std::size_t(r)]);
    massspring::SparseCholesky<double> llt;
    measure(scene, "Eigen SimplicialLLT, nested dissection", q, llt, reps, [&] {
      return llt.compute(q, massspring::nested_dissection(xyz, massspring::graph_of(q)));
    });
  }
  if (q.rows() <= 70000) {  // COLAMD (meant for LU) fills ~10x more: 43 s already at 256^2
    massspring::SparseCholesky<double, Eigen::COLAMDOrdering<int>> llt;
    measure(scene, "Eigen SimplicialLLT, COLAMD", q, llt, reps);
  }
  if (q.rows() <= 20000) {  // the natural order of a grid fills a band: n sqrt(n) entries
    massspring::SparseCholesky<double, Eigen::NaturalOrdering<int>> llt;
    measure(scene, "Eigen SimplicialLLT, natural", q, llt, reps);
  }
#if MASSSPRING_HAS_CHOLMOD
  const std::pair<massspring::CholmodOrdering, const char*> orderings[] = {
      {massspring::CholmodOrdering::Default, "CHOLMOD supernodal, its choice"},
      {massspring::CholmodOrdering::AMD, "CHOLMOD supernodal, AMD"},
      {massspring::CholmodOrdering::METIS, "CHOLMOD supernodal, METIS"},
      {massspring::CholmodOrdering::NESDIS, "CHOLMOD supernodal, NESDIS"},
  };
  for (const auto& [ordering, name] : orderings) {
    massspring::CholmodCholesky<double> llt;
    llt.ordering = ordering;
    measure(scene, name, q, llt, reps);
  }
#endif
}

}  // namespace

int main() {
  std::printf(
      "| scene | factorisation | nnz(L) | factorise ms | one n x 3 solve ms |\n"
      "|---|---|---:|---:|---:|\n");
  compare("curtain", massspring::curtain_recipe());
  for (const int n : {128, 256, 512}) {
    massspring::ClothOptions o;
    o.columns = o.rows = n;
    o.shear = massspring::ClothShear::Both;
    o.stiffness = 1000;
    compare("cloth" + std::to_string(n), o);
  }
  return 0;
}
