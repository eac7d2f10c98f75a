// Line crossing for 3D explicit cracks (seed 000, Appendix A): does the line from a particle to a
// node cross a triangulated crack surface and, if it does, on which side of the surface is the
// particle (field 1 "above" = the side its triangles' normals point to, field 2 "below")?
// Header-only: with the 2D polyline test (crossing.hpp) this is the hot path of every crack step.
//
// The seed's five signed volumes (eq. 66-67) per triangle 1-2-3, particle p, node i:
//   V1 = V(1,2,3,p), V2 = V(1,2,3,i)         p and i on opposite sides (i may lie on the plane);
//   V(i,1,2,p), V(i,2,3,p), V(i,3,1,p)       the line meets the triangle: all three of the sign
//                                            of V1 (the seed's V4 = V(i,1,3,p) is our -V(i,3,1,p)).
// Signs are EXACT (a floating-point filter with Shewchuk's orient3d error bound; exact expansion
// arithmetic for nearly degenerate cases), so the degenerate cases the appendix leaves open are
// decided by rules that hold for a whole mesh, not per triangle:
//   - the line passes exactly through an edge or a vertex between particle and node: the particle
//     is displaced by an infinitesimal (1, e, e^2) e' (simulation of simplicity). Each zero edge
//     volume takes the sign of its first-order term, and the perturbed line crosses a
//     consistently oriented mesh generically: an interior edge counts for exactly one of its two
//     triangles, a vertex for exactly one triangle of its fan; a line grazing the boundary (a
//     front) counts as the perturbed line does;
//   - the node lies on the surface (in a closed triangle): one crossing at the node, whatever the
//     number of triangles that hold it (edge, vertex), with the particle's side: as in 2D, a node on
//     the crack, also on a front, separates the particle from the other side;
//   - a particle on a triangle's plane (V1 = 0) is ignored for that triangle, as the seed says
//     ("particles should never be on the crack surface").
// An even number of crossings is none; an odd number gives the side of the net count.
// (Exactness assumes that no product of three coordinates under/overflows: SI lengths are far inside.)
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include <Eigen/Geometry>

#include "libmpm/core/types.hpp"
#include "libmpm/crack/crossing.hpp"

