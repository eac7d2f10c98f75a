// PEM material styles, one file each (pem_linear_elastic.cpp, pem_elastic_plastic.cpp), registered by
// the scene's material "type". A style reads its keys into a PemMaterial; the pair law's stretches
// (peak, cutoff, yield) are set once the mesh is known (pem_scene.cpp, set_pair_law), since the
// cutoff from a fracture energy depends on the pairs that cross a unit area.
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "libmpm/core/json_reader.hpp"
#include "libmpm/core/registry.hpp"
#include "libmpm/core/units.hpp"
#include "libmpm/pem/pem_model.hpp"

namespace cleave::pem {

struct PemMaterialContext {
  const UnitSystem& units;
  std::vector<std::string>& warnings;
};
using PemMaterialReader = PemMaterial (*)(const nlohmann::json& j, const std::string& path, const PemMaterialContext& c);
using PemMaterialStyles = NameTable<PemMaterialReader, PemMaterialContext>;

// The keys every style shares: E, nu (reported against the network's), density, and how pairs break:
// a toughness (fracture_energy, G_c or K_Ic; with or without tensile_strength), tensile_strength alone,
// or cutoff_strain; none: pairs never break.
void read_common_keys(const ObjectReader& r, const PemMaterialContext& c, PemMaterial& m);

// Sets m.law's peak and cutoff stretches from what the material declares. `fracture_sum` is
// S = (1/V) sum_p k_p l_p^3 <|t_p . n|> over the material's pairs (J/m^2 at unit stretch; the mean over
// crack orientations n): breaking every pair that crosses a unit area costs G = eps_peak eps_cut S / 2.
// `path` names the material for errors (a cutoff below the peak, or at or below the balance distance).
// breakable = false (pem.tip_growth: the tips decide where cracks run): no peak or cutoff, only yield.
void set_pair_law(PemMaterial& m, double fracture_sum, const std::string& path, bool breakable = true);

}  // namespace cleave::pem

#define CLEAVE_REGISTER_PEM_MATERIAL(name, reader)                     \
  namespace {                                                          \
  [[maybe_unused]] const bool CLEAVE_REGISTRAR(cleave_pem_material_) = \
      ::cleave::pem::PemMaterialStyles::instance().add(name, reader);  \
  }
