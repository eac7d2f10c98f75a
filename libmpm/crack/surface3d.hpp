// 3D crack surfaces as the scene declares them (docs/scenes.md, "Peridynamics": triangles or a
// quad), and the segment-against-triangle test. crack/surface.hpp turns them into the
// dimension-free Surface<3> that every method reads.
#pragma once
#include <array>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "libmpm/core/types.hpp"

namespace cleave::crack {

struct Crack3D {
  std::string name;
  std::vector<std::array<Vec<3>, 3>> triangles;  // SI
  Vec<3> lo, hi;                                  // extent of all vertices
};

// Parses the 3D "cracks" array: each entry is an object with "name" and exactly one of
//   "triangles": [[[x,y,z],[x,y,z],[x,y,z]], ...]    any number of triangles (>= 1)
//   "quad": [[x,y,z] x 4]                             a planar-or-not quadrilateral p0 p1 p2 p3,
//                                                     split into (p0,p1,p2) and (p0,p2,p3)
// Coordinates are in the scene's length unit (length_scale converts to metres). Throws
// SceneError naming the key path for: not an array/object, missing or duplicate name, both or
// neither form, wrong point counts, non-finite numbers, a degenerate (zero-area) triangle, unknown keys.
std::vector<Crack3D> parse_cracks3d(const nlohmann::json& cracks, const std::string& key_path,
                                    double length_scale);

// Closed segment p-q against closed triangle (a, b, c): true when they share a point, except that
// a segment lying in the triangle's plane never counts (it cannot separate the two sides).
// Orientation signs are plain floating point: place crack surfaces between lattice planes.
bool segment_hits_triangle(const Vec<3>& p, const Vec<3>& q, const Vec<3>& a, const Vec<3>& b,
                           const Vec<3>& c);

}  // namespace cleave::crack