namespace cleave::crack {

// V(a, b, c, d) * 6 as rounded doubles: ((b - a) x (c - a)) . (d - a), positive when d lies on the
// side the normal (b - a) x (c - a) points to (seed 000 eq. 66). Use volume_sign for the sign.
inline double signed_volume(const Vec<3>& a, const Vec<3>& b, const Vec<3>& c, const Vec<3>& d) {
  return (b - a).cross(c - a).dot(d - a);
}

namespace detail {

// Knuth's TwoProduct with fma: p + e == a * b exactly.
inline void two_product(double a, double b, double& p, double& e) {
  p = a * b;
  e = std::fma(a, b, -p);
}

// Exact sign of ((b - a) x (c - a)) . (d - a) = [b,c,d] + [a,b,d] - [a,c,d] - [a,b,c], with
// [p,q,r] = p . (q x r): 24 products of three coordinates, each split exactly into four doubles and
// summed exactly (Grow-Expansion). Only reached for (nearly) degenerate quadruples.
inline int volume_sign_exact(const Vec<3>& a, const Vec<3>& b, const Vec<3>& c, const Vec<3>& d) {
  Expansion<96> sum;
  auto product = [&](double s, double x, double y, double z) {  // s x y z, s = +-1
    double p, e, p1, e1, p2, e2;
    two_product(s * x, y, p, e);
    two_product(p, z, p1, e1);
    two_product(e, z, p2, e2);
    sum.add(e2), sum.add(p2), sum.add(e1), sum.add(p1);
  };
  auto triple = [&](double s, const Vec<3>& p, const Vec<3>& q, const Vec<3>& r) {  // s [p,q,r]
    product(s, p.x(), q.y(), r.z()), product(-s, p.x(), q.z(), r.y());
    product(s, p.y(), q.z(), r.x()), product(-s, p.y(), q.x(), r.z());
    product(s, p.z(), q.x(), r.y()), product(-s, p.z(), q.y(), r.x());
  };
  triple(1.0, b, c, d), triple(1.0, a, b, d), triple(-1.0, a, c, d), triple(-1.0, a, b, c);
  return sum.sign();
}

// The exact sign of V(a, b, c, d) when three of the points share a coordinate k. With
// b - a and c - a zero along k, V(a, b, c, d) = (d_k - a_k) [(b - a) x (c - a)]_k, and the latter is
// the 2D orientation of a, b, c projected on the axes (k + 1, k + 2); V alternates under swaps of
// points, which brings the other triples to that form. kNoAxisPlane when no three do.
constexpr int kNoAxisPlane = 2;
inline int axis_plane_volume_sign(const Vec<3>& a, const Vec<3>& b, const Vec<3>& c, const Vec<3>& d) {
  auto orient = [](int k, const Vec<3>& p, const Vec<3>& q, const Vec<3>& r) {
    const int u = (k + 1) % 3, v = (k + 2) % 3;
    return area_sign(Vec<2>(p[u], p[v]), Vec<2>(q[u], q[v]), Vec<2>(r[u], r[v]));
  };
  auto height = [](double x, double base) { return (x > base) - (x < base); };
  for (int k = 0; k < 3; ++k) {
    const bool ab = a[k] == b[k], cd = c[k] == d[k];
    if (ab && a[k] == c[k]) return height(d[k], a[k]) * orient(k, a, b, c);    // V(a,b,c,d)
    if (ab && a[k] == d[k]) return -height(c[k], a[k]) * orient(k, a, b, d);   // -V(a,b,d,c)
    if (cd && a[k] == c[k]) return height(b[k], a[k]) * orient(k, a, c, d);    // V(a,c,d,b)
    if (cd && b[k] == c[k]) return -height(a[k], b[k]) * orient(k, b, c, d);   // -V(b,c,d,a)
  }
  return kNoAxisPlane;
}

}  // namespace detail

// Exact sign (+1, -1 or 0) of signed_volume(a, b, c, d); 0 only for exactly coplanar points.
// Fast path: Shewchuk's orient3d filter, error bound (7 + 56 eps) eps times the permanent.
inline int volume_sign(const Vec<3>& a, const Vec<3>& b, const Vec<3>& c, const Vec<3>& d) {
  const Vec<3> u = b - a, v = c - a, w = d - a;
  const double yz = v.y() * w.z(), zy = v.z() * w.y(), zx = v.z() * w.x(), xz = v.x() * w.z();
  const double xy = v.x() * w.y(), yx = v.y() * w.x();
  const double det = u.x() * (yz - zy) + u.y() * (zx - xz) + u.z() * (xy - yx);
  const double perm = std::abs(u.x()) * (std::abs(yz) + std::abs(zy)) +
                      std::abs(u.y()) * (std::abs(zx) + std::abs(xz)) +
                      std::abs(u.z()) * (std::abs(xy) + std::abs(yx));
  constexpr double kEps = 1.1102230246251565e-16;  // 2^-53
  constexpr double kBound = (7.0 + 56.0 * kEps) * kEps;
  const double err = kBound * perm;
  if (det > err || -det > err) return detail::sgn(det);
  // Four points with one coordinate in common lie in that axis plane: exactly coplanar. (The common
  // degenerate case: nodes on a crack laid on a node plane. Much cheaper than the expansions.)
  for (int k = 0; k < 3; ++k)
    if (a[k] == b[k] && a[k] == c[k] && a[k] == d[k]) return 0;
  // Three in an axis plane (a node on such a crack, an edge and a particle off it): the volume is
  // the fourth point's height over the plane times the three's exact orientation in it.
  if (const int s = detail::axis_plane_volume_sign(a, b, c, d); s != detail::kNoAxisPlane) return s;
  return detail::volume_sign_exact(a, b, c, d);
}

namespace detail {

// Sign of the first-order term of V(i, a, b, p + e (1, e', e'^2)) in e: the first non-zero
// component of (a - i) x (b - i), each an exact 2D orientation of a projection. Zero only when i,
// a, b are collinear (then i lies in every plane through a and b, and the caller never asks).
inline int perturbed_edge_sign(const Vec<3>& i, const Vec<3>& a, const Vec<3>& b) {
  using P = Vec<2>;
  if (const int sx = area_sign(P(i.y(), i.z()), P(a.y(), a.z()), P(b.y(), b.z()))) return sx;
  if (const int sy = area_sign(P(i.z(), i.x()), P(a.z(), a.x()), P(b.z(), b.x()))) return sy;
  return area_sign(P(i.x(), i.y()), P(a.x(), a.y()), P(b.x(), b.y()));
}

}  // namespace detail

// Does the closed segment p-q meet the closed triangle (a, b, c) off its plane, by the orientation
// signs sign(a, b, c, d) of signed volumes? The line meets the plane inside the closed triangle iff
// it sees the three edges turning the same way (zero: through an edge or a vertex, which counts);
// a segment in the plane never counts (it cannot separate the two sides).
template <class Sign>
bool segment_meets_triangle(const Vec<3>& p, const Vec<3>& q, const Vec<3>& a, const Vec<3>& b, const Vec<3>& c,
                            Sign&& sign) {
  const int sp = sign(a, b, c, p), sq = sign(a, b, c, q);
  if (sp * sq > 0 || (sp == 0 && sq == 0)) return false;  // same side, or in the plane
  const int e0 = sign(p, q, a, b), e1 = sign(p, q, b, c), e2 = sign(p, q, c, a);
  return !((e0 < 0 || e1 < 0 || e2 < 0) && (e0 > 0 || e1 > 0 || e2 > 0));
}

// Whether the closed segment p-q meets the closed box [lo, hi] grown by `slack` on every side (the
// slab test, with inv = 1 / (q - p) per axis, inf where the segment lies across the axis). A
// triangle only counts for a line that meets it (triangle_crossing_given: a hit needs the closed
// segment to meet the closed triangle, hence its box), so callers skip the triangles whose boxes a
// line misses; for that this must never miss a box the line meets. It does not, while `slack`
// exceeds the slab parameters' rounding, a few ulps of the coordinates: segment_box_slack.
inline bool segment_meets_box(const Vec<3>& p, const Vec<3>& inv, const Vec<3>& lo, const Vec<3>& hi, double slack) {
  double t0 = 0.0, t1 = 1.0;
  for (int d = 0; d < 3; ++d) {
    const double a = lo[d] - slack - p[d], b = hi[d] + slack - p[d];
    if (std::isinf(inv[d])) {  // (along d the segment is a point)
      if (a > 0.0 || b < 0.0) return false;
      continue;
    }
    const double ta = a * inv[d], tb = b * inv[d];
    t0 = std::max(t0, std::min(ta, tb)), t1 = std::min(t1, std::max(ta, tb));
  }
  return t0 <= t1;
}
// The slack for segment_meets_box on lines of a grid of spacing h whose coordinates are at most
// `extent` in magnitude: a billionth of a cell, and far above the rounding of coordinates that large.
inline double segment_box_slack(double h, double extent) { return 1e-9 * h + 1e-13 * extent; }

// One triangle (t0, t1, t2) against the particle-node line, as seen by triangle_mesh_crossing.
enum class TriangleHit : int8_t {
  None = 0,
  Crossed,  // the (perturbed) line passes through the triangle between particle and node
  AtNode,   // the node lies in the closed triangle (on its plane)
};
// `side` receives the particle's side of the triangle's plane (+1 above, -1 below) for a hit.
// s1 = volume_sign(t0, t1, t2, particle), the particle's side of the triangle's plane, given: a
// particle's eight (or 27) lines share it, so the MPM classification computes it once per triangle.
inline TriangleHit triangle_crossing_given(int s1, const Vec<3>& particle, const Vec<3>& node, const Vec<3>& t0,
                                           const Vec<3>& t1, const Vec<3>& t2, int& side) {
  if (s1 == 0) return TriangleHit::None;
  const int s2 = volume_sign(t0, t1, t2, node);
  if (s2 == s1) return TriangleHit::None;
  const Vec<3>* v[3] = {&t0, &t1, &t2};
  int e[3];
  for (int k = 0; k < 3; ++k) {
    e[k] = volume_sign(node, *v[k], *v[(k + 1) % 3], particle) * s1;
    if (e[k] < 0) return TriangleHit::None;  // the line passes outside edge k
  }
  side = s1;
  if (s2 == 0) return TriangleHit::AtNode;  // node on the plane, inside or on the closed triangle
  for (int k = 0; k < 3; ++k)
    if (e[k] == 0 && detail::perturbed_edge_sign(node, *v[k], *v[(k + 1) % 3]) * s1 < 0) return TriangleHit::None;
  return TriangleHit::Crossed;
}
inline TriangleHit triangle_crossing(const Vec<3>& particle, const Vec<3>& node, const Vec<3>& t0, const Vec<3>& t1,
                                     const Vec<3>& t2, int& side) {
  return triangle_crossing_given(volume_sign(t0, t1, t2, particle), particle, node, t0, t1, t2, side);
}

// Crossing of the particle-node line with the triangles triangles[ids[0]], ..., triangles[ids[n-1]]
// of a surface, WITHOUT extent screening, by the rules at the top of this file. Exact for the whole
// surface when the triangles left out cannot meet the closed segment (the MPM crack fields pass
// those whose bounding boxes meet the particle-node box). `triangle` (optional) receives one
// crossed triangle on the returned side (the crack normal of contact is taken from it).
// particle_side(k): volume_sign of triangle ids[k] and the particle (triangle_list_crossing computes
// it; a caller with many lines from one particle may keep it). drop(t, particle, node, at_node): true
// when the hit of triangle t does not count (the band along a cut front, front_cut.hpp); an AtNode
// hit is dropped or kept as one, since the band is decided at the node for every triangle holding it.
struct KeepEveryHit {
  bool operator()(std::size_t, const Vec<3>&, const Vec<3>&, bool) const { return false; }
};
template <class Ids, class ParticleSide, class Drop = KeepEveryHit>
Side triangle_list_crossing_with(const Vec<3>* points, const std::array<int32_t, 3>* triangles, const Ids& ids,
                                 std::size_t n, const Vec<3>& particle, const Vec<3>& node,
                                 ParticleSide&& particle_side, std::size_t* triangle = nullptr,
                                 const Drop& drop = Drop{}) {
  int count = 0, net = 0, node_side = 0;
  std::size_t tri_above = 0, tri_below = 0, tri_node = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t t = static_cast<std::size_t>(ids[k]);
    const auto& T = triangles[t];
    int side = 0;
    const TriangleHit hit =
        triangle_crossing_given(particle_side(k), particle, node, points[T[0]], points[T[1]], points[T[2]], side);
    if (hit == TriangleHit::None || drop(t, particle, node, hit == TriangleHit::AtNode)) continue;
    if (hit == TriangleHit::AtNode) {  // one crossing at the node, however many triangles hold it
      if (node_side == 0) node_side = side, tri_node = t;
      continue;
    }
    ++count, net += side;
    (side > 0 ? tri_above : tri_below) = t;
  }
  if (node_side != 0) {
    ++count, net += node_side;
    (node_side > 0 ? tri_above : tri_below) = tri_node;
  }
  if (count % 2 == 0) return Side::None;
  if (triangle) *triangle = net > 0 ? tri_above : tri_below;
  return net > 0 ? Side::Above : Side::Below;
}
// The same, each triangle's particle side computed here.
template <class Ids, class Drop = KeepEveryHit>
Side triangle_list_crossing(const Vec<3>* points, const std::array<int32_t, 3>* triangles, const Ids& ids,
                            std::size_t n, const Vec<3>& particle, const Vec<3>& node, std::size_t* triangle = nullptr,
                            const Drop& drop = Drop{}) {
  auto particle_side = [&](std::size_t k) {
    const auto& T = triangles[static_cast<std::size_t>(ids[k])];
    return volume_sign(points[T[0]], points[T[1]], points[T[2]], particle);
  };
  return triangle_list_crossing_with(points, triangles, ids, n, particle, node, particle_side, triangle, drop);
}

// Whole-surface crossing (points, triangles: point indices, consistently oriented) WITHOUT extent
// screening: triangle_list_crossing over every triangle.
inline Side triangle_mesh_crossing(const Vec<3>* points, const std::array<int32_t, 3>* triangles, std::size_t n,
                                   const Vec<3>& particle, const Vec<3>& node, std::size_t* triangle = nullptr) {
  struct All {
    std::size_t operator[](std::size_t k) const { return k; }
  };
  return triangle_list_crossing(points, triangles, All{}, n, particle, node, triangle);
}

}  // namespace cleave::crack
