// Basic numeric types shared by every module. Everything is templated on the spatial dimension
// (2 or 3) so that 2D scenes allocate nothing three-dimensional.
#pragma once
#include <Eigen/Core>
#include <cstdint>

// Inlined wherever it is called: for the per-particle functions of the hot loops (a pass body, the
// stencil and shape-function evaluation, the elastic update). GCC 12 stops inlining once a pass
// function grows (a body used by two loops: a pass's variants with and without cracks), and a call
// per particle then costs several per cent of a step (docs/performance.md, crack overhead).
#define CLEAVE_INLINE __attribute__((always_inline))

namespace cleave {

template <int Dim> using Vec = Eigen::Matrix<double, Dim, 1>;
template <int Dim> using Mat = Eigen::Matrix<double, Dim, Dim>;

// Number of independent components of a symmetric stress/strain tensor as stored on particles.
// 2D keeps the out-of-plane normal component (plane strain has sigma_zz, plane stress has eps_zz):
//   2D: xx, yy, zz, xy          3D: xx, yy, zz, xy, yz, xz
// which is a prefix of VTK's symmetric-tensor order (XX, YY, ZZ, XY, YZ, XZ).
template <int Dim> constexpr int kSymComponents = Dim == 2 ? 4 : 6;
template <int Dim> using Sym = Eigen::Matrix<double, kSymComponents<Dim>, 1>;

enum class Analysis { PlaneStrain, PlaneStress, ThreeD };

inline constexpr int dimension_of(Analysis a) { return a == Analysis::ThreeD ? 3 : 2; }

// Symmetric part of a velocity gradient (tensor, not engineering, shear) into Sym storage.
template <int Dim> inline Sym<Dim> sym_part(const Mat<Dim>& L) {
  Sym<Dim> s;
  if constexpr (Dim == 2) {
    s << L(0, 0), L(1, 1), 0.0, 0.5 * (L(0, 1) + L(1, 0));
  } else {
    s << L(0, 0), L(1, 1), L(2, 2), 0.5 * (L(0, 1) + L(1, 0)), 0.5 * (L(1, 2) + L(2, 1)),
        0.5 * (L(0, 2) + L(2, 0));
  }
  return s;
}

// sigma . g for a Sym-stored stress and an in-space vector g (the out-of-plane zz part never enters in 2D).
template <int Dim> inline Vec<Dim> sym_dot(const Sym<Dim>& s, const Vec<Dim>& g) {
  Vec<Dim> r;
  if constexpr (Dim == 2) {
    r << s[0] * g[0] + s[3] * g[1], s[3] * g[0] + s[1] * g[1];
  } else {
    r << s[0] * g[0] + s[3] * g[1] + s[5] * g[2], s[3] * g[0] + s[1] * g[1] + s[4] * g[2],
        s[5] * g[0] + s[4] * g[1] + s[2] * g[2];
  }
  return r;
}

// Full double contraction sigma : eps for tensor-stored symmetric tensors (shear counted twice).
template <int Dim> inline double sym_contract(const Sym<Dim>& a, const Sym<Dim>& b) {
  if constexpr (Dim == 2) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + 2.0 * a[3] * b[3];
  } else {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + 2.0 * (a[3] * b[3] + a[4] * b[4] + a[5] * b[5]);
  }
}

}  // namespace cleave
