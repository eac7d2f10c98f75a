// Bottom layer of the crack fields (libmpm/mpm/crack_fields.hpp): the cell and node arithmetic
// every layer above shares. The crossing test is exact on the doubles it is given, so the spatial
// index, the classification and the surface look-ups must compute a point's cell and a node's
// position with the very same expressions: they all inherit them from here.
//
// Why layers: CrackFields is one object built as a chain of single inheritance (grid cells ->
// spatial index -> classification -> field slots -> crack motion -> contact -> CrackFields), each
// layer using the arrays and functions of those below it through the same `this`, as when it was
// one class. Separate objects joined by references compiled to other code, and GCC, which fuses
// multiplies and adds (-ffp-contract=fast) as the shape of the inlined code suggests, then
// rounded some sums differently: the results must stay bit-identical. For the same reason the
// functions that the stepper's passes inline are defined in CrackFields itself (see there).
//
// Cells are numbered i * ny + j (2D) or (i * ny + j) * nz + k (3D), nodes as the grid numbers them
// (grid.hpp); a point's cell has 2^Dim nodes. The 2D expressions are kept exactly as they were
// written for 2D alone: the results are bit-identical to theirs.
#pragma once
#include <omp.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>

#include "libmpm/core/types.hpp"
#include "libmpm/mpm/grid.hpp"

namespace cleave::crack_fields {

template <int Dim>
class GridCells {
  using V = Vec<Dim>;

 protected:
  explicit GridCells(const GridGeometry<Dim>& G) : G_(G) {
    stride_ = G_.strides();
    inv_h_ = 1.0 / G_.h;
    for (int d = 0; d < Dim; ++d) cells_[d] = G_.nodes[d] - 1;
  }

  std::size_t cell_count() const {
    std::size_t n = 1;
    for (int d = 0; d < Dim; ++d) n *= static_cast<std::size_t>(cells_[d]);
    return n;
  }

  // The cell holding x, or -1 outside the grid.
  int64_t cell_of(const V& x) const {
    if constexpr (Dim == 3) {
      int64_t c = 0;
      for (int d = 0; d < 3; ++d) {
        const double f = (x[d] - G_.origin[d]) * inv_h_;
        if (!(f >= 0.0 && f < cells_[d])) return -1;
        c = c * cells_[d] + static_cast<int64_t>(f);
      }
      return c;
    } else {
      const double fx = (x.x() - G_.origin.x()) * inv_h_, fy = (x.y() - G_.origin.y()) * inv_h_;
      if (!(fx >= 0.0 && fy >= 0.0 && fx < cells_[0] && fy < cells_[1])) return -1;
      return static_cast<int64_t>(fx) * cells_[1] + static_cast<int64_t>(fy);
    }
  }

  V node_position(int64_t n) const {
    if constexpr (Dim == 3) {
      const int64_t i = n / stride_[0], r = n % stride_[0];
      return node_position(i, r / stride_[1], r % stride_[1]);
    } else {
      const int64_t i = n / stride_[0], j = n % stride_[0];
      return node_position(i, j);
    }
  }
  V node_position(int64_t i, int64_t j) const
    requires(Dim == 2)
  {
    return V(G_.origin.x() + G_.h * i, G_.origin.y() + G_.h * j);
  }
  V node_position(int64_t i, int64_t j, int64_t k) const
    requires(Dim == 3)
  {
    return V(G_.origin.x() + G_.h * i, G_.origin.y() + G_.h * j, G_.origin.z() + G_.h * k);
  }

  // The 2^Dim nodes of x's cell with (bi/tri)linear weights (massless crack particles have no size).
  template <class F>
  void linear_nodes(const V& x, F&& f) const {
    if constexpr (Dim == 3) {
      double r[3];
      int64_t n0 = 0;
      for (int d = 0; d < 3; ++d) {
        const double fd = (x[d] - G_.origin[d]) * inv_h_;
        if (!(fd >= 0.0 && fd <= cells_[d])) return;
        const int i = std::min(static_cast<int>(fd), cells_[d] - 1);
        r[d] = fd - i;
        n0 += static_cast<int64_t>(i) * static_cast<int64_t>(stride_[d]);
      }
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b)
          for (int c = 0; c < 2; ++c)
            f(n0 + a * static_cast<int64_t>(stride_[0]) + b * static_cast<int64_t>(stride_[1]) + c,
              (a ? r[0] : 1 - r[0]) * (b ? r[1] : 1 - r[1]) * (c ? r[2] : 1 - r[2]));
      return;
    }
    const double fx = (x.x() - G_.origin.x()) * inv_h_, fy = (x.y() - G_.origin.y()) * inv_h_;
    if (!(fx >= 0.0 && fy >= 0.0 && fx <= cells_[0] && fy <= cells_[1])) return;
    const int i = std::min(static_cast<int>(fx), cells_[0] - 1), j = std::min(static_cast<int>(fy), cells_[1] - 1);
    const double rx = fx - i, ry = fy - j;
    const int64_t n00 = static_cast<int64_t>(i) * stride_[0] + j;
    f(n00, (1 - rx) * (1 - ry));
    f(n00 + 1, (1 - rx) * ry);
    f(n00 + stride_[0], rx * (1 - ry));
    f(n00 + stride_[0] + 1, rx * ry);
  }

  // Loops over crack points or multi-field nodes (a few hundred, each ~0.1-0.3 us of work) pay for
  // a fork/join from about this many.
  static constexpr std::size_t kParallelPoints = 128;
  static bool parallel_points(std::size_t n) { return n >= kParallelPoints && omp_get_max_threads() > 1; }

  const GridGeometry<Dim>& G_;
  std::array<std::size_t, Dim> stride_;
  double inv_h_;
  int cells_[Dim];
};

}  // namespace cleave::crack_fields
