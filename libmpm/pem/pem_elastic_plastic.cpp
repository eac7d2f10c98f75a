// The PEM "elastic_plastic" material: seed 004's plastic law (figure 5). The balance distance of a
// pair shifts once its force reaches the yield force k l0 (yield_stress / E), with linear kinematic
// hardening (hardening = H / k, default 0: perfectly plastic); the pair breaks when its total
// stretch passes ultimate_strain (or the cutoff from a toughness).
#include "libmpm/core/error.hpp"
#include "libmpm/pem/pem_material.hpp"

namespace cleave::pem {
namespace {

PemMaterial read_elastic_plastic(const nlohmann::json& j, const std::string& path, const PemMaterialContext& c) {
  const ObjectReader r(j, path, {"name", "type", "E", "nu", "density", "yield_stress", "hardening",
                                 "ultimate_strain", "fracture_energy", "G_c", "K_Ic"});
  PemMaterial m;
  read_common_keys(r, c, m);
  m.yield_stress = r.positive("yield_stress", c.units.factor(Quantity::Stress));
  m.hardening = r.number_or("hardening", 0.0);
  if (!(m.hardening >= 0.0)) throw SceneError(r.at("hardening"), "must be >= 0 (H / k)");
  if (r.has("ultimate_strain")) {
    if (m.fracture_energy > 0)
      throw SceneError(r.at("ultimate_strain"), "give the ultimate strain or a toughness, not both");
    m.ultimate_strain = r.positive("ultimate_strain");
    if (m.ultimate_strain <= m.yield_stress / m.E)
      throw SceneError(r.at("ultimate_strain"), "must exceed the yield strain yield_stress / E");
  }
  return m;
}

}  // namespace
}  // namespace cleave::pem

CLEAVE_REGISTER_PEM_MATERIAL("elastic_plastic", &cleave::pem::read_elastic_plastic)
