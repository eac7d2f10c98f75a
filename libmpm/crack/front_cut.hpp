// 3D: a crack's fronts cut back for the crossing test, as 2D cuts its tips back
// (ExplicitCrack::update_crossing says why: a node is split when a particle-node line crosses the
// crack, the displacement jump falls linearly to zero at the next whole node, so the discrete crack
// ends up to a cell beyond the front; cut back by tip_cut it ends within tip_cut behind and 1 -
// tip_cut beyond). A crossing whose point on the crack lies within tip_cut of a front edge does not
// count: the crossing test sees the crack less a band of that width along its fronts. The mesh is
// left as it is (its triangles are about half a cell, so moving the front's vertices back would
// fold them); only the crossings are filtered, and only on triangles near a front.
#pragma once
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "libmpm/core/types.hpp"
#include "libmpm/crack/fronts.hpp"
#include "libmpm/crack/surface.hpp"

namespace cleave::crack {

// Squared distance from x to the segment a-b.
inline double segment_distance2(const Vec<3>& x, const Vec<3>& a, const Vec<3>& b) {
  const Vec<3> ab = b - a;
  const double l2 = ab.squaredNorm();
  const double s = l2 > 0.0 ? std::clamp(ab.dot(x - a) / l2, 0.0, 1.0) : 0.0;
  return (a + s * ab - x).squaredNorm();
}

struct FrontCut {
  double cut = 0.0;  // m; 0: nothing is cut
  // Per triangle t, the front edges (point ids) that can lie within `cut` of it, edges[begin[t] ..
  // begin[t + 1]); begin is empty when nothing is cut.
  std::vector<int32_t> begin;
  std::vector<std::array<int32_t, 2>> edges;

  bool active() const { return !begin.empty(); }
  // Does the crossing of the line particle -> node through triangle t lie within `cut` of a front?
  // at_node: the node lies on the triangle (the crossing is the node itself).
  bool drops(const Vec<3>* points, const std::array<int32_t, 3>& T, std::size_t t, const Vec<3>& particle,
             const Vec<3>& node, bool at_node) const {
    if (begin[t] == begin[t + 1]) return false;
    Vec<3> x = node;
    if (!at_node) {
      // Where the line meets the triangle's plane (rounded: a band's edge needs no exact decision,
      // one crossing is tested once).
      const Vec<3> n = (points[T[1]] - points[T[0]]).cross(points[T[2]] - points[T[0]]);
      const double dp = n.dot(particle - points[T[0]]), dn = n.dot(node - points[T[0]]);
      const double w = dp != dn ? dp / (dp - dn) : 0.5;
      x = particle + w * (node - particle);
    }
    const double cut2 = cut * cut;
    for (int32_t k = begin[t]; k < begin[t + 1]; ++k)
      if (segment_distance2(x, points[edges[k][0]], points[edges[k][1]]) < cut2) return true;
    return false;
  }
  // The drop test triangle_list_crossing_with takes, on surface (points, triangles).
  auto dropper(const Vec<3>* points, const std::array<int32_t, 3>* triangles) const {
    return [this, points, triangles](std::size_t t, const Vec<3>& particle, const Vec<3>& node, bool at_node) {
      return active() && drops(points, triangles[t], t, particle, node, at_node);
    };
  }
};

// The cut of surface s's fronts by `cut` (m); `reach` (m) is added to the distances when the
// triangles' edge lists are made, so that they hold while the crack deforms by less than that.
FrontCut make_front_cut(const Surface<3>& s, const std::vector<CrackFront>& fronts, double cut, double reach);

}  // namespace cleave::crack
