// Shape functions: partition of unity, zero-sum gradients, gradients equal to the derivative of
// the weights, and uGIMP against its textbook piecewise form (Bardenhagen & Kober 2004).
#include <gtest/gtest.h>

#include <cmath>

#include "libmpm/shape/shape_function.hpp"

namespace cleave {
namespace {

// Piecewise uGIMP weight for a node at distance d (cells) from a particle of half-width l.
double gimp_reference(double d, double l) {
  const double a = std::fabs(d);
  if (a < l) return 1.0 - (d * d + l * l) / (2.0 * l);
  if (a <= 1.0 - l) return 1.0 - a;
  if (a < 1.0 + l) return (1.0 + l - a) * (1.0 + l - a) / (4.0 * l);
  return 0.0;
}

template <class SF>
void check_axis(double l) {
  for (double xi = 0.51; xi < 6.0; xi += 0.0123) {
    double w[SF::K], g[SF::K];
    const int base = SF::eval(xi, l, w, g);
    double sw = 0, sg = 0, first = 0;
    for (int a = 0; a < SF::K; ++a) sw += w[a], sg += g[a], first += w[a] * (base + a);
    EXPECT_NEAR(sw, 1.0, 1e-14) << xi;
    EXPECT_NEAR(sg, 0.0, 1e-13) << xi;
    EXPECT_NEAR(first, xi, 1e-13) << "linear completeness at " << xi;
    // Gradient = derivative of the weights (central difference).
    const double e = 1e-6;
    double wp[SF::K], wm[SF::K], t[SF::K];
    if (SF::eval(xi + e, l, wp, t) != base || SF::eval(xi - e, l, wm, t) != base) continue;
    // Central difference: exact for the quadratic pieces; across a curvature jump (|d| = l or
    // 1 -+ l, jump 1/(2l) <= 4) its error is at most e / (2l) = 4e-6.
    for (int a = 0; a < SF::K; ++a) EXPECT_NEAR(g[a], (wp[a] - wm[a]) / (2 * e), 1e-5) << xi;
  }
}

TEST(ShapeFunctions, LinearAxis) { check_axis<LinearShape>(0.25); }

TEST(ShapeFunctions, UGimpAxis) {
  for (double l : {0.5, 0.25, 1.0 / 6.0, 0.125}) check_axis<UGimpShape>(l);
}

TEST(ShapeFunctions, UGimpMatchesPiecewiseForm) {
  for (double l : {0.5, 0.25, 1.0 / 6.0, 0.125})
    for (double xi = 0.51; xi < 6.0; xi += 0.00731) {
      double w[3], g[3];
      const int base = UGimpShape::eval(xi, l, w, g);
      for (int a = -1; a < 4; ++a) {
        const double ref = gimp_reference(xi - (base + a), l);
        if (a < 0 || a > 2) EXPECT_EQ(ref, 0.0) << "a node outside the stencil has weight";
        else EXPECT_NEAR(w[a], ref, 2e-15) << "xi " << xi << " l " << l;
      }
    }
}

TEST(ShapeFunctions, UGimpWithZeroWidthIsTheHat) {
  // A loaded face is a surface: l = 0 must give the linear hat, not 0/0.
  for (double xi = 0.51; xi < 3.0; xi += 0.0371) {
    double w[3], g[3], wl[2], gl[2];
    const int b = UGimpShape::eval(xi, 0.0, w, g);
    const int bl = LinearShape::eval(xi, 0.0, wl, gl);
    for (int a = 0; a < 3; ++a) {
      const int node = b + a;
      const double expect = node == bl ? wl[0] : node == bl + 1 ? wl[1] : 0.0;
      EXPECT_NEAR(w[a], expect, 1e-15);
    }
  }
}

}  // namespace
}  // namespace cleave
