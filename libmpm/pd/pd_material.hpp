// Peridynamic material styles, one file each (pd_linear_elastic.cpp), registered by scene "type"
// where they are defined; the scene reader (pd_scene.cpp) looks the type up, and an unknown type
// lists the registered ones.
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "libmpm/core/registry.hpp"
#include "libmpm/core/units.hpp"
#include "libmpm/pd/pd_model.hpp"

namespace cleave::pd {

// What a style reads its keys against: it returns the bond constants of the lattice.
struct PdMaterialContext {
  const UnitSystem& units;
  PdModel model;
  double delta, thickness;
  std::vector<std::string>& warnings;
};
using PdMaterialReader = PdMaterial (*)(const nlohmann::json& j, const std::string& path, const PdMaterialContext& c);
using PdMaterialStyles = NameTable<PdMaterialReader, PdMaterialContext>;

}  // namespace cleave::pd

// Registers a peridynamic material style: `reader` is a PdMaterialReader.
#define CLEAVE_REGISTER_PD_MATERIAL(name, reader)                     \
  namespace {                                                         \
  [[maybe_unused]] const bool CLEAVE_REGISTRAR(cleave_pd_material_) = \
      ::cleave::pd::PdMaterialStyles::instance().add(name, reader);   \
  }
