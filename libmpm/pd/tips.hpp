// Crack tips and branching from the damage field (seed 003): a tip is the point with damage above
// a threshold (0.3) lying farthest along a tracker's direction; crack speed is the distance between
// successive tips over the time between them. Branching (2D) is read from lattice columns.
#pragma once
#include <optional>
#include <vector>

#include "libmpm/pd/pd_model.hpp"

namespace cleave::pd {

// Index of the point with damage > threshold maximising x0 . direction inside the tracker's region
// (reference positions, so the path is drawn in the undeformed body); none when no point qualifies.
// Ties go to the lowest index.
template <int Dim>
std::optional<std::size_t> find_tip(const PdSystem<Dim>& m, const std::vector<double>& damage,
                                    const TipTracker<Dim>& t, double threshold);

struct BranchPoint {
  double x = 0.0, y = 0.0;  // reference position of the fork (m)
};

// 2D branching test on lattice columns (constant x) with x0 > x_min: in each column the points
// with damage > threshold form runs along y, two runs being separate when at least two undamaged
// lattice rows lie between them. The crack has branched when `min_columns` consecutive columns
// each hold two or more runs; the fork is the first of those columns, at the mean y of its two
// outermost runs' inner ends. One running crack is one run per column (its damaged band).
std::optional<BranchPoint> find_branch(const PdSystem<2>& m, const std::vector<double>& damage, double x_min,
                                       double threshold, int min_columns = 3);

}  // namespace cleave::pd
