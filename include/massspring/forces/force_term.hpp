#pragma once
/// @file
/// @brief What a force term sees (ForceContext), where it writes its Jacobians (JacobianSink), and
/// ForceSet, the type-erased list of terms a MassSpringSystem carries.
///
/// A force term is a small value type. It must have
///
///     void add_force(const ForceContext<Scalar>& c, Points<Scalar>& f) const;   // f += F(x, v)
///
/// and may have any of
///
///     Scalar energy(const ForceContext<Scalar>& c) const;      // potential [J]; F = -dE/dx
///     void add_dfdx(const ForceContext<Scalar>& c, JacobianSink<Scalar>& j) const;  // dF/dx
///     void add_dfdv(const ForceContext<Scalar>& c, JacobianSink<Scalar>& j) const;  // dF/dv
///     static constexpr bool velocity_dependent = true;          // F reads c.v
///     static constexpr bool constant = true;                    // F reads neither c.x nor c.v
///     static constexpr bool symmetric = false;                  // dF/dx or dF/dv not symmetric
///     const char* name() const;                                 // for messages
///     Scalar linear_damping() const;  // F = -beta v exactly: dF/dx = 0, dF/dv = -beta I
///                                     // constant; returns beta [N s/m] (>= 0)
///
/// A term that declares `linear_damping()` is folded exactly into the integrators' matrices
/// where they can take it (FastMassSpring's Q, BackwardEuler's system) instead of being
/// evaluated as a force; its add_force must still give F = -beta v.
/// A term without `add_dfdx`/`add_dfdv` contributes nothing to the matrices of implicit
/// integrators (it is treated explicitly there). `velocity_dependent` defaults to "has add_dfdv".
/// The Jacobian functions must emit the same sequence of (row, column) entries at every call,
/// whatever the state (emit zeros rather than skipping): implicit integrators record the pattern
/// once and then add values into fixed slots, without allocating.
///
/// Rows and columns of the Jacobians are coordinates: point i's x, y, z are 3 i, 3 i + 1, 3 i + 2.

#include <Eigen/Core>
#include <memory>
#include <type_traits>
#include <typeinfo>
#include <utility>
#include <vector>

#include "massspring/error.hpp"
#include "massspring/types.hpp"

namespace massspring {

/// @brief The state and model a force term reads. Everything is borrowed from the system and the
/// integrator; a context lives for one evaluation.
template <class Scalar>
struct ForceContext {
  /// @brief #points by 3 positions [m] at which to evaluate.
  const Points<Scalar>& x;
  /// @brief #points by 3 velocities [m/s] at which to evaluate.
  const Points<Scalar>& v;
  /// @brief #points masses [kg].
  const Vector<Scalar>& masses;
  /// @brief #springs by 2 point indices.
  const Edges& springs;
  /// @brief #springs stiffness [N/m].
  const Vector<Scalar>& stiffness;
  /// @brief #springs rest lengths [m].
  const Vector<Scalar>& rest_lengths;
  /// @brief #springs damping along the spring axis [N s/m].
  const Vector<Scalar>& damping;
  /// @brief When true, a term whose -dF/dx can be indefinite (a compressed spring) emits a
  /// positive semidefinite projection instead, so that M - h^2 dF/dx stays positive definite
  /// (Newton's fallback). The exact Jacobian otherwise.
  bool definite = false;
};

/// @brief Receives Jacobian entries from force terms. Entries are coordinates of the 3n x 3n
/// matrix (point i, axis a is 3 i + a); repeated entries add up.
///
/// Integrators use it in two modes: recording the pattern (once), then accumulating
/// `scale * value` into fixed slots of a matrix's value array (every step, no allocation).
template <class Scalar>
class JacobianSink {
 public:
  /// @brief A sink that records the (row, column) of every entry, for the pattern.
  static JacobianSink recorder(std::vector<std::pair<int, int>>& entries) {
    JacobianSink s;
    s.entries_ = &entries;
    return s;
  }
  /// @brief A sink that adds `scale * value` of entry k to values[slots[k]]; a negative slot
  /// drops the entry (a pinned row or column).
  static JacobianSink accumulator(Scalar* values, const std::vector<Eigen::Index>& slots,
                                  Scalar scale) {
    JacobianSink s;
    s.values_ = values;
    s.slots_ = &slots;
    s.scale_ = scale;
    return s;
  }

