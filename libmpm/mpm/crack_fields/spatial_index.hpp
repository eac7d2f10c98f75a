// Layer of the crack fields (libmpm/mpm/crack_fields.hpp; layering: grid_cells.hpp): the per-step
// spatial index of the crack segments, which keeps the cost of cracks proportional to the particles
// near them. Each cell lists, per crack, the range of segments within kReach cells of it. The
// classification scans only its particle's cell's ranges, and the near test sends every particle
// farther than near_reach_ from its cell's ranges down the stepper's single-field fast path.
// 2D: the ranges are of polyline segments in their order (the crossing test of a contiguous range
// is that of the polyline: crossing.hpp). 3D: a range is of the list tri_ids_, which holds per cell
// and crack the triangles within kReach cells, in triangle order. The near test, which runs for every
// particle in the stepper's strip pass, is written out for each dimension's axes.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>
#include <vector>

#include "libmpm/core/part_costs.hpp"
#include "libmpm/crack/crack2d.hpp"
#include "libmpm/mpm/crack_fields/grid_cells.hpp"
#include "libmpm/mpm/model.hpp"

namespace cleave::crack_fields {

template <int Dim, class SF>
class SpatialIndex : public GridCells<Dim> {
  using Base = GridCells<Dim>;
  using V = Vec<Dim>;

 public:
  // Cells: a particle reaches nodes up to 1 cell away (linear) or 1.5 cells (uGIMP, half-width
  // <= 0.5 cell), so a particle sharing a node with a pair whose line crosses a segment is within
  // twice that of the segment.
  static constexpr int kReach = SF::K == 2 ? 2 : 3;

  // An entry of the spatial index (build_index): 2D, segments seg_lo .. seg_hi of the crack; 3D,
  // the triangles tri_ids_[seg_lo .. seg_hi].
  struct Entry {
    int32_t crack, seg_lo, seg_hi, next;
    V lo, hi;  // bounding box of the range's vertices (2D: seg_lo .. seg_hi + 1)
  };
  // Is a particle at x near a crack: in a cell with index entries, within near_reach_ of the box of
  // one of them? in_box(x): is x in the box of the cells with entries (a few comparisons, which
  // the caller's loop vectorises; 3D: along one axis); operator(): the full test, for x in_box.
  // (Everything by value: the caller's flag stores (uint8_t) could otherwise alias these members
  // and force reloads in its loop.)
  struct NearTest2 {
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
  // 3D: in_box tests one axis, the one along which the box is thinnest for the grid (a crack is a
  // surface: along its normal the box spans a few cells), and operator() the other two: the test
  // of every particle's three axes in the strip pass cost ~0.3 ms a step of the 830 000-particle rod.
  struct NearTest3 {
    double o[3], inv_h, lo[3], hi[3], reach;
    int64_t ny, nz;
    const int32_t* head;
    const Entry* entries;
    int axis;
    uint8_t in_box(const V& x) const {
      const double f = (x[axis] - o[axis]) * inv_h;
      return (f >= lo[axis]) & (f < hi[axis]);
    }
    uint8_t operator()(const V& x) const {
      int64_t cell = 0;
      const int64_t n[3] = {0, ny, nz};
      for (int d = 0; d < 3; ++d) {
        const double f = (x[d] - o[d]) * inv_h;
        if (!(f >= lo[d] && f < hi[d])) return 0;
        cell = cell * n[d] + static_cast<int64_t>(f);
      }
      for (int32_t e = head[cell]; e >= 0; e = entries[e].next) {
        const Entry& en = entries[e];
        if ((x.array() >= en.lo.array() - reach).all() && (x.array() <= en.hi.array() + reach).all()) return 1;
      }
      return 0;
    }
  };
  using NearTest = std::conditional_t<Dim == 2, NearTest2, NearTest3>;

