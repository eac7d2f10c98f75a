// Grid shape functions, evaluated per axis and combined as tensor products (both styles are
// separable on a regular grid, which is what makes them cheap). A style is a small struct with a
// compile-time stencil width K; the solver is templated on it so the hot loops are fully unrolled.
#pragma once
#include <algorithm>
#include <cmath>

#include "libmpm/core/types.hpp"

namespace cleave {

// The style a model uses (Model::shape_function); styles are registered by name
// (shape_registry.hpp), each with the stepper compiled for it.
enum class ShapeFunctionKind { Linear, UGimp };

// Linear (bilinear/trilinear) hat functions: 2 nodes per axis.
struct LinearShape {
  static constexpr int K = 2;
  static constexpr const char* name = "linear";
  static constexpr ShapeFunctionKind kind = ShapeFunctionKind::Linear;
  // xi: particle coordinate in cells from the grid origin; l: particle half-width in cells (unused).
  CLEAVE_INLINE static inline int eval(double xi, double /*l*/, double* w, double* dw) {
    const double fl = static_cast<double>(static_cast<int>(xi));  // xi > 0 inside the grid
    const double f = xi - fl;
    w[0] = 1.0 - f;
    w[1] = f;
    dw[0] = -1.0;
    dw[1] = 1.0;
    return static_cast<int>(fl);
  }
};

// uGIMP (Bardenhagen & Kober): the hat function averaged over the particle's undeformed domain of
// half-width l (0 < l <= 1/2 cell). 3 nodes per axis. Written as the difference of the hat's
// antiderivative H at d +- l, which is branch-free (min/max only): the piecewise form branches on
// data and mispredicts in the hot loops.
struct UGimpShape {
  static constexpr int K = 3;
  static constexpr const char* name = "ugimp";
  static constexpr ShapeFunctionKind kind = ShapeFunctionKind::UGimp;
  // H(s) = integral of max(0, 1 - |t|) from -inf to s.
  static inline double hat_integral(double s) {
    const double c = std::min(1.0, std::max(-1.0, s));
    return 0.5 + c - 0.5 * c * std::fabs(c);
  }
  static inline double hat(double s) { return std::max(0.0, 1.0 - std::fabs(s)); }
  CLEAVE_INLINE static inline double weight(double d, double l, double& g) {
    if (l <= 0.0) {  // a surface (loaded face): the plain hat, point-evaluated
      g = std::fabs(d) < 1.0 ? (d > 0 ? -1.0 : 1.0) : 0.0;
      return hat(d);
    }
    const double inv = 0.5 / l;
    g = (hat(d + l) - hat(d - l)) * inv;
    return (hat_integral(d + l) - hat_integral(d - l)) * inv;
  }
  // The three weights of one axis. With r = xi - base in [1/2, 3/2) and l <= 1/2, node 0 only sees
  // the right half of its hat and node 2 only the left half, where H is a single parabola; node 1
  // follows from the partition of unity. This is ~4x fewer operations than three general weights.
  CLEAVE_INLINE static inline int eval(double xi, double l, double* w, double* dw) {
    const int base = static_cast<int>(xi + 0.5) - 1;  // xi > 0 inside the grid: truncation = floor
    if (l <= 0.0) {
      for (int a = 0; a < 3; ++a) w[a] = weight(xi - (base + a), l, dw[a]);
      return base;
    }
    const double r = xi - base;
    const double A = std::max(0.0, 1.0 - r + l), B = std::max(0.0, 1.0 - r - l);
    const double C = std::max(0.0, r - 1.0 + l), D = std::max(0.0, r - 1.0 - l);
    const double q = 0.25 / l, g = 0.5 / l;
    w[0] = (A * A - B * B) * q;
    w[2] = (C * C - D * D) * q;
    w[1] = 1.0 - w[0] - w[2];
    dw[0] = (B - A) * g;
    dw[2] = (C - D) * g;
    dw[1] = -dw[0] - dw[2];
    return base;
  }
};

// True when every node of a particle at xi (cells from the grid origin) exists on an axis of `nodes`
// nodes, for a style of stencil width K: linear nodes [floor(xi), +1], uGIMP [floor(xi + 1/2) - 1, +2].
// False for NaN too.
inline bool stencil_fits(double xi, int nodes, int K) {
  const double lo = K == 3 ? 0.5 : 0.0, hi = K == 3 ? 1.5 : 1.0;
  return xi >= lo && xi < nodes - hi;
}

}  // namespace cleave
