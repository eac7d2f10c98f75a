#include "libmpm/pem/pem_loads.hpp"

#include <algorithm>
#include <map>

#include <Eigen/Geometry>

#include "libmpm/core/error.hpp"
#include "libmpm/scene/loads.hpp"
#include "libmpm/scene/sections.hpp"

namespace cleave::pem {
namespace {

// The facets of an element as local node lists (Gmsh's node order).
template <int Dim>
std::vector<std::vector<int>> local_facets(int nodes) {
  if constexpr (Dim == 2) {
    std::vector<std::vector<int>> f;
    for (int k = 0; k < nodes; ++k) f.push_back({k, (k + 1) % nodes});
    return f;
  } else {
    if (nodes == 4) return {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
    return {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  }
}

}  // namespace

template <int Dim>
std::vector<Facet<Dim>> boundary_facets(const Mesh<Dim>& m) {
  // Facets keyed by their sorted nodes; a key met once lies on the boundary.
  std::map<std::array<int32_t, 4>, std::pair<int, Facet<Dim>>> seen;
  for (std::size_t e = 0; e < m.element_count(); ++e) {
    const int n = m.nodes_of(e);
    const int32_t* en = m.element(e);
    Vec<Dim> centre = Vec<Dim>::Zero();
    for (int k = 0; k < n; ++k) centre += m.nodes[en[k]];
    centre /= n;
    for (const auto& lf : local_facets<Dim>(n)) {
      Facet<Dim> f;
      f.count = static_cast<int>(lf.size());
      std::array<int32_t, 4> key;
      key.fill(-1);
      for (int k = 0; k < f.count; ++k) key[k] = f.nodes[k] = en[lf[k]];
      // Insertion sort of the first f.count (2 to 4) nodes: std::sort on a variable prefix of the
      // array drew GCC 12's -Warray-bounds false positive.
      for (int a = 1; a < f.count; ++a)
        for (int b = a; b > 0 && key[b - 1] > key[b]; --b) std::swap(key[b - 1], key[b]);
      for (int k = 0; k < f.count; ++k) f.centroid += m.nodes[f.nodes[k]];
      f.centroid /= f.count;
      if constexpr (Dim == 2) {
        const Vec<2> d = m.nodes[f.nodes[1]] - m.nodes[f.nodes[0]];
        f.area = d.norm();
        f.normal = Vec<2>(d[1], -d[0]) / f.area;
      } else {
        Vec<3> nrm = Vec<3>::Zero();
        for (int k = 1; k + 1 < f.count; ++k)
          nrm += 0.5 * (m.nodes[f.nodes[k]] - m.nodes[f.nodes[0]]).cross(m.nodes[f.nodes[k + 1]] - m.nodes[f.nodes[0]]);
        f.area = nrm.norm();
        f.normal = nrm / f.area;
      }
      if (f.normal.dot(f.centroid - centre) < 0) f.normal = -f.normal;
      f.region = m.element_region[e];
      f.element = static_cast<int32_t>(e);
      auto [it, fresh] = seen.try_emplace(key, 0, f);
      ++it->second.first;
    }
  }
  std::vector<Facet<Dim>> out;
  for (const auto& [key, v] : seen)
    if (v.first == 1) out.push_back(v.second);
  return out;
}

template <int Dim>
void resolve_loads(const nlohmann::json& scene, const UnitSystem& units, PemSystem<Dim>& m) {
  auto& P = m.points;
  const std::size_t n = P.x0.size();
  const double tol = 1e-6 * m.mesh_size;
  const double depth = Dim == 2 ? m.thickness : 1.0;
  std::vector<Facet<Dim>> facets;  // built on the first traction
  scene::LoadResolvers<Dim> resolvers;
  resolvers["traction"] = [&](const scene::LoadSpec<Dim>& s) {
    if (facets.empty()) facets = boundary_facets(m.mesh);
    PemLoad<Dim> ld;
    ld.name = s.name;
    ld.rise_time = s.rise_time;
    std::map<int32_t, double> weight;   // node -> projected area (m^2)
    double total = 0.0;
    for (const auto& f : facets) {
      if (s.body >= 0 && f.region != s.body) continue;
      if (s.has_region && !scene::in_box<Dim>(f.centroid, s.lo, s.hi, tol)) continue;
      const double look = f.normal[s.axis] * s.side;  // the facet looks along the face
      if (!(look > 1e-9)) continue;
      const double projected = f.area * depth * look;
      total += projected;
      for (int k = 0; k < f.count; ++k) weight[f.nodes[k]] += projected / f.count;
    }
    if (weight.empty())
      throw SceneError(s.path, "no boundary facet looking along " + s.face + " lies inside the region: nothing would be loaded");
    const Vec<Dim> traction = s.total_force ? Vec<Dim>(s.vector / total) : s.vector;
    for (const auto& [node, w] : weight) ld.nodes.push_back(node), ld.force.push_back(traction * w);
    m.loads.push_back(std::move(ld));
  };
  resolvers["body_force"] = [&](const scene::LoadSpec<Dim>& s) { m.gravity += s.vector; };
  resolvers["velocity"] = [&](const scene::LoadSpec<Dim>& s) {
    int count = 0;
    for (std::size_t p = 0; p < n; ++p) {
      if (!scene::in_box<Dim>(P.x0[p], s.lo, s.hi, tol)) continue;
      if (s.body >= 0 && P.region[p] != s.body) continue;
      ++count;
      P.fixed[p] |= s.mask;
      for (int d = 0; d < Dim; ++d)
        if (s.mask & (1u << d)) P.v_fixed[p][d] = s.vector[d], P.v[p][d] = s.vector[d];
    }
    if (!count) {
      // Mesh nodes sit where Gmsh puts them: a region smaller than an element (a pin at a point) takes
      // the node nearest to its centre, when that node lies within one element size of the region.
      const Vec<Dim> centre = 0.5 * (s.lo + s.hi);
      std::size_t best = n;
      for (std::size_t p = 0; p < n; ++p)
        if ((s.body < 0 || P.region[p] == s.body) && (best == n || (P.x0[p] - centre).norm() < (P.x0[best] - centre).norm()))
          best = p;
      const double gap = best < n ? (P.x0[best] - P.x0[best].cwiseMax(s.lo).cwiseMin(s.hi)).norm() : INFINITY;
      if (!(gap <= m.mesh_size))
        throw SceneError(s.at("region"), "no particle (mesh node) lies inside the region or within one element size of it");
      m.warnings.push_back(s.at("region") + " holds no mesh node: the condition holds the nearest, " +
                           scene::fmt(gap) + " m outside the region");
      P.fixed[best] |= s.mask;
      for (int d = 0; d < Dim; ++d)
        if (s.mask & (1u << d)) P.v_fixed[best][d] = s.vector[d], P.v[best][d] = s.vector[d];
    }
  };
  resolvers["symmetry"] = [&](const scene::LoadSpec<Dim>& s) {
    int count = 0;
    for (std::size_t p = 0; p < n; ++p)
      if (std::fabs(P.x0[p][s.axis] - s.position) <= tol) {
        ++count;
        P.fixed[p] |= uint8_t(1u << s.axis);
        P.v_fixed[p][s.axis] = 0.0, P.v[p][s.axis] = 0.0;
      }
    if (!count) throw SceneError(s.at("position"), "no particle (mesh node) lies on the plane");
  };
  scene::read_loads<Dim>(scene, {units, m.regions}, "pem", resolvers);
}

template std::vector<Facet<2>> boundary_facets<2>(const Mesh<2>&);
template std::vector<Facet<3>> boundary_facets<3>(const Mesh<3>&);
template void resolve_loads<2>(const nlohmann::json&, const UnitSystem&, PemSystem<2>&);
template void resolve_loads<3>(const nlohmann::json&, const UnitSystem&, PemSystem<3>&);

}  // namespace cleave::pem
