// Layer of the crack fields (libmpm/mpm/crack_fields.hpp; layering: grid_cells.hpp): the values of
// the extra velocity fields at multi-field nodes, and what the step's tasks do to them beside the
// stepper's work on the ordinary fields: extrapolation of the near particles (Task 1), body force
// and damping (Task 3), prescribed velocities (Tasks 2, 3, 6c) and the nodal velocities
// (Subtask 1). x < 0 always means the node's ordinary field, in the stepper's arrays.
// 2D only: the nodal volume of contact detection (eq. 25) is the area of the particles.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "libmpm/crack/crack2d.hpp"
#include "libmpm/mpm/crack_fields/field_slots.hpp"
#include "libmpm/mpm/model.hpp"
#include "libmpm/mpm/stencil.hpp"

namespace cleave {

// Nodal velocity and acceleration side by side: Task 5 gathers both from one cache line.
template <int Dim>
struct NodeKinematics {
  Vec<Dim> v, a;
};

namespace crack_fields {

template <int Dim, class SF>
class ExtraFields : public FieldSlots<Dim, SF> {
  static_assert(Dim == 2, "crack fields: 2D only (particle areas for the nodal volume, eq. 25)");
  using Base = FieldSlots<Dim, SF>;
  using St = Stencil<Dim, SF>;
  using V = Vec<Dim>;

 public:
  // Task 1 for near particle k: masses and momenta per field (eq. 26), total nodal volume (eq. 27)
  // and, for displacement contact, mass-weighted displacements per field (seed 000 eq. 68).
  // Each detection method's sums only when a crack uses it (volumes: seed 002; displacements: seed 000).
  void extrapolate(std::size_t k, const St& s) {
    if (need_volume_) {
      if (need_disp_) return extrapolate<true, true>(k, s);
      return extrapolate<true, false>(k, s);
    }
    if (need_disp_) return extrapolate<false, true>(k, s);
    extrapolate<false, false>(k, s);
  }
  template <bool volume, bool disp>
  void extrapolate(std::size_t k, const St& s) {
    const std::size_t p = static_cast<std::size_t>(near_[k]);
    const double mp = P_.mass[p];
    const V mv = mp * P_.v[p];
    V mu = V::Zero();
    if constexpr (disp) mu = mp * P_.u[p];
    double area = 0.0;
    if constexpr (volume) {
      const auto& e = P_.strain[p];
      area = area0_[p] * (1.0 + e[0]) * (1.0 + e[1]);  // eq. 25
    }
    for_each_pair_weight(k, s, [&](int64_t n, int32_t x, double w) {
      if (x < 0) {
        grid_.mass[n] += mp * w;
        grid_.momentum[n] += mv * w;
        if constexpr (disp) {
          const int32_t b = node_block_[n];
          if (b >= 0) disp0_[b] += mu * w;
        }
      } else {
        mass_[x] += mp * w;
        momentum_[x] += mv * w;
        if constexpr (disp) disp_[x] += mu * w;
      }
      if constexpr (volume) {
        const int32_t b = node_block_[n];
        if (b >= 0) volume_[b] += area * w;
      }
    });
  }

  double& mass(int64_t n, int32_t x) { return x < 0 ? grid_.mass[n] : mass_[x]; }
  V& momentum(int64_t n, int32_t x) { return x < 0 ? grid_.momentum[n] : momentum_[x]; }
  V& force(int64_t n, int32_t x) { return x < 0 ? grid_.force[n] : force_[x]; }
  const NodeKinematics<Dim>& kin(int64_t n, int32_t x) const { return x < 0 ? kin_[n] : xkin_[x]; }

  // Task 3, grid part, for the extra fields: body force and damping (eq. 28).
  void body_force_and_damping(const V& gravity, double kappa) {
    for (std::size_t x = 0; x < mass_.size(); ++x)
      if (mass_[x] > 0.0) force_[x] += mass_[x] * gravity - kappa * momentum_[x];
  }

