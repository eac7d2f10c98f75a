// Layer of the crack fields (libmpm/mpm/crack_fields.hpp; layering: grid_cells.hpp): contact between
// bodies (Model::body_contact). Bodies in declared contact have field groups of their own; where
// particles of two groups reach one node, each group moves on its own field there, as the two faces
// of a crack do, and contact.hpp couples them by the pair's law. One machinery for both: a pair's
// field key carries its crack codes (classification.hpp) and, at a node that several groups reach,
// a body tag in bits 24-31: 0 for the node's lowest group (which keeps the node's ordinary field, as
// the uncracked side of a crack does) and g + 1 for group g. A node that one group alone reaches has
// no tag, so a body far from the others costs nothing.
//
// Which particles take the multi-field paths ("near"): those with a weight at a node that two groups
// reach. Each step marks every cell with the groups of the particles in it and grows the marks by the
// cells over which two particles can share a node (1 linear, 3 uGIMP); the particles of cells whose
// grown mark holds two groups are the candidates, and their stencils mark the nodes with their groups,
// exactly at every node two groups reach (both particles weighting it are candidates); a cell is hot
// when such a node is in the stencil range of a particle in it, and the near test asks for a hot cell.
// A far particle's nodes belong to its group alone, and its single field there is right.
#pragma once
#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "libmpm/core/parallel.hpp"
#include "libmpm/mpm/crack_fields/spatial_index.hpp"
#include "libmpm/mpm/model.hpp"
#include "libmpm/mpm/stencil.hpp"

namespace cleave::crack_fields {

template <int Dim, class SF>
class BodyGroups : public SpatialIndex<Dim, SF> {
  using Base = SpatialIndex<Dim, SF>;
  using V = Vec<Dim>;

 public:
  static constexpr int kTagShift = 24;

  // The crack index's near test, and near another body's group.
  struct NearTest {
    typename Base::NearTest crack;
    const uint32_t* cell_group;  // per cell: 3 when hot (mark_nodes_and_hot_cells); null without contact between bodies
    Vec<Dim> origin;
    double inv_h;
    int cells[Dim];
    uint8_t in_box(const V& x) const { return crack.in_box(x) | static_cast<uint8_t>(cell_group != nullptr); }
    uint8_t operator()(const V& x) const {
      if (crack.in_box(x) && crack(x)) return 1;
      if (!cell_group) return 0;
      int64_t c = 0;
      for (int d = 0; d < Dim; ++d) {
        const double f = (x[d] - origin[d]) * inv_h;
        if (!(f >= 0.0 && f < cells[d])) return 0;
        c = c * cells[d] + static_cast<int64_t>(f);
      }
      return std::popcount(cell_group[c]) > 1;
    }
  };
  NearTest near_test() const {
    NearTest t{Base::near_test(), bodies_ ? hot_.data() : nullptr, G_.origin, inv_h_, {}};
    for (int d = 0; d < Dim; ++d) t.cells[d] = cells_[d];
    return t;
  }
  // The crack index, and each cell's groups (only with contact between bodies).
  void prepare_index() {
    Base::prepare_index();
    if (bodies_) mark_cells();
  }

 protected:
  using Base::cell_count, Base::cell_of, Base::cells_, Base::G_, Base::inv_h_, Base::stride_;

  explicit BodyGroups(Model<Dim>& m)
      : Base(m), contact_(m.body_contact), X_(m.particles.x), HW_(m.particles.half_width) {
    bodies_ = contact_.active();
    if (!bodies_) return;
    group_ = particle_groups(m);
    raw_.assign(cell_count(), 0);
    grown_.assign(cell_count(), 0);
    hot_.assign(cell_count(), 0);
    node_group_.assign(G_.node_count(), 0);
    reach_ = SF::K == 2 ? 1 : 3;  // cells between two particles that can weight one node
    crack_group_.resize(m.cracks.size());
    for (std::size_t ci = 0; ci < m.cracks.size(); ++ci) crack_group_[ci] = crack_group(m, group_, ci);
  }

  // The groups of the particles in each cell, grown by reach_ cells along every axis.
  void mark_cells() {
    std::fill(raw_.begin(), raw_.end(), 0u);
    const std::size_t np = X_.size();
#pragma omp parallel for schedule(static) if (worth_parallel(np))
    for (std::size_t p = 0; p < np; ++p) {
      const int64_t c = cell_of(X_[p]);
      if (c >= 0) std::atomic_ref<uint32_t>(raw_[c]).fetch_or(1u << group_[p], std::memory_order_relaxed);
    }
    // Separable: along each axis, every cell takes the marks within reach_ cells.
    std::vector<uint32_t>* src = &raw_;
    std::vector<uint32_t>* dst = &grown_;
    for (int d = 0; d < Dim; ++d) {
      int64_t stride = 1;
      for (int e = d + 1; e < Dim; ++e) stride *= cells_[e];
      const int64_t len = cells_[d], total = static_cast<int64_t>(cell_count());
      const uint32_t* s = src->data();
      uint32_t* t = dst->data();
#pragma omp parallel for schedule(static) if (worth_parallel(static_cast<std::size_t>(total)))
      for (int64_t c = 0; c < total; ++c) {
        const int64_t i = (c / stride) % len;
        uint32_t m = 0;
        for (int64_t k = std::max<int64_t>(0, i - reach_); k <= std::min<int64_t>(len - 1, i + reach_); ++k)
          m |= s[c + (k - i) * stride];
        t[c] = m;
      }
      std::swap(src, dst);
    }
    if (src != &grown_) grown_.swap(raw_);  // (the last pass wrote raw_)
    mark_nodes_and_hot_cells();
  }

