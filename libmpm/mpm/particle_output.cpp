#include "libmpm/mpm/particle_output.hpp"

#include "libmpm/io/particle_fields.hpp"
#include "libmpm/io/point_set_builder.hpp"
#include "libmpm/mpm/particle_strain.hpp"

namespace cleave {

template <int Dim>
io::PointSet particle_point_set(const Model<Dim>& m, const std::set<std::string>& fields) {
  const auto& P = m.particles;
  const StrainOf<Dim> strain(m);  // (computed only for the fields that ask for it)
  io::PointSetBuilder<Dim> b(fields, P.size(), [&](std::size_t p) { return P.x[p]; });
  b.add_vectors("displacement", P.u);
  b.add_vectors("velocity", P.v);
  b.add("stress", 6, [&](std::size_t p, double* o) { const auto t = io::to_vtk6<Dim>(P.stress[p]); std::copy(t.begin(), t.end(), o); });
  b.add("strain", 6, [&](std::size_t p, double* o) { const auto t = io::to_vtk6<Dim>(strain(p)); std::copy(t.begin(), t.end(), o); });
  b.add_scalars("material", [&](std::size_t p) { return double(P.material[p]); });
  b.add_scalars("mass", [&](std::size_t p) { return P.mass[p]; });
  b.add_scalars("volume", [&](std::size_t p) { return strain.volume(p); });
  // Edge of the particle's initial (undeformed) domain: the renderer draws each particle's footprint.
  b.add_scalars("size", [&](std::size_t p) { return 2.0 * P.half_width[p] * m.grid.h; });
  if constexpr (Dim == 2)  // in-plane rotation, rad (the renderer turns footprints with it)
    b.add_scalars("rotation", [&](std::size_t p) { return P.rotation[p]; });
  b.add_scalars("von_mises", [&](std::size_t p) { return io::von_mises<Dim>(P.stress[p]); });
  b.add_scalars("principal_stress_difference", [&](std::size_t p) { return io::principal_stress_difference<Dim>(P.stress[p]); });
  return b.take();
}

template io::PointSet particle_point_set<2>(const Model<2>&, const std::set<std::string>&);
template io::PointSet particle_point_set<3>(const Model<3>&, const std::set<std::string>&);

}  // namespace cleave
