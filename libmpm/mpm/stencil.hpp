// Node indices, weights and weight gradients of one particle: the tensor product of the per-axis
// shape functions (S_ip and G_ip of seed 002 eq. 24), recomputed in each pass rather than stored,
// because on a regular grid the separable evaluation is cheaper than streaming a cache.
#pragma once
#include <array>
#include <cstdint>

#include "libmpm/core/types.hpp"
#include "libmpm/mpm/grid.hpp"
#include "libmpm/shape/shape_function.hpp"

namespace cleave {

template <int Dim, class SF>
struct Stencil {
  static constexpr int K = SF::K;
  static constexpr int N = Dim == 2 ? K * K : K * K * K;
  // Per-axis weights and derivatives (derivatives already divided by the cell size) and the
  // first node. The tensor products are formed on the fly in for_each, in registers: storing
  // them as arrays costs more (store-forwarding stalls) than the few multiplications.
  double w1[Dim][K], d1[Dim][K];
  int64_t base;
  std::array<std::size_t, Dim> stride;

  // l[d]: particle half-width in cells along axis d (0 along a loaded face's normal).
  // (Always inlined: called once per particle in every pass, and GCC leaves it out of line in the
  // larger pass bodies, ~7 % of a step spent in the call.)
  CLEAVE_INLINE inline void eval(const GridGeometry<Dim>& G, const std::array<std::size_t, Dim>& strides,
                                 double inv_h, const Vec<Dim>& x, const double* l) {
    stride = strides;
    base = 0;
    for (int d = 0; d < Dim; ++d) {
      const int b = SF::eval((x[d] - G.origin[d]) * inv_h, l[d], w1[d], d1[d]);
      for (int a = 0; a < K; ++a) d1[d][a] *= inv_h;
      base += b * int64_t(stride[d]);
    }
  }
  CLEAVE_INLINE inline void eval(const GridGeometry<Dim>& G, const std::array<std::size_t, Dim>& strides,
                                 double inv_h, const Vec<Dim>& x, double l) {
    double ls[Dim];
    for (int d = 0; d < Dim; ++d) ls[d] = l;
    eval(G, strides, inv_h, x, ls);
  }

  // f(node, weight S_ip, gradient G_ip) for every node of the stencil.
  template <class F>
  inline void for_each(F&& f) const {
    if constexpr (Dim == 2) {
      for (int a = 0; a < K; ++a) {
        const int64_t row = base + a * int64_t(stride[0]);
        for (int c = 0; c < K; ++c) {
          const Vec<2> g(d1[0][a] * w1[1][c], w1[0][a] * d1[1][c]);
          f(row + c, w1[0][a] * w1[1][c], g);
        }
      }
    } else {
      for (int a = 0; a < K; ++a)
        for (int c = 0; c < K; ++c) {
          const int64_t row = base + a * int64_t(stride[0]) + c * int64_t(stride[1]);
          const double wxy = w1[0][a] * w1[1][c];
          for (int e = 0; e < K; ++e) {
            const Vec<3> g(d1[0][a] * w1[1][c] * w1[2][e], w1[0][a] * d1[1][c] * w1[2][e], wxy * d1[2][e]);
            f(row + e, wxy * w1[2][e], g);
          }
        }
    }
  }
  // f(node, weight) when no gradient is needed.
  template <class F>
  inline void for_each_weight(F&& f) const {
    if constexpr (Dim == 2) {
      for (int a = 0; a < K; ++a)
        for (int c = 0; c < K; ++c) f(base + a * int64_t(stride[0]) + c, w1[0][a] * w1[1][c]);
    } else {
      for (int a = 0; a < K; ++a)
        for (int c = 0; c < K; ++c) {
          const int64_t row = base + a * int64_t(stride[0]) + c * int64_t(stride[1]);
          const double wxy = w1[0][a] * w1[1][c];
          for (int e = 0; e < K; ++e) f(row + e, wxy * w1[2][e]);
        }
    }
  }
};

// True when every node of a particle at x exists: the "left the grid" test.
template <int Dim, class SF>
inline bool stencil_inside(const GridGeometry<Dim>& G, double inv_h, const Vec<Dim>& x) {
  bool inside = true;
  for (int d = 0; d < Dim; ++d) inside = inside && stencil_fits((x[d] - G.origin[d]) * inv_h, G.nodes[d], SF::K);
  return inside;
}

}  // namespace cleave
