// Isotropic linear elasticity, small strain, integrated incrementally (hypoelastic form
// dsigma = C : deps), so the same code serves every stress-update scheme.
#include <cmath>
#include <set>

#include "libmpm/core/error.hpp"
#include "libmpm/material/material.hpp"

namespace cleave {
namespace {

template <int Dim>
class LinearElastic final : public Material<Dim> {
 public:
  explicit LinearElastic(const MaterialArgs& a) : analysis_(a.analysis) {
    const std::set<std::string> keys = {"name", "type", "E", "nu", "density"};
    for (auto it = a.json.begin(); it != a.json.end(); ++it)
      if (!keys.count(it.key()))
        throw SceneError(a.key_path + "." + it.key(),
                         "unknown key for a linear_elastic material; valid: name, type, E, nu, density");
    E_ = read_positive(a.json, "E", a.key_path, a.units.factor(Quantity::Stress));
    if (!a.json.contains("nu")) throw SceneError(a.key_path + ".nu", "missing (Poisson's ratio)");
    if (!a.json["nu"].is_number()) throw SceneError(a.key_path + ".nu", "expected a number");
    nu_ = a.json["nu"].get<double>();
    if (!(nu_ > -1.0 && nu_ < 0.5))
      throw SceneError(a.key_path + ".nu", "Poisson's ratio must satisfy -1 < nu < 0.5 (got " +
                                               std::to_string(nu_) + ")");
    this->density_ = read_positive(a.json, "density", a.key_path, a.units.factor(Quantity::Density));
    this->name_ = a.json.value("name", std::string());
    G_ = E_ / (2.0 * (1.0 + nu_));
    lambda_ = E_ * nu_ / ((1.0 + nu_) * (1.0 - 2.0 * nu_));
    if (analysis_ == Analysis::PlaneStress) lambda_ = 2.0 * G_ * lambda_ / (lambda_ + 2.0 * G_);
  }

  void update(Sym<Dim>& s, Sym<Dim>& e, const Mat<Dim>& L, double dt) const override {
    Sym<Dim> de = sym_part<Dim>(L) * dt;
    if constexpr (Dim == 2) {
      const double tr = de[0] + de[1];
      // Out of plane: plane strain keeps eps_zz = 0 and carries sigma_zz; plane stress the reverse.
      if (analysis_ == Analysis::PlaneStress) {
        de[2] = -nu_ / (1.0 - nu_) * tr;
      } else {
        s[2] += lambda_ * tr;
      }
      s[0] += lambda_ * tr + 2.0 * G_ * de[0];
      s[1] += lambda_ * tr + 2.0 * G_ * de[1];
      s[3] += 2.0 * G_ * de[3];
    } else {
      const double tr = de[0] + de[1] + de[2];
      for (int k = 0; k < 3; ++k) s[k] += lambda_ * tr + 2.0 * G_ * de[k];
      for (int k = 3; k < 6; ++k) s[k] += 2.0 * G_ * de[k];
    }
    e += de;
  }

  double strain_energy_density(const Sym<Dim>& s, const Sym<Dim>& e) const override {
    return 0.5 * sym_contract<Dim>(s, e);
  }

  double wave_speed() const override {
    // Dilatational speed; the plane-stress value is smaller, so this bound is safe for every analysis.
    const double M = E_ * (1.0 - nu_) / ((1.0 + nu_) * (1.0 - 2.0 * nu_));
    return std::sqrt(M / this->density_);
  }

 private:
  Analysis analysis_;
  double E_ = 0, nu_ = 0, G_ = 0, lambda_ = 0;
};

}  // namespace

double read_positive(const nlohmann::json& j, const std::string& key, const std::string& key_path,
                     double factor) {
  const std::string path = key_path + "." + key;
  if (!j.contains(key)) throw SceneError(path, "missing");
  if (!j[key].is_number()) throw SceneError(path, "expected a number");
  const double v = j[key].get<double>();
  if (!std::isfinite(v) || v <= 0.0)
    throw SceneError(path, "must be a positive number (got " + j[key].dump() + ")");
  return v * factor;
}

void register_builtin_materials() {
  static bool done = [] {
    MaterialRegistry<2>::instance().add("linear_elastic", [](const MaterialArgs& a) {
      return std::unique_ptr<Material<2>>(new LinearElastic<2>(a));
    });
    MaterialRegistry<3>::instance().add("linear_elastic", [](const MaterialArgs& a) {
      return std::unique_ptr<Material<3>>(new LinearElastic<3>(a));
    });
    return true;
  }();
  (void)done;
}

}  // namespace cleave
