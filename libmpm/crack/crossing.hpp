// Line crossing for 2D explicit cracks (seed 002, Appendix A "Line Crossing Algorithm"): decides
// whether the line from a particle to a node crosses a crack and, if it does, on which side of the
// crack the particle lies, which selects the node's velocity field (0 none, 1 above, 2 below).
// Header-only: this is the hot path of every crack step (every particle-node pair near a crack).
//
// Orientation signs are EXACT: a floating-point filter (Shewchuk's orient2d error bound) decides
// almost every case in a few flops; only nearly or exactly degenerate triples (a node on a crack
// segment or on a vertex, a line through a vertex) fall back to exact expansion arithmetic. The
// classification therefore matches the exact geometry of the stored doubles, the node's side of
// a segment (the sign of (342)) never depends on the particle, and crack-extent screening provably
// never changes an answer. (Exactness assumes no product of two coordinates under/overflows, i.e.
// |coordinates| between about 1e-150 and 1e150 or exactly 0: SI lengths are far inside.)
#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "libmpm/core/types.hpp"

namespace cleave::crack {

// Velocity field of a particle-node pair (seed 002 eq. 2): None = field 0 (the particle-node line
// crosses no crack), Above = field 1, Below = field 2.
//
// CONVENTION. "Above"/"below" are relative to the crack's direction x3 -> x4 (and, for a polyline,
// the direction points[0] -> points[1] -> ...): the particle is ABOVE when it lies on the LEFT of
// the directed segment (signed area (341) > 0, the triangle x3 -> x4 -> particle turns counter-
// clockwise) and the particle-node line crosses the segment; BELOW when it lies on the right.
// Worked example (by hand, eq. 33): crack x3 = (0,0) -> x4 = (1,0) (pointing +x), particle
// x1 = (0.5, 1) (left of the crack, +y), node x2 = (0.5, -1):
//   (123) = x1(y2-y3) + x2(y3-y1) + x3(y1-y2) = 0.5(-1-0) + 0.5(0-1) + 0 = -1      -> "-"
//   (124) = 0.5(-1-0) + 0.5(0-1) + 1(1-(-1))              = -1 + 2  = +1          -> "+"
//   (341) = 0(0-1) + 1(1-0) + 0.5(0-0)                    = +1                    -> "+"
//   (342) = 0(0-(-1)) + 1(-1-0) + 0.5(0-0)                = -1                    -> "-"
// i.e. (-++-), which the appendix calls "particle above". Swapping particle and node (or reversing
// the crack) gives (+--+), "below". So: a crack drawn left to right has "above" = +y, as the word
// suggests; a crack drawn right to left has "above" = -y.
enum class Side : int8_t { None = 0, Above = 1, Below = 2 };

// Signed area of the triangle (a, b, c) (seed 002 eq. 33: x1(y2-y3) + x2(y3-y1) + x3(y1-y2), the
// same polynomial evaluated as (b-a) x (c-a)): positive when a -> b -> c is counter-clockwise,
// negative when clockwise, zero when collinear. This is the rounded value; use area_sign for the
// sign, which is exact.
inline double signed_area(const Vec<2>& a, const Vec<2>& b, const Vec<2>& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

namespace detail {

inline int sgn(double v) { return (v > 0.0) - (v < 0.0); }

// Knuth's TwoSum: s + e == a + b exactly, s = fl(a + b).
inline void two_sum(double a, double b, double& s, double& e) {
  s = a + b;
  const double bv = s - a;
  const double av = s - bv;
  e = (a - av) + (b - bv);
}

// An exact sum of doubles as a nonoverlapping expansion (Shewchuk's Grow-Expansion): add(t) keeps
// the sum exact, sign() is the sign of its largest nonzero component. N: the most terms added.
template <int N>
struct Expansion {
  double h[N];
  int m = 0;
  void add(double t) {
    double q = t;
    for (int i = 0; i < m; ++i) two_sum(q, h[i], q, h[i]);
    h[m++] = q;
  }
  int sign() const {
    for (int i = m - 1; i >= 0; --i)
      if (h[i] != 0.0) return sgn(h[i]);
    return 0;
  }
};

// Exact sign of eq. 33 by expansion arithmetic: the six products of eq. 33 expanded, each split
// exactly into value + error with fma, summed exactly into a nonoverlapping expansion (Shewchuk's
// Grow-Expansion) whose largest nonzero component carries the sign. Only reached for (nearly)
// degenerate triples.
inline int area_sign_exact(const Vec<2>& a, const Vec<2>& b, const Vec<2>& c) {
  const double f[6][2] = {{a.x(), b.y()}, {-a.x(), c.y()}, {b.x(), c.y()},
                          {-b.x(), a.y()}, {c.x(), a.y()}, {-c.x(), b.y()}};
  Expansion<12> sum;
  for (const auto& p : f) {
    const double prod = p[0] * p[1];
    sum.add(std::fma(p[0], p[1], -prod));  // exact rounding error of the product
    sum.add(prod);
  }
  return sum.sign();
}

}  // namespace detail

// Exact sign (+1, -1 or 0) of signed_area(a, b, c); the zero test is exact (0 only for exactly
// collinear points). Fast path: Shewchuk's orient2d filter, error bound (3 + 16 eps) eps |..|.
inline int area_sign(const Vec<2>& a, const Vec<2>& b, const Vec<2>& c) {
  const double detleft = (b.x() - a.x()) * (c.y() - a.y());
  const double detright = (b.y() - a.y()) * (c.x() - a.x());
  const double det = detleft - detright;
  double detsum;
  if (detleft > 0.0) {
    if (detright <= 0.0) return detail::sgn(det);
    detsum = detleft + detright;
  } else if (detleft < 0.0) {
    if (detright >= 0.0) return detail::sgn(det);
    detsum = -detleft - detright;
  } else {
    return detail::sgn(det);  // a difference is exactly 0: det = -detright, whose sign is exact
  }
  constexpr double kEps = 1.1102230246251565e-16;  // 2^-53
  constexpr double kBound = (3.0 + 16.0 * kEps) * kEps;
  const double err = kBound * detsum;
  if (det >= err || -det >= err) return detail::sgn(det);
  return detail::area_sign_exact(a, b, c);
}

// Appendix Subtask 3 from the four signs s123, s124, s341, s342 (each +1, -1, 0) of the triangles
// (123), (124), (341), (342) with x1 = particle, x2 = node, x3 -> x4 the crack segment:
//   Above: (-++-) proper crossing, (-++0) node on the segment, (0++0) node on the start point x3,
//          (-0+0) node on the end point x4;
//   Below: (+--+), (+--0), (0--0), (+0-0) (the same four with every sign flipped);
//   anything else: None. In particular a particle on the crack line (s341 = 0) is None ("can be
//   ignored"), a collinear particle-node line and crack (0000 etc.) is None, and a particle-node
//   line passing exactly through x3 or x4 with the node off the segment ((0++-), (-0+-), ...) is
//   None: only the node itself may sit on an end point.
inline Side classify_signs(int s123, int s124, int s341, int s342) {
  if (s341 == 0) return Side::None;
  // Normalise so that the particle is on the + side of x3 -> x4; the "above" rows then apply.
  const int a = s123 * s341, b = s124 * s341, e = s342 * s341;
  const bool hit = (a == -1 && b == 1 && e <= 0)      // (-++-), (-++0)
                   || (a == 0 && b == 1 && e == 0)    // (0++0)
                   || (a == -1 && b == 0 && e == 0);  // (-0+0)
  if (!hit) return Side::None;
  return s341 > 0 ? Side::Above : Side::Below;
}

// One crack segment x3 -> x4 against the particle-node line x1 = particle -> x2 = node: exactly
// the appendix's sign rules (classify_signs), skipping (341)/(342) when (123) and (124) already
// show that x3 and x4 lie strictly on the same side of the line, or that all four points are
// collinear.
inline Side segment_crossing(const Vec<2>& particle, const Vec<2>& node, const Vec<2>& x3,
                             const Vec<2>& x4) {
  const int s123 = area_sign(particle, node, x3);
  const int s124 = area_sign(particle, node, x4);
  if (s123 * s124 > 0 || (s123 == 0 && s124 == 0)) return Side::None;
  const int s341 = area_sign(x3, x4, particle);
  if (s341 == 0) return Side::None;
  return classify_signs(s123, s124, s341, area_sign(x3, x4, node));
}

// Side of the particle at an interior vertex v of a polyline (v_prev -> v -> v_next) when the
// crossing happens exactly at v: the particle is above when the direction v -> particle lies in
// the open sector on the left of the polyline (counter-clockwise from v_next - v to v_prev - v).
// c1 = sign (v_prev, v, particle), c2 = sign (v, v_next, particle), turn = sign (v_prev, v, v_next).
// A particle on either arm (on the crack) gives None.
inline Side vertex_side(int c1, int c2, int turn) {
  bool above, below;
  if (turn > 0) {  // left turn: the left sector is the intersection of the two left half-planes
    above = c1 > 0 && c2 > 0;
    below = c1 < 0 || c2 < 0;
  } else if (turn < 0) {  // right turn: the left sector is their union
    above = c1 > 0 || c2 > 0;
    below = c1 < 0 && c2 < 0;
  } else {  // straight on
    above = c2 > 0;
    below = c2 < 0;
  }
  return above ? Side::Above : below ? Side::Below : Side::None;
}

// Whole-polyline crossing (points[0..n), n >= 2) WITHOUT extent screening (crack_crossing in
// crack2d.hpp screens first). Segment by segment with the appendix rules (Subtasks 2-3); an even
// number of crossings is None (Subtask 4); an odd number gives the side of the net count
// (#above - #below, never 0 when the count is odd): for a zig-zag crack crossed three times the
// sides alternate (above, below, above -> above), which is the side the particle is on locally.
//
// Interior vertices (shared by two segments) are decided once, at the vertex, because the
// appendix rules applied per segment get them wrong: a node exactly on an interior vertex would be
// counted twice (end point (-0+0) of one segment + start point (0++0) of the next = even = None),
// and a particle-node line passing exactly through an interior vertex would be counted zero times
// (both segments see only an end point). Instead:
//   - node exactly on the vertex: the particle's side by the sector rule (vertex_side);
//   - line passing through the vertex strictly between particle and node: a crossing iff the two
//     neighbouring vertices lie strictly on opposite sides of the line (otherwise the line only
//     touches the crack), with the side by the sector rule.
// The crack's two end points (tips) follow the appendix unchanged: a node on a tip is separated,
// a line grazing a tip is not.
// When `segment` is given, it receives the index of one crossed segment on the returned side (at
// an interior vertex, the segment that ends there): the crack normal of seed 002's contact is taken
// from it.
inline Side polyline_crossing(const Vec<2>* points, std::size_t n, const Vec<2>& particle,
                              const Vec<2>& node, std::size_t* segment = nullptr) {
  if (n < 2) return Side::None;
  const std::size_t nseg = n - 1;
  int count = 0, net = 0;
  std::size_t seg_above = 0, seg_below = 0;
  int s_next = area_sign(particle, node, points[0]);  // sign (1 2 v_j), shared by two segments
  for (std::size_t j = 0; j < nseg; ++j) {
    const Vec<2>& x3 = points[j];
    const Vec<2>& x4 = points[j + 1];
    const int s123 = s_next;
    const int s124 = area_sign(particle, node, x4);
    s_next = s124;
    if (s123 * s124 > 0) continue;

    if (s124 == 0 && j + 1 < nseg) {
      // x4 is an interior vertex on the particle-node line: decided here, once.
      const Vec<2>& x5 = points[j + 2];
      bool at_vertex = false;
      if (node == x4) {
        at_vertex = particle != x4;
      } else if (particle != x4 &&
                 x4.x() >= std::min(particle.x(), node.x()) && x4.x() <= std::max(particle.x(), node.x()) &&
                 x4.y() >= std::min(particle.y(), node.y()) && x4.y() <= std::max(particle.y(), node.y())) {
        // Exactly collinear, so the box test is exact: x4 strictly between particle and node.
        at_vertex = s123 * area_sign(particle, node, x5) < 0;  // transversal, not touching
      }
      if (at_vertex) {
        const Side s = vertex_side(area_sign(x3, x4, particle), area_sign(x4, x5, particle),
                                   area_sign(x3, x4, x5));
        if (s != Side::None) {
          ++count;
          net += s == Side::Above ? 1 : -1;
          (s == Side::Above ? seg_above : seg_below) = j;
        }
      }
      continue;  // this segment's only contact with the line is its end point x4
    }
    if (s123 == 0 && (s124 == 0 || j > 0)) continue;  // collinear, or x3 interior (done at j - 1)

    const int s341 = area_sign(x3, x4, particle);
    if (s341 == 0) continue;
    const Side s = classify_signs(s123, s124, s341, area_sign(x3, x4, node));
    if (s != Side::None) {
      ++count;
      net += s == Side::Above ? 1 : -1;
      (s == Side::Above ? seg_above : seg_below) = j;
    }
  }
  if (count % 2 == 0) return Side::None;
  if (segment) *segment = net > 0 ? seg_above : seg_below;
  return net > 0 ? Side::Above : Side::Below;
}

}  // namespace cleave::crack
