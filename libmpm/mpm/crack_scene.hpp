// MPM's crack sections of the scene: "cracks" and "crack_tips" (docs/scenes.md), read by
// build_model (mpm_scene.cpp) after the grid and the particles. Errors name the key path.
#pragma once
#include <nlohmann/json.hpp>

#include "libmpm/mpm/model.hpp"

namespace cleave {

// "cracks": 2D polylines (crack::parse_cracks), each inside the grid with room for its nodes and
// touching a body, "tips": "auto" resolved against the particles; 3D surfaces (crack::parse_cracks3d)
// meshed at half a cell, clipped to the material but for a band of a cell, inside the grid, with
// their fronts.
template <int Dim>
void read_cracks(const nlohmann::json& scene, double length, Model<Dim>& m);

// "crack_tips": the J-integral contour (m.crack_tips) and the older spelling of the table's cadence
// (crack_tips.interval for output.tip_interval; read_output must have run). 3D: an error.
template <int Dim>
void read_crack_tips(const nlohmann::json& scene, double time_scale, Model<Dim>& m);

}  // namespace cleave
