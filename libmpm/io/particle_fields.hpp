// Per-point quantities every method writes the same way: symmetric tensors expanded to VTK's 6
// components (XX, YY, ZZ, XY, YZ, XZ) and the scalars derived from a stress.
#pragma once
#include <array>

#include "libmpm/core/types.hpp"

namespace cleave::io {

template <int Dim>
std::array<double, 6> to_vtk6(const Sym<Dim>& s);

// Derived scalars of a stress (also used by the renderer's tests).
template <int Dim>
double von_mises(const Sym<Dim>& s);
// 2D: in-plane sigma1 - sigma2 = sqrt((sxx - syy)^2 + 4 sxy^2); 3D: sigma_max - sigma_min.
template <int Dim>
double principal_stress_difference(const Sym<Dim>& s);

}  // namespace cleave::io
