// Multiple velocity fields at nodes near explicit cracks: 2D polylines (seed 002, §2.1-2.2 and
// Appendix A) and 3D triangulated surfaces (seed 000, Appendices A-B), with crack contact and crack
// motion (Task 7); one code path, the dimension's geometry in the layers below.
//
// Every particle-node pair has a field key: the cracks its connecting line crosses and the side
// the particle is on (at most two crossings, so two cracks may meet at a node). Key 0 (no
// crossing) is the node's ordinary field and lives in the stepper's grid arrays; a node that also
// receives another key gets a block of up to three extra slots, so a node holds up to four fields
// as in NairnMPM. A pair that would need a fifth field is counted and reported, and its particle
// then uses the node's ordinary field.
//
// Cost model: a per-step spatial index maps each cell to the crack segments within kReach cells of
// it. Particles farther than near_reach_ from every segment of their cell's entries ("far"
// particles) can neither cross a crack nor touch a multi-field node with a non-zero weight, so they
// keep the stepper's single-field fast path; only "near" particles take the paths here.
//
// The state and the machinery are layers in libmpm/mpm/crack_fields/, each built on the ones
// before it (grid_cells.hpp says why layers):
//   grid_cells.hpp      cell and node arithmetic
//   spatial_index.hpp   the segment index and the near test
//   classification.hpp  near-particle list, stencils and the field key of every pair (line crossing)
//   field_slots.hpp     the extra fields of multi-field nodes and which one each pair uses
//   crack_motion.hpp    the fields each crack surface follows; moving the cracks (Task 7)
//   contact.hpp         contact detection and laws between a node's fields (line_weight.hpp: the
//                       crack's weight in a node's volume, for volume detection)
// This class is the stepper's interface: what each task of the step does with the crack fields.
// The functions with loops that the stepper's particle and grid passes inline (slot iteration,
// Task 1, the grid tasks) are defined here rather than taken from a layer: called through a base
// class they changed the shape of the inlined code, and with it which multiplies GCC fused into
// adds and the last bits of the force pass (grid_cells.hpp). One-line accessors, which fold into
// plain memory references, and the crack-wide steps come from the layers.
//
// The run's costs (core/part_costs.hpp): prepare_index() and prepare_fields() are charged to
// "crack fields", contact() (Tasks 2, 4 and 6c) to "contact", each by a pair of out-of-line calls
// (costs::enter/leave) inside the function. All else the crack module does counts as the step: the
// near particles' paths inside the particle passes and the near flags of the strip-order pass (they
// run in the step's parallel loops), the extra fields' grid tasks and crack motion (Task 7). Those
// are the places where the calls leave this translation unit's machine code as it was: pairs in the
// stepper around its calls into this class, or one pair in, around or beside move_cracks (tried: in
// the stepper, in the layer, in a wrapper here, in 2D only), changed what GCC inlines elsewhere in
// mpm_step.cpp and with it which multiplies it fuses into adds (the last bits of the 2D DCB's
// global.csv, or of a 3D uGIMP crack_fronts.csv). (Checked on 2d3261d; the 3D uGIMP front
// evaluation sits at such a threshold for any edit of the unit: docs/performance.md, "What each
// part costs".)
#pragma once
#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <utility>
#include <vector>

#include "libmpm/core/part_costs.hpp"
#include "libmpm/crack/crack2d.hpp"
#include "libmpm/mpm/crack_fields/contact.hpp"
#include "libmpm/mpm/crack_tip_eval.hpp"
#include "libmpm/mpm/particle_strain.hpp"
#include "libmpm/mpm/model.hpp"
#include "libmpm/mpm/stencil.hpp"
#include "libmpm/mpm/step_timers.hpp"

namespace cleave {

template <int Dim, class SF>
class CrackFields : crack_fields::CrackContact<Dim, SF> {
  using Base = crack_fields::CrackContact<Dim, SF>;
  using St = Stencil<Dim, SF>;
  using V = Vec<Dim>;
  using Law = crack::ContactLaw;

