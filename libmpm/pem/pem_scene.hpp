// Scene -> PEM model for scenes with "method": "pem" (docs/pem.md, docs/scenes.md "PEM"): the bodies
// meshed by Gmsh (or "pem.mesh_file"), particles at the nodes, pairs of every element with calibrated
// stiffness, pre-cracks, loads on nodes and facets, the run settings. Errors name the key path.
#pragma once
#include <nlohmann/json.hpp>

#include "libmpm/pem/pem_model.hpp"

namespace cleave::pem {

template <int Dim>
PemSystem<Dim> build_pem_system(const nlohmann::json& scene);

// The pairs of element e: every two of its nodes, (i, j) with i < j, in node order.
template <int Dim>
void element_pairs(const Mesh<Dim>& m, std::size_t e, std::vector<std::pair<int32_t, int32_t>>& out);

}  // namespace cleave::pem
