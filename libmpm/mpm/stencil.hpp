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
  // sum over the nodes of u(n) g_n^T (the velocity gradient, eq. 36, from nodal velocities u). The
  // gradients are products of the per-axis factors (2D: g = (d0 w1, w0 d1)), so each row of nodes sums
  // u against its last axis's weights and derivatives once and scales the two sums by the row's factors:
  // two vector multiply-adds per node instead of forming g and its outer product (2D: 4 against 6
  // multiplications a node; 3D: 6 against 14).
  template <class U>
  CLEAVE_INLINE inline Mat<Dim> gradient(U&& u) const {
    constexpr int L = Dim - 1;  // the innermost axis
    Vec<Dim> col[Dim];
    for (int j = 0; j < Dim; ++j) col[j].setZero();
    auto row_sums = [&](int64_t row, Vec<Dim>& sw, Vec<Dim>& sd) CLEAVE_INLINE {
      sw.setZero(), sd.setZero();
      for (int e = 0; e < K; ++e) {
        const Vec<Dim>& v = u(row + e);
        axpy(sw, w1[L][e], v);
        axpy(sd, d1[L][e], v);
      }
    };
    Vec<Dim> sw, sd;
    if constexpr (Dim == 2) {
      for (int a = 0; a < K; ++a) {
        row_sums(base + a * int64_t(stride[0]), sw, sd);
        axpy(col[0], d1[0][a], sw);
        axpy(col[1], w1[0][a], sd);
      }
    } else {
      for (int a = 0; a < K; ++a)
        for (int c = 0; c < K; ++c) {
          row_sums(base + a * int64_t(stride[0]) + c * int64_t(stride[1]), sw, sd);
          axpy(col[0], d1[0][a] * w1[1][c], sw);
          axpy(col[1], w1[0][a] * d1[1][c], sw);
          axpy(col[2], w1[0][a] * w1[1][c], sd);
        }
    }
    Mat<Dim> G;
    for (int j = 0; j < Dim; ++j) G.col(j) = col[j];
    return G;
  }
  // f(node, s . g_n) for a symmetric s stored as Sym (the internal force's share, eq. 28), factored by
  // rows like gradient(): s . g = (s_0 g_0 + ...), so a row's first factors scale s's columns once.
  template <class F>
  CLEAVE_INLINE inline void for_each_divergence(const Sym<Dim>& s, F&& f) const {
    if constexpr (Dim == 2) {
      const Vec<2> s0(s[0], s[3]), s1(s[3], s[1]);
      for (int a = 0; a < K; ++a) {
        const int64_t row = base + a * int64_t(stride[0]);
        const Vec<2> A = d1[0][a] * s0, B = w1[0][a] * s1;
        for (int c = 0; c < K; ++c) f(row + c, Vec<2>(w1[1][c] * A + d1[1][c] * B));
      }
    } else {
      const Vec<3> s0(s[0], s[3], s[5]), s1(s[3], s[1], s[4]), s2(s[5], s[4], s[2]);
      for (int a = 0; a < K; ++a)
        for (int c = 0; c < K; ++c) {
          const int64_t row = base + a * int64_t(stride[0]) + c * int64_t(stride[1]);
          const Vec<3> A = (d1[0][a] * w1[1][c]) * s0 + (w1[0][a] * d1[1][c]) * s1, B = (w1[0][a] * w1[1][c]) * s2;
          for (int e = 0; e < K; ++e) f(row + e, Vec<3>(w1[2][e] * A + d1[2][e] * B));
        }
    }
  }

  // y += a x. For the 3D linear shape (K = 2) component by component: with Eigen's operator+= GCC left
  // the sum out of line in that stress pass (the rod of issue 17), a call per node that cost more than
  // the factoring saves. Elsewhere Eigen's form, which GCC inlines and which measured faster (the 2D
  // DCB's stress passes 3.8-3.9 against 4.0-4.2 Task-1 units, 2D linear 5.6-5.7 against 6.55;
  // docs/performance.md).
  static CLEAVE_INLINE inline void axpy(Vec<Dim>& y, double a, const Vec<Dim>& x) {
    if constexpr (K == 2 && Dim == 3) {
      y[0] += a * x[0], y[1] += a * x[1], y[2] += a * x[2];
    } else {
      y += a * x;
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
