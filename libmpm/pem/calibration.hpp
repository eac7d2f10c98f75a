// Pair stiffness from the continuum, element by element (docs/pem.md, "Calibration"). Under a uniform
// strain eps a pair of direction t and length l stretches by l (t.eps.t), so an element's pairs store
// 1/2 sum_p a_p (t_p.eps.t_p)^2 with a_p = k_p l_p^2, and match the element's continuum energy
// V/2 eps:C:eps when sum_p a_p t_p(x)t_p(x)t_p(x)t_p = V C. A sum of such tensors is fully symmetric
// (Cauchy relations: lambda = mu), so the target C is the isotropic tensor with that symmetry and the
// material's E (nu 1/3 in plane stress, 1/4 in plane strain and 3D); the a_p >= 0 are its least-squares
// fit (Frobenius norm; Gram matrix (t_p.t_q)^4, right side 3 mu V). A triangle's three pairs fit it
// exactly only when equilateral, so each material's stiffnesses are then scaled together so that the
// network's homogenised tensor has the material's E; its nu and its departure from isotropy are
// reported, not hidden.
#pragma once
#include <vector>

#include "libmpm/core/types.hpp"

namespace cleave::pem {

// The non-negative least-squares a_p of one element whose pairs have unit directions t[0..n), for an
// element volume V and the target shear modulus mu (lambda = mu).
template <int Dim>
std::vector<double> fit_element_pairs(const std::vector<Vec<Dim>>& t, double volume, double mu);

// Non-negative least squares on normal equations: argmin 1/2 a^T G a - b^T a subject to a >= 0
// (Lawson and Hanson's active set method; G symmetric positive semi-definite).
std::vector<double> nnls_normal(const std::vector<double>& G, const std::vector<double>& b, int n);

// Homogenised fourth-order tensor of a set of pairs, kept as the Dim^4 components: accumulates
// a t(x)t(x)t(x)t, then reads off the isotropic part.
template <int Dim>
struct NetworkTensor {
  std::vector<double> c = std::vector<double>(Dim * Dim * Dim * Dim, 0.0);
  double volume = 0.0;
  void add(const Vec<Dim>& t, double a);
  // Least-squares isotropic part (Lame lambda, mu) of c / volume, and the relative Frobenius norm
  // of the rest.
  void isotropic(double& lambda, double& mu, double& anisotropy) const;
};

// E and nu of an isotropic Lame pair in the analysis (plane stress: the 2D constants are the plane-stress
// ones; plane strain and 3D: the 3D constants).
void young_poisson(double lambda, double mu, bool plane_stress_2d, double& E, double& nu);

// The Cauchy (central-force) Poisson's ratio of an analysis: 1/3 in plane stress, 1/4 otherwise.
inline double cauchy_nu(bool plane_stress_2d) { return plane_stress_2d ? 1.0 / 3.0 : 0.25; }

}  // namespace cleave::pem
