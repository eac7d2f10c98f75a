// The weight of a crack line in a node's nodal volume (2D): the integral of the node's bilinear hat
// function N along a segment. Why (contact.hpp, volume detection): faces opened by a small gap g take
// g times this integral from the node's volume sum, whatever shape functions spread the particles'
// volumes (uGIMP exactly to first order: the particles' domains part by g along the line), so the
// volume deficit over the integral is the gap itself, wherever the crack lies among the nodes.
#pragma once
#include <algorithm>
#include <cmath>

#include "libmpm/core/types.hpp"

namespace cleave::crack_fields {

// The integral of N(x) = max(0, 1 - |x - node_x| / h) max(0, 1 - |y - node_y| / h) along the segment
// a -> b (metres: N is dimensionless, the result a length; h along a segment through the node on a
// node line of length 2h or more). Exact: the segment is cut where a factor changes slope or support
// (|x - node_x| and |y - node_y| at 0 and h), and on each piece N is a quadratic in the arc length,
// which Simpson's rule integrates exactly.
inline double hat_integral_along(const Vec<2>& a, const Vec<2>& b, const Vec<2>& node, double h) {
  const Vec<2> d = b - a;
  const double length = d.norm();
  if (!(length > 0.0)) return 0.0;
  // Nothing to add unless the segment's box meets the support's.
  if (std::max(a.x(), b.x()) <= node.x() - h || std::min(a.x(), b.x()) >= node.x() + h ||
      std::max(a.y(), b.y()) <= node.y() - h || std::min(a.y(), b.y()) >= node.y() + h)
    return 0.0;
  double t[8];
  int n = 0;
  t[n++] = 0.0;
  for (int k = 0; k < 2; ++k) {
    if (d[k] == 0.0) continue;
    for (const double offset : {-h, 0.0, h}) {
      const double s = (node[k] + offset - a[k]) / d[k];
      if (s > 0.0 && s < 1.0) t[n++] = s;
    }
  }
  t[n++] = 1.0;
  std::sort(t, t + n);
  const auto N = [&](double s) {
    const Vec<2> x = a + s * d;
    return std::max(0.0, 1.0 - std::fabs(x.x() - node.x()) / h) * std::max(0.0, 1.0 - std::fabs(x.y() - node.y()) / h);
  };
  double sum = 0.0;
  for (int i = 0; i + 1 < n; ++i) {
    const double s0 = t[i], s1 = t[i + 1];
    if (!(s1 > s0)) continue;
    sum += (s1 - s0) * (N(s0) + 4.0 * N(0.5 * (s0 + s1)) + N(s1)) / 6.0;
  }
  return sum * length;
}

}  // namespace cleave::crack_fields
