// Isotropic linear elasticity, small strain, integrated incrementally (hypoelastic form
// dsigma = C : deps, stress and strain first turned with the material's spin: SpinRotation), so the
// same code serves every stress-update scheme. Declared in a header so
// that the solver's stress pass can call it without a virtual call when every material is of this
// kind (the common case, and the one the benchmark measures).
#pragma once
#include <cmath>

#include "libmpm/core/error.hpp"
#include "libmpm/material/material.hpp"
#include "libmpm/core/json_reader.hpp"

namespace cleave {

template <int Dim>
class LinearElastic final : public Material<Dim> {
 public:
  explicit LinearElastic(const MaterialArgs& a) : analysis_(a.analysis) {
    const ObjectReader r(a.json, a.key_path, {"name", "type", "E", "nu", "density", "G_c", "K_Ic", "fracture_energy"});
    E_ = r.positive("E", a.units.factor(Quantity::Stress));
    nu_ = r.number("nu");
    if (!(nu_ > -1.0 && nu_ < 0.5))
      throw SceneError(r.at("nu"), "Poisson's ratio must satisfy -1 < nu < 0.5 (got " + std::to_string(nu_) + ")");
    this->density_ = r.positive("density", a.units.factor(Quantity::Density));
    this->name_ = a.json.value("name", std::string());
    this->read_toughness(r, a.units);
    G_ = E_ / (2.0 * (1.0 + nu_));
    lambda_ = E_ * nu_ / ((1.0 + nu_) * (1.0 - 2.0 * nu_));
    plane_stress_ = analysis_ == Analysis::PlaneStress;
    if (plane_stress_) lambda_ = 2.0 * G_ * lambda_ / (lambda_ + 2.0 * G_);
  }

  void update(Sym<Dim>& s, Sym<Dim>& e, const Mat<Dim>& L, double dt) const override { update_inline(s, e, L, dt); }

  // The update on scalars (no temporaries in memory): called directly by the solver's stress pass.
  CLEAVE_INLINE inline void update_inline(Sym<Dim>& s, Sym<Dim>& e, const Mat<Dim>& L, double dt) const {
    update_impl<true>(s, &e, L, dt);
  }
  // The same without the strain, for a solver that takes the strain from the stress (strain_from_stress)
  // where it is read: the strain's turn and increments were half of what the spin's rotation added to
  // a 2D step (docs/performance.md, "Issue 14's performance").
  CLEAVE_INLINE inline void update_stress_inline(Sym<Dim>& s, const Mat<Dim>& L, double dt) const {
    update_impl<false>(s, nullptr, L, dt);
  }

  // Stress and strain start at zero and change together (sigma = C : eps, both turned alike, which C,
  // isotropic, commutes with), so the strain is C^-1 : sigma: plane strain keeps eps_zz = 0, plane
  // stress has eps_zz = -nu / (1 - nu) (eps_xx + eps_yy), as update_inline carries them.
  bool strain_from_stress(const Sym<Dim>& s, Sym<Dim>& e) const override {
    strain_from_stress_inline(s, e);
    return true;
  }
  CLEAVE_INLINE void strain_from_stress_inline(const Sym<Dim>& s, Sym<Dim>& e) const {
    const double inv_2g = 0.5 / G_;
    if constexpr (Dim == 2) {
      const double tr = (s[0] + s[1]) / (2.0 * (lambda_ + G_));  // eps_xx + eps_yy
      e[0] = (s[0] - lambda_ * tr) * inv_2g, e[1] = (s[1] - lambda_ * tr) * inv_2g, e[3] = s[3] * inv_2g;
      e[2] = plane_stress_ ? -nu_ / (1.0 - nu_) * tr : 0.0;
    } else {
      const double tr = (s[0] + s[1] + s[2]) / (3.0 * lambda_ + 2.0 * G_);
      for (int i = 0; i < 3; ++i) e[i] = (s[i] - lambda_ * tr) * inv_2g;
      for (int i = 3; i < 6; ++i) e[i] = s[i] * inv_2g;
    }
  }

  double strain_energy_density(const Sym<Dim>& s, const Sym<Dim>& e) const override {
    return 0.5 * sym_contract<Dim>(s, e);
  }

  bool isotropic_elastic(double& shear_modulus, double& poisson) const override {
    shear_modulus = G_;
    poisson = nu_;
    return true;
  }

  double wave_speed() const override {
    // Dilatational speed of the analysis: a thin plate's in-plane P-wave modulus is E / (1 - nu^2), lower than
    // the solid's (for nu = 0.37 the plane-strain bound took 24 % more steps than stability needs).
    const double M = plane_stress_ ? E_ / (1.0 - nu_ * nu_) : E_ * (1.0 - nu_) / ((1.0 + nu_) * (1.0 - 2.0 * nu_));
    return std::sqrt(M / this->density_);
  }

 private:
  template <bool kStrain>
  CLEAVE_INLINE inline void update_impl(Sym<Dim>& s, Sym<Dim>* e, const Mat<Dim>& L, double dt) const {
    const SpinRotation<Dim> R(L, dt);
    R.apply(s);
    if constexpr (kStrain) R.apply(*e);
    const double exx = L(0, 0) * dt, eyy = L(1, 1) * dt, exy = 0.5 * (L(0, 1) + L(1, 0)) * dt;
    if constexpr (Dim == 2) {
      const double tr = exx + eyy;
      // Out of plane: plane strain keeps eps_zz = 0 and carries sigma_zz; plane stress the reverse.
      if (plane_stress_) {
        if constexpr (kStrain) (*e)[2] -= nu_ / (1.0 - nu_) * tr;
      } else {
        s[2] += lambda_ * tr;
      }
      s[0] += lambda_ * tr + 2.0 * G_ * exx;
      s[1] += lambda_ * tr + 2.0 * G_ * eyy;
      s[3] += 2.0 * G_ * exy;
      if constexpr (kStrain) (*e)[0] += exx, (*e)[1] += eyy, (*e)[3] += exy;
    } else {
      const double ezz = L(2, 2) * dt, eyz = 0.5 * (L(1, 2) + L(2, 1)) * dt, exz = 0.5 * (L(0, 2) + L(2, 0)) * dt;
      const double tr = exx + eyy + ezz;
      s[0] += lambda_ * tr + 2.0 * G_ * exx;
      s[1] += lambda_ * tr + 2.0 * G_ * eyy;
      s[2] += lambda_ * tr + 2.0 * G_ * ezz;
      s[3] += 2.0 * G_ * exy;
      s[4] += 2.0 * G_ * eyz;
      s[5] += 2.0 * G_ * exz;
      if constexpr (kStrain) (*e)[0] += exx, (*e)[1] += eyy, (*e)[2] += ezz, (*e)[3] += exy, (*e)[4] += eyz, (*e)[5] += exz;
    }
  }
  Analysis analysis_;
  bool plane_stress_ = false;
  double E_ = 0, nu_ = 0, G_ = 0, lambda_ = 0;
};

}  // namespace cleave
