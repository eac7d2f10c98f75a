// "crack_tips" in a 3D MPM scene (docs/scenes.md, "Crack-front parameters"): J and K_I, K_II, K_III
// at every node of every crack front, with the checks that need the model: every contour inside the
// grid (else an error naming the crack, front and node), contours that leave the material or cross
// a crack (a warning, and a flag on those nodes' rows), an isotropic elastic material at the fronts;
// and "reference", a closed form to compare with (crack_fronts.csv's *_ref columns).
#pragma once
#include <nlohmann/json.hpp>

#include "libmpm/core/units.hpp"
#include "libmpm/mpm/model.hpp"

namespace cleave {

// Sets m.crack_tips, the fronts' flags, m.front_references, and allocates the particles' rotations
// (the displacement gradients of the J integrand need them).
void read_front_tips(const nlohmann::json& scene, const UnitSystem& units, Model<3>& m);

}  // namespace cleave
