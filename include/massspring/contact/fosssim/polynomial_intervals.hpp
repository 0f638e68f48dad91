#pragma once
/// @file
/// @brief first_time_all_positive(): the first time t >= 0 at which every one of a few
/// polynomials is >= 0 and > 0 just after t (FOSSSim's PolynomialIntervalSolver::
/// findFirstIntersectionTime, FOSSSim Theme 2, ContinuousTimeUtilities), searched on [0, t_max].
///
/// Method: the real roots of each polynomial in (0, t_max) split [0, t_max] into pieces on which
/// no polynomial changes sign; the answer is the left end of the first piece where all of them
/// are > 0 at its midpoint. Roots are isolated recursively: the roots of p' split the interval
/// into pieces where p is monotone, and a monotone piece with a sign change holds one root, found
/// by bisection to the last bit. Degrees up to 5 (the particle-edge velocity polynomial).

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace massspring::contact {

/// @brief A polynomial of degree <= 5: c[0] + c[1] t + ... + c[5] t^5.
template <class Scalar>
struct Polynomial {
  std::array<Scalar, 6> c{};
  int degree = 0;  ///< highest index used (coefficients above are 0)

  [[nodiscard]] Scalar operator()(Scalar t) const {
    Scalar s = 0;
    for (int k = degree; k >= 0; --k) s = s * t + c[std::size_t(k)];
    return s;
  }
  [[nodiscard]] Polynomial derivative() const {
    Polynomial d;
    d.degree = std::max(0, degree - 1);
    for (int k = 1; k <= degree; ++k) d.c[std::size_t(k - 1)] = Scalar(k) * c[std::size_t(k)];
    return d;
  }
  /// @brief The product (degrees adding up to at most 5).
  friend Polynomial operator*(const Polynomial& a, const Polynomial& b) {
    Polynomial p;
    p.degree = std::min(5, a.degree + b.degree);
    for (int i = 0; i <= a.degree; ++i)
      for (int j = 0; j <= b.degree && i + j <= 5; ++j)
        p.c[std::size_t(i + j)] += a.c[std::size_t(i)] * b.c[std::size_t(j)];
    return p;
  }
  friend Polynomial operator+(const Polynomial& a, const Polynomial& b) {
    Polynomial p;
    p.degree = std::max(a.degree, b.degree);
    for (int k = 0; k <= p.degree; ++k)
      p.c[std::size_t(k)] = a.c[std::size_t(k)] + b.c[std::size_t(k)];
    return p;
  }
  friend Polynomial operator-(const Polynomial& a, const Polynomial& b) {
    Polynomial m = b;
    for (auto& x : m.c) x = -x;
    return a + m;
  }
  friend Polynomial operator*(Scalar s, const Polynomial& a) {
    Polynomial p = a;
    for (auto& x : p.c) x *= s;
    return p;
  }
  /// @brief c0 + c1 t.
  static Polynomial linear(Scalar c0, Scalar c1) {
    Polynomial p;
    p.c[0] = c0;
    p.c[1] = c1;
    p.degree = 1;
    return p;
  }
  /// @brief c0 + c1 t + c2 t^2.
  static Polynomial quadratic(Scalar c0, Scalar c1, Scalar c2) {
    Polynomial p = linear(c0, c1);
    p.c[2] = c2;
    p.degree = 2;
    return p;
  }
};

namespace detail {

/// @brief Appends the points in (lo, hi) where p changes sign, and the critical points, to `out`
/// (at most 2 * 5 + ... values; `count` is updated). Fixed storage, no allocation.
template <class Scalar, std::size_t N>
void sign_breaks(const Polynomial<Scalar>& p, Scalar lo, Scalar hi, std::array<Scalar, N>& out,
                 int& count) {
  int degree = p.degree;
  while (degree > 0 && p.c[std::size_t(degree)] == 0) --degree;
  if (degree == 0) return;
  Polynomial<Scalar> q = p;
  q.degree = degree;
  // pieces on which q is monotone
  std::array<Scalar, 16> ends{};
  int m = 0;
  ends[std::size_t(m++)] = lo;
  if (degree >= 2) {
    std::array<Scalar, N> crit{};
    int nc = 0;
    sign_breaks(q.derivative(), lo, hi, crit, nc);
    std::sort(crit.begin(), crit.begin() + nc);
    for (int k = 0; k < nc && m < 15; ++k) ends[std::size_t(m++)] = crit[std::size_t(k)];
  }
  ends[std::size_t(m++)] = hi;
  for (int k = 1; k + 1 < m && count < int(N); ++k)
    out[std::size_t(count++)] = ends[std::size_t(k)];
  for (int k = 0; k + 1 < m; ++k) {
    Scalar a = ends[std::size_t(k)], b = ends[std::size_t(k + 1)];
    Scalar fa = q(a), fb = q(b);
    if (!((fa < 0 && fb > 0) || (fa > 0 && fb < 0))) continue;
    for (int it = 0; it < 200; ++it) {  // bisection to the last bit
      const Scalar mid = a + (b - a) / 2;
      if (!(mid > a && mid < b)) break;
      const Scalar fm = q(mid);
      if (fm == 0) {
        a = b = mid;
        break;
      }
      if ((fm < 0) == (fa < 0)) {
        a = mid;
        fa = fm;
      } else {
        b = mid;
      }
    }
    if (count < int(N)) out[std::size_t(count++)] = a;
  }
}

}  // namespace detail

/// @brief The first t in [0, t_max] at which every polynomial is >= 0 and > 0 just after, or
/// +infinity when there is none. A polynomial that is identically 0 is never > 0.
template <class Scalar>
Scalar first_time_all_positive(const Polynomial<Scalar>* polys, int count, Scalar t_max = 2) {
  constexpr Scalar none = std::numeric_limits<Scalar>::infinity();
  if (count <= 0) return none;
  std::array<Scalar, 128> breaks{};
  int nb = 0;
  breaks[std::size_t(nb++)] = 0;
  for (int k = 0; k < count; ++k) {
    std::array<Scalar, 32> b{};
    int c = 0;
    detail::sign_breaks(polys[k], Scalar(0), t_max, b, c);
    for (int i = 0; i < c && nb < 127; ++i) breaks[std::size_t(nb++)] = b[std::size_t(i)];
  }
  breaks[std::size_t(nb++)] = t_max;
  std::sort(breaks.begin(), breaks.begin() + nb);
  for (int k = 0; k + 1 < nb; ++k) {
    const Scalar a = breaks[std::size_t(k)], b = breaks[std::size_t(k + 1)];
    if (!(b > a)) continue;
    const Scalar mid = a + (b - a) / 2;
    bool all = true;
    for (int j = 0; j < count && all; ++j) all = polys[j](mid) > 0;
    if (all) return a;
  }
  return none;
}

}  // namespace massspring::contact
