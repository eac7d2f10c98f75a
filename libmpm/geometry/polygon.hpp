// Planar polygon predicates shared by the 2D polygon and the 3D prism. Edge i runs from
// points[i] to points[(i + 1) % n]; either orientation is accepted.
#pragma once
#include <optional>
#include <utility>
#include <vector>

#include "libmpm/core/types.hpp"

namespace cleave::geom {

using Polyline = std::vector<Vec<2>>;

// Shoelace area: positive for counter-clockwise vertex order.
double signed_area(const Polyline& p);

// True when every vertex lies within `tol` (a length) of one straight line.
bool all_collinear(const Polyline& p, double tol);

// First pair of edges (i, j), i < j, that touch or cross although they should not: non-adjacent
// edges sharing any point, or adjacent edges folding back onto each other. nullopt for a simple
// polygon. O(n^2), which is fine for hand-written scene polygons.
std::optional<std::pair<int, int>> find_self_intersection(const Polyline& p);

// Closed point-in-polygon test: non-zero winding number (Sunday's crossing rule with an exact
// orientation sign, so no division and no double-counted vertices), plus points exactly on an edge.
bool polygon_contains(const Polyline& p, const Vec<2>& x);

}  // namespace cleave::geom
