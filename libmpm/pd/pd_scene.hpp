// Scene -> peridynamic model for scenes with "method": "peridynamics" (docs/scenes.md, section
// "Peridynamics"). Same bodies, materials, cracks, loads, time and output keys as MPM scenes where
// they make sense; errors name the key path as everywhere else.
#pragma once
#include <nlohmann/json.hpp>

#include "libmpm/pd/pd_model.hpp"

namespace cleave::pd {

template <int Dim>
PdSystem<Dim> build_pd_system(const nlohmann::json& scene);

}  // namespace cleave::pd
