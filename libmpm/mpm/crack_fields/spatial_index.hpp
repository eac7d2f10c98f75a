// Layer of the crack fields (libmpm/mpm/crack_fields.hpp; layering: grid_cells.hpp): the per-step
// spatial index of the crack segments, which keeps the cost of cracks proportional to the particles
// near them. Each cell lists, per crack, the range of segments within kReach cells of it. The
// classification scans only its particle's cell's ranges, and the near test sends every particle
// farther than near_reach_ from its cell's ranges down the stepper's single-field fast path.
// 2D only: the ranges are of crack::Crack2D polyline segments, and the near test, which runs for
// every particle in the stepper's strip pass, is written out for two axes.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "libmpm/crack/crack2d.hpp"
#include "libmpm/mpm/crack_fields/grid_cells.hpp"
#include "libmpm/mpm/model.hpp"

namespace cleave::crack_fields {

template <int Dim, class SF>
class SpatialIndex : public GridCells<Dim> {
  static_assert(Dim == 2, "crack fields: 2D only (segment ranges of crack::Crack2D polylines)");
  using Base = GridCells<Dim>;
  using V = Vec<Dim>;

 public:
  // Cells: a particle reaches nodes up to 1 cell away (linear) or 1.5 cells (uGIMP, half-width
  // <= 0.5 cell), so a particle sharing a node with a pair whose line crosses a segment is within
  // twice that of the segment.
  static constexpr int kReach = SF::K == 2 ? 2 : 3;

  // An entry of the spatial index (build_index).
  struct Entry {
    int32_t crack, seg_lo, seg_hi, next;
    V lo, hi;  // bounding box of the range's vertices seg_lo .. seg_hi + 1
  };
  // Is a particle at x near a crack: in a cell with index entries, within near_reach_ of the box of
  // one of them? in_box(x): is x in the box of the cells with entries (a few comparisons, which
  // the caller's loop vectorises); operator(): the full test, for x in that box.
  // (Everything by value: the caller's flag stores (uint8_t) could otherwise alias these members
  // and force reloads in its loop.)
  struct NearTest {
    double ox, oy, inv_h, lo0, hi0, lo1, hi1, reach;
    int64_t ny;
    const int32_t* head;
    const Entry* entries;
    uint8_t in_box(const V& x) const {
      const double fx = (x.x() - ox) * inv_h, fy = (x.y() - oy) * inv_h;
      return (fx >= lo0) & (fx < hi0) & (fy >= lo1) & (fy < hi1);
    }
    uint8_t operator()(const V& x) const {
      const double fx = (x.x() - ox) * inv_h, fy = (x.y() - oy) * inv_h;  // (= cell_of's cell)
      for (int32_t e = head[static_cast<int64_t>(fx) * ny + static_cast<int64_t>(fy)]; e >= 0; e = entries[e].next) {
        const Entry& en = entries[e];
        if (x.x() >= en.lo.x() - reach && x.x() <= en.hi.x() + reach && x.y() >= en.lo.y() - reach &&
            x.y() <= en.hi.y() + reach)
          return 1;
      }
      return 0;
    }
  };

  // The index for the cracks as they are now (Task 1 preamble).
  void prepare_index() {
    for (auto& c : cracks_) c.update_extent();
    build_index();
  }
  NearTest near_test() const {
    return {G_.origin.x(), G_.origin.y(), inv_h_, box_lo_[0], box_hi_[0], box_lo_[1], box_hi_[1], near_reach_,
            static_cast<int64_t>(cells_[1]), cell_head_.data(), entries_.data()};
  }

 protected:
  using Base::cells_, Base::G_, Base::inv_h_;

  explicit SpatialIndex(Model<Dim>& m) : Base(m.grid), cracks_(m.cracks) {
    cell_head_.assign(static_cast<std::size_t>(cells_[0]) * cells_[1], -1);
    // A node has a non-zero weight for a particle within r cells of it on each axis: r = 1 (linear),
    // 1 + half-width (uGIMP). A multi-field node's field comes from a particle-node line that meets a
    // segment, so that segment point lies within r of the node, and a particle weighting the node
    // lies within 2 r of it. (Nodes of zero weight receive nothing and are read with weight 0, so
    // a far particle that has one at a multi-field node is still exact on the fast path; and no line
    // from a far particle to a node of its stencil or of a loaded face, at most 1.5 cells away, can
    // reach a segment, so field_of's -1 for it is the classification's answer.) A little slack
    // covers the rounding of the weights at the edge of the support; at most kReach.
    const Particles<Dim>& P = m.particles;
    double r = 1.0;
    if constexpr (SF::K == 3) {
      double lmax = 0.5;
      if (!P.half_width.empty()) lmax = *std::max_element(P.half_width.begin(), P.half_width.end());
      r += std::clamp(lmax, 0.0, 0.5);
    }
    near_reach_ = std::min(static_cast<double>(kReach), 2.0 * r + 1e-6) * G_.h;
  }

