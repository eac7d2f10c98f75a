#include "libmpm/pd/tips.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace cleave::pd {

template <int Dim>
std::optional<std::size_t> find_tip(const PdSystem<Dim>& m, const std::vector<double>& damage,
                                    const TipTracker<Dim>& t, double threshold) {
  std::optional<std::size_t> best;
  double best_proj = 0.0;
  const double tol = 1e-9 * m.dx;
  for (std::size_t p = 0; p < m.points.size(); ++p) {
    if (!(damage[p] > threshold)) continue;
    const Vec<Dim>& x = m.points.x0[p];
    if (t.has_region) {
      bool in = true;
      for (int d = 0; d < Dim; ++d) in = in && x[d] >= t.lo[d] - tol && x[d] <= t.hi[d] + tol;
      if (!in) continue;
    }
    const double proj = x.dot(t.direction);
    if (!best || proj > best_proj) best = p, best_proj = proj;
  }
  return best;
}

std::optional<BranchPoint> find_branch(const PdSystem<2>& m, const std::vector<double>& damage, double x_min,
                                       double threshold, int min_columns) {
  // Lattice indices: points sit at (k + 1/2) dx.
  std::map<long, std::vector<long>> columns;  // column -> damaged rows
  for (std::size_t p = 0; p < m.points.size(); ++p) {
    const Vec<2>& x = m.points.x0[p];
    if (x.x() <= x_min || !(damage[p] > threshold)) continue;
    columns[std::lround(x.x() / m.dx - 0.5)].push_back(std::lround(x.y() / m.dx - 0.5));
  }
  long run_start = 0, prev = 0;
  int streak = 0;
  BranchPoint first{};
  for (auto& [col, rows] : columns) {
    std::sort(rows.begin(), rows.end());
    // Runs: a new run starts after a gap of >= 2 undamaged rows (index step >= 3).
    std::vector<std::pair<long, long>> runs;
    for (long r : rows) {
      if (runs.empty() || r - runs.back().second >= 3) runs.emplace_back(r, r);
      else runs.back().second = r;
    }
    const bool forked = runs.size() >= 2;
    if (forked && streak > 0 && col == prev + 1) {
      ++streak;
    } else if (forked) {
      streak = 1;
      run_start = col;
      const double y_lo = (runs.front().second + 0.5) * m.dx, y_hi = (runs.back().first + 0.5) * m.dx;
      first = {(col + 0.5) * m.dx, 0.5 * (y_lo + y_hi)};
    } else {
      streak = 0;
    }
    prev = col;
    if (streak >= min_columns) return first;
  }
  (void)run_start;
  return std::nullopt;
}

template std::optional<std::size_t> find_tip<2>(const PdSystem<2>&, const std::vector<double>&,
                                                const TipTracker<2>&, double);
template std::optional<std::size_t> find_tip<3>(const PdSystem<3>&, const std::vector<double>&,
                                                const TipTracker<3>&, double);

}  // namespace cleave::pd
