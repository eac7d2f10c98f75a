// Velocity-Verlet pieces every point method (peridynamics, PEM) shares: a kick that holds the
// prescribed velocity components, and the power of the reactions at those components. Points is a
// structure of arrays with v, a (Vec<Dim>), fixed (bit d: component d prescribed) and v_fixed.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "libmpm/core/types.hpp"

namespace cleave {

// Point p's velocity after a kick of h: v + h a, with its prescribed components held.
template <int Dim, class Points>
Vec<Dim> kicked_velocity(const Points& P, std::size_t p, double h) {
  Vec<Dim> v = P.v[p] + h * P.a[p];
  if (P.fixed[p])
    for (int d = 0; d < Dim; ++d)
      if (P.fixed[p] & (1u << d)) v[d] = P.v_fixed[p][d];
  return v;
}

// w plus the power of the reactions at the prescribed components of the points `fixed` (added one
// by one, in order): the reaction holding a component is -(f_int + f_ext) there, moving at v_fixed.
template <int Dim, class Points>
double add_reaction_power(double w, const Points& P, const std::vector<int32_t>& fixed,
                          const std::vector<Vec<Dim>>& fint, const std::vector<Vec<Dim>>& fext) {
  for (int32_t p : fixed)
    for (int d = 0; d < Dim; ++d)
      if (P.fixed[p] & (1u << d)) w -= (fint[p][d] + fext[p][d]) * P.v_fixed[p][d];
  return w;
}

}  // namespace cleave
