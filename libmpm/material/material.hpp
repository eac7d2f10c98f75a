// Constitutive laws. A material is a small class registered by name (see linear_elastic.cpp);
// the scene names it with "type". Stresses are Cauchy, strains small-strain tensor components,
// both in the Sym<Dim> layout of core/types.hpp.
#pragma once
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "libmpm/core/error.hpp"
#include "libmpm/core/registry.hpp"
#include "libmpm/core/types.hpp"
#include "libmpm/core/units.hpp"

namespace cleave {

template <int Dim>
class Material {
 public:
  virtual ~Material() = default;
  // Advance stress and strain by the velocity gradient L over dt (one of the paper's Subtask 3).
  virtual void update(Sym<Dim>& stress, Sym<Dim>& strain, const Mat<Dim>& L, double dt) const = 0;
  // Stored elastic energy per unit volume for the current state.
  virtual double strain_energy_density(const Sym<Dim>& stress, const Sym<Dim>& strain) const = 0;
  // Isotropic elastic constants, for K from J at crack tips: true and the shear modulus and
  // Poisson's ratio when the law has them.
  virtual bool isotropic_elastic(double& shear_modulus, double& poisson) const {
    (void)shear_modulus, (void)poisson;
    return false;
  }
  // Largest wave speed (for the stable time step).
  virtual double wave_speed() const = 0;
  double density() const { return density_; }
  const std::string& name() const { return name_; }
  // Fracture toughness, for growing cracks (crack::Propagation): the scene gives G_c (J/m^2) or
  // K_Ic (Pa sqrt(m)), the other being 0 here; both 0 when it gives neither.
  double toughness_Gc() const { return Gc_; }
  double toughness_KIc() const { return KIc_; }

 protected:
  double density_ = 0.0;
  std::string name_;
  double Gc_ = 0.0, KIc_ = 0.0;
  // Reads the optional toughness keys "G_c" (or "fracture_energy", peridynamics' spelling, so that
  // one material serves both methods) and "K_Ic", at most one of them, each > 0.
  template <class Reader>
  void read_toughness(const Reader& r, const UnitSystem& units) {
    const char* given[] = {"G_c", "fracture_energy", "K_Ic"};
    const char* first = nullptr;
    for (const char* k : given)
      if (r.has(k)) {
        if (first) throw SceneError(r.at(k), std::string("give one toughness, not both \"") + first + "\" and \"" + k + "\"");
        first = k;
      }
    const double stress = units.factor(Quantity::Stress), length = units.factor(Quantity::Length);
    if (r.has("K_Ic")) KIc_ = r.positive("K_Ic", stress * std::sqrt(length));
    else if (first) Gc_ = r.positive(first, stress * length);
  }
};

// Arguments to a material factory: its JSON object, its key path for errors, units and analysis.
struct MaterialArgs {
  const nlohmann::json& json;
  std::string key_path;
  const UnitSystem& units;
  Analysis analysis;
};

template <int Dim>
using MaterialRegistry = Registry<Material<Dim>, const MaterialArgs&>;

}  // namespace cleave

// Registers a material class template (taking the dimension, constructed from MaterialArgs) for 2D
// and 3D under `name`, the scene's "type". Put it in the material's own .cpp.
#define CLEAVE_REGISTER_MATERIAL(name, Class)                                                       \
  namespace {                                                                                       \
  [[maybe_unused]] const bool CLEAVE_REGISTRAR(cleave_material_2_) =                                \
      ::cleave::MaterialRegistry<2>::instance().add(name, [](const ::cleave::MaterialArgs& a) {     \
        return std::unique_ptr<::cleave::Material<2>>(new Class<2>(a));                             \
      });                                                                                           \
  [[maybe_unused]] const bool CLEAVE_REGISTRAR(cleave_material_3_) =                                \
      ::cleave::MaterialRegistry<3>::instance().add(name, [](const ::cleave::MaterialArgs& a) {     \
        return std::unique_ptr<::cleave::Material<3>>(new Class<3>(a));                             \
      });                                                                                           \
  }
