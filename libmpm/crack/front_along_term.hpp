// The along-front part of the 3D J's out-of-plane term (docs/scenes.md, "The out-of-plane term").
// J at a front node = J on the plane contour - int_A d(sigma_i3 u_i,1)/dx3 dA, x3 along the front.
// The curvature part of that integral is taken from the particles (crack_front_eval.hpp); this is
// the other part: the change along the front of int_A q dA, q = sigma_i3 u_i,1 in the front's own
// frame. Over the near-tip fields only modes II and III couple in q (the I-III and I-II products
// are odd in the angle about the front and integrate to zero), and
//     int_A q dA = L (1/8 + nu) / mu K_II K_III,
// L = r for a circle of radius r, (4 / pi) ln(1 + sqrt 2) r for a square of half-side r (the
// angular integral of q is (1/8 + nu - 3/4 cos theta + 1/8 cos 2 theta) / (2 pi mu) per unit K_II
// K_III; tests/test_front_along_term.cpp checks it against the Williams fields). So the term is
// -L (1/8 + nu) / mu d(K_II K_III)/dx3, taken from the K of the neighbouring front nodes: it
// vanishes where K_II or K_III is zero all along a front (modes I and II, the penny, the rod), and
// on an inclined penny crack (K_II ~ cos theta, K_III ~ sin theta) it is ~ r / a of J, with the sign of
// cos 2 theta.
//
// Taken from the K rather than from a derivative of the particles' area integrals, which reads the
// particle lattice (docs/validation.md). The derivative is the slope of a least-squares line through
// the products at the front nodes within one contour radius along the front (the contour's own
// reach), with the products self-consistent with the corrected J: the openings fix K / sqrt(J) at
// each node, so the corrected J of a front solve one sparse linear system.
#pragma once
#include <vector>

#include "libmpm/core/types.hpp"
#include "libmpm/crack/front_parameters.hpp"
#include "libmpm/crack/tip_parameters.hpp"

namespace cleave::crack {

// L of the contour's area: int_A q dA = L (1/8 + nu) / mu K_II K_III.
double along_front_length(const TipSettings& s, double cell);

// One evaluated front node, in node order along its front.
struct AlongFrontNode {
  Vec<3> x = Vec<3>::Zero(), e3 = Vec<3>::UnitZ();  // position and its frame's e3
  double s = 0.0;                                     // arc length from node 0
  double J1 = 0.0;                                    // J on the contour (with the curvature part)
  double cod_I = 0.0, cod_II = 0.0, cod_III = 0.0;    // the openings K is split by
  double mu = 0.0, nu = 0.0;
  bool fit = true;  // whether its K may enter its neighbours' slopes (false: a flagged node)
};
struct AlongFrontResult {
  double J1 = 0.0, KI = 0.0, KII = 0.0, KIII = 0.0;
  bool applied = false;  // false: too few neighbours in reach for a slope (J1 and K as without)
};
// The nodes' J1 less the term, and their K from it. closed: the front is a loop of arc length
// `length` (node 0 follows the last); `reach`: the half-width of the slope's window along the front.
std::vector<AlongFrontResult> subtract_along_front_term(const std::vector<AlongFrontNode>& nodes, bool closed,
                                                        double length, double L, double reach);

}  // namespace cleave::crack
