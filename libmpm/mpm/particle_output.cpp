#include "libmpm/mpm/particle_output.hpp"

#include "libmpm/io/particle_fields.hpp"

namespace cleave {

template <int Dim>
io::PointSet particle_point_set(const Model<Dim>& m, const std::set<std::string>& fields) {
  const auto& P = m.particles;
  const std::size_t n = P.size();
  io::PointSet ps;
  ps.points.assign(3 * n, 0.0);
  for (std::size_t p = 0; p < n; ++p)
    for (int d = 0; d < Dim; ++d) ps.points[3 * p + d] = P.x[p][d];
  auto add = [&](const char* name, int comps, auto&& fill) {
    if (!fields.count(name)) return;
    io::PointArray a{name, comps, std::vector<double>(comps * n, 0.0)};
    for (std::size_t p = 0; p < n; ++p) fill(p, &a.values[comps * p]);
    ps.arrays.push_back(std::move(a));
  };
  add("displacement", 3, [&](std::size_t p, double* o) { for (int d = 0; d < Dim; ++d) o[d] = P.u[p][d]; });
  add("velocity", 3, [&](std::size_t p, double* o) { for (int d = 0; d < Dim; ++d) o[d] = P.v[p][d]; });
  add("stress", 6, [&](std::size_t p, double* o) { const auto t = io::to_vtk6<Dim>(P.stress[p]); std::copy(t.begin(), t.end(), o); });
  add("strain", 6, [&](std::size_t p, double* o) { const auto t = io::to_vtk6<Dim>(P.strain[p]); std::copy(t.begin(), t.end(), o); });
  add("material", 1, [&](std::size_t p, double* o) { o[0] = P.material[p]; });
  add("mass", 1, [&](std::size_t p, double* o) { o[0] = P.mass[p]; });
  add("volume", 1, [&](std::size_t p, double* o) { o[0] = P.volume(p); });
  // Edge of the particle's initial (undeformed) domain: the renderer draws each particle's footprint.
  add("size", 1, [&](std::size_t p, double* o) { o[0] = 2.0 * P.half_width[p] * m.grid.h; });
  if constexpr (Dim == 2)  // in-plane rotation, rad (the renderer turns footprints with it)
    add("rotation", 1, [&](std::size_t p, double* o) { o[0] = P.rotation[p]; });
  add("von_mises", 1, [&](std::size_t p, double* o) { o[0] = io::von_mises<Dim>(P.stress[p]); });
  add("principal_stress_difference", 1,
      [&](std::size_t p, double* o) { o[0] = io::principal_stress_difference<Dim>(P.stress[p]); });
  return ps;
}

template io::PointSet particle_point_set<2>(const Model<2>&, const std::set<std::string>&);
template io::PointSet particle_point_set<3>(const Model<3>&, const std::set<std::string>&);

}  // namespace cleave
