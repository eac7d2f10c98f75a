// Layer of the crack fields (libmpm/mpm/crack_fields.hpp; layering: grid_cells.hpp): multi-field
// nodes, i.e. the extra velocity fields of a node and which of its fields each classified
// particle-node pair uses. Key 0 (no crossing) is the node's ordinary field and lives in the
// stepper's grid arrays; a node that also receives another key gets a block of kExtra slots, so a
// node holds up to four fields as in NairnMPM. A pair that would need a fifth field is counted
// (take_overflow) and uses the node's ordinary field. Slots are numbered serially in particle
// order, so the layout, and with it every sum over a node's fields, is the same for any thread
// count. Field x < 0 always means the node's ordinary field.
// Each slot also sums the normals of the crack simplices (segments, triangles) its pairs crossed.
#pragma once
#include <cstdint>
#include <vector>

#include "libmpm/crack/crack2d.hpp"
#include "libmpm/mpm/crack_fields/classification.hpp"
#include "libmpm/mpm/model.hpp"

namespace cleave {

// Nodal velocity and acceleration side by side: Task 5 gathers both from one cache line.
template <int Dim>
struct NodeKinematics {
  Vec<Dim> v, a;
};

namespace crack_fields {

template <int Dim, class SF>
class FieldSlots : public Classification<Dim, SF> {
  using Base = Classification<Dim, SF>;
  using V = Vec<Dim>;

 public:
  static constexpr int kExtra = 3;  // extra fields per node: four in all

  double& mass(int64_t n, int32_t x) { return x < 0 ? grid_.mass[n] : mass_[x]; }
  V& momentum(int64_t n, int32_t x) { return x < 0 ? grid_.momentum[n] : momentum_[x]; }
  V& force(int64_t n, int32_t x) { return x < 0 ? grid_.force[n] : force_[x]; }
  const NodeKinematics<Dim>& kin(int64_t n, int32_t x) const { return x < 0 ? kin_[n] : xkin_[x]; }

  // Pairs that needed a fifth field since the last call (reported by the stepper).
  long take_overflow() {
    const long o = overflow_;
    overflow_ = 0;
    return o;
  }

 protected:
  using Base::cracks_, Base::G_, Base::key_any_, Base::kOverflow, Base::N, Base::near_, Base::near_st_;
  using Base::pair_key_, Base::pair_seg_, Base::bodies_;

  FieldSlots(Model<Dim>& m, GridFields<Dim>& grid, std::vector<NodeKinematics<Dim>>& kin)
      : Base(m), grid_(grid), kin_(kin) {
    node_block_.assign(G_.node_count(), -1);
  }

  // Serial, in particle order: deterministic slot numbering for any thread count.
  void allocate_fields() {
    for (int64_t n : block_node_) node_block_[n] = -1;
    block_node_.clear();
    block_nslots_.clear();
    block_key_.clear();
    std::vector<V>& normals = normals_next_;  // per slot, two (one per code of the key)
    normals.clear();
    seg_normal_.resize(cracks_.size());
    for (std::size_t ci = 0; ci < cracks_.size(); ++ci) {
      const auto& c = cracks_[ci];
      if constexpr (Dim == 3) {
        seg_normal_[ci].resize(c.simplices.size());
        for (std::size_t t = 0; t < c.simplices.size(); ++t) seg_normal_[ci][t] = triangle_normal(c, t);
      } else {
        seg_normal_[ci].resize(c.points.size() - 1);
        for (std::size_t sgi = 0; sgi + 1 < c.points.size(); ++sgi) seg_normal_[ci][sgi] = segment_normal(c, sgi);
      }
    }
    const std::size_t nn = near_.size();
    pair_slot_.assign(nn * N, 0);
    slot_any_.assign(nn, 0);
    for (std::size_t k = 0; k < nn; ++k) {
      if (!key_any_[k]) continue;  // every key 0: every pair uses the ordinary field
      int j = 0;
      near_st_[k].for_each_weight([&](int64_t n, double) {
        const std::size_t q = k * N + j++;
        const uint32_t key = pair_key_[q];
        if (key == 0) return;
        if (key == kOverflow) {
          ++overflow_;  // more crossings than a key holds: the pair uses the ordinary field
          return;
        }
        int32_t b = node_block_[n];
        if (b < 0) {
          b = static_cast<int32_t>(block_node_.size());
          node_block_[n] = b;
          block_node_.push_back(n);
          block_nslots_.push_back(0);
          block_key_.insert(block_key_.end(), kExtra, 0u);
          normals.insert(normals.end(), 2 * kExtra, V::Zero());
        }
        const int32_t x = extra_field(n, key);
        int slot = x < 0 ? -1 : x - b * kExtra;
        if (slot < 0) {
          if (block_nslots_[b] == kExtra) {
            ++overflow_;  // a fifth field: this pair falls back to the ordinary field
            return;
          }
          slot = block_nslots_[b]++;
          block_key_[b * kExtra + slot] = key;
        }
        pair_slot_[q] = static_cast<uint8_t>(slot + 1);
        slot_any_[k] = 1;
        for (int c = 0; c < 2; ++c) {
          const uint32_t code = crack::key_code(key, c);
          if (!code) continue;
          normals[2 * (b * kExtra + slot) + c] += seg_normal_[crack::code_crack(code)][pair_seg_[2 * q + c]];
        }
      });
    }
    // Which near particles reach a multi-field node at all (with an extra field or without one).
    block_any_.resize(nn);
#pragma omp parallel for schedule(static) if (worth_parallel(nn))
    for (std::size_t k = 0; k < nn; ++k) {
      uint8_t any = slot_any_[k];
      if (!any) near_st_[k].for_each_weight([&](int64_t n, double) { any |= node_block_[n] >= 0; });
      block_any_[k] = any;
    }
    const std::size_t ns = block_node_.size() * kExtra;
    mass_.assign(ns, 0.0);
    momentum_.assign(ns, V::Zero());
    force_.assign(ns, V::Zero());
    disp_.assign(ns, V::Zero());
    pos_.assign(ns, V::Zero());
    xkin_.assign(ns, NodeKinematics<Dim>{V::Zero(), V::Zero()});
    normal_.swap(normals);
    volume_.assign(block_node_.size(), 0.0);
    disp0_.assign(block_node_.size(), V::Zero());
    pos0_.assign(block_node_.size(), V::Zero());
    rot_.assign(block_node_.size(), 0.0);
    if (bodies_) {
      grad_.assign(ns, V::Zero());
      grad0_.assign(block_node_.size(), V::Zero());
      fvol_.assign(ns, 0.0);
      fvol0_.assign(block_node_.size(), 0.0);
    }
  }