  /// @brief Adds `value` at (row, col).
  void add(int row, int col, Scalar value) {
    if (entries_) {
      entries_->emplace_back(row, col);
      return;
    }
    if (next_ >= slots_->size())
      throw Error(
          "force term Jacobian: more entries than when its pattern was recorded (a term must emit "
          "the same entries at every call)");
    const Eigen::Index s = (*slots_)[next_++];
    if (s >= 0) values_[s] += scale_ * value;
  }
  /// @brief Adds the 3x3 block b at points (i, j).
  template <class Block>
  void add_block(int i, int j, const Block& b) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) add(3 * i + r, 3 * j + c, b(r, c));
  }
  /// @brief Adds value * I (3x3) at point i's diagonal block.
  void add_diagonal(int i, Scalar value) {
    for (int a = 0; a < 3; ++a) add(3 * i + a, 3 * i + a, value);
  }
  /// @brief Entries received so far (accumulating mode).
  [[nodiscard]] std::size_t count() const { return entries_ ? entries_->size() : next_; }

 private:
  JacobianSink() = default;
  std::vector<std::pair<int, int>>* entries_ = nullptr;
  Scalar* values_ = nullptr;
  const std::vector<Eigen::Index>* slots_ = nullptr;
  Scalar scale_ = 1;
  std::size_t next_ = 0;
};

namespace detail {

template <class T, class S, class = void>
struct has_energy : std::false_type {};
template <class T, class S>
struct has_energy<
    T, S,
    std::void_t<decltype(std::declval<const T&>().energy(std::declval<const ForceContext<S>&>()))>>
    : std::true_type {};

template <class T, class S, class = void>
struct has_dfdx : std::false_type {};
template <class T, class S>
struct has_dfdx<T, S,
                std::void_t<decltype(std::declval<const T&>().add_dfdx(
                    std::declval<const ForceContext<S>&>(), std::declval<JacobianSink<S>&>()))>>
    : std::true_type {};

template <class T, class S, class = void>
struct has_dfdv : std::false_type {};
template <class T, class S>
struct has_dfdv<T, S,
                std::void_t<decltype(std::declval<const T&>().add_dfdv(
                    std::declval<const ForceContext<S>&>(), std::declval<JacobianSink<S>&>()))>>
    : std::true_type {};

template <class T, class = void>
struct declared_velocity_dependent {
  static constexpr int value = -1;
};
template <class T>
struct declared_velocity_dependent<T, std::void_t<decltype(T::velocity_dependent)>> {
  static constexpr int value = T::velocity_dependent ? 1 : 0;
};

template <class T, class = void>
struct declared_constant : std::false_type {};
template <class T>
struct declared_constant<T, std::void_t<decltype(T::constant)>> : std::bool_constant<T::constant> {
};

template <class T, class = void>
struct declared_symmetric : std::true_type {};
template <class T>
struct declared_symmetric<T, std::void_t<decltype(T::symmetric)>>
    : std::bool_constant<T::symmetric> {};

template <class T, class = void>
struct has_name : std::false_type {};
template <class T>
struct has_name<T, std::void_t<decltype(std::declval<const T&>().name())>> : std::true_type {};

template <class T, class = void>
struct has_linear_damping : std::false_type {};
template <class T>
struct has_linear_damping<T, std::void_t<decltype(std::declval<const T&>().linear_damping())>>
    : std::true_type {};

template <class T, class = void>
struct has_max_index : std::false_type {};
template <class T>
struct has_max_index<T, std::void_t<decltype(std::declval<const T&>().max_index())>>
    : std::true_type {};

template <class T, class S, class = void>
struct has_add_force : std::false_type {};
template <class T, class S>
struct has_add_force<T, S,
                     std::void_t<decltype(std::declval<const T&>().add_force(
                         std::declval<const ForceContext<S>&>(), std::declval<Points<S>&>()))>>
    : std::true_type {};

/// @brief A term's name() when it has one, else "force term".
template <class T>
const char* term_name(const T& term) {
  if constexpr (has_name<T>::value)
    return term.name();
  else
    return "force term";
}

/// @brief The type-erased interface of one term.
template <class Scalar>
class ForceConcept {
 public:
  virtual ~ForceConcept() = default;
  virtual std::unique_ptr<ForceConcept> clone() const = 0;
  virtual void add_force(const ForceContext<Scalar>& c, Points<Scalar>& f) const = 0;
  virtual Scalar energy(const ForceContext<Scalar>& c) const = 0;
  virtual void add_dfdx(const ForceContext<Scalar>& c, JacobianSink<Scalar>& j) const = 0;
  virtual void add_dfdv(const ForceContext<Scalar>& c, JacobianSink<Scalar>& j) const = 0;
  /// beta of a term that declares linear_damping() (see the file), else 0.
  virtual Scalar linear_damping_coefficient() const = 0;
  virtual const void* target(const std::type_info& type) const = 0;
  virtual void* target(const std::type_info& type) = 0;

