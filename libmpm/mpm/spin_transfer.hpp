// The scene's rigid spin carried from each node's mass centre to the node (`mpm.spin_transfer`).
//
// Why: a node's velocity p/m is the velocity of its particles' mass centre, which at a free surface lies
// up to half a cell inside the body. In a body spinning at omega the surface node then moves with
// omega x (mass centre) instead of omega x (node), and the velocity gradient of the surface particles
// carries a strain rate of about omega (centre - node) / h that the body does not have: an aluminium
// DCB spinning at 0.1 rad/ms built 8.8 MPa at its edges within 0.5 ms (the centrifugal stress is
// 0.08 MPa), and a loaded one read J off by up to 30 % (docs/validation.md, cracks under rigid rotation).
// With spin_transfer the velocity each particle reads from a node is carried there with the scene's spin:
//   v_n = p_n / m_n + omega x (x_n - xbar_n),  xbar_n = sum m_p N_np x_p / m_n,
// omega the least-squares rigid fit of all particle velocities, once per step. Momenta and
// accelerations are untouched (momentum is conserved as before; with linear completeness
// sum_n m_n (x_n - xbar_n) = 0, so the nodal velocities carry no net momentum either). Exact for a
// rigid rotation; first order in the spread of the body's own spin otherwise. Nodes whose velocity a
// support prescribes keep it; the crack fields carry theirs with each crack's spin and overwrite these
// at multi-field nodes (crack_fields/crack_motion.hpp). One spin for the scene: right for one body, or
// bodies that turn together.
#pragma once
#include <Eigen/LU>
#include <array>
#include <cstdint>
#include <vector>

#include "libmpm/core/parallel.hpp"
#include "libmpm/mpm/grid.hpp"
#include "libmpm/mpm/model.hpp"

namespace cleave {

template <int Dim>
class SpinTransfer {
 public:
  using V = Vec<Dim>;
  using Spin = std::conditional_t<Dim == 2, double, Vec<3>>;

  SpinTransfer(const Model<Dim>& m) : G_(m.grid) {
    moment_.assign(G_.node_count(), V::Zero());
    held_.assign(G_.node_count(), 0);
    for (std::size_t c = 0; c < m.conditions.node.size(); ++c)
      if (m.conditions.mask[c]) held_[m.conditions.node[c]] = 1;
    ref_ = G_.origin + 0.5 * (G_.upper() - G_.origin);
  }

  // Task 1: the nodes' mass-weighted positions start afresh; add(n, m_p N_np, offset(x_p)) per
  // particle-node pair.
  void clear() { std::fill(moment_.begin(), moment_.end(), V::Zero()); }
  V offset(const V& x) const { return x - ref_; }
  void add(int64_t n, double mw, const V& r) { moment_[n] += mw * r; }

  // The rigid spin of all particles: angular momentum about their mass centre over its inertia.
  void fit(const Particles<Dim>& P) {
    // Moments about a point of the grid (ref_), in one pass, summed in a fixed order:
    // m, m r, m v, m r x v, m r r^T (r = x - ref).
    constexpr int kRot = Dim == 2 ? 1 : 3, kRR = Dim == 2 ? 3 : 6;
    constexpr int K = 1 + 2 * Dim + kRot + kRR;
    const std::array<double, K> s = deterministic_sums<K>(P.size(), [&](std::size_t p, double* a) {
      const double m = P.mass[p];
      const V r = P.x[p] - ref_, v = P.v[p];
      int k = 0;
      a[k++] += m;
      for (int d = 0; d < Dim; ++d) a[k++] += m * r[d];
      for (int d = 0; d < Dim; ++d) a[k++] += m * v[d];
      if constexpr (Dim == 2) {
        a[k++] += m * (r.x() * v.y() - r.y() * v.x());
      } else {
        const Vec<3> l = r.cross(v);
        for (int d = 0; d < 3; ++d) a[k++] += m * l[d];
      }
      for (int i = 0; i < Dim; ++i)
        for (int j = i; j < Dim; ++j) a[k++] += m * r[i] * r[j];
    });
    const double M = s[0];
    if constexpr (Dim == 3) spin_ = Vec<3>::Zero();
    else spin_ = 0.0;
    if (!(M > 0.0)) return;
    V c, vc;
    for (int d = 0; d < Dim; ++d) c[d] = s[1 + d] / M, vc[d] = s[1 + Dim + d] / M;
    Mat<Dim> rr;  // sum m (r - c)(r - c)^T
    for (int i = 0, k = 1 + 2 * Dim + kRot; i < Dim; ++i)
      for (int j = i; j < Dim; ++j, ++k) rr(i, j) = rr(j, i) = s[k] - M * c[i] * c[j];
    if constexpr (Dim == 2) {
      const double L = s[1 + 2 * Dim] - M * (c.x() * vc.y() - c.y() * vc.x());
      const double I = rr.trace();
      if (I > 0.0) spin_ = L / I;
    } else {
      Vec<3> L;
      for (int d = 0; d < 3; ++d) L[d] = s[1 + 2 * Dim + d];
      L -= M * c.cross(vc);
      const Mat<3> I = rr.trace() * Mat<3>::Identity() - rr;
      if (I.determinant() > 0.0) spin_ = I.fullPivLu().solve(L);
    }
  }

  // The nodal velocities v_n (set from p_n / m_n) carried to their nodes with the spin; position(n)
  // is node n's position (the stepper's node_position).
  template <class Kin, class Position>
  void carry(const std::vector<double>& mass, std::vector<Kin>& kin, Position&& position) const {
    const std::size_t nn = mass.size();
#pragma omp parallel for schedule(static) if (nn > 65536 && omp_get_max_threads() > 1)
    for (std::size_t n = 0; n < nn; ++n) {
      if (!(mass[n] > 0.0) || held_[n]) continue;
      const V r = position(static_cast<int64_t>(n)) - ref_ - moment_[n] / mass[n];  // node less mass centre
      if constexpr (Dim == 2) kin[n].v += spin_ * V(-r.y(), r.x());
      else kin[n].v += spin_.cross(r);
    }
  }

  Spin spin() const { return spin_; }

 private:
  const GridGeometry<Dim>& G_;
  V ref_;
  std::vector<V> moment_;      // per node: sum m_p N_np (x_p - ref_)
  std::vector<uint8_t> held_;  // per node: a support prescribes some of its velocity
  Spin spin_ = zero_spin();
  static Spin zero_spin() {
    if constexpr (Dim == 3) return Vec<3>::Zero();
    else return 0.0;
  }
};

}  // namespace cleave
