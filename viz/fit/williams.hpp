// The Williams series of the stresses round a crack tip in a plane body with traction-free faces,
// and the isochromatic fringe order it gives: the model that fringe-order fits (fringe_fit.hpp)
// adjust to measured points.
//
// Conventions: the tip at (x0, y0), the crack ahead direction at angle alpha from +x (the crack
// faces lie along theta = +-pi in the tip frame). Term n (n = 1, 2, ...) has the mode I
// coefficient A_n and the mode II coefficient B_n (units Pa m^(1 - n/2)); with lambda = n/2 and
// s = (-1)^n, in the tip frame (r, theta),
//   sxx = lambda r^(lambda-1) { A_n [(2+lambda+s) cos((lambda-1)th) - (lambda-1) cos((lambda-3)th)]
//                             - B_n [(2+lambda-s) sin((lambda-1)th) - (lambda-1) sin((lambda-3)th)] }
//   syy = lambda r^(lambda-1) { A_n [(2-lambda-s) cos((lambda-1)th) + (lambda-1) cos((lambda-3)th)]
//                             - B_n [(2-lambda+s) sin((lambda-1)th) + (lambda-1) sin((lambda-3)th)] }
//   sxy = lambda r^(lambda-1) { A_n [(lambda-1) sin((lambda-3)th) - (lambda+s) sin((lambda-1)th)]
//                             + B_n [(lambda-1) cos((lambda-3)th) - (lambda-s) cos((lambda-1)th)] }
// (Ramesh, Digital Photoelasticity, ch. 7; each term is in equilibrium, compatible and free of
// traction on the faces: tests/test_viz_fringe_fit.cpp checks it). K_I = sqrt(2 pi) A_1,
// K_II = -sqrt(2 pi) B_1, T = 4 A_2 (the stress parallel to the crack); B_2 gives no stress.
#pragma once
#include <array>
#include <cstddef>
#include <vector>

namespace cleave::viz {

// Tip frame stresses (sxx, syy, sxy) of term n with coefficients A, B at (r, theta).
std::array<double, 3> williams_term(int n, double A, double B, double r, double theta);

// A crack tip and its Williams coefficients: a[k] = A_(k+1), b[k] = B_(k+1) (b[1], B_2, is ignored).
struct TipField {
  double x0 = 0, y0 = 0, alpha = 0;  // tip position (m) and crack direction (rad from +x)
  std::vector<double> a, b;
  double KI() const;
  double KII() const;
  double T() const;
  // Principal stress difference s1 - s2 (Pa) at the model point (x, y).
  double stress_difference(double x, double y) const;
  // Tip-frame stresses at (x, y) (model point).
  std::array<double, 3> tip_frame_stress(double x, double y) const;
};

// A field with K_I, K_II and T (and no higher terms): the coefficients of the first two terms.
TipField tip_field_from_K(double x0, double y0, double alpha, double KI, double KII, double T);

}  // namespace cleave::viz
