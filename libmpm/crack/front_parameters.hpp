// Crack-front parameters in 3D (seed 000 §3): at each node of a crack front, the J contour in the
// plane normal to the front, the split of J1 into K_I, K_II, K_III by the crack-opening ratios
// behind the node (eqs. 40-57, stationary crack, with the mode-III factor of validation.md §4), and
// closed-form references a scene may name for comparison. Geometry and closed forms only: the field
// values come from the solver (libmpm/mpm/crack_front_eval.hpp).
#pragma once
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "libmpm/core/types.hpp"
#include "libmpm/crack/explicit_crack.hpp"
#include "libmpm/crack/tip_parameters.hpp"

namespace cleave::crack {

// The right-handed crack-front frame of seed 000 eqs. 24-26 at front node k: e1 ahead of the front
// (in the crack's plane, into the uncracked material), e2 the crack's normal (towards "above"), e3 =
// e1 x e2 along the front. (fronts.hpp's tangent runs the other way: e3 = -tangent.)
struct FrontFrame {
  Vec<3> x, e1, e2, e3;
};
FrontFrame front_frame(const ExplicitCrack<3>& c, std::size_t front, std::size_t k);

// Arc length from node 0 along the front to each node.
std::vector<double> front_arc_lengths(const ExplicitCrack<3>& c, std::size_t front);

// A contour point in the plane (e1, e2) through the front node: position, outward unit normal (in
// that plane) and its length (the weight of the midpoint rule).
struct FrontContourPoint {
  Vec<3> x, n;
  double length;
};
// The circle (or square) of TipSettings about the node, starting at the angle theta0 (in the
// frame: atan2 of the e2 and e1 components) where it meets the crack: the same points as the 2D
// contour (tip_parameters.hpp) laid into the plane; theta0 = -pi for a plane crack.
std::vector<FrontContourPoint> front_contour_points(const FrontFrame& f, const TipSettings& s, double cell,
                                                    double theta0 = -M_PI);
// Is x inside the contour's region, projected on the plane (e1, e2)?
bool inside_front_contour(const FrontFrame& f, const TipSettings& s, double cell, const Vec<3>& x);

// K_I, K_II, K_III of a stationary crack from J1 (the energy release rate) and the openings of the
// "+" face relative to the "-" face along e2 (cod_I), e1 (cod_II) and e3 (cod_III), at one point
// behind the front: G = (A (K_I^2 + K_II^2) + K_III^2) / (2 mu), A = (kappa + 1) / 4 (eq. 40 with
// C -> 0, kappa of plane strain); K_II / K_I = cod_II / cod_I; K_III / K_I = A cod_III / cod_I
// (the near-tip openings carry (kappa + 1) / mu for modes I and II and 4 / mu for mode III: the
// factor (1 - nu) of validation.md §4 in plane strain). The three ratios are taken against the
// largest opening (eqs. 49-57), signs from the openings. Negative J gives zero; no opening at all
// gives pure mode I.
struct StressIntensity3 {
  double KI = 0.0, KII = 0.0, KIII = 0.0;
};
StressIntensity3 stress_intensity3(double J1, double cod_I, double cod_II, double cod_III, double shear_modulus,
                                   double nu);

// A closed-form reference the scene names (crack_tips.reference): an embedded elliptical (or
// penny) crack in an infinite body under a uniform remote stress sigma d d^T (d the load axis).
// Irwin's K_I(phi) for the ellipse with d along its normal; for a circle also K_II and K_III under
// an inclined load (Tada, Paris & Irwin; validation.md §4): K_I = (2/pi) s_nn sqrt(pi a), K_II =
// 4 / (pi (2 - nu)) s_1n sqrt(pi a), K_III = 4 (1 - nu) / (pi (2 - nu)) s_3n sqrt(pi a), with s_1n,
// s_3n the remote shear tractions on the crack plane along e1 and e3 of the front node.
struct EllipseReference {
  int crack = 0;  // the crack it describes
  Vec<3> center = Vec<3>::Zero(), normal = Vec<3>::UnitZ(), major = Vec<3>::UnitX();  // unit normal, major
  double a = 0, b = 0;  // semi-axes along major and normal x major
  double stress = 0;    // Pa
  Vec<3> load_axis = Vec<3>::UnitZ();
  double nu = 0.3;
  // The ellipse angle of x (x = center + a cos(phi) major + b sin(phi) (normal x major)).
  double phi(const Vec<3>& x) const;
  StressIntensity3 at(const FrontFrame& f) const;
};

// One row of crack_fronts.csv.
struct FrontRecord {
  int crack = 0, front = 0, node = 0;
  double s = 0;  // arc length from the front's node 0
  Vec<3> x = Vec<3>::Zero();
  double J1 = 0, J2 = 0, KI = 0, KII = 0, KIII = 0;
  double cod_I = 0, cod_II = 0, cod_III = 0;
  // Bits: kFlagContourOutside (some contour points lie outside the material: a free surface within
  // the contour, J misses their part), kFlagNoOpening (the opening behind the node could not be
  // read: K is pure mode I from J), kFlagContourCrossesCrack (the contour crosses a crack other
  // than at its own start: J is not path-independent there).
  int flag = 0;
};
inline constexpr int kFlagContourOutside = 1, kFlagNoOpening = 2, kFlagContourCrossesCrack = 4;

}  // namespace cleave::crack
