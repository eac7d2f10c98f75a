// MPM's "contact" section of the scene (docs/scenes.md): contact between bodies, read by build_model
// (mpm_scene.cpp) once the bodies exist. Errors name the key path.
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "libmpm/mpm/body_contact.hpp"

namespace cleave {

// "contact": an array of {"bodies": [name, name, ...] | "all", "law", "mu", "detection", "d_contact",
// "v_sep", "v_contact", "normal"}: every pair among the named bodies (or among all bodies) interacts by
// that law (the keys of a crack's "contact", contact_keys.hpp, detection "position" or "volume"),
// with the normal from both bodies ("average") or from the one named (a flat face). A later entry's law
// replaces an earlier one's for the pairs both name (a default for "all", then exceptions).
// body_names: Model::bodies' names, in order.
BodyContact read_body_contact(const nlohmann::json& scene, const std::vector<std::string>& body_names);

}  // namespace cleave
