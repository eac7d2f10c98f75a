// MPM particle arrays as written to VTU frames: only the fields the scene asks for. Vectors are
// padded to 3 components and symmetric tensors expanded to VTK's 6 (io/particle_fields.hpp).
#pragma once
#include <set>
#include <string>

#include "libmpm/io/point_set.hpp"
#include "libmpm/mpm/model.hpp"

namespace cleave {

template <int Dim>
io::PointSet particle_point_set(const Model<Dim>& m, const std::set<std::string>& fields);

}  // namespace cleave
