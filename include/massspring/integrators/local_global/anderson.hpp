#pragma once
/// @file
/// @brief local_global::Anderson: Anderson acceleration of the local-global fixed-point map G
/// (Peng et al. 2018, "Anderson Acceleration for Geometry Optimization and Physics Simulation",
/// Algorithm 2), as an accelerator of guarded_loop(): x_{k+1} = G(x_k) - dG theta with
/// theta = argmin |f_k - dF theta| over the last `window` differences of the residuals
/// f = G(x) - x (dF) and of the maps (dG). An iterate whose energy is not below the last accepted
/// one is replaced by the plain step from that one, and the history is cleared.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>

#include "massspring/integrators/local_global/options.hpp"

namespace massspring::local_global {

/// @brief The Anderson accelerator. Its history persists across steps (allocated by reserve());
/// start() begins a step over five buffers.
template <class Scalar>
class Anderson {
 public:
  /// @brief The largest window.
  static constexpr int kMaxWindow = kMaxAndersonWindow;

  /// @brief The history for `window` (<= kMaxWindow) iterates of `free_rows` rows: allocates, so
  /// call it from precompute (and when the window grows).
  void reserve(Eigen::Index free_rows, int window) {
    df_.setZero(3 * free_rows, window);
    dg_.setZero(3 * free_rows, window);
  }

  /// @brief Begins a step: buffers[0] holds the start; the free rows are the first `free_rows`.
  /// Allocates only when `window` is larger than the last reserve()'s.
  void start(const std::array<Scalar*, 5>& buffers, Eigen::Index free_rows, int window) {
    size_ = 3 * free_rows;
    window_ = window;
    if (window > df_.cols()) reserve(free_rows, window);
    x_ = buffers[0];
    w_ = buffers[1];
    g_ = buffers[2];
    f_ = buffers[3];
    fn_ = buffers[4];
    count_ = 0;
    slot_ = 0;
    have_previous_ = false;
  }

  Scalar* x() { return x_; }
  Scalar* w() { return w_; }
  static bool accepts(double e, double e_prev) { return e < e_prev; }

  /// @brief The plain step from the last accepted iterate (whose energy is <= e_prev).
  void reject() {
    std::copy_n(g_, size_, x_);
    count_ = 0;
    slot_ = 0;
    have_previous_ = false;
  }

  /// @brief x_{k+1} from x_k and w = G(x_k).
  void advance() {
    // Residual, new history column and its inner products, in one pass.
    const int s = slot_;
    Scalar* dfs = df_.col(s).data();
    Scalar* dgs = dg_.col(s).data();
    if (have_previous_) {
      double dfs_f = 0, dfs_dfs = 0;
      for (Eigen::Index i = 0; i < size_; ++i) {
        const Scalar r = w_[i] - x_[i];
        const Scalar d = r - f_[i];
        fn_[i] = r;
        dfs[i] = d;
        dgs[i] = w_[i] - g_[i];
        dfs_f += double(d * r);
        dfs_dfs += double(d * d);
      }
      count_ = std::min(count_ + 1, window_);
      slot_ = (slot_ + 1) % window_;
      const Eigen::Map<const Buffer> dfs_map(dfs, size_), fn_map(fn_, size_);
      for (int j = 0; j < count_; ++j) {
        if (j == s) {
          gram_(s, s) = dfs_dfs;
          rhs_(s) = dfs_f;
        } else {
          gram_(s, j) = gram_(j, s) = double(df_.col(j).dot(dfs_map));
          rhs_(j) = double(df_.col(j).dot(fn_map));
        }
      }
    } else {
      for (Eigen::Index i = 0; i < size_; ++i) fn_[i] = w_[i] - x_[i];
    }
    std::swap(f_, fn_);  // f = residual of x_k
    std::swap(g_, w_);   // g = G(x_k), w free
    have_previous_ = true;
    // x_{k+1} = G(x_k) - dG theta, theta = argmin |f - dF theta|.
    if (count_ > 0 && solve_normal_equations(count_)) {
      for (Eigen::Index i = 0; i < size_; ++i) {
        Scalar v = g_[i];
        for (int j = 0; j < count_; ++j) v -= Scalar(theta_[std::size_t(j)]) * dg_(i, j);
        x_[i] = v;
      }
    } else {
      count_ = 0;
      slot_ = 0;
      std::copy_n(g_, size_, x_);
    }
  }

