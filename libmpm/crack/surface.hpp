// A crack's geometry in any dimension: a (Dim-1)-simplex mesh -- the segments of a polyline in 2D,
// triangles in 3D -- whose boundary is its fronts (the end points in 2D, the edges used by one
// triangle only in 3D). One type and one crossing test for every method: peridynamics cuts the
// bonds that cross it; MPM's explicit cracks (explicit_crack.hpp) are surfaces with the state of
// their faces added.
#pragma once
#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "libmpm/core/types.hpp"

namespace cleave::crack {

template <int Dim>
struct Surface {
  std::string name;
  std::vector<Vec<Dim>> points;                  // SI
  std::vector<std::array<int32_t, Dim>> simplices;  // point indices: segments (2D), triangles (3D)
  Vec<Dim> lo = Vec<Dim>::Constant(std::numeric_limits<double>::infinity());
  Vec<Dim> hi = Vec<Dim>::Constant(-std::numeric_limits<double>::infinity());

  void update_extent();
  // The fronts: facets ((Dim-1)-tuples of point indices) that belong to one simplex only, in
  // simplex order (2D: the end points; 3D: the boundary edges, each running as in its triangle).
  std::vector<std::array<int32_t, Dim - 1>> boundary() const;
};

// Does the closed segment a-b cross the surface? 2D: it meets a segment of the polyline
// (segments_intersect, crossing.hpp); 3D: it passes through a triangle (segment_hits_triangle,
// surface3d.hpp; a segment in a triangle's plane does not cross). Screened by the extent first.
template <int Dim>
bool segment_crosses(const Surface<Dim>& s, const Vec<Dim>& a, const Vec<Dim>& b);

// How a method wants its 3D surfaces meshed: generated shapes at `default_size` (m) unless the
// crack gives "element_size"; given triangles refined to that size too when `refine_given` (MPM's
// crack particles sit at the vertices), else kept as given (peridynamics only cuts bonds with them).
struct SurfaceMeshing {
  double default_size = 0.0;
  bool refine_given = false;
};

// The scene's "cracks" as surfaces: 2D polylines (parse_cracks, crack2d.hpp), 3D triangle meshes
// (parse_surfaces3d, surface3d.hpp). SceneError names the key path.
template <int Dim>
std::vector<Surface<Dim>> read_surfaces(const nlohmann::json& cracks, const std::string& key_path, double length_scale,
                                        const SurfaceMeshing& meshing);

}  // namespace cleave::crack