  bool has_energy = false, has_dfdx = false, has_dfdv = false;
  bool velocity_dependent = false, constant = false, symmetric = true;
  /// The term declares linear_damping(): F = -beta v, dF/dv = -beta I constant.
  bool linear_damping = false;
  const char* name = "force term";
};

template <class Scalar, class T>
class ForceModel final : public ForceConcept<Scalar> {
 public:
  explicit ForceModel(T term) : term_(std::move(term)) {
    this->has_energy = has_energy<T, Scalar>::value;
    this->has_dfdx = has_dfdx<T, Scalar>::value;
    this->has_dfdv = has_dfdv<T, Scalar>::value;
    constexpr int declared = declared_velocity_dependent<T>::value;
    this->velocity_dependent = declared < 0 ? has_dfdv<T, Scalar>::value : declared == 1;
    this->constant = declared_constant<T>::value;
    this->symmetric = declared_symmetric<T>::value;
    this->linear_damping = has_linear_damping<T>::value;
    this->name = term_name(term_);
  }
  std::unique_ptr<ForceConcept<Scalar>> clone() const override {
    return std::make_unique<ForceModel>(term_);
  }
  void add_force(const ForceContext<Scalar>& c, Points<Scalar>& f) const override {
    term_.add_force(c, f);
  }
  Scalar energy(const ForceContext<Scalar>& c) const override {
    if constexpr (has_energy<T, Scalar>::value)
      return term_.energy(c);
    else
      return Scalar(0);
  }
  void add_dfdx(const ForceContext<Scalar>& c, JacobianSink<Scalar>& j) const override {
    if constexpr (has_dfdx<T, Scalar>::value) term_.add_dfdx(c, j);
  }
  void add_dfdv(const ForceContext<Scalar>& c, JacobianSink<Scalar>& j) const override {
    if constexpr (has_dfdv<T, Scalar>::value) term_.add_dfdv(c, j);
  }
  Scalar linear_damping_coefficient() const override {
    if constexpr (has_linear_damping<T>::value)
      return term_.linear_damping();
    else
      return Scalar(0);
  }
  const void* target(const std::type_info& type) const override {
    return type == typeid(T) ? &term_ : nullptr;
  }
  void* target(const std::type_info& type) override { return type == typeid(T) ? &term_ : nullptr; }

 private:
  T term_;
};

}  // namespace detail

/// @brief The force terms of a system, beyond its springs: a list of type-erased terms, copyable.
/// Each call goes through one virtual function per term (not per point), so a term costs only
/// what its own loop costs, and an absent term costs nothing.
template <class Scalar>
class ForceSet {
 public:
  using Term = detail::ForceConcept<Scalar>;

  ForceSet() = default;
  ForceSet(const ForceSet& other) { *this = other; }
  ForceSet(ForceSet&&) noexcept = default;
  ForceSet& operator=(const ForceSet& other) {
    if (this != &other) {
      std::vector<std::unique_ptr<Term>> copy;
      copy.reserve(other.terms_.size());
      for (const auto& t : other.terms_) copy.push_back(t->clone());
      terms_ = std::move(copy);
    }
    return *this;
  }
  ForceSet& operator=(ForceSet&&) noexcept = default;
  ~ForceSet() = default;

  /// @brief Appends a term (see the file's documentation for what a term type provides).
  /// @return its index in this set.
  template <class T>
  int add(T term) {
    static_assert(detail::has_add_force<T, Scalar>::value,
                  "a force term needs `void add_force(const ForceContext<Scalar>&, "
                  "Points<Scalar>&) const`");
    terms_.push_back(std::make_unique<detail::ForceModel<Scalar, T>>(std::move(term)));
    return int(terms_.size()) - 1;
  }
  /// @brief Number of terms.
  [[nodiscard]] int size() const { return int(terms_.size()); }
  [[nodiscard]] bool empty() const { return terms_.empty(); }
  /// @brief Term k's type-erased interface.
  [[nodiscard]] const Term& operator[](int k) const { return *terms_[std::size_t(k)]; }
  /// @brief The first term of type T, or nullptr.
  template <class T>
  [[nodiscard]] const T* find() const {
    for (const auto& t : terms_)
      if (const void* p = t->target(typeid(T))) return static_cast<const T*>(p);
    return nullptr;
  }
  /// @brief Term k as a T, or nullptr when it is another type.
  template <class T>
  [[nodiscard]] T* get(int k) {
    return static_cast<T*>(terms_.at(std::size_t(k))->target(typeid(T)));
  }
  void clear() { terms_.clear(); }

  auto begin() const { return terms_.begin(); }
  auto end() const { return terms_.end(); }

 private:
  std::vector<std::unique_ptr<Term>> terms_;
};

}  // namespace massspring
