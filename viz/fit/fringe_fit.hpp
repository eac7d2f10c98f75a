// K from fringes: the multi-point ("overdeterministic") fit of the Williams series (williams.hpp)
// to measured isochromatic fringe orders (Sanford & Dally 1979; Ramesh, Digital Photoelasticity;
// /work/shared/reference/validation.md section 7), and Irwin's two-point estimate from a fringe
// loop's apogee as a cross-check.
//
// The fit minimises sum_k (N_model(x_k) - N_k)^2 with N_model = t (s1 - s2) / f_sigma over the
// coefficients A_1..A_n, B_1, B_3..B_n (n = `terms`) and, on request, the tip position and the
// crack direction, by Levenberg-Marquardt from several starts (the isochromatic field is the same
// for the coefficients and their negatives: the result has K_I >= 0). The residual is in fringe
// orders (what a user digitised), not the squared form of Sanford & Dally, so that points far
// from and near the tip count alike. Standard errors: s^2 (J^T J)^-1 at the solution with
// s^2 = RSS / (m - p), which covers the data's scatter but not the truncation of the series.
#pragma once
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "viz/fit/williams.hpp"

namespace cleave::viz {

struct FringePoint {
  double x = 0, y = 0;  // model coordinates, m
  double N = 0;         // measured fringe order
};

struct FringeFitOptions {
  int terms = 3;                       // Williams terms per mode (1: K only, 2: and T, ...), 1..8
  double x0 = 0, y0 = 0, alpha = 0;    // tip (m) and crack direction (rad): given, or the start
  bool fit_tip = false;                // the tip position as two more unknowns
  bool fit_angle = false;              // the crack direction as one more unknown
  double fringe_constant = 0;          // f_sigma, Pa m / fringe (> 0)
  double thickness = 0;                // t, m (> 0)
  int max_iterations = 3000;
};

struct FitParameter {
  std::string name, unit;  // "K_I" "Pa m^0.5", "T" "Pa", "A_3" "Pa m^-0.5", "x0" "m", "alpha" "rad", ...
  double value = 0, std_error = 0;
};

struct FringeOrderSummary {
  double N = 0;           // the measured order
  std::size_t count = 0;  // points of that order
  double rms = 0;         // RMS residual of those points (fringe orders)
};

struct FringeFitResult {
  TipField field;
  std::vector<FitParameter> parameters;  // K_I, K_II, T, higher terms, then x0, y0, alpha if fitted
  std::vector<double> model_N, residual;  // per point (model - measured)
  std::vector<FringeOrderSummary> orders;
  double rms = 0;          // fringe orders, over all points
  int degrees_of_freedom = 0;
  int iterations = 0;
  const FitParameter& parameter(const std::string& name) const;
};

// Bad input (fewer points than unknowns, a point on the tip, non-positive constants, points that
// leave an unknown undetermined): std::invalid_argument. A fit that does not converge:
// FitNotConverged.
struct FitNotConverged : std::runtime_error {
  using std::runtime_error::runtime_error;
};

FringeFitResult fit_fringe_orders(const std::vector<FringePoint>& points, const FringeFitOptions& options);

// Irwin's two-parameter estimate (K_I, sigma_ox) from the apogee (r_m, theta_m) of one fringe loop:
// the loop's point farthest from the tip, where dr/dtheta = 0. Solved exactly from the loop
// equation (N f/t)^2 = s^2 sin^2 th + 2 sigma_ox s sin th sin(3th/2) + sigma_ox^2 (s = K/sqrt(2 pi r))
// and its theta derivative; equals validation.md's closed form.
struct IrwinEstimate {
  double N = 0, r_m = 0, theta_m = 0, KI = 0, sigma_ox = 0;
};
IrwinEstimate irwin_from_apogee(double N, double r_m, double theta_m, double fringe_constant, double thickness);

// Irwin's estimate for every fringe order with at least three points at 20..160 degrees from the
// crack line on one side: the loop's outer edge per 2 degrees of angle, and the apogee from a
// parabola r(theta) through the farthest point and its two neighbours in angle. Loops whose farthest
// point lies within 3 % of the points' outer radius are cut off and left out. Orders without a usable loop (too few points, the apogee not between
// two points, or a vertex more than 5 % beyond the farthest point: a loop cut off) are left out.
std::vector<IrwinEstimate> irwin_two_point(const std::vector<FringePoint>& points, double x0, double y0,
                                           double alpha, double fringe_constant, double thickness);

}  // namespace cleave::viz
