#include "libmpm/io/particle_fields.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace cleave::io {
namespace {

template <int Dim>
std::array<double, 6> to_vtk6(const Sym<Dim>& s) {
  if constexpr (Dim == 2) return {s[0], s[1], s[2], s[3], 0.0, 0.0};
  else return {s[0], s[1], s[2], s[3], s[4], s[5]};
}

}  // namespace

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

template <int Dim>
PointSet particle_point_set(const Model<Dim>& m, const std::set<std::string>& fields) {
  const auto& P = m.particles;
  const std::size_t n = P.size();
  PointSet ps;
  ps.points.assign(3 * n, 0.0);
  for (std::size_t p = 0; p < n; ++p)
    for (int d = 0; d < Dim; ++d) ps.points[3 * p + d] = P.x[p][d];
  auto add = [&](const char* name, int comps, auto&& fill) {
    if (!fields.count(name)) return;
    PointArray a{name, comps, std::vector<double>(comps * n, 0.0)};
    for (std::size_t p = 0; p < n; ++p) fill(p, &a.values[comps * p]);
    ps.arrays.push_back(std::move(a));
  };
  add("displacement", 3, [&](std::size_t p, double* o) { for (int d = 0; d < Dim; ++d) o[d] = P.u[p][d]; });
  add("velocity", 3, [&](std::size_t p, double* o) { for (int d = 0; d < Dim; ++d) o[d] = P.v[p][d]; });
  add("stress", 6, [&](std::size_t p, double* o) { const auto t = to_vtk6<Dim>(P.stress[p]); std::copy(t.begin(), t.end(), o); });
  add("strain", 6, [&](std::size_t p, double* o) { const auto t = to_vtk6<Dim>(P.strain[p]); std::copy(t.begin(), t.end(), o); });
  add("material", 1, [&](std::size_t p, double* o) { o[0] = P.material[p]; });
  add("mass", 1, [&](std::size_t p, double* o) { o[0] = P.mass[p]; });
  add("volume", 1, [&](std::size_t p, double* o) { o[0] = P.volume(p); });
  // Edge of the particle's initial (undeformed) domain: the renderer draws each particle's footprint.
  add("size", 1, [&](std::size_t p, double* o) { o[0] = 2.0 * P.half_width[p] * m.grid.h; });
  if constexpr (Dim == 2)  // in-plane rotation, rad (the renderer turns footprints with it)
    add("rotation", 1, [&](std::size_t p, double* o) { o[0] = P.rotation[p]; });
  add("von_mises", 1, [&](std::size_t p, double* o) { o[0] = von_mises<Dim>(P.stress[p]); });
  add("principal_stress_difference", 1,
      [&](std::size_t p, double* o) { o[0] = principal_stress_difference<Dim>(P.stress[p]); });
  return ps;
}

template PointSet particle_point_set<2>(const Model<2>&, const std::set<std::string>&);
template PointSet particle_point_set<3>(const Model<3>&, const std::set<std::string>&);
template double von_mises<2>(const Sym<2>&);
template double von_mises<3>(const Sym<3>&);
template double principal_stress_difference<2>(const Sym<2>&);
template double principal_stress_difference<3>(const Sym<3>&);

}  // namespace cleave::io
