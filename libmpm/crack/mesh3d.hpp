// Triangle meshes of 3D crack surfaces: the shapes a scene can generate, refinement to an element
// size, and the checks every crack surface must pass before a method sees it. The orientation of
// the triangles is the crack's "above" side (the normal (b - a) x (c - a) points above), so it must
// be consistent over the surface.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "libmpm/core/types.hpp"

namespace cleave::crack {

struct TriMesh {
  std::vector<Vec<3>> points;
  std::vector<std::array<int32_t, 3>> triangles;
};

// The parallelogram corner + s e1 + t e2 (s, t in [0, 1]), normal e1 x e2, cut into about
// |e1| / size x |e2| / size cells of two triangles each.
TriMesh rectangle_mesh(const Vec<3>& corner, const Vec<3>& e1, const Vec<3>& e2, double size);
// The ellipse centre + a cos(t) u + b sin(t) v with u the major-axis direction (made normal to
// `normal`), v = normal x u: concentric rings, ring k of 6k points, as many rings as
// max(a, b) / size rounds up to; normal along `normal`. A circle is a = b.
TriMesh ellipse_mesh(const Vec<3>& centre, const Vec<3>& normal, const Vec<3>& major, double a, double b,
                     double size);
// Every triangle cut into k^2 alike, k = ceil(longest edge / size) over the mesh, so neighbours cut
// their shared edge at the same points (no hanging vertices); a point on a shared edge is computed
// from the same two vertices in the same order by both triangles, so it is one point.
TriMesh refine(const TriMesh& m, double size);
// Points with identical coordinates merged (triangles given vertex by vertex, STL files).
TriMesh merge_identical_points(const TriMesh& m);
// Triangles with no vertex inside the material dropped, and the points no triangle uses: a surface
// crack's part outside the body goes, its edges outside the body become mouths, not fronts.
TriMesh clip_to(const TriMesh& m, const std::function<bool(const Vec<3>&)>& inside);

// The checks: no degenerate (zero-area) triangle, every edge shared by at most two triangles,
// neighbours oriented alike, no two triangles without a common vertex that intersect (off their
// plane: exact signs). Throws SceneError at `path` naming the triangle(s) by index and vertices.
void check_surface_mesh(const TriMesh& m, const std::string& path);

}  // namespace cleave::crack