  // The index for the cracks as they are now (Task 1 preamble). 3D: nothing to do while no crack
  // has changed (a crack at rest, e.g. before the load reaches it); a crack that moved keeps its
  // triangle lists while every point stays within half a margin of where it was when they were
  // built (fit_index3), and only the boxes follow it.
  void prepare_index() {
    const int was = costs::enter(costs::CrackFields);  // the run's costs (crack_fields.hpp says why calls)
    for (auto& c : cracks_) c.update_extent();
    if constexpr (Dim == 3) {
      note_crack_state();
      if (index_epoch_ == crack_epoch_) return costs::leave(was);
      index_epoch_ = crack_epoch_;
      fit_index3();
    } else {
      build_index2();
    }
    costs::leave(was);
  }
  NearTest near_test() const {
    if constexpr (Dim == 3) {
      int axis = 0;
      for (int d = 1; d < 3; ++d)
        if ((box_hi_[d] - box_lo_[d]) * cells_[axis] < (box_hi_[axis] - box_lo_[axis]) * cells_[d]) axis = d;
      return {{G_.origin.x(), G_.origin.y(), G_.origin.z()}, inv_h_, {box_lo_[0], box_lo_[1], box_lo_[2]},
              {box_hi_[0], box_hi_[1], box_hi_[2]}, near_reach_, static_cast<int64_t>(cells_[1]),
              static_cast<int64_t>(cells_[2]), cell_head_.data(), entries_.data(), axis};
    } else
    return {G_.origin.x(), G_.origin.y(), inv_h_, box_lo_[0], box_hi_[0], box_lo_[1], box_hi_[1], near_reach_,
            static_cast<int64_t>(cells_[1]), cell_head_.data(), entries_.data()};
  }

 protected:
  using Base::cell_count, Base::cells_, Base::G_, Base::inv_h_, Base::parallel_points;
  struct Span {  // 3D: a triangle's cells (fit_triangle_boxes, build_index3)
    int lo[3], hi[3];
  };

