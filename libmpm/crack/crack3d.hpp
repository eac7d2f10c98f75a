// 3D explicit cracks (seed 000, CRAMP in 3D): the scene's "cracks" in a 3D MPM scene, triangulated
// surfaces (surface3d.hpp) with the crack state of explicit_crack.hpp. The MPM scene reader
// (mpm/crack_scene.cpp) then clips them to the material, finds their fronts and checks them
// against the grid and the bodies.
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "libmpm/crack/explicit_crack.hpp"
#include "libmpm/crack/surface.hpp"

namespace cleave::crack {

// The surfaces of parse_surfaces3d meshed as `meshing` says, each with its "contact" (contact_keys.hpp)
// and "tips": "auto" (every front inside the material; the default), "all" (the same: a 3D front
// is by definition inside the material) or "none". id = index in the array; above / below = points.
std::vector<ExplicitCrack<3>> parse_cracks3d(const nlohmann::json& cracks, const std::string& key_path,
                                             double length_scale, const SurfaceMeshing& meshing);

}  // namespace cleave::crack
