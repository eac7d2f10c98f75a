// What every PEM material style shares: the elastic keys, how its pairs break, and the pair law's
// stretches once the mesh is known (pem_material.hpp).
#include <cmath>

#include "libmpm/core/error.hpp"
#include "libmpm/pem/pem_material.hpp"

namespace cleave::pem {

void read_common_keys(const ObjectReader& r, const PemMaterialContext& c, PemMaterial& m) {
  const double stress = c.units.factor(Quantity::Stress), length = c.units.factor(Quantity::Length);
  m.E = r.positive("E", stress);
  m.density = r.positive("density", c.units.factor(Quantity::Density));
  if (r.has("nu")) {
    m.nu_given = r.number("nu");
    if (!(m.nu_given > -1.0 && m.nu_given < 0.5)) throw SceneError(r.at("nu"), "must lie in (-1, 0.5)");
  }
  const char* toughness[] = {"fracture_energy", "G_c", "K_Ic"};
  const char* first = nullptr;
  for (const char* k : toughness)
    if (r.has(k)) {
      if (first) throw SceneError(r.at(k), std::string("give one toughness, not both \"") + first + "\" and \"" + k + "\"");
      first = k;
    }
  if (r.has("K_Ic")) {
    // G = K^2 / E (the pair network is a plane-stress or 3D body with its own nu; E is what it matches).
    const double K = r.positive("K_Ic", stress * std::sqrt(length));
    m.fracture_energy = K * K / m.E;
  } else if (first) {
    m.fracture_energy = r.positive(first, stress * length);
  }
  if (r.has("tensile_strength")) m.tensile_strength = r.positive("tensile_strength", stress);
  if (r.has("cutoff_strain")) {
    if (first || r.has("tensile_strength"))
      throw SceneError(r.at("cutoff_strain"), "give the cutoff strain or a toughness / tensile strength, not both");
    const double eps = r.number("cutoff_strain");
    if (!(eps > 0.0))
      throw SceneError(r.at("cutoff_strain"), "the cutoff distance must lie beyond the balance distance (a cutoff "
                                              "strain > 0; got " + r["cutoff_strain"].dump() + ")");
    m.law.eps_cut = m.law.eps_peak = eps;
  }
}

void set_pair_law(PemMaterial& m, double S, const std::string& path, bool breakable) {
  PairLaw& law = m.law;
  if (!breakable) {  // the tips decide where cracks run (pem.tip_growth): no cutoff, plasticity kept
    if (m.yield_stress > 0) law.eps_yield = m.yield_stress / m.E, law.hardening = m.hardening;
    return;
  }
  if (m.fracture_energy > 0 && !(S > 0))
    throw SceneError(path, "no pair of this material: its fracture energy cannot set a cutoff");
  if (m.yield_stress > 0) {
    // No softening branch: the pair carries the (hardened) yield force up to the cutoff, then breaks.
    // The work to break a perfectly plastic pair per unit a = k l^2 is eps_y eps_c - eps_y^2 / 2.
    law.eps_yield = m.yield_stress / m.E;
    law.hardening = m.hardening;
    law.eps_peak = INFINITY;
    if (m.ultimate_strain > 0) law.eps_cut = m.ultimate_strain;
    else if (m.fracture_energy > 0)
      law.eps_cut = (m.fracture_energy / S + 0.5 * law.eps_yield * law.eps_yield) / law.eps_yield;
    return;
  }
  if (m.tensile_strength > 0) law.eps_peak = m.tensile_strength / m.E;
  if (m.fracture_energy > 0) {
    if (m.tensile_strength > 0) {
      law.eps_cut = 2.0 * m.fracture_energy / (law.eps_peak * S);
      if (law.eps_cut < law.eps_peak)
        throw SceneError(path + ".fracture_energy",
                         "the cutoff falls below the peak: breaking the pairs at the tensile strength already costs " +
                             std::to_string(0.5 * law.eps_peak * law.eps_peak * S) +
                             " J/m^2 on this mesh, more than the fracture energy; give a larger fracture energy, a "
                             "lower tensile strength, or a finer mesh");
    } else {
      law.eps_cut = law.eps_peak = std::sqrt(2.0 * m.fracture_energy / S);
    }
  } else if (m.tensile_strength > 0) {
    law.eps_cut = law.eps_peak;  // brittle at the strength
  }
}

}  // namespace cleave::pem
