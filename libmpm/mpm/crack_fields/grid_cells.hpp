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
// 2D only: cells are numbered i * ny + j and nodes i * stride + j, and a point's cell has four
// nodes; the crack fields exist for crack::Crack2D polylines alone.
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
  static_assert(Dim == 2, "crack fields: 2D only (cells i * ny + j, four nodes per cell)");
  using V = Vec<Dim>;

 protected:
  explicit GridCells(const GridGeometry<Dim>& G) : G_(G) {
    stride_ = G_.strides();
    inv_h_ = 1.0 / G_.h;
    cells_[0] = G_.nodes[0] - 1;
    cells_[1] = G_.nodes[1] - 1;
  }

  // The cell holding x, or -1 outside the grid.
  int64_t cell_of(const V& x) const {
    const double fx = (x.x() - G_.origin.x()) * inv_h_, fy = (x.y() - G_.origin.y()) * inv_h_;
    if (!(fx >= 0.0 && fy >= 0.0 && fx < cells_[0] && fy < cells_[1])) return -1;
    return static_cast<int64_t>(fx) * cells_[1] + static_cast<int64_t>(fy);
  }

  V node_position(int64_t n) const {
    const int64_t i = n / stride_[0], j = n % stride_[0];
    return node_position(i, j);
  }
  V node_position(int64_t i, int64_t j) const { return V(G_.origin.x() + G_.h * i, G_.origin.y() + G_.h * j); }

  // The four nodes of x's cell with bilinear weights (massless crack particles have no size).
  template <class F>
  void linear_nodes(const V& x, F&& f) const {
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
