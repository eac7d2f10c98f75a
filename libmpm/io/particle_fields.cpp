#include "libmpm/io/particle_fields.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace cleave::io {
template <int Dim>
std::array<double, 6> to_vtk6(const Sym<Dim>& s) {
  if constexpr (Dim == 2) return {s[0], s[1], s[2], s[3], 0.0, 0.0};
  else return {s[0], s[1], s[2], s[3], s[4], s[5]};
}

template <int Dim>
double von_mises(const Sym<Dim>& s) {
  const auto t = to_vtk6<Dim>(s);
  const double a = t[0] - t[1], b = t[1] - t[2], c = t[2] - t[0];
  return std::sqrt(0.5 * (a * a + b * b + c * c) + 3.0 * (t[3] * t[3] + t[4] * t[4] + t[5] * t[5]));
}

template <int Dim>
double principal_stress_difference(const Sym<Dim>& s) {
  if constexpr (Dim == 2) {
    return std::sqrt((s[0] - s[1]) * (s[0] - s[1]) + 4.0 * s[3] * s[3]);
  } else {
    Eigen::Matrix3d M;
    M << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
    const Eigen::Vector3d ev = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(M, Eigen::EigenvaluesOnly).eigenvalues();
    return ev[2] - ev[0];
  }
}

template std::array<double, 6> to_vtk6<2>(const Sym<2>&);
template std::array<double, 6> to_vtk6<3>(const Sym<3>&);
template double von_mises<2>(const Sym<2>&);
template double von_mises<3>(const Sym<3>&);
template double principal_stress_difference<2>(const Sym<2>&);
template double principal_stress_difference<3>(const Sym<3>&);

}  // namespace cleave::io
