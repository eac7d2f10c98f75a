// Scene -> peridynamic model for scenes with "method": "peridynamics" (docs/scenes.md, section
// "Peridynamics"). Same bodies, materials, cracks, loads, time and output keys as MPM scenes where
// they make sense; errors name the key path as everywhere else.
#pragma once
#include <nlohmann/json.hpp>

#include "libmpm/pd/pd_model.hpp"

namespace cleave::pd {

// True when the scene asks for peridynamics ("method": "peridynamics"); SceneError("method") for a
// value other than "mpm" or "peridynamics".
bool is_peridynamics(const nlohmann::json& scene);

template <int Dim>
PdSystem<Dim> build_pd_system(const nlohmann::json& scene);

}  // namespace cleave::pd
