// The fronts of a 3D crack surface: its boundary edges that lie inside the material, ordered into
// polylines of front nodes, with a local frame per node (seed 000 §3; the J vector and K_I, K_II,
// K_III along a front are taken in it). Boundary edges outside the material are mouths (a surface
// crack's opening on the body's face), not fronts.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "libmpm/core/types.hpp"
#include "libmpm/crack/surface.hpp"

namespace cleave::crack {

struct CrackFront {
  std::vector<int32_t> nodes;  // point indices of the surface, in the order of the boundary
  bool closed = false;         // a loop (an embedded crack's whole boundary): nodes.back() joins nodes[0]
  // Per node, orthonormal: normal (the surface's, towards "above"), tangent (along the front in the
  // node order, smoothed over the two neighbouring edges) and ahead = tangent x normal, in the
  // surface's plane, pointing away from the crack into the uncracked material.
  std::vector<Vec<3>> normal, tangent, ahead;
  // Per node, what the crack_tips checks found (front_parameters.hpp's kFlag bits, e.g. a contour
  // that leaves the material); empty when the scene asks for no front parameters.
  std::vector<uint8_t> flags;
};

// Unit normals at the points of s: the area-weighted mean of the normals of the triangles around
// each point (towards "above").
std::vector<Vec<3>> point_normals(const Surface<3>& s);

// The boundary of s (consistently oriented triangles; the boundary runs counter-clockwise about
// the normal) in loops, each cut into fronts where it leaves the material: an edge is a front
// edge when inside(its midpoint). A loop that is all front is one closed front.
std::vector<CrackFront> crack_fronts(const Surface<3>& s, const std::function<bool(const Vec<3>&)>& inside);

}  // namespace cleave::crack
