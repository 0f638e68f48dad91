#pragma once
/// @file
/// @brief SurfaceContactSlot: how a system holds its surface contact pass (contact/response/
/// surface_contact.hpp) without including it. The pass is created, with a table of pointers to
/// its code, by the first call of get(), which MassSpringSystem::set_surface() and
/// surface_contact() make and which needs that header; resolve(), the integrators' call, goes
/// through the table and does nothing while there is no pass. A program that never sets a surface
/// neither includes nor compiles the pipeline (candidates, spatial hash, CCD, impact zones).
/// Also what a pass is given (SurfaceContactInput) and what it did (SurfaceContactReport), which
/// the integrators see without that header.

#include <optional>
#include <utility>
#include <vector>

#include "massspring/contact/self_collision.hpp"
#include "massspring/detail/is_complete.hpp"
#include "massspring/types.hpp"

namespace massspring::contact {

template <class Scalar>
class ColliderSet;
// Incomplete until the header named here is included: set_surface() and surface_contact() need it.
template <class Scalar>
class SurfaceContact;  // #include <massspring/contact/response/surface_contact.hpp> for a surface

/// @brief What surface contact is given for one step (see SurfaceContact::resolve()).
template <class Scalar>
struct SurfaceContactInput {
  const Points<Scalar>& x_start;
  Points<Scalar>& x_end;
  Points<Scalar>& v_end;
  Scalar dt;
  const Vector<Scalar>& masses;
  const std::vector<int>& pinned;
  const Triangles& triangles;
  const Edges& edges;
  const std::optional<SelfCollision<Scalar>>& self_collision;
  const ColliderSet<Scalar>& colliders;
};

/// @brief What one SurfaceContact pass did.
struct SurfaceContactReport {
  /// @brief Repulsion and collision impulses applied.
  int impulses = 0;
  /// @brief Rounds of continuous detection (1 when the proposed motion had no collision).
  int rounds = 0;
  /// @brief Points moved rigidly in impact zones (in the last round that moved zones).
  int zone_points = 0;
  /// @brief Points the inelastic projection of impact zones moved, summed over its rounds.
  int projected_points = 0;
  /// @brief False when the fail-safe ran out of rounds with collisions left, or when a rigid
  /// zone would have had to move a pinned point off its prescribed motion (the state is then the
  /// last one tried; see SurfaceContact::max_rounds()).
  bool resolved = true;
};

/// @brief Owns at most one SurfaceContact<Scalar> (see the file comment); copies deep-copy it.
template <class Scalar>
class SurfaceContactSlot {
 public:
  SurfaceContactSlot() = default;
  SurfaceContactSlot(const SurfaceContactSlot& o)
      : ops_(o.ops_), pass_(o.pass_ ? o.ops_->clone(*o.pass_) : nullptr) {}
  SurfaceContactSlot(SurfaceContactSlot&& o) noexcept
      : ops_(o.ops_), pass_(std::exchange(o.pass_, nullptr)) {}
  SurfaceContactSlot& operator=(const SurfaceContactSlot& o) {
    if (this != &o) *this = SurfaceContactSlot(o);
    return *this;
  }
  SurfaceContactSlot& operator=(SurfaceContactSlot&& o) noexcept {
    std::swap(ops_, o.ops_);
    std::swap(pass_, o.pass_);
    return *this;
  }
  ~SurfaceContactSlot() {
    if (pass_) ops_->destroy(pass_);
  }

  /// @brief The pass, created (not armed) on first use. Needs surface_contact.hpp.
  SurfaceContact<Scalar>& get() {
    static constexpr Ops kOps{&SurfaceContactSlot::destroy, &SurfaceContactSlot::clone,
                              &SurfaceContactSlot::resolve_pass};
    static_assert(massspring::detail::is_complete_v<SurfaceContact<Scalar>>,
                  "set_surface() and surface_contact() need "
                  "#include <massspring/contact/response/surface_contact.hpp>");
    if (!pass_) {
      pass_ = new SurfaceContact<Scalar>();
      ops_ = &kOps;
    }
    return *pass_;
  }

  /// @brief SurfaceContact::resolve() of the pass on `in`; nothing (an empty report) when there
  /// is no pass.
  SurfaceContactReport resolve(const SurfaceContactInput<Scalar>& in) {
    if (!pass_) return {};
    return ops_->resolve(*pass_, in);
  }

 private:
  struct Ops {
    void (*destroy)(SurfaceContact<Scalar>*);
    SurfaceContact<Scalar>* (*clone)(const SurfaceContact<Scalar>&);
    SurfaceContactReport (*resolve)(SurfaceContact<Scalar>&, const SurfaceContactInput<Scalar>&);
  };
  static void destroy(SurfaceContact<Scalar>* p) { delete p; }
  static SurfaceContact<Scalar>* clone(const SurfaceContact<Scalar>& p) {
    return new SurfaceContact<Scalar>(p);
  }
  static SurfaceContactReport resolve_pass(SurfaceContact<Scalar>& p,
                                           const SurfaceContactInput<Scalar>& in) {
    return p.resolve(in.x_start, in.x_end, in.v_end, in.dt, in.masses, in.pinned, in.triangles,
                     in.edges, in.self_collision, in.colliders);
  }

  const Ops* ops_ = nullptr;
  SurfaceContact<Scalar>* pass_ = nullptr;
};

}  // namespace massspring::contact
