// Bond lists for bond-based peridynamics on a (possibly perturbed) lattice of points.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "libmpm/core/types.hpp"

namespace cleave::pd {

// Structure of arrays, one entry per bond. Each bond is stored once with i < j, and the list is
// sorted by i, then j, so it does not depend on the thread count or on the binning.
template <int Dim> struct BondList {
  std::vector<int32_t> i, j;
  std::vector<double> xi_len;      // reference bond length |x_j - x_i|
  std::vector<double> vol_factor;  // partial-volume factor beta in (0, 1]
  std::vector<uint8_t> intact;     // 1 while the bond carries force, 0 once broken

  std::size_t size() const { return i.size(); }
};

// All pairs with |xi| < delta + dx/2 (xi = x[j] - x[i]), found by binning the points into cells
// of edge delta + dx/2 (so only the 3^Dim surrounding cells are searched; O(N) expected).
// Partial-volume factor: beta = 1 for |xi| <= delta - dx/2, (delta + dx/2 - |xi|)/dx above.
// A pair at exactly |xi| = delta + dx/2 would get beta = 0 and is left out.
// Throws std::invalid_argument for dx <= 0, delta <= 0, non-finite coordinates, coincident points
// or more than 2^31 - 1 points.
template <int Dim>
BondList<Dim> build_bonds(const std::vector<Vec<Dim>>& x, double dx, double delta);

// Stable explicit time step (Silling & Askari 2005, velocity-Verlet / central difference):
//   dt = min over points i of sqrt(2 rho / sum_j beta_ij V_j c_ij),   c_ij = c / |xi_ij|
// (the PMB bond stiffness: d(c s)/du = c/|xi|), summed over intact bonds of i, with beta_ij the
// partial-volume factor. Points without intact bonds impose no limit; with none anywhere the result
// is +infinity. Apply a safety factor < 1 at the call site. Throws std::invalid_argument if
// volume.size() != n_points, c <= 0, rho <= 0 or a bond index is out of range.
template <int Dim>
double stable_dt(const BondList<Dim>& bonds, const std::vector<double>& volume, double c, double rho,
                 std::size_t n_points);

}  // namespace cleave::pd
