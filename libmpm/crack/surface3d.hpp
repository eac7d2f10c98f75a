// 3D crack surfaces as the scene declares them (docs/scenes.md, "3D crack surfaces"): explicit
// triangles, a quad, an indexed mesh, a generated rectangle or ellipse, or a mesh file; meshed into
// triangles of about an element size with shared vertices (crack/mesh3d.hpp) and checked, as the
// dimension-free Surface<3> that every method reads. Also the segment-against-triangle test.
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "libmpm/core/types.hpp"
#include "libmpm/crack/surface.hpp"

namespace cleave::crack {

// Each entry is an object with "name", optional "element_size" (scene length unit), the MPM keys
// "contact" and "tips" (read by parse_cracks3d, crack3d.hpp; other methods ignore them, as for 2D
// polylines) and exactly one of
//   "triangles": [[[x,y,z],[x,y,z],[x,y,z]], ...]   triangles vertex by vertex (shared ones merged)
//   "quad": [p0, p1, p2, p3]                       split into (p0,p1,p2) and (p0,p2,p3)
//   "mesh": {"points": [[x,y,z], ...], "triangles": [[i,j,k], ...]}   an indexed mesh
//   "rectangle": {"corner": p, "edges": [e1, e2]}  the parallelogram corner + s e1 + t e2
//   "ellipse": {"center": p, "normal": n, "major_axis": d, "semi_axes": [a, b]} (or "radius": r)
//   "file": "crack.stl" | "crack.msh"              STL (ASCII/binary) or Gmsh ASCII 2.2/4.1
// Coordinates are in the scene's length unit (length_scale converts to metres); the triangles'
// orientation (normal (b - a) x (c - a), or the generated shape's normal) is the crack's above
// side. Throws SceneError naming the key path and the triangle or file for: a wrong form or point
// count, non-finite numbers, a degenerate triangle, a non-manifold edge, inconsistent orientation,
// a self-intersecting surface, an unreadable mesh file, unknown keys, a duplicate name.
std::vector<Surface<3>> parse_surfaces3d(const nlohmann::json& cracks, const std::string& key_path,
                                         double length_scale, const SurfaceMeshing& meshing);

// Closed segment p-q against closed triangle (a, b, c): true when they share a point, except that
// a segment lying in the triangle's plane never counts (it cannot separate the two sides).
// Orientation signs are plain floating point: place crack surfaces between lattice planes.
bool segment_hits_triangle(const Vec<3>& p, const Vec<3>& q, const Vec<3>& a, const Vec<3>& b,
                           const Vec<3>& c);

}  // namespace cleave::crack
