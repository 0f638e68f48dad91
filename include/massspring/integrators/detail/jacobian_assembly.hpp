#pragma once
/// @file
/// @brief Assembles A = M - h dF/dv - h^2 dF/dx (3n x 3n) into fixed slots of a Dense or Sparse
/// matrix: the pattern is recorded once, then each assembly adds values without allocating.
/// Pinned points' rows and columns are the identity.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <algorithm>
#include <utility>
#include <vector>

#include "massspring/error.hpp"
#include "massspring/forces/evaluate.hpp"
#include "massspring/forces/force_term.hpp"
#include "massspring/storage/tags.hpp"
#include "massspring/types.hpp"

namespace massspring::detail {

template <class Storage, class Scalar>
struct JacobianMatrix;

template <class Scalar>
struct JacobianMatrix<Dense, Scalar> {
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  Matrix a;
  void build(int size, const std::vector<std::pair<int, int>>&) { a.setZero(size, size); }
  [[nodiscard]] Eigen::Index slot(int r, int c) const { return Eigen::Index(c) * a.rows() + r; }
  Scalar* values() { return a.data(); }
  void zero() { a.setZero(); }
};

template <class Scalar>
struct JacobianMatrix<Sparse, Scalar> {
  using Matrix = Eigen::SparseMatrix<Scalar, Eigen::ColMajor, int>;
  Matrix a;
  void build(int size, const std::vector<std::pair<int, int>>& entries) {
    std::vector<Eigen::Triplet<Scalar, int>> t;
    t.reserve(entries.size() + std::size_t(size));
    for (const auto& [r, c] : entries) t.emplace_back(r, c, Scalar(0));
    for (int r = 0; r < size; ++r) t.emplace_back(r, r, Scalar(0));
    a.resize(size, size);
    a.setFromTriplets(t.begin(), t.end());
    a.makeCompressed();
  }
  [[nodiscard]] Eigen::Index slot(int r, int c) const {
    const int* inner = a.innerIndexPtr();
    const int* first = inner + a.outerIndexPtr()[c];
    const int* last = inner + a.outerIndexPtr()[c + 1];
    return Eigen::Index(std::lower_bound(first, last, r) - inner);
  }
  Scalar* values() { return a.valuePtr(); }
  void zero() { std::fill(a.valuePtr(), a.valuePtr() + a.nonZeros(), Scalar(0)); }
};

/// @brief The implicit-Euler matrix of a system, assembled into fixed slots.
template <class System>
class JacobianAssembly {
 public:
  using Scalar = typename System::Scalar;
  using Storage = typename System::Storage;
  using Matrix = typename JacobianMatrix<Storage, Scalar>::Matrix;

  /// @brief Records the pattern of the system's Jacobians and the slots (allocates).
  void record(const System& system) {
    const int size = 3 * system.num_points();
    std::vector<std::pair<int, int>> ex, ev;
    auto rx = JacobianSink<Scalar>::recorder(ex);
    auto rv = JacobianSink<Scalar>::recorder(ev);
    add_jacobians(system, system.force_context(system.positions(), system.velocities()), rx, rv);
    std::vector<std::pair<int, int>> all(ex);
    all.insert(all.end(), ev.begin(), ev.end());
    for (const auto& [r, c] : all)
      if (r < 0 || c < 0 || r >= size || c >= size)
        throw Error(
            message("force Jacobian entry (", r, ", ", c, ") out of range [0, ", size, ")"));
    m_.build(size, all);
    pinned_.assign(std::size_t(size), 0);
    for (int i : system.pinned())
      for (int a = 0; a < 3; ++a) pinned_[std::size_t(3 * i + a)] = 1;
    auto slots = [&](const std::vector<std::pair<int, int>>& e, std::vector<Eigen::Index>& s) {
      s.resize(e.size());
      for (std::size_t k = 0; k < e.size(); ++k) {
        const auto [r, c] = e[k];
        s[k] = pinned_[std::size_t(r)] || pinned_[std::size_t(c)] ? -1 : m_.slot(r, c);
      }
    };
    slots(ex, slots_x_);
    slots(ev, slots_v_);
    diagonal_.resize(std::size_t(size));
    for (int r = 0; r < size; ++r) diagonal_[std::size_t(r)] = m_.slot(r, r);
    revision_ = system.revision();
    damped_ = system.has_spring_damping();
  }

  /// @brief True when the system changed in a way that changes the pattern or the pinned set.
  [[nodiscard]] bool stale(const System& system) const {
    return system.revision() != revision_ || system.has_spring_damping() != damped_ ||
           int(pinned_.size()) != 3 * system.num_points();
  }

  /// @brief A = M - h dF/dv - h^2 dF/dx at (x, v); identity rows and columns for pinned points.
  void assemble(const System& system, const typename System::PointsType& x,
                const typename System::PointsType& v, Scalar h, bool definite) {
    m_.zero();
    Scalar* values = m_.values();
    const auto& masses = system.masses();
    for (std::size_t r = 0; r < diagonal_.size(); ++r)
      values[diagonal_[r]] += pinned_[r] ? Scalar(1) : masses(Eigen::Index(r / 3));
    auto sx = JacobianSink<Scalar>::accumulator(values, slots_x_, -h * h);
    auto sv = JacobianSink<Scalar>::accumulator(values, slots_v_, -h);
    add_jacobians(system, system.force_context(x, v, definite), sx, sv);
    if (sx.count() != slots_x_.size() || sv.count() != slots_v_.size())
      throw Error(
          "force term Jacobian: fewer entries than when its pattern was recorded (a term must "
          "emit the same entries at every call)");
  }

  /// @brief Adds w to the three diagonal entries of point i (not pinned) of the assembled A.
  void add_to_diagonal(int i, Scalar w) {
    Scalar* values = m_.values();
    for (int a = 0; a < 3; ++a) values[diagonal_[std::size_t(3 * i + a)]] += w;
  }

  [[nodiscard]] const Matrix& matrix() const { return m_.a; }
  /// @brief 1 for the coordinates of pinned points.
  [[nodiscard]] const std::vector<char>& pinned_coordinates() const { return pinned_; }

 private:
  JacobianMatrix<Storage, Scalar> m_;
  std::vector<Eigen::Index> slots_x_, slots_v_, diagonal_;
  std::vector<char> pinned_;
  std::uint64_t revision_ = 0;
  bool damped_ = false;
};

}  // namespace massspring::detail
