#pragma once
/// @file
/// @brief Rigid impact zones (FOSSSim, Theme 2, HybridCollisionHandler: growImpactZones,
/// mergeAllZones, performFailsafe; Bridson, Fedkiw and Anderson 2002, section 7.4): groups of
/// particles that keep colliding, each then moved as one rigid body over the step.
///
/// ImpactZones holds the zones as a partition (union-find) of the particles that are in one;
/// grow() adds a collision's particles as a zone and merges zones that share a particle, as
/// FOSSSim's growImpactZones does, and reports whether the zones changed (FOSSSim's loop ends
/// when they do not). rigid_zone_motion() is performFailsafe in 3D: see its documentation.

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <vector>

#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief Disjoint zones of particles, each flagged when a plane is part of it.
class ImpactZones {
 public:
  /// @brief No zone, n particles.
  void reset(int n) {
    parent_.resize(std::size_t(n));
    std::iota(parent_.begin(), parent_.end(), 0);
    in_zone_.assign(std::size_t(n), 0);
    plane_.assign(std::size_t(n), 0);
  }
  /// @brief Adds the zone {particles} (a plane with it when `with_plane`), merging it with every
  /// zone it shares a particle with. @return true when the zones changed.
  template <std::size_t N>
  bool add(const std::array<int, N>& particles, int count, bool with_plane) {
    bool changed = false;
    int root = -1;
    for (int k = 0; k < count; ++k) {
      const int p = particles[std::size_t(k)];
      if (!in_zone_[std::size_t(p)]) {
        in_zone_[std::size_t(p)] = 1;
        changed = true;
      }
      const int r = find(p);
      if (root < 0) {
        root = r;
      } else if (r != root) {
        parent_[std::size_t(r)] = root;
        plane_[std::size_t(root)] = char(plane_[std::size_t(root)] | plane_[std::size_t(r)]);
        changed = true;
      }
    }
    if (with_plane && root >= 0 && !plane_[std::size_t(root)]) {
      plane_[std::size_t(root)] = 1;
      changed = true;
    }
    return changed;
  }
  /// @brief The zone (root) of particle p, or -1 when p is in none.
  [[nodiscard]] int zone_of(int p) { return in_zone_[std::size_t(p)] ? find(p) : -1; }
  /// @brief True when the zone with root r holds a plane.
  [[nodiscard]] bool has_plane(int r) const { return plane_[std::size_t(r)] != 0; }
  /// @brief Lists the zones: `members` gets the particles grouped by zone, `starts` the offset of
  /// each group (one more entry than zones). Buffers keep their capacity.
  void groups(std::vector<int>& members, std::vector<int>& starts) {
    members.clear();
    starts.clear();
    for (int p = 0; p < int(parent_.size()); ++p)
      if (in_zone_[std::size_t(p)]) members.push_back(p);
    // By zone, each zone's particles ascending (std::sort: no buffer, where stable_sort takes one).
    std::sort(members.begin(), members.end(), [&](int a, int b) {
      const int ra = find(a), rb = find(b);
      return ra != rb ? ra < rb : a < b;
    });
    for (std::size_t k = 0; k < members.size(); ++k)
      if (k == 0 || find(members[k]) != find(members[k - 1])) starts.push_back(int(k));
    starts.push_back(int(members.size()));
  }

 private:
  int find(int p) {
    while (parent_[std::size_t(p)] != p) {
      parent_[std::size_t(p)] = parent_[std::size_t(parent_[std::size_t(p)])];
      p = parent_[std::size_t(p)];
    }
    return p;
  }
  std::vector<int> parent_;
  std::vector<char> in_zone_, plane_;
};

/// @brief Moves a zone rigidly over the step (FOSSSim's performFailsafe, in 3D).
///
/// With masses m_k, start positions qs, displacements dx_k = qe_k - qs_k: centre of mass c,
/// mean displacement p = sum m dx / M, r_k = qs_k - c, angular momentum
/// \f$ L = \sum m_k r_k \times (dx_k - p) \f$, inertia \f$ I = \sum m_k (|r_k|^2 1 - r_k r_k^T)
/// \f$, rotation vector \f$ \omega = I^+ L \f$ (pseudo-inverse: collinear zones; 0 for a single
/// particle, where FOSSSim divides 0 by 0); then qe_k = c + p + R(omega) r_k and
/// v_k = (qe_k - qs_k) / dt. In the plane z = 0 this is FOSSSim's cm + p + cos(w) r +
/// sin(w) r_perp with w = L_z / I_zz. A zone with a fixed particle or a plane stays where it
/// started, at rest.
/// @param[in] members  the zone's particles
/// @param[in] pinned_or_plane true when the zone holds a fixed particle or a plane
template <class Scalar>
void rigid_zone_motion(const int* members, int count, bool pinned_or_plane,
                       const Vector<Scalar>& masses, const Points<Scalar>& qs, Scalar dt,
                       Points<Scalar>& qe, Points<Scalar>& ve) {
  using V3 = Vector3<Scalar>;
  using M3 = Eigen::Matrix<Scalar, 3, 3>;
  if (pinned_or_plane) {
    for (int k = 0; k < count; ++k) {
      qe.row(members[k]) = qs.row(members[k]);
      ve.row(members[k]).setZero();
    }
    return;
  }
  Scalar total = 0;
  V3 c = V3::Zero(), p = V3::Zero();
  for (int k = 0; k < count; ++k) {
    const int i = members[k];
    c += masses(i) * qs.row(i).transpose();
    p += masses(i) * (qe.row(i) - qs.row(i)).transpose();
    total += masses(i);
  }
  c /= total;
  p /= total;
  V3 L = V3::Zero();
  M3 I = M3::Zero();
  for (int k = 0; k < count; ++k) {
    const int i = members[k];
    const V3 r = qs.row(i).transpose() - c;
    const V3 u = (qe.row(i) - qs.row(i)).transpose() - p;
    L += masses(i) * r.cross(u);
    I += masses(i) * (r.squaredNorm() * M3::Identity() - r * r.transpose());
  }
  V3 omega = V3::Zero();
  const Eigen::SelfAdjointEigenSolver<M3> eig(I);
  const V3 lambda = eig.eigenvalues();
  const Scalar top = lambda.cwiseAbs().maxCoeff();
  for (int a = 0; a < 3; ++a)
    if (lambda(a) > top * Scalar(1e-12) && lambda(a) > 0) {
      const V3 e = eig.eigenvectors().col(a);
      omega += (e.dot(L) / lambda(a)) * e;
    }
  const Scalar theta = omega.norm();
  const V3 axis = theta > 0 ? V3(omega / theta) : V3::UnitZ();
  const Scalar cs = std::cos(theta), sn = std::sin(theta);
  for (int k = 0; k < count; ++k) {
    const int i = members[k];
    const V3 r = qs.row(i).transpose() - c;
    const V3 rotated = cs * r + sn * axis.cross(r) + (1 - cs) * axis.dot(r) * axis;
    const V3 x = c + p + rotated;
    qe.row(i) = x.transpose();
    ve.row(i) = ((x - qs.row(i).transpose()) / dt).transpose();
  }
}

}  // namespace massspring::contact
