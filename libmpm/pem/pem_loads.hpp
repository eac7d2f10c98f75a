// The scene's "loads" on a PEM mesh (scene/loads.hpp reads them): tractions on boundary facets
// (shared equally by the facet's nodes, on the facet's area projected on the face's axis, as MPM
// counts particle faces), body force on every particle's mass, velocity conditions and symmetry
// planes on the nodes they hold.
#pragma once
#include <array>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "libmpm/core/units.hpp"
#include "libmpm/pem/pem_model.hpp"

namespace cleave::pem {

// A facet of the mesh's boundary (an edge in 2D, a triangle or quadrangle in 3D): it belongs to one
// element only.
template <int Dim>
struct Facet {
  std::array<int32_t, 4> nodes{};
  int count = 0;
  Vec<Dim> normal = Vec<Dim>::Zero();  // unit, outward
  Vec<Dim> centroid = Vec<Dim>::Zero();
  double area = 0.0;  // length in 2D (the thickness is applied by the caller)
  int32_t region = 0;
  int32_t element = 0;
};

template <int Dim>
std::vector<Facet<Dim>> boundary_facets(const Mesh<Dim>& m);

// Resolves every load of the scene on m's particles (m.loads, m.gravity, fixed components).
template <int Dim>
void resolve_loads(const nlohmann::json& scene, const UnitSystem& units, PemSystem<Dim>& m);

}  // namespace cleave::pem
