// The direction rules of crack propagation (propagation.hpp), one registration each: the kink
// angle from the tip's e1 towards e2.
#include "libmpm/crack/propagation.hpp"

namespace cleave::crack {
namespace {

double max_hoop_stress(const TipLoading& t) { return hoop_stress_angle(t.KI, t.KII); }
double max_energy_release_rate(const TipLoading& t) { return max_energy_release_angle(t.KI, t.KII); }
// Straight ahead, whatever the mode mix (a crack kept on its plane, e.g. along a weak interface).
double straight(const TipLoading&) { return 0.0; }

}  // namespace
}  // namespace cleave::crack

CLEAVE_REGISTER_DIRECTION_RULE("max_hoop_stress", 0, cleave::crack::max_hoop_stress)
CLEAVE_REGISTER_DIRECTION_RULE("max_energy_release_rate", 1, cleave::crack::max_energy_release_rate)
CLEAVE_REGISTER_DIRECTION_RULE("straight", 2, cleave::crack::straight)
