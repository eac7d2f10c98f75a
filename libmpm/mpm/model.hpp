// Everything a run needs, built from a scene and expressed in SI: grid, bodies as particles,
// materials, loads, grid conditions and the solver settings. Only what the scene declares exists.
#pragma once
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "libmpm/core/run_settings.hpp"
#include "libmpm/crack/crack2d.hpp"
#include "libmpm/crack/front_parameters.hpp"
#include "libmpm/crack/propagation.hpp"
#include "libmpm/crack/tip_parameters.hpp"
#include "libmpm/material/material.hpp"
#include "libmpm/mpm/body_contact.hpp"
#include "libmpm/mpm/grid.hpp"
#include "libmpm/mpm/loads.hpp"
#include "libmpm/mpm/particles.hpp"
#include "libmpm/shape/shape_function.hpp"
#include "libmpm/shape/shape_registry.hpp"
#include "libmpm/mpm/scheme.hpp"

namespace cleave {

struct Body {
  std::string name;
  int material = 0;
  std::size_t first = 0, count = 0;  // particle range
  double thickness = 1.0;            // 2D only
};

// Prescribed nodal velocity components, merged over every condition of the scene: one entry per node.
template <int Dim>
struct GridConditions {
  std::vector<int64_t> node;
  std::vector<uint8_t> mask;  // bit d set: velocity component d prescribed
  std::vector<Vec<Dim>> velocity;
};

template <int Dim>
// The run settings (end time, dt, output, checks, damping, title, warnings) come from the shared
// scene sections (core/run_settings.hpp).
struct Model : RunSettings {
  Analysis analysis = Dim == 3 ? Analysis::ThreeD : Analysis::PlaneStrain;
  GridGeometry<Dim> grid;
  ShapeFunctionKind shape_function = ShapeFunctionKind::UGimp;
  Scheme scheme = Scheme::USAVG;
  bool spin_transfer = false;  // mpm.spin_transfer: nodal velocities carried with the scene's spin (spin_transfer.hpp)
  std::vector<std::unique_ptr<Material<Dim>>> materials;
  std::vector<Body> bodies;
  Particles<Dim> particles;
  BodyContact body_contact;  // fields of their own for bodies in contact (none unless the scene declares it)
  std::vector<crack::ExplicitCrack<Dim>> cracks;  // explicit cracks (none in uncracked scenes)
  std::optional<crack::TipSettings> crack_tips;  // J and K at the crack tips, when the scene asks
  // 2D: per crack, how it grows (cracks[i].propagation); empty when no crack grows.
  std::vector<std::optional<crack::Propagation>> propagation;
  // 3D: the closed-form references crack_tips.reference names (crack_fronts.csv's *_ref columns).
  std::vector<crack::EllipseReference> front_references;
  std::vector<TractionLoad<Dim>> tractions;
  Vec<Dim> gravity = Vec<Dim>::Zero();
  GridConditions<Dim> conditions;
  // The symmetry planes of the scene's loads: (axis, position). The conditions above hold them as
  // node velocities; the crack-front parameters need the planes (a front node on one is mirrored).
  std::vector<std::pair<int, double>> symmetry_planes;
};

// With contact between bodies: each particle's field group (body_contact.hpp), and each crack's, that of
// the particle nearest its first point (the body the crack lies in). Empty without it.
template <int Dim>
std::vector<uint8_t> particle_groups(const Model<Dim>& m) {
  std::vector<uint8_t> g;
  if (!m.body_contact.active()) return g;
  g.assign(m.particles.size(), 0);
  for (std::size_t k = 0; k < m.bodies.size(); ++k)
    for (std::size_t p = m.bodies[k].first; p < m.bodies[k].first + m.bodies[k].count; ++p) g[p] = m.body_contact.group[k];
  return g;
}
template <int Dim>
uint8_t crack_group(const Model<Dim>& m, const std::vector<uint8_t>& groups, std::size_t crack) {
  uint8_t best_g = 0;
  double best = INFINITY;
  for (std::size_t p = 0; p < groups.size(); ++p) {
    const double d = (m.particles.x[p] - m.cracks[crack].points[0]).squaredNorm();
    if (d < best) best = d, best_g = groups[p];
  }
  return best_g;
}

}  // namespace cleave