  // For each cell, per crack, the range of segments whose bounding box grown by kReach cells
  // overlaps the cell. A contiguous range is exact for the crossing test: a segment outside it
  // cannot reach the particle-node box, and the range's end vertices are either the crack's tips or
  // vertices no particle-node line of this cell can touch.
  void build_index() {
    for (int64_t c : touched_) cell_head_[c] = -1;
    touched_.clear();
    entries_.clear();
    box_lo_[0] = box_lo_[1] = 0.0;  // empty until a cell gets an entry
    box_hi_[0] = box_hi_[1] = 0.0;
    int bi0 = cells_[0], bi1 = -1, bj0 = cells_[1], bj1 = -1;
    const double grow = kReach * G_.h;
    for (std::size_t ci = 0; ci < cracks_.size(); ++ci) {
      const auto& pts = cracks_[ci].points;
      for (std::size_t s = 0; s + 1 < pts.size(); ++s) {
        const V lo = pts[s].cwiseMin(pts[s + 1]).array() - grow, hi = pts[s].cwiseMax(pts[s + 1]).array() + grow;
        const int i0 = std::max(0, static_cast<int>(std::floor((lo.x() - G_.origin.x()) * inv_h_)));
        const int i1 = std::min(cells_[0] - 1, static_cast<int>(std::floor((hi.x() - G_.origin.x()) * inv_h_)));
        const int j0 = std::max(0, static_cast<int>(std::floor((lo.y() - G_.origin.y()) * inv_h_)));
        const int j1 = std::min(cells_[1] - 1, static_cast<int>(std::floor((hi.y() - G_.origin.y()) * inv_h_)));
        if (i0 <= i1 && j0 <= j1) {
          bi0 = std::min(bi0, i0), bi1 = std::max(bi1, i1);
          bj0 = std::min(bj0, j0), bj1 = std::max(bj1, j1);
        }
        for (int i = i0; i <= i1; ++i)
          for (int j = j0; j <= j1; ++j) {
            const int64_t cell = static_cast<int64_t>(i) * cells_[1] + j;
            int32_t e = cell_head_[cell];
            while (e >= 0 && entries_[e].crack != static_cast<int32_t>(ci)) e = entries_[e].next;
            if (e >= 0) {
              Entry& en = entries_[e];
              // The box takes every vertex of the range, also those of segments that skip this cell.
              for (std::size_t v = static_cast<std::size_t>(en.seg_hi) + 2; v <= s + 1; ++v)
                en.lo = en.lo.cwiseMin(pts[v]), en.hi = en.hi.cwiseMax(pts[v]);
              en.seg_hi = static_cast<int32_t>(s);  // segments arrive in order
            } else {
              if (cell_head_[cell] < 0) touched_.push_back(cell);
              entries_.push_back({static_cast<int32_t>(ci), static_cast<int32_t>(s), static_cast<int32_t>(s),
                                  cell_head_[cell], pts[s].cwiseMin(pts[s + 1]), pts[s].cwiseMax(pts[s + 1])});
              cell_head_[cell] = static_cast<int32_t>(entries_.size() - 1);
            }
          }
      }
    }
    if (bi0 <= bi1) {
      box_lo_[0] = bi0, box_hi_[0] = bi1 + 1.0;
      box_lo_[1] = bj0, box_hi_[1] = bj1 + 1.0;
    }
  }

  std::vector<crack::Crack2D>& cracks_;
  double near_reach_;  // a particle is near when within this distance of an index entry's box
  std::vector<int32_t> cell_head_;
  double box_lo_[2] = {0.0, 0.0}, box_hi_[2] = {0.0, 0.0};  // cells [lo, hi) holding all index entries
  std::vector<int64_t> touched_;
  std::vector<Entry> entries_;
};

}  // namespace cleave::crack_fields
