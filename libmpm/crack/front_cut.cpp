#include "libmpm/crack/front_cut.hpp"

#include <algorithm>

namespace cleave::crack {
FrontCut make_front_cut(const Surface<3>& s, const std::vector<CrackFront>& fronts, double cut, double reach) {
  FrontCut fc;
  if (!(cut > 0.0)) return fc;
  std::vector<std::array<int32_t, 2>> edges;
  for (const auto& f : fronts) {
    const std::size_t m = f.nodes.size();
    for (std::size_t k = 0; k + 1 < m; ++k) edges.push_back({f.nodes[k], f.nodes[k + 1]});
    if (f.closed && m > 2) edges.push_back({f.nodes[m - 1], f.nodes[0]});
  }
  if (edges.empty()) return fc;
  fc.cut = cut;
  fc.begin.assign(1, 0);
  for (const auto& T : s.simplices) {
    const Vec<3> c = (s.points[T[0]] + s.points[T[1]] + s.points[T[2]]) / 3.0;
    double r = 0.0;
    for (int k = 0; k < 3; ++k) r = std::max(r, (s.points[T[k]] - c).norm());
    // Any point of the triangle lies within r of its centroid.
    const double within = cut + r + reach;
    for (const auto& e : edges)
      if (segment_distance2(c, s.points[e[0]], s.points[e[1]]) <= within * within) fc.edges.push_back(e);
    fc.begin.push_back(static_cast<int32_t>(fc.edges.size()));
  }
  return fc;
}

}  // namespace cleave::crack