 public:
  using Base::kExtra;  // extra fields per node: four in all
  using Base::kReach;  // cells from a segment that its index entries reach
  using Base::N;
  using typename Base::Entry;
  using typename Base::NearTest;
  using Base::follow_scene_spin;  // mpm.spin_transfer (crack_fields/crack_motion.hpp)

  CrackFields(Model<Dim>& m, GridFields<Dim>& grid, std::vector<NodeKinematics<Dim>>& kin) : Base(m, grid, kin), strain_(m) {
    area0_.resize(P_.size());
    for (const auto& b : m.bodies)
      for (std::size_t p = b.first; p < b.first + b.count; ++p)
        area0_[p] = Dim == 2 ? P_.volume0[p] / b.thickness : P_.volume0[p];
    for (const auto& c : cracks_) {
      if (c.contact_law == Law::None) continue;
      (c.detection == crack::Detection::Volume ? need_volume_ : need_disp_) = true;
    }
  }

  bool active() const { return !cracks_.empty() || bodies_; }
  // One flag per particle: near a crack at the start of the step (set by the stepper's strip-order
  // pass with near_test(), between prepare_index() and prepare_fields()).
  const uint8_t* near_flags() const { return near_flag_.data(); }
  uint8_t* near_flags() { return near_flag_.data(); }
  const std::vector<int32_t>& near_list() const { return near_; }
  // Per particle: its index in near_list(), or -1 when it is not near a crack.
  const int32_t* near_index() const { return near_index_.data(); }
  // The stencil of near particle k (index into near_list()), evaluated once in prepare_fields(): every pass
  // of a step evaluates the shape functions at the start-of-step positions (a pass that moves the
  // particles does so after its last use of them), so one evaluation serves the whole step.
  const St& stencil(std::size_t k) const { return near_st_[k]; }
  std::size_t block_count() const { return block_node_.size(); }

  // --- Task 1 preamble: spatial index, near particles, line crossing (Appendix A), field slots ----
  // In three parts: prepare_index(); then the near flags, set from near_test() in the stepper's
  // strip-order pass, which streams every particle's position anyway (a pass of its own here cost
  // about 2 % of a step at 230 000 particles); then prepare_fields(whether a flag changed).
  using Base::near_test, Base::prepare_index;
  void prepare_fields(bool flags_changed) {
    const int was = costs::enter(costs::CrackFields);  // (calls, not a scope: see the header)
    side_fields_.resize(cracks_.size());
    side_valid_.assign(cracks_.size(), 0);
    if (flags_changed) {
      CLEAVE_TIME(NearList);
      collect_near_particles();
    }
    {
      CLEAVE_TIME(Classify);
      classify_pairs();
    }
    {
      CLEAVE_TIME(Allocate);
      allocate_fields();
    }
    begin_step_contact();
    costs::leave(was);
  }

  // Near particle k uses only its nodes' ordinary fields (the stepper's arrays): in the passes that read
  // or add to fields alone (stresses, forces, Task 5), its path is the far particles' (one that
  // evaluates its stencil afresh, the same values as the cached one: cheaper than loading 300-1000
  // bytes of stencil per particle; about half of the near particles of a crack lie beyond the cell
  // rows that it cuts). plain_extrapolation(k): nor does Task 1 add to a multi-field node's sums.
  bool plain(std::size_t k) const { return !slot_any_[k]; }
  bool plain_extrapolation(std::size_t k) const { return !block_any_[k]; }

  // Calls f(node, x, w, g) for every stencil node of near particle k (index into near_list()):
  // x < 0 means the node's ordinary field (the stepper's arrays), else the extra slot index.
  // (Most near particles use only ordinary fields: they take a path with x = -1 known to the compiler.)
  template <class F>
  void for_each_pair(std::size_t k, const St& s, F&& f) const {
    if (!slot_any_[k]) {
      s.for_each([&](int64_t n, double w, const V& g) { f(n, -1, w, g); });
      return;
    }
    const uint8_t* sl = &pair_slot_[k * N];
    int j = 0;
    s.for_each([&](int64_t n, double w, const V& g) {
      const uint8_t q = sl[j++];
      f(n, q ? static_cast<int32_t>(node_block_[n] * kExtra + q - 1) : -1, w, g);
    });
  }
  template <class F>
  void for_each_pair_weight(std::size_t k, const St& s, F&& f) const {
    if (!slot_any_[k]) {
      s.for_each_weight([&](int64_t n, double w) { f(n, -1, w); });
      return;
    }
    const uint8_t* sl = &pair_slot_[k * N];
    int j = 0;
    s.for_each_weight([&](int64_t n, double w) {
      const uint8_t q = sl[j++];
      f(n, q ? static_cast<int32_t>(node_block_[n] * kExtra + q - 1) : -1, w);
    });
  }

