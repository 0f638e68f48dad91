#pragma once
/// @file
/// @brief SolidPath: a point's straight path through one of Collider's convex solids over a step
/// (the start at the collider's current pose, the end at its end pose): whether a path that ends
/// outside passed through it, and the push of its end onto the tangent plane where it entered.
/// Collider::contact() uses both; Collider includes this header at its end.

#include <Eigen/Core>
#include <algorithm>
#include <tuple>

#include "massspring/contact/colliders/collider.hpp"
#include "massspring/contact/distance/path_search.hpp"
#include "massspring/contact/distance/path_sphere.hpp"

namespace massspring::contact {

template <class Scalar>
struct SolidPath {
  using C = Collider<Scalar>;
  using V3 = Vector3<Scalar>;

  // For a point that ends outside a convex solid (phi_end = phi(x_end) >= thickness): whether
  // its local path a -> b starts outside and passes inside the contact zone; if so, c pushes
  // x_end onto the tangent plane at the entry. phi is 1-Lipschitz and convex along the path, so
  // its minimum is at least (phi(a) + phi_end - |b - a|) / 2 (most paths stop there), and is
  // found by golden-section search (60 steps), or for a sphere at the path's nearest point to
  // the centre, s = clamp(-a.d / |d|^2, 0, 1) with d = b - a.
  static bool crossed(const C& self, const V3& x_start, const V3& x_end, Scalar phi_end,
                      Scalar slop, ColliderContact<Scalar>& c) {
    const V3 a = self.rotation_.transpose() * (x_start - self.translation_);
    const V3 b = self.end_rotation_.transpose() * (x_end - self.end_translation_);
    V3 n;
    const Scalar phi_a = self.local_phi(a, n);
    if ((phi_a + phi_end - (b - a).norm()) / 2 >= self.thickness_) return false;
    const auto phi_at = [&](Scalar s) { return self.local_phi(a + s * (b - a), n); };
    Scalar s_min = 0, f_min = 0;  // the path's deepest point and its phi
    if (self.shape_ == ColliderShape::Sphere) {
      s_min = path_nearest_to_origin<Scalar>(a, b - a);
      f_min = phi_at(s_min);
    } else {
      std::tie(s_min, f_min) = golden_section_minimum<Scalar>(phi_at);
    }
    if (!(f_min < self.thickness_)) return false;
    c.depth = 0;
    entry_push(self, x_start, x_end, slop, s_min, c);
    return c.depth > 0;
  }

  // For a deep point whose path started outside: the entry point e of the local path a -> b
  // into the contact zone (the parameters [0, inside]; the path is in the zone at `inside`), and
  // the push of x_end onto the tangent plane there (outside the solid, which is convex). A
  // sphere's entry is in closed form (distance/path_sphere.hpp, rho = r + thickness - tol); the
  // other shapes' by bisection on phi - thickness (48 halvings).
  static void entry_push(const C& self, const V3& x_start, const V3& x_end, Scalar slop,
                         Scalar inside, ColliderContact<Scalar>& c) {
    const V3 a = self.rotation_.transpose() * (x_start - self.translation_);
    const V3 b = self.end_rotation_.transpose() * (x_end - self.end_translation_);
    V3 n;
    // A start within a millionth of the solid's inner size below the surface counts as outside
    // (a point resting on it sits there up to rounding, and must not fall through).
    const Scalar start_tol = std::max(slop, Scalar(1e-6) * self.inner_);
    const Scalar phi_a = self.local_phi(a, n);
    if (!(phi_a >= self.thickness_ - start_tol)) return;  // started inside: nearest surface
    Scalar lo = 0, hi = inside;
    if (self.shape_ == ColliderShape::Sphere &&
        path_enters_ball(a, V3(b - a), phi_a + self.radius_,
                         self.radius_ + self.thickness_ - start_tol, lo))
      hi = lo = std::min(lo, inside);
    lo = bisect_last<Scalar>(
        [&](Scalar s) { return self.local_phi(a + s * (b - a), n) >= self.thickness_ - start_tol; },
        lo, hi);
    const V3 e = a + lo * (b - a);
    const Scalar phi_e = self.local_phi(e, n);
    // Onto the plane tangent at e, moved out to phi = thickness (e may start a rounding inside).
    c.depth = (e - b).dot(n) + (self.thickness_ - phi_e);
    c.normal = self.end_rotation_ * n;
  }
};

}  // namespace massspring::contact