  explicit SpatialIndex(Model<Dim>& m) : Base(m.grid), cracks_(m.cracks) {
    cell_head_.assign(cell_count(), -1);
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
  void build_index2() {
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

  // 3D. The lists of triangles (per cell, per entry, the tight ones) are supersets: built with every
  // triangle's box grown by a margin of kMargin cells, they hold every triangle that the box as it
  // is now brings into them while no crack point has moved more than half the margin since they were
  // built (the other half absorbs rounding), so they are kept that long: a loaded crack moves a
  // fraction of a micrometre a step, and rebuilding them every step cost 2.1-2.5 ms of a 95 ms step
  // of the 2.5 mm rod (serial). Every answer is a function of the current boxes alone: the
  // classification filters the lists by them (the keys and segments of a superset list in triangle
  // order are the same), and the entries' boxes, which the near test reads, are refitted every time
  // a crack moved, from the triangles whose box grown by kReach cells reaches the cell now
  // (fit_entry_boxes). So a run is bit-identical whenever the lists were last built (a resumed run
  // builds them afresh).
  void fit_index3() {
    fit_triangle_boxes();
    if (!lists_hold_cracks()) build_index3();
    fit_entry_boxes();
  }
  // Each triangle's box, and the cells of the box grown by kReach cells (spans_, crack by crack).
  void fit_triangle_boxes() {
    tri_lo_.resize(cracks_.size()), tri_hi_.resize(cracks_.size());
    crack_first_.resize(cracks_.size() + 1);
    crack_first_[0] = 0;
    for (std::size_t ci = 0; ci < cracks_.size(); ++ci) {
      const auto& c = cracks_[ci];
      tri_lo_[ci].resize(c.simplices.size()), tri_hi_[ci].resize(c.simplices.size());
      for (std::size_t t = 0; t < c.simplices.size(); ++t) {
        const auto& T = c.simplices[t];
        tri_lo_[ci][t] = c.points[T[0]].cwiseMin(c.points[T[1]]).cwiseMin(c.points[T[2]]);
        tri_hi_[ci][t] = c.points[T[0]].cwiseMax(c.points[T[1]]).cwiseMax(c.points[T[2]]);
      }
      crack_first_[ci + 1] = crack_first_[ci] + static_cast<int64_t>(c.simplices.size());
    }
    spans_.resize(static_cast<std::size_t>(crack_first_.back()));
    int blo[3] = {cells_[0], cells_[1], cells_[2]}, bhi[3] = {-1, -1, -1};
    std::size_t si = 0;
    for (std::size_t ci = 0; ci < cracks_.size(); ++ci)
      for (std::size_t t = 0; t < cracks_[ci].simplices.size(); ++t) {
        const Span sp = span_of(tri_lo_[ci][t], tri_hi_[ci][t], kReach * G_.h);
        spans_[si++] = sp;
        for (int d = 0; d < 3; ++d)
          if (sp.lo[d] <= sp.hi[d]) blo[d] = std::min(blo[d], sp.lo[d]), bhi[d] = std::max(bhi[d], sp.hi[d]);
      }
    for (int d = 0; d < 3; ++d) box_lo_[d] = box_hi_[d] = 0.0;  // cells [lo, hi) with entries: in_box()
    if (bhi[0] >= 0 && bhi[1] >= 0 && bhi[2] >= 0)
      for (int d = 0; d < 3; ++d) box_lo_[d] = blo[d], box_hi_[d] = bhi[d] + 1.0;
  }
  // 3D: the grid indices of cell (i * ny + j) * nz + k.
  std::array<int64_t, 3> cell_ijk(int64_t cell) const {
    return {cell / (static_cast<int64_t>(cells_[1]) * cells_[2]), (cell / cells_[2]) % cells_[1], cell % cells_[2]};
  }
  // The cells (clamped to the grid) that the box [lo - grow, hi + grow] overlaps.
  Span span_of(const V& lo0, const V& hi0, double grow) const {
    const V lo = lo0.array() - grow, hi = hi0.array() + grow;
    Span sp;
    for (int d = 0; d < 3; ++d) {
      sp.lo[d] = std::max(0, static_cast<int>(std::floor((lo[d] - G_.origin[d]) * inv_h_)));
      sp.hi[d] = std::min(cells_[d] - 1, static_cast<int>(std::floor((hi[d] - G_.origin[d]) * inv_h_)));
    }
    return sp;
  }
  // Are the lists built for these triangles, and is every crack point within half the margin of
  // where it was then?
  bool lists_hold_cracks() const {
    if (lists_topology_ != topology_epoch_ || lists_points_.size() != cracks_.size()) return false;
    const double slack = 0.5 * kMargin * G_.h;
    for (std::size_t ci = 0; ci < cracks_.size(); ++ci) {
      const auto& now = cracks_[ci].points;
      const auto& then = lists_points_[ci];
      if (now.size() != then.size()) return false;
      for (std::size_t i = 0; i < now.size(); ++i)
        if (!((now[i] - then[i]).cwiseAbs().maxCoeff() <= slack)) return false;
    }
    return true;
  }

  // The lists. Per crack, every triangle's box grown by kReach cells and the margin is binned into
  // the cells it overlaps (a counting sort by cell: the list of a cell holds its triangles crack by
  // crack, in triangle order, for any thread count); one entry per cell and crack. Then each entry's
  // tight list. (The work arrays are members: allocated once, not paged in afresh every step.)
  void build_index3() {
    for (int64_t c : touched_) cell_head_[c] = -1, cell_fill_[c] = 0;
    touched_.clear();
    entries_.clear();
    entry_cell_.clear();
    cell_fill_.resize(cell_head_.size(), 0);
    const double grow = (kReach + kMargin) * G_.h;
    auto for_cells = [&](const Span& sp, auto&& f) {
      for (int i = sp.lo[0]; i <= sp.hi[0]; ++i)
        for (int j = sp.lo[1]; j <= sp.hi[1]; ++j)
          for (int k = sp.lo[2]; k <= sp.hi[2]; ++k)
            f((static_cast<int64_t>(i) * cells_[1] + j) * cells_[2] + k);
    };
    // Pass 1: how many triangles each cell receives; pass 2: fill at the cells' offsets.
    std::size_t total = 0;
    list_spans_.clear();
    for (std::size_t ci = 0; ci < cracks_.size(); ++ci)
      for (std::size_t t = 0; t < cracks_[ci].simplices.size(); ++t) {
        const Span sp = span_of(tri_lo_[ci][t], tri_hi_[ci][t], grow);
        list_spans_.push_back(sp);
        for_cells(sp, [&](int64_t cell) {
          if (cell_fill_[cell]++ == 0) touched_.push_back(cell);
          ++total;
        });
      }
    std::sort(touched_.begin(), touched_.end());
    cell_offset_.resize(touched_.size() + 1);
    cell_offset_[0] = 0;
    for (std::size_t k = 0; k < touched_.size(); ++k) {
      cell_offset_[k + 1] = cell_offset_[k] + cell_fill_[touched_[k]];
      cell_fill_[touched_[k]] = static_cast<int32_t>(k);  // now: the cell's rank in touched_
    }
    tri_ids_.resize(total);
    cursor_.assign(cell_offset_.begin(), cell_offset_.end() - 1);
    tri_crack_.resize(total);
    std::size_t si = 0;
    for (std::size_t ci = 0; ci < cracks_.size(); ++ci)
      for (std::size_t t = 0; t < cracks_[ci].simplices.size(); ++t)
        for_cells(list_spans_[si++], [&](int64_t cell) {
          const int32_t at = cursor_[cell_fill_[cell]]++;
          tri_ids_[at] = static_cast<int32_t>(t);
          tri_crack_[at] = static_cast<int32_t>(ci);
        });
    // Entries: one per cell and crack, chained per cell (the last crack first, as 2D chains them);
    // their boxes from fit_entry_boxes.
    const V empty = V::Constant(std::numeric_limits<double>::infinity());
    for (std::size_t k = 0; k < touched_.size(); ++k) {
      const int64_t cell = touched_[k];
      for (int32_t a = cell_offset_[k]; a < cell_offset_[k + 1];) {
        const int32_t ci = tri_crack_[a];
        int32_t b = a;
        while (b < cell_offset_[k + 1] && tri_crack_[b] == ci) ++b;
        entries_.push_back({ci, a, b - 1, cell_head_[cell], empty, -empty});
        entry_cell_.push_back(cell);
        cell_head_[cell] = static_cast<int32_t>(entries_.size() - 1);
        a = b;
      }
      cell_fill_[cell] = 0;
    }
    build_tight_lists();
    lists_topology_ = topology_epoch_;
    lists_points_.resize(cracks_.size());
    for (std::size_t ci = 0; ci < cracks_.size(); ++ci) lists_points_[ci] = cracks_[ci].points;
  }

  // Each entry's box: that of the triangles of its list whose box grown by kReach cells overlaps the
  // entry's cell now (empty, +inf / -inf, when none does: then no particle of the cell is near it).
  // The same boxes as lists built for the cracks as they are would have. In parallel over entries.
  void fit_entry_boxes() {
    const std::size_t ne = entries_.size();
#pragma omp parallel for schedule(static) if (parallel_points(ne))
    for (std::size_t e = 0; e < ne; ++e) {
      Entry& en = entries_[e];
      const auto ijk = cell_ijk(entry_cell_[e]);
      const Span* spans = spans_.data() + crack_first_[en.crack];
      const std::vector<V>&tlo = tri_lo_[en.crack], &thi = tri_hi_[en.crack];
      V lo = V::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
      for (int32_t a = en.seg_lo; a <= en.seg_hi; ++a) {
        const int32_t t = tri_ids_[a];
        const Span& sp = spans[t];
        if (ijk[0] < sp.lo[0] || ijk[0] > sp.hi[0] || ijk[1] < sp.lo[1] || ijk[1] > sp.hi[1] || ijk[2] < sp.lo[2] ||
            ijk[2] > sp.hi[2])
          continue;
        lo = lo.cwiseMin(tlo[t]), hi = hi.cwiseMax(thi[t]);
      }
      en.lo = lo, en.hi = hi;
    }
  }

  // 3D, per entry: its tight list, the triangles of its range whose boxes, grown by the margin,
  // meet the closed box S of its cell grown by kTightGrow cells (S is stored with the entry: the test
  // that a particle's box lies in S must see the very doubles that chose the list). In parallel over
  // entries, each list at the offset of a prefix sum of the counts: the same lists for any thread count.
  void build_tight_lists() {
    const std::size_t ne = entries_.size();
    tight_.resize(ne);
    const double m = kMargin * G_.h;
    auto meets = [&](const Tight& T, int32_t ci, int32_t t) {
      return (tri_hi_[ci][t].array() + m >= T.lo.array()).all() && (tri_lo_[ci][t].array() - m <= T.hi.array()).all();
    };
#pragma omp parallel for schedule(static) if (parallel_points(ne))
    for (std::size_t e = 0; e < ne; ++e) {
      const Entry& en = entries_[e];
      Tight& T = tight_[e];
      const auto ijk = cell_ijk(entry_cell_[e]);
      for (int d = 0; d < 3; ++d) {
        T.lo[d] = G_.origin[d] + G_.h * (static_cast<double>(ijk[d]) - kTightGrow);
        T.hi[d] = G_.origin[d] + G_.h * (static_cast<double>(ijk[d]) + 1.0 + kTightGrow);
      }
      int32_t n = 0;
      for (int32_t a = en.seg_lo; a <= en.seg_hi; ++a) n += meets(T, en.crack, tri_ids_[a]);
      T.count = n;
    }
    tight_begin_.resize(ne + 1);
    tight_begin_[0] = 0;
    for (std::size_t e = 0; e < ne; ++e) tight_begin_[e + 1] = tight_begin_[e] + tight_[e].count;
    tight_ids_.resize(static_cast<std::size_t>(tight_begin_[ne]));
#pragma omp parallel for schedule(static) if (parallel_points(ne))
    for (std::size_t e = 0; e < ne; ++e) {
      const Entry& en = entries_[e];
      int32_t at = tight_begin_[e];
      for (int32_t a = en.seg_lo; a <= en.seg_hi; ++a)
        if (meets(tight_[e], en.crack, tri_ids_[a])) tight_ids_[at++] = tri_ids_[a];
    }
  }

  // 3D: the first index entry of a cell whose tight lists serve the closed box [lo, hi] (a particle
  // and its stencil nodes), or -1 (then the full lists of `cell`, the particle's, serve). The cell is
  // the one holding the box's centre; it serves when its box S holds [lo, hi] and it is `cell` or a
  // neighbour of it. Exact: every triangle that meets [lo, hi] meets S, so it is in the tight list,
  // and it lies within 1 + kTightGrow cells of `cell`, so it is in `cell`'s full list (kReach);
  // the lists keep triangle order. The box's triangles are thus the same from either list.
  int32_t tight_head(int64_t cell, const V& lo, const V& hi) const {
    const auto own = cell_ijk(cell);
    int64_t c = 0;
    for (int d = 0; d < 3; ++d) {
      const double f = (0.5 * (lo[d] + hi[d]) - G_.origin[d]) * inv_h_;
      const int64_t i = std::clamp<int64_t>(static_cast<int64_t>(std::floor(f)), 0, cells_[d] - 1);
      if (i < own[d] - 1 || i > own[d] + 1) return -1;
      c = c * cells_[d] + i;
    }
    const int32_t e = cell_head_[c];
    if (e < 0) return -1;
    const Tight& T = tight_[static_cast<std::size_t>(e)];
    return (lo.array() >= T.lo.array()).all() && (hi.array() <= T.hi.array()).all() ? e : -1;
  }

  // 3D: bumps crack_epoch_ when a crack's points, triangles or faces differ, bit for bit, from their
  // copies of the last call (then taken afresh). Whatever is a function of the crack geometry alone
  // (the index, the side-field keys, a particle's keys) is kept while the epoch stays.
  void note_crack_state() {
    bool same = state_.size() == cracks_.size(), same_topology = same;
    state_.resize(cracks_.size());
    auto keep = [](auto& kept, const auto& now) {  // true when kept equals now; kept = now
      if (kept.size() == now.size() && std::memcmp(kept.data(), now.data(), now.size() * sizeof(now[0])) == 0)
        return true;
      kept = now;
      return false;
    };
    for (std::size_t ci = 0; ci < cracks_.size(); ++ci) {
      const auto& c = cracks_[ci];
      CrackState& st = state_[ci];
      const bool p = keep(st.points, c.points), a = keep(st.above, c.above), b = keep(st.below, c.below),
                 t = keep(st.simplices, c.simplices);
      same = same && p && a && b && t;
      same_topology = same_topology && t;
    }
    if (!same) ++crack_epoch_;
    if (!same_topology) ++topology_epoch_;
  }

  std::vector<crack::ExplicitCrack<Dim>>& cracks_;
  struct CrackState {  // a crack's geometry at the last note_crack_state
    std::vector<V> points, above, below;
    std::vector<std::array<int32_t, Dim>> simplices;
  };
  std::vector<CrackState> state_;
  uint64_t crack_epoch_ = 0, index_epoch_ = ~uint64_t{0};
  uint64_t topology_epoch_ = 0, lists_topology_ = ~uint64_t{0};  // 3D: bumped when a crack's triangles change
  double near_reach_;  // a particle is near when within this distance of an index entry's box
  std::vector<int32_t> cell_head_;
  double box_lo_[Dim] = {}, box_hi_[Dim] = {};  // cells [lo, hi) holding all index entries
  std::vector<int32_t> tri_ids_, cell_offset_, cell_fill_;  // 3D (build_index3)
  std::vector<Span> spans_;       // 3D, per triangle (crack by crack, from crack_first_): its box grown by kReach cells, now
  std::vector<Span> list_spans_;  // the same grown by the margin too, when the lists were built
  std::vector<int64_t> crack_first_;
  static constexpr double kMargin = 1.0 / 16;  // cells (fit_index3)
  std::vector<std::vector<V>> lists_points_;   // the crack points when the lists were built
  std::vector<int32_t> cursor_, tri_crack_;
  // 3D tight lists (build_tight_lists): S is a cell grown by kTightGrow cells, so that the box of a
  // particle and its stencil (one cell linear, two uGIMP) fits, as does a crack-surface probe's a
  // hair off its cell.
  static constexpr double kTightGrow = (SF::K - 2) + 1.0 / 16;
  struct Tight {
    V lo, hi;  // S
    int32_t count;
  };
  std::vector<Tight> tight_;  // per entry
  std::vector<int32_t> tight_begin_, tight_ids_;  // entry e's tight list: tight_ids_[tight_begin_[e] ..]
  std::vector<int64_t> entry_cell_;  // per entry: its cell
  std::vector<std::vector<V>> tri_lo_, tri_hi_;  // 3D, per crack and triangle: its bounding box
  std::vector<int64_t> touched_;
  std::vector<Entry> entries_;
};

}  // namespace cleave::crack_fields
