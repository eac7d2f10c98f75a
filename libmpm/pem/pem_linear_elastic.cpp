// The PEM "linear_elastic" material: seed 004's elastic law (figure 4), linear up to the peak
// attraction, then a falling second slope to the cutoff distance where the pair breaks for good.
#include "libmpm/pem/pem_material.hpp"

namespace cleave::pem {
namespace {

PemMaterial read_linear_elastic(const nlohmann::json& j, const std::string& path, const PemMaterialContext& c) {
  const ObjectReader r(j, path, {"name", "type", "E", "nu", "density", "fracture_energy", "G_c", "K_Ic",
                                 "tensile_strength", "cutoff_strain"});
  PemMaterial m;
  read_common_keys(r, c, m);
  return m;
}

}  // namespace
}  // namespace cleave::pem

CLEAVE_REGISTER_PEM_MATERIAL("linear_elastic", &cleave::pem::read_linear_elastic)
