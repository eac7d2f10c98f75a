// A particle's strain where the stepper does not carry it. For linear elasticity the strain is
// C^-1 : sigma exactly (LinearElastic::strain_from_stress), so when every material is linear elastic
// the stepper (mpm_step.cpp) advances only the stress: the strain's turn and increments were most of
// what the objective update added to a step (docs/performance.md, issue 14). Particles::strain is then
// current only after Stepper::sync_strain(); whatever reads it between steps (frames, crack contact's
// particle volumes, the J evaluators) takes it through StrainOf.
#pragma once
#include <cstddef>
#include <stdexcept>

#include "libmpm/material/linear_elastic.hpp"
#include "libmpm/mpm/model.hpp"

namespace cleave {

template <int Dim>
class StrainOf {
 public:
  explicit StrainOf(const Model<Dim>& m) : P_(m.particles), materials_(m.materials) {
    if (P_.strain_derived)
      for (const auto& mat : materials_)
        if (!dynamic_cast<const LinearElastic<Dim>*>(mat.get()))
          throw std::logic_error("StrainOf: the strain is taken from the stress, but material '" + mat->name() +
                                 "' is not linear elastic");
  }

  // (While strain_derived every material is linear elastic, checked above: no virtual call, for the J
  // evaluators read it per particle.)
  CLEAVE_INLINE Sym<Dim> operator()(std::size_t p) const {
    if (!P_.strain_derived) return P_.strain[p];
    Sym<Dim> e;
    static_cast<const LinearElastic<Dim>*>(materials_[P_.material[p]].get())->strain_from_stress_inline(P_.stress[p], e);
    return e;
  }
  // The volume from the normal strains (seed 002's eq. 25, strained_volume).
  double volume(std::size_t p) const { return strained_volume<Dim>(P_.volume0[p], (*this)(p)); }

 private:
  const Particles<Dim>& P_;
  const std::vector<std::unique_ptr<Material<Dim>>>& materials_;
};

}  // namespace cleave
