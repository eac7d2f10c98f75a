// The initiation criteria of crack propagation (propagation.hpp), one registration each: the
// ratio of the driving quantity to its critical value, the tip growing at 1.
#include <algorithm>
#include <cmath>

#include "libmpm/crack/propagation.hpp"

namespace cleave::crack {
namespace {

// Griffith / Irwin: the dynamic J (the energy release rate) against G_c, whatever the mode mix.
double energy_release_rate(const TipLoading& t) { return t.J / t.Gc; }
// Irwin's K_I against K_Ic (mode I).
double stress_intensity(const TipLoading& t) { return t.KI / t.KIc; }
// Erdogan & Sih: the largest hoop stress intensity, at the kink angle, against K_Ic.
double max_hoop_stress(const TipLoading& t) {
  return hoop_stress_intensity(t.KI, t.KII, hoop_stress_angle(t.KI, t.KII)) / t.KIc;
}
// The largest G(theta) of a small kink (Cotterell & Rice) against G_c.
double max_energy_release_rate(const TipLoading& t) {
  const auto [a, b] = kink_intensities(t.KI, t.KII, max_energy_release_angle(t.KI, t.KII));
  return (std::max(a, 0.0) * std::max(a, 0.0) + b * b) / t.e_prime / t.Gc;
}

}  // namespace
}  // namespace cleave::crack

CLEAVE_REGISTER_INITIATION_CRITERION("energy_release_rate", 0, cleave::crack::energy_release_rate)
CLEAVE_REGISTER_INITIATION_CRITERION("stress_intensity", 1, cleave::crack::stress_intensity)
CLEAVE_REGISTER_INITIATION_CRITERION("max_hoop_stress", 2, cleave::crack::max_hoop_stress)
CLEAVE_REGISTER_INITIATION_CRITERION("max_energy_release_rate", 3, cleave::crack::max_energy_release_rate)