  // Task 1 for near particle k: masses and momenta per field (eq. 26), mass-weighted positions per
  // field at multi-field nodes (a field's velocity is that of its mass centre: crack motion and contact
  // extrapolate it to the crack with the crack's spin), total nodal volume (eq. 27) and, for
  // displacement contact, mass-weighted displacements per field (seed 000 eq. 68) and rotations per node.
  // Each detection method's sums only when a crack uses it (volumes: seed 002; displacements: seed 000).
  void extrapolate(std::size_t k, const St& s) {
    if (bodies_) return extrapolate_with_gradients(k, s);
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
    const V mx = mp * P_.x[p];
    V mu = V::Zero();
    double mrot = 0.0;
    if constexpr (disp) {
      mu = mp * P_.u[p];
      if constexpr (Dim == 2) mrot = mp * P_.rotation[p];
    }
    double area = 0.0;
    if constexpr (volume) {
      const Sym<Dim> e = strain_(p);
      area = area0_[p] * (1.0 + e[0]) * (1.0 + e[1]);  // eq. 25
      if constexpr (Dim == 3) area *= 1.0 + e[2];  // (3D: the volume)
    }
    for_each_pair_weight(k, s, [&](int64_t n, int32_t x, double w) {
      const int32_t b = node_block_[n];
      if (x < 0) {
        grid_.mass[n] += mp * w;
        grid_.momentum[n] += mv * w;
        if (b >= 0) {
          pos0_[b] += mx * w;
          if constexpr (disp) disp0_[b] += mu * w;
        }
      } else {
        mass_[x] += mp * w;
        momentum_[x] += mv * w;
        pos_[x] += mx * w;
        if constexpr (disp) disp_[x] += mu * w;
      }
      if constexpr (disp)
        if (b >= 0) rot_[b] += mrot * w;
      if constexpr (volume)
        if (b >= 0) volume_[b] += area * w;
    });
  }

  // The same with contact between bodies: always the nodal volumes (volume detection, and a body's
  // share of a node by volume), and each field's sum m_p grad S, from which contact takes the normal
  // between two bodies, and its volume.
  void extrapolate_with_gradients(std::size_t k, const St& s) {
    if (need_disp_) extrapolate<true, true>(k, s);
    else extrapolate<true, false>(k, s);
    const std::size_t p = static_cast<std::size_t>(near_[k]);
    const double mp = P_.mass[p];
    const Sym<Dim> e = strain_(p);
    double vol = area0_[p] * (1.0 + e[0]) * (1.0 + e[1]);
    if constexpr (Dim == 3) vol *= 1.0 + e[2];
    for_each_pair(k, s, [&](int64_t n, int32_t x, double w, const V& g) {
      if (x >= 0) grad_[x] += mp * g, fvol_[x] += vol * w;
      else if (node_block_[n] >= 0) grad0_[node_block_[n]] += mp * g, fvol0_[node_block_[n]] += vol * w;
    });
  }

  using Base::force, Base::kin, Base::mass, Base::momentum;  // field x of node n (x < 0: the ordinary one)

  // Field slot (as in for_each_pair) for the pair particle p - node n, classified afresh: for loads
  // whose stencil is not the particle's own (face tractions). Falls back to the ordinary field when
  // the node has no field with this key.
  int32_t field_of(std::size_t p, int64_t n, const V& node_pos) const {
    if (!near_flag_[p]) return -1;
    int32_t seg[2];
    uint32_t key = classify(P_.x[p], node_pos, seg);
    if (key == kOverflow) return -1;
    key |= body_tag(p, n);
    if (key == 0) return -1;
    return extra_field(n, key);
  }

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

