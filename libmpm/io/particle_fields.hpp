// Particle arrays as written to VTU: only the fields the scene asks for. Vectors are padded to 3
// components and symmetric tensors expanded to VTK's 6 (XX, YY, ZZ, XY, YZ, XZ).
#pragma once
#include <set>
#include <string>

#include "libmpm/io/point_set.hpp"
#include "libmpm/mpm/model.hpp"

namespace cleave::io {

template <int Dim>
PointSet particle_point_set(const Model<Dim>& m, const std::set<std::string>& fields);

// Derived scalars of a stress (also used by the renderer's tests).
template <int Dim>
double von_mises(const Sym<Dim>& s);
// 2D: in-plane sigma1 - sigma2 = sqrt((sxx - syy)^2 + 4 sxy^2); 3D: sigma_max - sigma_min.
template <int Dim>
double principal_stress_difference(const Sym<Dim>& s);

}  // namespace cleave::io
