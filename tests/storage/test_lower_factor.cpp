// storage/lower_factor.hpp: forward and back substitution against Eigen's triangular solves, in
// double and float, on the SSE2 rows and on the AVX2 + FMA rows (where the CPU has them), the row
// copy and the choice between the two.
#include <doctest/doctest.h>

#include <cstddef>
#include <massspring/storage/lower_factor.hpp>
#include <massspring/storage/sparse.hpp>
#include <type_traits>
#include <vector>

#include "support/random_spd.hpp"

using massspring::test::random_spd;

namespace {

// What view().simd must be when the AVX2 rows are allowed: the CPU (and the build) decide.
bool expect_simd() { return massspring::detail::cpu_has_avx2_fma(); }

}  // namespace

TEST_CASE_TEMPLATE(
    "LowerFactor: forward and back substitution each equal Eigen's triangular solves", Scalar,
    float, double) {
  using Rows = Eigen::Matrix<Scalar, Eigen::Dynamic, 3, Eigen::RowMajor>;
  using Columns = Eigen::Matrix<Scalar, Eigen::Dynamic, 3>;
  // Eigen's solves and ours round differently. Measured: up to 1.6e-7 in float and 2.8e-16 in
  // double (relative, either path); the bounds leave about ten times that.
  const double tol = std::is_same_v<Scalar, float> ? 1e-6 : 3e-15;
  // Rows and columns of every length: the SSE2 rows split each sum in two, the AVX2 rows in four,
  // the last count % 4 entries apart; with 1200 edges rows and columns of 4 or more entries leave
  // every remainder 0 .. 3 (checked below).
  for (const int edges : {0, 40, 1200}) {
    CAPTURE(edges);
    const int n = 300;
    const auto q = random_spd<Scalar>(n, edges, 5);
    massspring::SparseCholesky<Scalar> llt;
    REQUIRE(llt.compute(q));
    const auto& l = llt.factor();
    if (edges == 1200) {
      int row_tails[4] = {}, column_tails[4] = {};
      const auto view = llt.lower();
      for (int i = 0; i < n; ++i) {
        const int in_row = view.row_outer[i + 1] - view.row_outer[i];
        const int in_column = view.outer[i + 1] - view.outer[i] - 1;  // without the diagonal
        if (in_row >= 4) ++row_tails[in_row % 4];
        if (in_column >= 4) ++column_tails[in_column % 4];
      }
      for (int r = 0; r < 4; ++r) {
        CAPTURE(r);
        CHECK(row_tails[r] > 0);
        CHECK(column_tails[r] > 0);
      }
    }
    const Columns b = Columns::Random(n, 3);
    const Columns z = l.template triangularView<Eigen::Lower>().solve(b);
    const Columns u = l.transpose().template triangularView<Eigen::Upper>().solve(b);
    Rows sse2_z, sse2_u;
    for (const bool simd : {false, true}) {
      CAPTURE(simd);
      llt.set_simd(simd);
      const auto view = llt.lower();
      CHECK(view.simd == (simd && expect_simd()));
      CHECK(llt.simd() == view.simd);
      // The row copy is the strict lower part of L, row by row, columns ascending.
      const Eigen::SparseMatrix<Scalar, Eigen::RowMajor, int> rows =
          Eigen::SparseMatrix<Scalar, Eigen::ColMajor, int>(
              l.template triangularView<Eigen::StrictlyLower>());
      REQUIRE(view.row_outer[n] == rows.nonZeros());
      for (int i = 0; i <= n; ++i) REQUIRE(view.row_outer[i] == rows.outerIndexPtr()[i]);
      for (Eigen::Index p = 0; p < rows.nonZeros(); ++p) {
        REQUIRE(view.row_inner[p] == rows.innerIndexPtr()[p]);
        REQUIRE(view.row_value[p] == rows.valuePtr()[p]);
      }

      Rows w = b;
      view.forward(w.data());
      CHECK((w - z).norm() <= tol * z.norm());
      Rows v = b;
      view.backward(v.data());
      CHECK((v - u).norm() <= tol * u.norm());
      if (!simd) {
        sse2_z = w;
        sse2_u = v;
      } else if (view.simd && edges > 0) {
        // The AVX2 rows ran: fused multiply-adds round differently somewhere in 300 rows.
        CHECK(w != sse2_z);
        CHECK(v != sse2_u);
      }
    }
  }
}

TEST_CASE_TEMPLATE("LowerFactor: a substitution writes three values per row, never the next row's",
                   Scalar, float, double) {
  // Rows of w stored back to back with a sentinel row after the last: an AVX2 row that stored
  // its fourth lane would overwrite the next row's first value (and the solve would be wrong), and
  // the last row's would reach the sentinel.
  const int n = 64;
  const auto q = random_spd<Scalar>(n, 200, 3);
  massspring::SparseCholesky<Scalar> llt;
  REQUIRE(llt.compute(q));
  const auto view = llt.lower();
  CAPTURE(view.simd);
  using Columns = Eigen::Matrix<Scalar, Eigen::Dynamic, 3>;
  const Columns b = Columns::Random(n, 3);
  std::vector<Scalar> w(std::size_t(3 * n + 3), Scalar(7));
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < 3; ++c) w[std::size_t(3 * r + c)] = b(r, c);
  view.solve(w.data());
  CHECK(w[std::size_t(3 * n)] == Scalar(7));
  CHECK(w[std::size_t(3 * n + 1)] == Scalar(7));
  CHECK(w[std::size_t(3 * n + 2)] == Scalar(7));
  const Eigen::Map<const Eigen::Matrix<Scalar, Eigen::Dynamic, 3, Eigen::RowMajor>> x(w.data(), n,
                                                                                      3);
  const auto& l = llt.factor();  // of P Q P^T: w is in the factor's order
  const Columns lltx = l * (l.transpose() * x);
  // Measured: 1.7e-7 (float) and 2.8e-16 (double) on either path; about ten times that.
  const double tol = std::is_same_v<Scalar, float> ? 2e-6 : 3e-15;
  CHECK((lltx - b).norm() <= tol * b.norm());
}

TEST_CASE("LowerFactorRows refuses a column that does not start with its diagonal") {
  // 2 x 2, column 0 holding only the entry (1, 0): no diagonal first.
  const int outer[] = {0, 1, 2};
  const int inner[] = {1, 1};
  const double value[] = {0.5, 2.0};
  massspring::detail::LowerFactorRows<double> rows;
  CHECK_FALSE(rows.build(2, outer, inner, value));
  const int good_inner[] = {0, 1};
  CHECK(rows.build(2, outer, good_inner, value));
  CHECK(rows.inv_diag[0] == doctest::Approx(2.0));
}