  // Exact node marks from the candidates (particles whose grown cell holds two groups): two particles of
  // two groups that weight one node are both candidates, so every node that two groups reach is marked
  // with both. A cell is then hot when such a node lies in the stencil range of a particle in it (nodes
  // i .. i + 1 per axis, linear; i - 1 .. i + 2, uGIMP), and only particles in hot cells are near: those
  // around the nodes two bodies share, not every particle within reach of another body (in five_disks
  // 10 % of the particles were, and the run took 1.28x as long as without contact).
  void mark_nodes_and_hot_cells() {
    std::fill(node_group_.begin(), node_group_.end(), 0u);
    const std::size_t np = X_.size();
#pragma omp parallel for schedule(static) if (worth_parallel(np))
    for (std::size_t p = 0; p < np; ++p) {
      const int64_t c = cell_of(X_[p]);
      if (c < 0 || std::popcount(grown_[c]) < 2) continue;
      Stencil<Dim, SF> st;
      st.eval(G_, stride_, inv_h_, X_[p], HW_[p]);
      const uint32_t bit = 1u << group_[p];
      st.for_each_weight([&](int64_t n, double w) {
        if (w != 0.0) std::atomic_ref<uint32_t>(node_group_[n]).fetch_or(bit, std::memory_order_relaxed);
      });
    }
    constexpr int lo = SF::K == 2 ? 0 : 1, hi = SF::K == 2 ? 1 : 2;
    const int64_t total = static_cast<int64_t>(cell_count());
#pragma omp parallel for schedule(static) if (worth_parallel(static_cast<std::size_t>(total)))
    for (int64_t c = 0; c < total; ++c) {
      uint32_t hot = 0;
      if (std::popcount(grown_[c]) >= 2) {
        int64_t idx[Dim], r = c;
        for (int d = Dim - 1; d >= 0; --d) idx[d] = r % cells_[d], r /= cells_[d];
        int64_t a[Dim], b[Dim];
        for (int d = 0; d < Dim; ++d) a[d] = std::max<int64_t>(0, idx[d] - lo), b[d] = std::min<int64_t>(cells_[d], idx[d] + hi);
        if constexpr (Dim == 2) {
          for (int64_t i = a[0]; i <= b[0] && !hot; ++i)
            for (int64_t j = a[1]; j <= b[1] && !hot; ++j)
              hot = std::popcount(node_group_[i * static_cast<int64_t>(stride_[0]) + j]) >= 2;
        } else {
          for (int64_t i = a[0]; i <= b[0] && !hot; ++i)
            for (int64_t j = a[1]; j <= b[1] && !hot; ++j)
              for (int64_t k = a[2]; k <= b[2] && !hot; ++k)
                hot = std::popcount(node_group_[i * static_cast<int64_t>(stride_[0]) + j * static_cast<int64_t>(stride_[1]) + k]) >= 2;
        }
      }
      hot_[c] = hot ? 3u : 0u;  // (two bits: the near test's "two groups")
    }
  }

  // The body tag of particle p's field at node n (0 where one group alone reaches the node, or p is
  // of the node's lowest group).
  uint32_t body_tag(std::size_t p, int64_t n) const { return bodies_ ? group_tag(group_[p], n) : 0u; }
  // The same for a field of group g (a crack's surfaces: the group of the body the crack lies in).
  uint32_t group_tag(uint32_t g, int64_t n) const {
    const uint32_t m = node_group_[n];
    if (std::popcount(m) < 2) return 0;
    return g == static_cast<uint32_t>(std::countr_zero(m)) ? 0u : (g + 1) << kTagShift;
  }
  // The group of the field with `key` at node n.
  int field_group(int64_t n, uint32_t key) const {
    const uint32_t tag = key >> kTagShift;
    return tag ? static_cast<int>(tag) - 1 : std::countr_zero(node_group_[n] | (1u << 31));
  }

  const BodyContact& contact_;
  const std::vector<Vec<Dim>>& X_;
  const std::vector<double>& HW_;
  bool bodies_ = false;
  int reach_ = 1;
  std::vector<uint8_t> group_;         // per particle: its body's group
  std::vector<uint32_t> raw_, grown_;  // per cell: group marks, then grown (the candidates')
  std::vector<uint32_t> hot_;          // per cell: 3 when a node two groups reach is in range (the near test's)
  std::vector<uint32_t> node_group_;   // per node: the groups of the candidates weighting it
  std::vector<uint8_t> crack_group_;   // per crack: the group of the body it lies in
};

}  // namespace cleave::crack_fields
