// The peridynamic "linear_elastic" material (bond-based, prototype microelastic brittle).
#include <cmath>
#include <string>

#include "libmpm/core/error.hpp"
#include "libmpm/core/json_reader.hpp"
#include "libmpm/pd/constants.hpp"
#include "libmpm/pd/pd_material.hpp"

namespace cleave::pd {
namespace {

// "linear_elastic": Young's modulus and density, plus the fracture energy that sets the critical
// stretch. Bond-based peridynamics fixes nu (1/3 plane stress, 1/4 otherwise); E is matched, and in
// 3D K = E / (3 (1 - 2 nu)) with that nu, so the lattice reproduces the scene's Young's modulus.
PdMaterial read_linear_elastic(const nlohmann::json& j, const std::string& path, const PdMaterialContext& c) {
  const ObjectReader r(j, path, {"name", "type", "E", "nu", "density", "fracture_energy"});
  PdMaterial pm;
  pm.E = r.positive("E", c.units.factor(Quantity::Stress));
  pm.density = r.positive("density", c.units.factor(Quantity::Density));
  if (!r.has("fracture_energy"))
    throw SceneError(r.at("fracture_energy"), "missing: peridynamics needs the fracture energy G0 (critical stretch)");
  pm.G0 = r.positive("fracture_energy", c.units.factor(Quantity::Stress) * c.units.factor(Quantity::Length));
  const double nu_implied = c.model == PdModel::PlaneStress ? 1.0 / 3.0 : 0.25;
  if (r.has("nu")) {
    pm.nu_given = r.number("nu");
    if (std::fabs(pm.nu_given - nu_implied) > 1e-6)
      c.warnings.push_back(path + ".nu = " + std::to_string(pm.nu_given) +
                           " is ignored: bond-based peridynamics implies nu = " + std::to_string(nu_implied) +
                           " for this analysis (E is matched)");
  }
  const double modulus = c.model == PdModel::ThreeD ? pm.E / (3.0 * (1.0 - 2.0 * nu_implied)) : pm.E;
  pm.k = pd_constants(c.model, modulus, pm.G0, c.delta, c.thickness);
  return pm;
}


}  // namespace
}  // namespace cleave::pd

CLEAVE_REGISTER_PD_MATERIAL("linear_elastic", &cleave::pd::read_linear_elastic)
