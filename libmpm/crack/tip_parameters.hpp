// Crack-tip parameters in 2D (seed 000 §3 reduced to the plane): the crack-tip frame, the J-integral
// contour (circle or square around the tip, midpoint rule, eq. 38), and the split of J into K_I and
// K_II by the near-tip crack-opening ratio (eqs. 40-57, stationary crack). The field values on the
// contour come from the solver (libmpm/mpm/crack_tip_eval.hpp); this file holds the geometry
// and the closed-form parts, free of any solver state.
#pragma once
#include <vector>

#include "libmpm/core/types.hpp"
#include "libmpm/crack/crack2d.hpp"

namespace cleave::crack {

// The scene key "crack_tips": what to compute at the crack tips, and how often.
struct TipSettings {
  enum class Contour { Circle, Rectangle } contour = Contour::Circle;
  double radius = 2.0;       // cells: the circle's radius, or half the side of the square
  int points = 16;           // integration points on the contour (n_J)
  bool volume_term = false;  // eq. 33 (contour + volume) instead of eq. 32 (contour only)
  // 3D fronts only: subtract the out-of-plane term of the 3D J, the integral over the contour's area
  // of d(sigma_i3 u_i,k)/dx3 (x3 along the front; Shih, Moran & Nakamura 1986). Without it the plane
  // contour of a curved front overestimates J by about 0.46 r / R (contour radius r, front radius
  // R: +12 % for a 2-cell contour on a penny crack of 8 cells; docs/validation.md).
  bool out_of_plane_term = true;
  // 3D fronts only: J1 by the equivalent domain integral (crack_front_domain.hpp) over a tube of
  // `radius` cells about the front instead of the plane contour (which still gives J2): its weight is 1
  // within `inner` x radius of the front, falls to 0 at the radius, and along the front falls from 1 at
  // the node to 0 at `along` cells from it (smooth steps). It takes the out-of-plane term exactly.
  enum class Integral { Contour, Domain } integral = Integral::Contour;
  double along = 4.0, inner = 0.5;
};

// Crack-tip frame: e1 along the crack, pointing ahead of the tip; e2 its left normal. The "+" face
// is the one on the e2 side.
struct TipFrame {
  Vec<2> tip, e1, e2;
};
// end 0: the tip at points[0]; end 1: the tip at points.back().
TipFrame tip_frame(const Crack2D& c, int end);
// The crack's k-th vertex counted from the tip of `end` inwards.
Vec<2> vertex_from_tip(const Crack2D& c, int end, std::size_t k);

// The point on the crack at arc length `distance` behind the tip (the crack's end point when the
// crack is shorter), with the crack's unit normal there oriented towards the "+" face.
struct CrackPoint {
  Vec<2> x, normal;
};
CrackPoint point_behind_tip(const Crack2D& c, int end, double distance);

// A contour integration point: position, outward unit normal, and its length (the weight of the
// midpoint rule). Points run counter-clockwise from the "-" face to the "+" face; none lies on the
// crack. The circle starts where it meets the crack (seed 000 step 1); the square starts at the
// same angle.
struct ContourPoint {
  Vec<2> x, n;
  double length;
};
std::vector<ContourPoint> contour_points(const Crack2D& c, int end, const TipSettings& s, double cell);

// Is x inside the contour (the region of eq. 33's volume term)?
bool inside_contour(const TipFrame& f, const TipSettings& s, double cell, const Vec<2>& x);

// kappa: 3 - 4 nu (plane strain), (3 - nu) / (1 + nu) (plane stress).
double kolosov_kappa(Analysis a, double nu);

// K_I, K_II of a stationary crack from J1 (the energy release rate) and the near-tip crack-opening
// displacements of the "+" face relative to the "-" face, normal (cod_I) and tangential (cod_II):
// G = (A_I K_I^2 + A_II K_II^2) / (2 mu) with A_I = A_II = (kappa + 1) / 4 (eqs. 40-45, C -> 0);
// K_II / K_I = cod_II / cod_I (eqs. 46-47); signs from the openings (eqs. 49-57: the larger opening
// is the divisor). A negative J (round-off of a closed crack) gives zero K. Pure mode I when both
// openings vanish.
struct StressIntensity {
  double KI = 0.0, KII = 0.0;
};
StressIntensity stress_intensity(double J1, double cod_I, double cod_II, double shear_modulus, double kappa);

// One row of crack_tips.csv.
struct TipRecord {
  int crack = 0, end = 0;  // crack id; 0 start / 1 end
  Vec<2> x = Vec<2>::Zero();
  double J1 = 0, J2 = 0, KI = 0, KII = 0;
  double cod_I = 0, cod_II = 0;  // the openings that split K (max(radius, 3 cells) behind the tip)
  int material = -1;             // of the particle nearest the tip (MPM), for its toughness
};

}  // namespace cleave::crack