  // Prescribed velocity components hold for every field at the node (Task 2 / Task 6c).
  void apply_momentum_conditions(const GridConditions<Dim>& C) {
    for (std::size_t c = 0; c < C.node.size(); ++c) {
      const int32_t b = node_block_[C.node[c]];
      if (b < 0) continue;
      for (int s = 0; s < block_nslots_[b]; ++s)
        for (int d = 0; d < Dim; ++d)
          if (C.mask[c] & (1u << d)) momentum_[b * kExtra + s][d] = mass_[b * kExtra + s] * C.velocity[c][d];
    }
  }
  // Zero force on prescribed components for every field (Task 3); returns the reaction power of
  // the extra fields, sum f . v_prescribed, for the external-work account.
  double zero_prescribed_forces(const GridConditions<Dim>& C) {
    double power = 0.0;
    for (std::size_t c = 0; c < C.node.size(); ++c) {
      const int32_t b = node_block_[C.node[c]];
      if (b < 0) continue;
      for (int s = 0; s < block_nslots_[b]; ++s)
        for (int d = 0; d < Dim; ++d)
          if (C.mask[c] & (1u << d)) {
            power += force_[b * kExtra + s][d] * C.velocity[c][d];
            force_[b * kExtra + s][d] = 0.0;
          }
    }
    return power;
  }

  // Task 6c starts the extra fields' momenta afresh (the ordinary field's are zeroed by the stepper).
  void clear_momenta() { std::fill(momentum_.begin(), momentum_.end(), V::Zero()); }

  // Nodal velocities of the extra fields from the latest momenta (Subtask 1, eq. 34).
  void nodal_velocities() {
    for (std::size_t x = 0; x < mass_.size(); ++x)
      if (mass_[x] > 0.0) xkin_[x].v = momentum_[x] / mass_[x];
  }

 protected:
  using Base::allocate_slots;
  using Base::block_node_;
  using Base::block_nslots_;
  using Base::for_each_pair_weight;
  using Base::kExtra;
  using Base::near_;
  using Base::node_block_;
  using Base::P_;
  using Law = crack::Crack2D::ContactLaw;

  ExtraFields(Model<Dim>& m, GridFields<Dim>& grid, std::vector<NodeKinematics<Dim>>& kin)
      : Base(m), grid_(grid), kin_(kin) {
    area0_.resize(P_.size());
    for (const auto& b : m.bodies)
      for (std::size_t p = b.first; p < b.first + b.count; ++p) area0_[p] = P_.volume0[p] / b.thickness;
    for (const auto& c : m.cracks) {
      if (c.contact_law == Law::None) continue;
      (c.detection == crack::Crack2D::Detection::Volume ? need_volume_ : need_disp_) = true;
    }
  }

  // The slots of this step (allocate_slots), and their values zeroed.
  void allocate_fields() {
    allocate_slots();
    const std::size_t ns = block_node_.size() * kExtra;
    mass_.assign(ns, 0.0);
    momentum_.assign(ns, V::Zero());
    force_.assign(ns, V::Zero());
    disp_.assign(ns, V::Zero());
    xkin_.assign(ns, NodeKinematics<Dim>{V::Zero(), V::Zero()});
    volume_.assign(block_node_.size(), 0.0);
    disp0_.assign(block_node_.size(), V::Zero());
  }

  GridFields<Dim>& grid_;
  std::vector<NodeKinematics<Dim>>& kin_;
  std::vector<double> area0_;
  bool need_volume_ = false, need_disp_ = false;  // some crack detects contact by volume / displacement
  std::vector<double> mass_, volume_;             // per slot; volume: per block (all its fields)
  std::vector<V> momentum_, force_, disp_, disp0_;  // per slot; disp0: per block, the ordinary field
  std::vector<NodeKinematics<Dim>> xkin_;
};

}  // namespace crack_fields
}  // namespace cleave
