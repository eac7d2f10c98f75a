// Material points stored as a structure of arrays: each field is one contiguous array, so the
// per-particle loops stream memory and vectorise, and a 2D model holds only 2D vectors.
#pragma once
#include <cstdint>
#include <vector>

#include "libmpm/core/types.hpp"

namespace cleave {

template <int Dim>
struct Particles {
  std::vector<Vec<Dim>> x;       // position
  std::vector<Vec<Dim>> v;       // velocity
  std::vector<Vec<Dim>> u;       // displacement from the initial position
  std::vector<Sym<Dim>> stress;  // Cauchy stress
  std::vector<Sym<Dim>> strain;  // small-strain tensor (see strain_derived)
  std::vector<double> mass;
  std::vector<double> volume0;     // initial volume (2D: area times thickness)
  std::vector<double> half_width;  // half the particle's domain, in cells (uGIMP)
  std::vector<int32_t> material;   // index into Model::materials
  std::vector<double> rotation;    // 2D only: in-plane rotation (rad) integrated from the spin
  // 3D, only when the scene asks for crack-front parameters (their displacement gradients need the
  // rotation, the strain alone is symmetric): the rotation vector (W_21, W_02, W_10) integrated from
  // the spin. Empty otherwise, so that other 3D runs neither store nor update it.
  std::vector<Vec<3>> rotation3;
  // Set by a stepper that advances only the stress (every material linear elastic): `strain` is then
  // current only after Stepper::sync_strain(), and readers between steps use StrainOf
  // (particle_strain.hpp), which takes it from the stress.
  bool strain_derived = false;

  std::size_t size() const { return x.size(); }
  void resize(std::size_t n) {
    x.resize(n);
    v.resize(n);
    u.resize(n);
    stress.resize(n);
    strain.resize(n);
    mass.resize(n);
    volume0.resize(n);
    half_width.resize(n);
    material.resize(n);
    if constexpr (Dim == 2) rotation.resize(n);
  }
};

// The volume of a particle of initial volume v0 at strain e (seed 002's eq. 25, times the out-of-plane
// stretch).
template <int Dim>
inline double strained_volume(double v0, const Sym<Dim>& e) {
  return v0 * (1.0 + e[0]) * (1.0 + e[1]) * (1.0 + e[2]);
}

// The rotation of particle p advanced by the spin of its velocity gradient L over dts (2D: in-plane,
// for the renderer and for displacement contact detection; 3D: only where rotation3 is kept).
template <int Dim>
CLEAVE_INLINE inline void integrate_spin(Particles<Dim>& P, std::size_t p, const Mat<Dim>& L, double dts) {
  if constexpr (Dim == 2) P.rotation[p] += 0.5 * (L(1, 0) - L(0, 1)) * dts;
  else if (!P.rotation3.empty()) {  // on scalars: as an Eigen expression, an out-of-line call per particle
    const double k = 0.5 * dts;
    Vec<3>& r = P.rotation3[p];
    r[0] += k * (L(2, 1) - L(1, 2)), r[1] += k * (L(0, 2) - L(2, 0)), r[2] += k * (L(1, 0) - L(0, 1));
  }
}

}  // namespace cleave
