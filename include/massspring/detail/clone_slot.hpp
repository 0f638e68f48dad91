#pragma once
/// @file
/// @brief CloneSlot: a value-semantic holder of at most one object of a type derived from Base,
/// the one way a system holds a part of its contact whose code a program compiles only when it
/// uses it (the collision handler, contact/collision_handler.hpp; the surface pass,
/// contact/response/surface_contact_slot.hpp). The holder needs Base only; the derived type needs
/// to be complete only where emplace() is called, and its code (Base's virtual functions) is
/// compiled only there.

#include <memory>
#include <utility>

namespace massspring::detail {

/// @brief At most one object derived from Base (which declares `virtual std::unique_ptr<Base>
/// clone() const` and a virtual destructor). Copies clone the object; moves move it.
template <class Base>
class CloneSlot {
 public:
  CloneSlot() = default;
  CloneSlot(const CloneSlot& o) : p_(o.p_ ? o.p_->clone() : nullptr) {}
  CloneSlot(CloneSlot&&) noexcept = default;
  CloneSlot& operator=(const CloneSlot& o) {
    if (this != &o) p_ = o.p_ ? o.p_->clone() : nullptr;
    return *this;
  }
  CloneSlot& operator=(CloneSlot&&) noexcept = default;
  ~CloneSlot() = default;

  /// @brief Replaces the object with `value`; returns the one held.
  template <class Derived>
  Derived& emplace(Derived value) {
    auto p = std::make_unique<Derived>(std::move(value));
    Derived& held = *p;
    p_ = std::move(p);
    return held;
  }
  void reset() { p_.reset(); }
  /// @brief The object, or nullptr.
  [[nodiscard]] Base* get() const { return p_.get(); }

 private:
  std::unique_ptr<Base> p_;
};

}  // namespace massspring::detail
