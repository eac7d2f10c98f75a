// Bodies that overlap: both fill the shared region with points, so it gets the mass of both, and in
// MPM their points share grid nodes, so the two move as one body there (they stick). A scene that
// wants a body inside another cuts it out with a "difference" shape. Methods whose bodies may not
// share space refuse it themselves (peridynamics: a lattice site holds one point).
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "libmpm/scene/bodies.hpp"

namespace cleave::scene {

// One warning per pair of bodies that overlap (a point of one inside the other's shape), naming
// both, how many points, and `consequence`. points[i]: the positions of body i's points.
template <int Dim>
std::vector<std::string> overlap_warnings(const std::vector<BodySpec<Dim>>& specs,
                                          const std::vector<std::pair<const Vec<Dim>*, std::size_t>>& points,
                                          const std::string& unit, const std::string& consequence);

}  // namespace cleave::scene
