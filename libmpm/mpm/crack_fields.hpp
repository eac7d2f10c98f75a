// Multiple velocity fields at nodes near 2D explicit cracks (seed 002, §2.1-2.2 and Appendix A),
// with crack contact and crack translation (Task 7): the stepper's one view of the crack machinery.
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
// The work is split into layers in libmpm/mpm/crack_fields/, each built on the ones before it
// (grid_cells.hpp says why layers rather than separate objects):
//   grid_cells.hpp      cell and node arithmetic
//   spatial_index.hpp   the segment index and the near test
//   classification.hpp  near-particle list, stencils and the field key of every pair (line crossing)
//   field_slots.hpp     which slot of which multi-field node each pair uses
//   extra_fields.hpp    the extra fields' values and the grid tasks on them
//   crack_motion.hpp    the fields each crack surface follows; moving the cracks (Task 7)
//   contact.hpp         contact detection and laws between a node's fields
// This class runs them in the step's order and shows the stepper only what it uses.
#pragma once
#include <cstdint>
#include <vector>

#include "libmpm/mpm/crack_fields/contact.hpp"
#include "libmpm/mpm/model.hpp"
#include "libmpm/mpm/stencil.hpp"
#include "libmpm/mpm/step_timers.hpp"

namespace cleave {

template <class SF>
class CrackFields : crack_fields::CrackContact<2, SF> {
  static constexpr int Dim = 2;
  using Base = crack_fields::CrackContact<Dim, SF>;
  using V = Vec<2>;

 public:
  using Base::kExtra;
  using Base::kReach;
  using Base::N;
  using typename Base::Entry;
  using typename Base::NearTest;

  CrackFields(Model<2>& m, GridFields<2>& grid, std::vector<NodeKinematics<2>>& kin) : Base(m, grid, kin) {}

  bool active() const { return !cracks_.empty(); }
  using Base::block_count;
  using Base::near_flags;
  using Base::near_index;
  using Base::near_list;
  using Base::stencil;

  // --- Task 1 preamble: spatial index, near particles, line crossing (Appendix A), field slots ----
  // In three parts: prepare_index(); then the near flags, set from near_test() in the stepper's
  // strip-order pass, which streams every particle's position anyway (a pass of its own here cost
  // about 2 % of a step at 230 000 particles); then prepare_fields(whether a flag changed).
  using Base::near_test;
  using Base::prepare_index;
  void prepare_fields(bool flags_changed) {
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
    CLEAVE_TIME(Allocate);
    allocate_fields();
  }

  // The pairs of a near particle with their fields (for_each_pair, for_each_pair_weight), Task 1
  // for a near particle (extrapolate), and any field's nodal values (field x < 0: the ordinary one).
  using Base::extrapolate;
  using Base::for_each_pair;
  using Base::for_each_pair_weight;
  using Base::force;
  using Base::kin;
  using Base::mass;
  using Base::momentum;

  // Field slot (as in for_each_pair) for the pair particle p - node n, classified afresh: for loads
  // whose stencil is not the particle's own (face tractions). Falls back to the ordinary field when
  // the node has no field with this key.
  int32_t field_of(std::size_t p, int64_t n, const V& node_pos) const {
    if (!near_flag_[p]) return -1;
    int32_t seg[2];
    const uint32_t key = classify(P_.x[p], node_pos, seg);
    if (key == 0 || key == kOverflow) return -1;
    return extra_field(n, key);
  }

  // The grid tasks for the extra fields.
  using Base::apply_momentum_conditions;
  using Base::body_force_and_damping;
  using Base::clear_momenta;
  using Base::nodal_velocities;
  using Base::zero_prescribed_forces;

  // Task 4 for the extra fields (eq. 29), then contact with force back-calculation, then the
  // velocities and accelerations of every field at multi-field nodes.
  void update_momenta(double dt) {
    for (std::size_t x = 0; x < mass_.size(); ++x)
      if (mass_[x] > 0.0) momentum_[x] += dt * force_[x];
    contact(dt, true);
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
  }

  using Base::contact;      // crack contact (Tasks 2 and 6c; Task 4 in update_momenta)
  using Base::move_cracks;  // Task 7
  using Base::take_overflow;

 private:
  using Base::allocate_fields;
  using Base::block_node_;
  using Base::block_nslots_;
  using Base::classify;
  using Base::classify_pairs;
  using Base::collect_near_particles;
  using Base::cracks_;
  using Base::extra_field;
  using Base::force_;
  using Base::grid_;
  using Base::kin_;
  using Base::kOverflow;
  using Base::mass_;
  using Base::momentum_;
  using Base::near_flag_;
  using Base::P_;
  using Base::side_fields_;
  using Base::side_valid_;
  using Base::xkin_;
};

}  // namespace cleave
