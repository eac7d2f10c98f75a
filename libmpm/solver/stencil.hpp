// Node indices, weights and weight gradients of one particle: the tensor product of the per-axis
// shape functions (S_ip and G_ip of seed 002 eq. 24), recomputed in each pass rather than stored,
// because on a regular grid the separable evaluation is cheaper than streaming a cache.
#pragma once
#include <cstdint>

#include "libmpm/core/types.hpp"
#include "libmpm/model/grid.hpp"

namespace cleave {

template <int Dim, class SF>
struct Stencil {
  static constexpr int K = SF::K;
  static constexpr int N = Dim == 2 ? K * K : K * K * K;
  int64_t node[N];
  double w[N];
  Vec<Dim> g[N];

  // l[d]: particle half-width in cells along axis d (0 along a loaded face's normal).
  inline void eval(const GridGeometry<Dim>& G, const std::array<std::size_t, Dim>& stride, double inv_h,
                   const Vec<Dim>& x, const double* l) {
    double w1[Dim][K], d1[Dim][K];
    int base[Dim];
    for (int d = 0; d < Dim; ++d) base[d] = SF::eval((x[d] - G.origin[d]) * inv_h, l[d], w1[d], d1[d]);
    if constexpr (Dim == 2) {
      const int64_t b = base[0] * int64_t(stride[0]) + base[1];
      for (int a = 0; a < K; ++a)
        for (int c = 0; c < K; ++c) {
          const int k = a * K + c;
          node[k] = b + a * int64_t(stride[0]) + c;
          w[k] = w1[0][a] * w1[1][c];
          g[k][0] = d1[0][a] * w1[1][c] * inv_h;
          g[k][1] = w1[0][a] * d1[1][c] * inv_h;
        }
    } else {
      const int64_t b = base[0] * int64_t(stride[0]) + base[1] * int64_t(stride[1]) + base[2];
      for (int a = 0; a < K; ++a)
        for (int c = 0; c < K; ++c)
          for (int e = 0; e < K; ++e) {
            const int k = (a * K + c) * K + e;
            node[k] = b + a * int64_t(stride[0]) + c * int64_t(stride[1]) + e;
            const double wyz = w1[1][c] * w1[2][e];
            w[k] = w1[0][a] * wyz;
            g[k][0] = d1[0][a] * wyz * inv_h;
            g[k][1] = w1[0][a] * d1[1][c] * w1[2][e] * inv_h;
            g[k][2] = w1[0][a] * w1[1][c] * d1[2][e] * inv_h;
          }
    }
  }
  inline void eval(const GridGeometry<Dim>& G, const std::array<std::size_t, Dim>& stride, double inv_h,
                   const Vec<Dim>& x, double l) {
    double ls[Dim];
    for (int d = 0; d < Dim; ++d) ls[d] = l;
    eval(G, stride, inv_h, x, ls);
  }
};

// True when every node of a particle at x (half-width l cells) exists: the "left the grid" test.
template <int Dim, class SF>
inline bool stencil_inside(const GridGeometry<Dim>& G, double inv_h, const Vec<Dim>& x, double l) {
  for (int d = 0; d < Dim; ++d) {
    const double xi = (x[d] - G.origin[d]) * inv_h;
    if (!(xi > 0.0 && xi < G.nodes[d] - 1)) return false;
    const int base = SF::K == 3 ? static_cast<int>(std::floor(xi + 0.5)) - 1 : static_cast<int>(std::floor(xi));
    if (base < 0 || base + SF::K - 1 > G.nodes[d] - 1) return false;
  }
  (void)l;
  return true;
}

}  // namespace cleave
