// What the stepper keeps from one crack-front evaluation to the next (crack_front_eval.hpp): the
// particles near the fronts, binned, and the evaluation's buffers.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "libmpm/mpm/crack_front_fit.hpp"
#include "libmpm/mpm/crack_front_sums.hpp"

namespace cleave::detail {

// The particles near the fronts and their bins, kept from one evaluation to the next by the stepper
// that owns this (bins_for), with the evaluation's buffers (sums, fits). A list of the particles of a
// box of cells two cells wider on each side than the box an evaluation needs, made in one pass over
// all particles, holds every particle of a later evaluation's box as long as that box, grown by how
// far a particle may have moved since (travel, a bound the stepper keeps), lies in the listed one: an
// evaluation then tests the list instead of all particles, and keeps the last bins when no particle
// of the list changed cell.
struct FrontParticles {
  double travel = 0.0;  // set by the owner before each evaluation: its bound on any particle's path
  // The nodal sums and the rigid-motion fits of the last evaluation, whose memory the next one reuses
  // (made afresh, their buffers were zeroed and faulted in by one thread each time: on the rod at 3 mm
  // cells about a tenth of an evaluation at two threads).
  NodeSums sums;
  FitCells fits;

  // The particles of x in the grid's cells that meet [box_lo, box_hi], binned: the same bins as
  // CellBins::build's.
  const CellBins& bins_for(const GridGeometry<3>& G, const std::vector<Vec<3>>& x, const Vec<3>& box_lo,
                           const Vec<3>& box_hi) {
    CellBins box;
    box.set_box(G, box_lo, box_hi);
    std::array<int64_t, 3> cells;
    for (int d = 0; d < 3; ++d) cells[d] = std::max(1, G.nodes[d] - 1);
    bool holds = particles_ == x.size() && travel >= listed_at_;
    if (holds) {
      // A particle outside the listed box then has since moved by at most `moved` cells (+ rounding).
      const int64_t moved = static_cast<int64_t>(std::ceil((travel - listed_at_) / G.h + 1e-9));
      for (int d = 0; d < 3; ++d)
        holds = holds && (box.lo[d] - moved >= lo_[d] || lo_[d] == 0) &&
                (box.lo[d] + box.n[d] - 1 + moved <= hi_[d] || hi_[d] == cells[d] - 1);
    }
    if (!holds) {  // list afresh
      std::array<int64_t, 3> span;
      for (int d = 0; d < 3; ++d) {
        lo_[d] = std::max<int64_t>(0, box.lo[d] - 2), hi_[d] = std::min(cells[d] - 1, box.lo[d] + box.n[d] + 1);
        span[d] = hi_[d] - lo_[d] + 1;
      }
      std::vector<int64_t> in(x.size());
      CellBins::cells_in_box(G, x, lo_, span, nullptr, x.size(), in.data());
      list_.clear();
      for (std::size_t p = 0; p < x.size(); ++p)
        if (in[p] >= 0) list_.push_back(static_cast<int32_t>(p));
      listed_at_ = travel, particles_ = x.size();
      cell_.clear();
    }
    // No listed particle has changed cell while none can have moved as far as the nearest was from
    // a face of its cell when the cells were taken.
    if (holds && box.lo == bins_.lo && box.n == bins_.n && travel < same_cells_until_) return bins_;
    next_.resize(list_.size());
    const double slack = CellBins::cells_in_box(G, x, box.lo, box.n, list_.data(), list_.size(), next_.data());
    same_cells_until_ = travel + (slack - 1e-9) * G.h;  // (less the rounding of the cell coordinates)
    if (box.lo != bins_.lo || box.n != bins_.n || next_ != cell_) {
      box.place(list_.data(), next_.data(), list_.size());
      bins_ = std::move(box);
      cell_.swap(next_);
    }
    return bins_;
  }

 private:
  std::vector<int32_t> list_;           // in index order
  std::array<int64_t, 3> lo_{}, hi_{};  // the listed box (cells, inclusive)
  double listed_at_ = 0.0;              // travel when listed
  std::size_t particles_ = 0;           // the model's particle count then (0: nothing listed)
  std::vector<int64_t> cell_, next_;    // per listed particle: its cell in bins_'s box, or -1 (next_: scratch)
  double same_cells_until_ = -1.0;      // travel until which no listed particle can change cell
  CellBins bins_;
};

}  // namespace cleave::detail
