// Williams' near-tip displacement fields in a crack tip's (or front node's) frame: x1 ahead, x2 the
// crack's normal, the crack along -x1; modes I and II in plane strain, mode III antiplane (along x3).
// Shared by the exact-field tests of the 2D J evaluator (test_crack_tips.cpp) and of the 3D
// along-front term (test_front_along_term.cpp).
#pragma once
#include <cmath>

#include "libmpm/core/types.hpp"

namespace cleave::test {

inline Vec<3> williams_displacement(double KI, double KII, double KIII, double mu, double nu, double x1, double x2) {
  constexpr double pi = 3.14159265358979323846;
  const double r = std::hypot(x1, x2), t = std::atan2(x2, x1), k = 3 - 4 * nu;
  const double f = std::sqrt(r / (2 * pi)), c = f / (2 * mu);
  const double ch = std::cos(t / 2), sh = std::sin(t / 2);
  return {c * (KI * ch * (k - 1 + 2 * sh * sh) + KII * sh * (k + 1 + 2 * ch * ch)),
          c * (KI * sh * (k + 1 - 2 * ch * ch) - KII * ch * (k - 1 - 2 * sh * sh)), 2 * KIII / mu * f * sh};
}

}  // namespace cleave::test