  /// @brief The plain step from the last accepted iterate, into x.
  Scalar* fallback() {
    std::copy_n(g_, size_, x_);
    return x_;
  }

 private:
  using Buffer = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

  // theta = (dF^T dF + eps I)^-1 dF^T f, eps = 1e-12 of the mean diagonal, by a Cholesky
  // factorization of the count x count matrix (count <= kMaxWindow) held in place, written out:
  // Eigen's LLT does the same without allocating, but instantiating it (the blocked factorization
  // with triangular solves and rank updates, never used at this size) is a large share of the
  // compile time of a translation unit that steps a solver. False when the matrix is not
  // numerically positive definite or theta is not finite.
  bool solve_normal_equations(int count) {
    double trace = 0;
    for (int j = 0; j < count; ++j) trace += gram_(j, j);
    const double eps = 1e-12 * trace / count + std::numeric_limits<double>::min();
    std::array<double, kMaxWindow * kMaxWindow> a{};  // row-major count x count
    for (int i = 0; i < count; ++i)
      for (int j = 0; j < count; ++j)
        a[std::size_t(i * count + j)] = gram_(i, j) + (i == j ? eps : 0.0);
    for (int j = 0; j < count; ++j) {  // a = L L^T, L in the lower triangle
      double d = a[std::size_t(j * count + j)];
      for (int q = 0; q < j; ++q)
        d -= a[std::size_t(j * count + q)] * a[std::size_t(j * count + q)];
      if (!(d > 0)) return false;
      const double l = std::sqrt(d);
      a[std::size_t(j * count + j)] = l;
      for (int i = j + 1; i < count; ++i) {
        double v = a[std::size_t(i * count + j)];
        for (int q = 0; q < j; ++q)
          v -= a[std::size_t(i * count + q)] * a[std::size_t(j * count + q)];
        a[std::size_t(i * count + j)] = v / l;
      }
    }
    for (int i = 0; i < count; ++i) {  // L z = rhs
      double v = rhs_(i);
      for (int q = 0; q < i; ++q) v -= a[std::size_t(i * count + q)] * theta_[std::size_t(q)];
      theta_[std::size_t(i)] = v / a[std::size_t(i * count + i)];
    }
    for (int i = count - 1; i >= 0; --i) {  // L^T theta = z
      double v = theta_[std::size_t(i)];
      for (int q = i + 1; q < count; ++q)
        v -= a[std::size_t(q * count + i)] * theta_[std::size_t(q)];
      theta_[std::size_t(i)] = v / a[std::size_t(i * count + i)];
    }
    for (int i = 0; i < count; ++i)
      if (!std::isfinite(theta_[std::size_t(i)])) return false;
    return true;
  }

  Eigen::Index size_ = 0;
  int window_ = 1, count_ = 0, slot_ = 0;
  bool have_previous_ = false;
  // x: x_k (pinned rows fixed, never swapped); w: right-hand side, then G(x_k); g: G of the last
  // accepted iterate (the fallback); f: its residual G - x; fn: the new residual.
  Scalar *x_ = nullptr, *w_ = nullptr, *g_ = nullptr, *f_ = nullptr, *fn_ = nullptr;
  // The differences of the last `window` residuals and maps, column-major.
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> df_, dg_;
  Eigen::Matrix<double, kMaxWindow, kMaxWindow> gram_ =
      Eigen::Matrix<double, kMaxWindow, kMaxWindow>::Zero();
  Eigen::Matrix<double, kMaxWindow, 1> rhs_ = Eigen::Matrix<double, kMaxWindow, 1>::Zero();
  std::array<double, kMaxWindow> theta_{};
};

}  // namespace massspring::local_global
