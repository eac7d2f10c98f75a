// The "contact" object of an explicit crack, the same in 2D and 3D scenes (docs/scenes.md):
// {"law": stick | frictionless | friction | none, "mu", "detection": volume | displacement,
// "v_sep", "v_contact"}, and its "tip_cut". Defined in crack2d.cpp beside the contact-law registry.
#pragma once
#include "libmpm/core/json_reader.hpp"
#include "libmpm/crack/explicit_crack.hpp"

namespace cleave::crack {

// Reads crack_entry["contact"] into c (law, friction, detection and its thresholds). SceneError
// names the key path: an unknown law (the valid ones listed), mu missing / negative / given with a
// law that takes none, an unknown detection, thresholds out of range or given with displacement.
template <int Dim>
void read_crack_contact(const ObjectReader& crack_entry, ExplicitCrack<Dim>& c);

// "tip_cut" (cells, in [0, 1]) of a crack entry, or fallback when absent; SceneError names the key.
double read_tip_cut(const ObjectReader& crack_entry, double fallback);

// The same keys read from r (an object whose allowed keys the caller set) into c. Cracks detect by
// "volume" (default) or "displacement"; bodies (bodies = true) by "position" (default, with
// "d_contact") or "volume": the displacement test needs faces that start together.
void read_contact_settings(const ObjectReader& r, ContactSettings& c, bool bodies);

}  // namespace cleave::crack