  // The extra-field slot of node n holding `key`, or -1 when the node has none.
  int32_t extra_field(int64_t n, uint32_t key) const {
    const int32_t b = node_block_[n];
    if (b < 0) return -1;
    for (int s = 0; s < block_nslots_[b]; ++s)
      if (block_key_[b * kExtra + s] == key) return b * kExtra + s;
    return -1;
  }

  // Sum of the crack normals stored for crack ci in field x (none for the ordinary field).
  V normal_sum(int32_t x, int ci) const {
    if (x < 0) return V::Zero();
    const uint32_t key = block_key_[x];
    V s = V::Zero();
    for (int c = 0; c < 2; ++c) {
      const uint32_t code = crack::key_code(key, c);
      if (code && crack::code_crack(code) == ci) s += normal_[2 * x + c];
    }
    return s;
  }

  // 3D: minus the triangle's unit normal (which points above): from above to below, as in 2D.
  static V triangle_normal(const crack::ExplicitCrack<Dim>& c, std::size_t t) {
    const auto& T = c.simplices[t];
    const V n = (c.points[T[1]] - c.points[T[0]]).cross(c.points[T[2]] - c.points[T[0]]);
    return -n / n.norm();
  }
  static V segment_normal(const crack::ExplicitCrack<Dim>& c, std::size_t s) {
    const V t = c.points[s + 1] - c.points[s];
    return V(t.y(), -t.x()) / t.norm();  // right of the crack direction: from above to below
  }

  GridFields<Dim>& grid_;                  // the ordinary fields (the stepper's)
  std::vector<NodeKinematics<Dim>>& kin_;  // and their velocities and accelerations
  std::vector<uint8_t> slot_any_;   // per near particle: does a pair use an extra field (allocate_fields)
  std::vector<uint8_t> block_any_;  // per near particle: is a node of its stencil a multi-field node
  std::vector<uint8_t> pair_slot_;  // per pair: 0 for the ordinary field, else 1 + slot in the block
  std::vector<int32_t> node_block_;  // per node: its block, or -1
  std::vector<int64_t> block_node_;
  std::vector<uint8_t> block_nslots_;
  std::vector<uint32_t> block_key_;  // per slot x = block * kExtra + s
  std::vector<double> mass_, volume_;  // per slot; volume: per block (all its fields)
  std::vector<V> momentum_, force_, disp_, normal_, disp0_, normals_next_;  // normal_: two per slot; disp0: per block
  // Mass-weighted positions per field (pos_ per slot, pos0_ the ordinary field's, per block): a field's
  // velocity is that of its mass centre, not of the node (crack_motion.hpp, contact.hpp); and, for
  // displacement detection, the mass-weighted in-plane rotation of all the node's fields (per block).
  std::vector<V> pos_, pos0_;
  std::vector<double> rot_;
  // With contact between bodies: each field's sum m_p grad S_n(x_p) (grad_ per slot, grad0_ the
  // ordinary field's, per block), minus its mass gradient at the node: it points out of the field's
  // body, and the difference across two bodies' fields is their contact normal (contact.hpp).
  std::vector<V> grad_, grad0_;
  std::vector<double> fvol_, fvol0_;  // the same fields' volumes, sum V_p S (a body's share of a node)
  std::vector<NodeKinematics<Dim>> xkin_;
  long overflow_ = 0;
  std::vector<std::vector<V>> seg_normal_;  // per crack and segment: segment_normal, for allocate_fields
};

}  // namespace crack_fields
}  // namespace cleave
