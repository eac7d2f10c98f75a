// Bond-based (PMB) peridynamics material constants: micromodulus c and critical stretch s0 from the
// macroscopic elastic modulus and fracture energy, for a constant (horizon-uniform) micromodulus.
// See reference/validation.md section 5 (seed 003).
#pragma once

namespace cleave::pd {

enum class PdModel { PlaneStress, PlaneStrain, ThreeD };

struct PdConstants {
  double c;           // micromodulus (per unit thickness in 2D, i.e. divided by t)
  double s0;          // critical stretch
  double implied_nu;  // Poisson ratio fixed by the bond-based model
};

// E_or_K: Young's modulus E for the 2D models, bulk modulus K for ThreeD. G0: fracture energy.
// delta: horizon. thickness: plate thickness t (2D only; ignored for ThreeD).
//   PlaneStress: c = 9E/(pi t delta^3),     s0 = sqrt(4 pi G0/(9 E delta)),  nu = 1/3
//   PlaneStrain: c = 48E/(5 pi t delta^3),  s0 = sqrt(5 pi G0/(12 E delta)), nu = 1/4
//   ThreeD:      c = 18K/(pi delta^4),      s0 = sqrt(5 G0/(9 K delta)),     nu = 1/4
// Throws std::invalid_argument for non-positive or non-finite inputs.
PdConstants pd_constants(PdModel model, double E_or_K, double G0, double delta, double thickness);

}  // namespace cleave::pd
