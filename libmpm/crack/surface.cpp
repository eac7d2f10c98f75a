#include "libmpm/crack/surface.hpp"

#include <algorithm>
#include <map>

#include "libmpm/crack/crack2d.hpp"
#include "libmpm/crack/surface3d.hpp"

namespace cleave::crack {

template <int Dim>
void Surface<Dim>::update_extent() {
  lo = Vec<Dim>::Constant(std::numeric_limits<double>::infinity());
  hi = Vec<Dim>::Constant(-std::numeric_limits<double>::infinity());
  for (const auto& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
}

template <int Dim>
std::vector<std::array<int32_t, Dim - 1>> Surface<Dim>::boundary() const {
  using Facet = std::array<int32_t, Dim - 1>;
  std::map<Facet, int> uses;  // facets with sorted indices
  std::vector<Facet> order;   // each facet as first met (simplex order, orientation kept)
  for (const auto& s : simplices)
    for (int k = 0; k < Dim; ++k) {
      Facet f;  // the facet opposite vertex k, in the simplex's cyclic order (3D: edges run as the triangle does)
      for (int n = 0; n + 1 < Dim; ++n) f[n] = s[(k + 1 + n) % Dim];
      Facet key = f;
      std::sort(key.begin(), key.end());
      if (uses[key]++ == 0) order.push_back(f);
    }
  std::vector<Facet> out;
  for (const auto& f : order) {
    Facet key = f;
    std::sort(key.begin(), key.end());
    if (uses[key] == 1) out.push_back(f);
  }
  return out;
}

template <int Dim>
bool segment_crosses(const Surface<Dim>& s, const Vec<Dim>& a, const Vec<Dim>& b) {
  if ((a.cwiseMax(b).array() < s.lo.array()).any() || (a.cwiseMin(b).array() > s.hi.array()).any()) return false;
  for (const auto& t : s.simplices) {
    if constexpr (Dim == 2) {
      if (segments_intersect(a, b, s.points[t[0]], s.points[t[1]])) return true;
    } else {
      if (segment_hits_triangle(a, b, s.points[t[0]], s.points[t[1]], s.points[t[2]])) return true;
    }
  }
  return false;
}

template <>
std::vector<Surface<2>> read_surfaces<2>(const nlohmann::json& cracks, const std::string& key_path, double L,
                                         const SurfaceMeshing&) {
  std::vector<Surface<2>> out;
  for (auto& c : parse_cracks(cracks, key_path, L)) out.push_back(static_cast<Surface<2>&&>(c));  // the geometry alone
  return out;
}

template <>
std::vector<Surface<3>> read_surfaces<3>(const nlohmann::json& cracks, const std::string& key_path, double L,
                                         const SurfaceMeshing& meshing) {
  return parse_surfaces3d(cracks, key_path, L, meshing);
}

template struct Surface<2>;
template struct Surface<3>;
template bool segment_crosses<2>(const Surface<2>&, const Vec<2>&, const Vec<2>&);
template bool segment_crosses<3>(const Surface<3>&, const Vec<3>&, const Vec<3>&);

}  // namespace cleave::crack
