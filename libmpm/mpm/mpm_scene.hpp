// Scene -> MPM model: the shared sections (scene/sections.hpp) plus MPM's own ("grid", "mpm",
// bodies filled with particles, loads resolved on the grid, cracks and crack_tips), all in SI.
#pragma once
#include <nlohmann/json.hpp>

#include "libmpm/mpm/model.hpp"
#include "libmpm/scene/scene.hpp"

namespace cleave {

// Validates the scene and builds the model (bodies filled with particles, loads resolved).
template <int Dim>
Model<Dim> build_model(const nlohmann::json& scene);

}  // namespace cleave
