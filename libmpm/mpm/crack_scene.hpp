// MPM's crack sections of the scene: "cracks" and "crack_tips" (docs/scenes.md), read by
// build_model (mpm_scene.cpp) after the grid and the particles. Errors name the key path.
#pragma once
#include <nlohmann/json.hpp>
#include <span>
#include <vector>

#include "libmpm/core/units.hpp"
#include "libmpm/mpm/model.hpp"

namespace cleave {

// "cracks": 2D polylines (crack::parse_cracks), each inside the grid with room for its nodes and
// touching a body, "tips": "auto" resolved against the particles; 3D surfaces (crack::parse_cracks3d)
// meshed at half a cell, clipped to the material but for a band of a cell, inside the grid, with
// their fronts.
template <int Dim>
void read_cracks(const nlohmann::json& scene, double length, Model<Dim>& m);

// "crack_tips": the J-integral contour (m.crack_tips) and the older spelling of the table's cadence
// (crack_tips.interval for output.tip_interval; read_output must have run). 2D: at the crack tips;
// 3D: at the nodes of the crack fronts (crack_front_scene.hpp).
template <int Dim>
void read_crack_tips(const nlohmann::json& scene, const UnitSystem& units, Model<Dim>& m);

// A warning per crack that detects contact by nodal volume in a damped or static run (the damping
// and static settings read), where that detection ratchets the faces open.
template <int Dim>
void warn_volume_detection_when_slow(Model<Dim>& m);

// The keys of "crack_tips": those common to 2D and 3D, then more_keys.
inline std::vector<const char*> crack_tips_keys(std::span<const char* const> more_keys) {
  std::vector<const char*> keys = {"interval", "contour", "radius", "points", "volume_term"};
  keys.insert(keys.end(), more_keys.begin(), more_keys.end());
  return keys;
}
// Reads the common keys, with more_keys also allowed (read by the caller); checks that the scene has cracks.
template <int Dim>
crack::TipSettings read_contour_settings(const nlohmann::json& scene, Model<Dim>& m, double time_scale,
                                         std::span<const char* const> more_keys);

}  // namespace cleave
