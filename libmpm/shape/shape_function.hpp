// Grid shape functions, evaluated per axis and combined as tensor products (both styles are
// separable on a regular grid, which is what makes them cheap). A style is a small struct with a
// compile-time stencil width K; the solver is templated on it so the hot loops are fully unrolled.
#pragma once
#include <cmath>

namespace cleave {

// Linear (bilinear/trilinear) hat functions: 2 nodes per axis.
struct LinearShape {
  static constexpr int K = 2;
  static constexpr const char* name = "linear";
  // xi: particle coordinate in cells from the grid origin; l: particle half-width in cells (unused).
  static inline int eval(double xi, double /*l*/, double* w, double* dw) {
    const double fl = std::floor(xi);
    const double f = xi - fl;
    w[0] = 1.0 - f;
    w[1] = f;
    dw[0] = -1.0;
    dw[1] = 1.0;
    return static_cast<int>(fl);
  }
};

// uGIMP (Bardenhagen & Kober): the hat function averaged over the particle's undeformed domain of
// half-width l (l <= 1/2 cell). 3 nodes per axis; l = 0 reduces exactly to the linear hat.
struct UGimpShape {
  static constexpr int K = 3;
  static constexpr const char* name = "ugimp";
  static inline double weight(double d, double l, double& g) {
    const double a = std::fabs(d);
    const double s = d < 0 ? -1.0 : 1.0;
    if (a < l) {
      g = -d / l;
      return 1.0 - (d * d + l * l) / (2.0 * l);
    }
    if (a <= 1.0 - l) {
      g = -s;
      return 1.0 - a;
    }
    if (a < 1.0 + l) {
      const double r = 1.0 + l - a;
      g = -s * r / (2.0 * l);
      return r * r / (4.0 * l);
    }
    g = 0.0;
    return 0.0;
  }
  static inline int eval(double xi, double l, double* w, double* dw) {
    const int base = static_cast<int>(std::floor(xi + 0.5)) - 1;
    for (int a = 0; a < 3; ++a) w[a] = weight(xi - (base + a), l, dw[a]);
    return base;
  }
};

enum class ShapeFunctionKind { Linear, UGimp };

}  // namespace cleave