  // Task 4 for the extra fields (eq. 29), then contact with force back-calculation, then the
  // velocities and accelerations of every field at multi-field nodes.
  void update_momenta(double dt) {
    for (std::size_t x = 0; x < mass_.size(); ++x)
      if (mass_[x] > 0.0) momentum_[x] += dt * force_[x];
    contact(dt, Base::Call::Forces);
    for (std::size_t b = 0; b < block_node_.size(); ++b) {
      const int64_t n = block_node_[b];
      if (grid_.mass[n] > 0.0) {
        kin_[n].v = grid_.momentum[n] / grid_.mass[n];
        kin_[n].a = grid_.force[n] / grid_.mass[n];
      }
      for (int s = 0; s < block_nslots_[b]; ++s) {
        const std::size_t x = b * kExtra + s;
        if (mass_[x] > 0.0) {
          xkin_[x].v = momentum_[x] / mass_[x];
          xkin_[x].a = force_[x] / mass_[x];
        }
      }
    }
    carry_nodal_velocities_to_nodes();  // (with the spins contact() found from these momenta)
  }

  // Task 6c starts the extra fields' momenta afresh (the ordinary field's are zeroed by the stepper).
  void clear_momenta() { std::fill(momentum_.begin(), momentum_.end(), V::Zero()); }

  // Nodal velocities of the extra fields from the latest momenta (Subtask 1, eq. 34).
  void nodal_velocities() {
    for (std::size_t x = 0; x < mass_.size(); ++x)
      if (mass_[x] > 0.0) xkin_[x].v = momentum_[x] / mass_[x];
    for (std::size_t b = 0; b < block_node_.size(); ++b) {  // the ordinary fields' (the stepper set them)
      const int64_t n = block_node_[b];
      if (grid_.mass[n] > 0.0) kin_[n].v = grid_.momentum[n] / grid_.mass[n];
    }
    update_spins();
    carry_nodal_velocities_to_nodes();
  }

  // J and K at the crack tips in the current state (crack_tip_eval.hpp); accel(p): particle p's
  // acceleration in the last step, each node's from the field the particle uses there.
  template <class Accel>
  std::vector<crack::TipRecord> tip_parameters(const Model<Dim>& m, const crack::TipSettings& ts, Accel&& accel) const {
    if constexpr (Dim == 3) return {};  // 3D: the stepper's crack_front_parameters (crack_front_eval.hpp)
    else return evaluate_crack_tips<SF>(m, ts, std::forward<Accel>(accel));
  }

  using Base::begin_step_contact, Base::contact;  // crack contact (Tasks 2 and 6c; Task 4 in update_momenta)
  using ContactCall = typename Base::Call;
  using Base::move_cracks;  // Task 7 (the step's in the run's costs: crack_fields.hpp's header says why)
  using Base::take_overflow;

 private:
  using Base::allocate_fields, Base::block_node_, Base::carry_nodal_velocities_to_nodes, Base::update_spins, Base::block_nslots_, Base::classify, Base::classify_pairs;
  using Base::collect_near_particles, Base::cracks_, Base::disp0_, Base::disp_, Base::extra_field, Base::pos0_, Base::pos_;
  using Base::force_, Base::grid_, Base::kin_, Base::kOverflow, Base::mass_, Base::momentum_, Base::near_;
  using Base::near_flag_, Base::near_index_, Base::near_st_, Base::node_block_, Base::P_, Base::pair_slot_;
  using Base::bodies_, Base::body_tag, Base::fvol_, Base::fvol0_, Base::grad_, Base::grad0_;
  using Base::rot_, Base::side_fields_, Base::side_valid_, Base::slot_any_, Base::block_any_, Base::volume_, Base::xkin_;

  StrainOf<Dim> strain_;  // particle strains, carried or taken from the stress
  std::vector<double> area0_;  // per particle: its area (2D) or volume (3D) at zero strain (eq. 25)
  bool need_volume_ = false, need_disp_ = false;  // some crack detects contact by volume / displacement
};

}  // namespace cleave
