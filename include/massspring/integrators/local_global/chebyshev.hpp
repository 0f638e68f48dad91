#pragma once
/// @file
/// @brief local_global::Chebyshev: Chebyshev semi-iterative acceleration of the local-global
/// iteration (Wang 2015, "A Chebyshev Semi-Iterative Approach for Accelerating Projective and
/// Position-Based Dynamics"), as an accelerator of guarded_loop(): after `delay` plain
/// iterations, x_{k+1} = omega_{k+1} (gamma (G(x_k) - x_k) + x_k - x_{k-1}) + x_{k-1} with
/// omega = 2 / (2 - rho^2) at the first accelerated iteration and omega_{k+1} = 4 / (4 - rho^2
/// omega_k) after it; restarted (momentum dropped, back to the plain iterate) whenever the energy
/// rises.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace massspring::local_global {

/// @brief rho, the spectral radius of the plain iteration G, from `iterations` trial iterations
/// from x (buffers x and w, each `size` values of the free rows, both overwritten): the geometric
/// mean ratio of the update norms |G(x_k) - x_k| over the second half. 0 when that is not in
/// (0, 1). `it` gives `local_only(x, w)` (the local step) and `global(w)` (the global step).
template <class Iteration, class Scalar>
double estimate_spectral_radius(Iteration& it, Scalar* x, Scalar* w, Eigen::Index size,
                                int iterations) {
  using Buffer = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  const int half = iterations / 2;
  double norm_half = 0, norm_last = 0;
  for (int k = 0; k < iterations; ++k) {
    it.local_only(x, w);
    it.global(w);
    if (k == half - 1 || k == iterations - 1) {
      const double d = (Eigen::Map<const Buffer>(w, size) - Eigen::Map<const Buffer>(x, size))
                           .template cast<double>()
                           .norm();
      (k == half - 1 ? norm_half : norm_last) = d;
    }
    std::swap(x, w);
  }
  const double rho = std::pow(norm_last / norm_half, 1.0 / double(iterations - half));
  return std::isfinite(rho) && rho > 0 && rho < 1 ? rho : 0.0;
}

/// @brief The Chebyshev accelerator over four buffers of one step (see guarded_loop()).
template <class Scalar>
class Chebyshev {
 public:
  /// @param buffers four buffers of `rows` iterate rows each, the first holding the start
  ///   (pinned rows at their targets); the free rows are the first `free_rows`.
  /// @param rho the spectral radius of the plain iteration, in [0, 1) (0: no acceleration).
  /// @param gamma the under-relaxation, in (0, 1]. @param delay plain iterations first, >= 1.
  Chebyshev(const std::array<Scalar*, 4>& buffers, Eigen::Index free_rows, Eigen::Index rows,
            double rho, double gamma, int delay)
      : buffers_(buffers),
        x_(buffers[0]),
        p_(buffers[1]),
        h_(buffers[2]),
        w_(buffers[3]),
        size_(3 * free_rows),
        rho_(rho),
        gamma_(gamma),
        delay_(delay) {
    std::copy_n(x_, 3 * rows, p_);
    std::copy_n(x_, 3 * rows, h_);
  }

  Scalar* x() { return x_; }
  Scalar* w() { return w_; }
  static bool accepts(double e, double e_prev) { return e <= e_prev; }

  /// @brief Back to the plain iterate G(x_{k-1}), momentum dropped.
  void reject() {
    std::swap(x_, h_);
    std::copy_n(x_, size_, p_);
    since_ = 0;
  }

  /// @brief x_{k+1} from x_k, x_{k-1} and w = G(x_k).
  void advance() {
    ++since_;
    if (since_ < delay_ || !(rho_ > 0)) {
      omega_ = 1;
    } else if (since_ == delay_) {
      omega_ = 2 / (2 - rho_ * rho_);
    } else {
      omega_ = 4 / (4 - rho_ * rho_ * omega_);
    }
    if (omega_ == 1 && gamma_ == 1) {
      // x_{k+1} = G(x_k): rotate, no arithmetic.
      Scalar* old_p = p_;  // never x_k or G(x_k): the one buffer free after the rotation
      p_ = x_;
      x_ = w_;
      h_ = w_;
      w_ = old_p;
    } else {
      const auto om = Scalar(omega_), ga = Scalar(gamma_);
      for (Eigen::Index i = 0; i < size_; ++i)
        p_[i] = om * (ga * (w_[i] - x_[i]) + x_[i] - p_[i]) + p_[i];
      // Now p = x_{k+1}, x = x_k, w = G(x_k).
      Scalar* old_h = h_;
      h_ = w_;
      std::swap(x_, p_);
      w_ = old_h == x_ || old_h == p_ || old_h == h_ ? free_buffer() : old_h;
    }
  }

  /// @brief The plain iterate G(x_{k-1}), or null when it is the current iterate.
  Scalar* fallback() { return x_ != h_ ? h_ : nullptr; }

 private:
  // The one buffer of the four not among x, p, h (which may coincide).
  Scalar* free_buffer() const {
    for (Scalar* b : buffers_)
      if (b != x_ && b != p_ && b != h_) return b;
    return nullptr;
  }

  std::array<Scalar*, 4> buffers_;
  // x: x_k; p: x_{k-1}; h: G(x_{k-1}) (the plain iterate, E(h) <= E(x_{k-1})); w: free.
  Scalar *x_, *p_, *h_, *w_;
  Eigen::Index size_;
  double rho_, gamma_, omega_ = 1;
  int delay_;
  int since_ = 0;  // iterations since the (re)start
};

}  // namespace massspring::local_global
