// The 3D crack crossing predicate (libmpm/crack/crossing3d.hpp, seed 000 Appendix A): exact signed
// volumes, the seed's five-volume test, and every degenerate case (line through an edge or a vertex,
// node on the surface, on an edge, on a vertex, on a front; particle on the plane).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "libmpm/crack/crossing3d.hpp"

namespace {

using cleave::Vec;
using cleave::crack::Side;
using V3 = Vec<3>;
using Tri = std::array<int32_t, 3>;

struct Mesh {
  std::vector<V3> points;
  std::vector<Tri> triangles;
  Side cross(const V3& p, const V3& i) const {
    return cleave::crack::triangle_mesh_crossing(points.data(), triangles.data(), triangles.size(), p, i);
  }
};

// The square [0, n]^2 in the plane z = 0, n x n unit squares each cut along a diagonal (alternating),
// normals +z (counter-clockwise seen from above).
Mesh flat_grid(int n) {
  Mesh m;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) m.points.emplace_back(i, j, 0.0);
  auto id = [&](int i, int j) { return static_cast<int32_t>(i * (n + 1) + j); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2 == 0) {
        m.triangles.push_back({a, b, c}), m.triangles.push_back({a, c, d});
      } else {
        m.triangles.push_back({a, b, d}), m.triangles.push_back({b, c, d});
      }
    }
  return m;
}

TEST(VolumeSign, IsPositiveWhenTheFourthPointLiesOnTheNormalSideAsSeed000Eq66Says) {
  const V3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_EQ(cleave::crack::volume_sign(a, b, c, V3(0.2, 0.2, 1)), 1);
  EXPECT_EQ(cleave::crack::volume_sign(a, b, c, V3(0.2, 0.2, -1)), -1);
  EXPECT_EQ(cleave::crack::volume_sign(a, c, b, V3(0.2, 0.2, 1)), -1);
}

TEST(VolumeSign, IsExactForCoplanarPointsFarFromTheOriginAndForOneUlpOffThePlane) {
  // Exactly coplanar doubles (the plane x + y + z = 3 * 1024.5) that rounding in the differences
  // and products would misjudge, and the fourth point moved one ulp off the plane either way.
  const double o = 1024.5;
  const V3 a(o + 0.25, o - 0.5, o + 0.25), b(o - 0.125, o + 0.0625, o + 0.0625), c(o + 3.0, o - 1.0, o - 2.0);
  const V3 d(o + 0.375, o + 0.125, o - 0.5);
  ASSERT_EQ(a.sum(), 3 * o);
  ASSERT_EQ(d.sum(), 3 * o);
  EXPECT_EQ(cleave::crack::volume_sign(a, b, c, d), 0);
  const int up = cleave::crack::volume_sign(a, b, c, V3(d.x(), d.y(), std::nextafter(d.z(), 1e9)));
  const int down = cleave::crack::volume_sign(a, b, c, V3(d.x(), d.y(), std::nextafter(d.z(), -1e9)));
  EXPECT_NE(up, 0);
  EXPECT_EQ(down, -up);
  // The normal (b - a) x (c - a) has a positive z component iff `up` is +1.
  EXPECT_EQ(up, (b - a).cross(c - a).z() > 0 ? 1 : -1);
}

TEST(VolumeSign, AgreesWithTheRoundedVolumeWheneverThatIsFarFromZero) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 20000; ++k) {
    const V3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng)), d(u(rng), u(rng), u(rng));
    const double v = cleave::crack::signed_volume(a, b, c, d);
    if (std::abs(v) < 1e-12) continue;
    ASSERT_EQ(cleave::crack::volume_sign(a, b, c, d), v > 0 ? 1 : -1);
    ASSERT_EQ(cleave::crack::detail::volume_sign_exact(a, b, c, d), v > 0 ? 1 : -1);
  }
}

TEST(TriangleMeshCrossing, ALineThroughATriangleCrossesFromAboveOrBelowAsSeed000Fig16) {
  Mesh m{{V3(0, 0, 0), V3(1, 0, 0), V3(0, 1, 0)}, {Tri{0, 1, 2}}};
  EXPECT_EQ(m.cross(V3(0.2, 0.2, 1), V3(0.3, 0.2, -1)), Side::Above);  // fig. 16b: particle above
  EXPECT_EQ(m.cross(V3(0.3, 0.2, -1), V3(0.2, 0.2, 1)), Side::Below);  // fig. 16c
  EXPECT_EQ(m.cross(V3(0.2, 0.2, 1), V3(0.3, 0.2, 0.5)), Side::None);  // fig. 16a: same side
  EXPECT_EQ(m.cross(V3(2.0, 2.0, 1), V3(2.0, 2.0, -1)), Side::None);   // passes beside the triangle
}

TEST(TriangleMeshCrossing, ALineThroughAnInteriorEdgeOrVertexCountsExactlyOnce) {
  const Mesh m = flat_grid(4);
  // Every line from a point above to a point below that passes through the surface at a point of
  // the half-unit lattice (vertices, edge midpoints, diagonal midpoints, and the points in between)
  // strictly inside the square crosses once.
  int tested = 0;
  for (int i = 1; i < 8; ++i)
    for (int j = 1; j < 8; ++j) {
      const V3 hit(0.5 * i, 0.5 * j, 0.0);
      for (const V3& dir : {V3(0, 0, 1), V3(0.5, 0.25, 1), V3(-1, 1, 1), V3(1, 0, 1), V3(0.5, 0.5, 1)}) {
        const V3 p = hit + dir, node = hit - 0.5 * dir;  // (exact: dyadic coordinates)
        ASSERT_EQ(m.cross(p, node), Side::Above) << "through " << hit.transpose() << " along " << dir.transpose();
        ASSERT_EQ(m.cross(node, p), Side::Below) << "through " << hit.transpose() << " along " << dir.transpose();
        ++tested;
      }
    }
  EXPECT_EQ(tested, 245);
}

TEST(TriangleMeshCrossing, ANodeOnTheSurfaceSeparatesItsParticlesOnEitherSideOnceAlsoOnEdgesVerticesAndFronts) {
  const Mesh m = flat_grid(2);
  // Interior of a triangle, an interior edge, an interior vertex, a diagonal, a front edge, a corner.
  for (const V3& node : {V3(0.25, 0.5, 0), V3(1.0, 0.5, 0), V3(1.0, 1.0, 0), V3(0.5, 0.5, 0), V3(0.0, 0.5, 0),
                         V3(2.0, 2.0, 0), V3(0.0, 0.0, 0)}) {
    EXPECT_EQ(m.cross(node + V3(0.25, 0.125, 1), node), Side::Above) << node.transpose();
    EXPECT_EQ(m.cross(node + V3(-0.25, 0.125, -1), node), Side::Below) << node.transpose();
  }
  // A node on the plane but outside the surface is not separated.
  EXPECT_EQ(m.cross(V3(2.5, 1.0, 1.0), V3(2.5, 1.0, 0.0)), Side::None);
}

TEST(TriangleMeshCrossing, AParticleOnTheCrackPlaneIsIgnoredAsTheSeedSays) {
  const Mesh m = flat_grid(2);
  EXPECT_EQ(m.cross(V3(0.5, 0.25, 0.0), V3(0.5, 0.25, -1.0)), Side::None);
  EXPECT_EQ(m.cross(V3(0.5, 0.25, 0.0), V3(0.5, 0.25, 1.0)), Side::None);
}

TEST(TriangleMeshCrossing, AnEvenNumberOfCrossingsIsNone) {
  // Two parallel sheets of one crack (a folded surface) crossed by one line.
  Mesh m{{V3(0, 0, 0), V3(1, 0, 0), V3(0, 1, 0), V3(0, 0, 1), V3(1, 0, 1), V3(0, 1, 1)}, {Tri{0, 1, 2}, Tri{3, 4, 5}}};
  EXPECT_EQ(m.cross(V3(0.2, 0.2, 2), V3(0.2, 0.2, -1)), Side::None);
  EXPECT_EQ(m.cross(V3(0.2, 0.2, 2), V3(0.2, 0.2, 0.5)), Side::Above);
}

TEST(TriangleMeshCrossing, ALineGrazingAFrontCountsAsTheInfinitesimallyDisplacedLineDoes) {
  // The edge x = 0 of the square is a front. The rule displaces the particle by e (1, e', e'^2):
  // towards +x, into the surface, so a line through the front edge crosses; through the front edge
  // x = 2 (displaced outwards) it does not.
  const Mesh m = flat_grid(2);
  EXPECT_EQ(m.cross(V3(0.0, 0.5, 1), V3(0.0, 0.5, -1)), Side::Above);
  EXPECT_EQ(m.cross(V3(2.0, 0.5, 1), V3(2.0, 0.5, -1)), Side::None);
  // ... and agrees with a particle displaced by a small finite amount the same way.
  EXPECT_EQ(m.cross(V3(1e-9, 0.5, 1), V3(0.0, 0.5, -1)), Side::Above);
  EXPECT_EQ(m.cross(V3(2.0 + 1e-9, 0.5, 1), V3(2.0, 0.5, -1)), Side::None);
}

TEST(TriangleMeshCrossing, NamesTheCrossedTriangleForTheContactNormal) {
  const Mesh m = flat_grid(2);
  std::size_t t = 99;
  const Side s = cleave::crack::triangle_mesh_crossing(m.points.data(), m.triangles.data(), m.triangles.size(),
                                                        V3(1.75, 0.25, 1), V3(1.75, 0.25, -1), &t);
  ASSERT_EQ(s, Side::Above);
  ASSERT_LT(t, m.triangles.size());
  const auto& T = m.triangles[t];
  int side = 0;
  EXPECT_EQ(cleave::crack::triangle_crossing(V3(1.75, 0.25, 1), V3(1.75, 0.25, -1), m.points[T[0]], m.points[T[1]],
                                             m.points[T[2]], side),
            cleave::crack::TriangleHit::Crossed);
}

// segment_meets_box screens triangles for the MPM's particle-node lines (crack_front_sums.hpp):
// it may keep a triangle the line misses, never drop one the line meets.
TEST(SegmentMeetsBox, KeepsTheBoxesASegmentPassesThroughOrTouchesAndDropsThoseItPassesBy) {
  using cleave::crack::segment_meets_box;
  const auto inv = [](const V3& p, const V3& q) { return V3((q - p).cwiseInverse()); };
  const V3 lo(0, 0, 0), hi(1, 1, 0);  // a flat box, as a triangle of a crack on a node plane
  const double s = cleave::crack::segment_box_slack(1.0, 2.0);
  EXPECT_TRUE(segment_meets_box(V3(0.5, 0.5, 1), inv(V3(0.5, 0.5, 1), V3(0.5, 0.5, -1)), lo, hi, s));
  // Ending on the box's plane inside it (a node on the crack), or on its edge.
  EXPECT_TRUE(segment_meets_box(V3(0.2, 0.3, -0.5), inv(V3(0.2, 0.3, -0.5), V3(0.7, 0.4, 0)), lo, hi, s));
  EXPECT_TRUE(segment_meets_box(V3(0.2, 0.3, -0.5), inv(V3(0.2, 0.3, -0.5), V3(1.0, 0.4, 0)), lo, hi, s));
  // Its box meets the segment's box, but the segment crosses the plane beside it.
  EXPECT_FALSE(segment_meets_box(V3(1.9, 0.5, 1), inv(V3(1.9, 0.5, 1), V3(0.9, 0.5, -1)), lo, hi, s));
  // Stops short of the plane.
  EXPECT_FALSE(segment_meets_box(V3(0.5, 0.5, 1), inv(V3(0.5, 0.5, 1), V3(0.5, 0.5, 1e-6)), lo, hi, s));
  // A point (every component of q - p zero), inside and outside.
  EXPECT_TRUE(segment_meets_box(V3(0.5, 0.5, 0), inv(V3(0.5, 0.5, 0), V3(0.5, 0.5, 0)), lo, hi, s));
  EXPECT_FALSE(segment_meets_box(V3(0.5, 1.5, 0), inv(V3(0.5, 1.5, 0), V3(0.5, 1.5, 0)), lo, hi, s));
}

// The property the screen rests on, over lines of every kind the MPM asks about on a crack laid on
// node planes and on a tilted one: particles anywhere, nodes on the grid (also on the surface, its
// edges and vertices), far from the origin as in SI metres of a body placed away from it.
TEST(SegmentMeetsBox, NeverDropsATriangleThatTheCrossingTestCounts) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int hits = 0;
  for (const double tilt : {0.0, 0.37}) {
    for (const double offset : {0.0, 1234.5}) {
      const double h = 0.25;
      Mesh m = flat_grid(4);
      for (auto& p : m.points) p = V3(p.x() * h, p.y() * h, tilt * p.x() * h) + V3::Constant(offset);
      for (int n = 0; n < 20000; ++n) {
        const V3 particle = V3::Constant(offset) + V3(u(rng), u(rng), u(rng) - 0.5) * (4 * h);
        V3 node = particle;
        for (int d = 0; d < 3; ++d)  // a node of the particle's cell, or of the one beyond
          node[d] = offset + h * (std::floor((particle[d] - offset) / h) + static_cast<double>(static_cast<int>(rng() % 4) - 1));
        const V3 inv = (node - particle).cwiseInverse();
        const double slack = cleave::crack::segment_box_slack(h, std::max(particle.cwiseAbs().maxCoeff(), node.cwiseAbs().maxCoeff()));
        for (const auto& T : m.triangles) {
          const V3 &a = m.points[T[0]], &b = m.points[T[1]], &c = m.points[T[2]];
          int side = 0;
          if (cleave::crack::triangle_crossing(particle, node, a, b, c, side) == cleave::crack::TriangleHit::None) continue;
          ++hits;
          ASSERT_TRUE(cleave::crack::segment_meets_box(particle, inv, a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c), slack))
              << "tilt " << tilt << " offset " << offset << " line " << particle.transpose() << " -> " << node.transpose();
        }
      }
    }
  }
  EXPECT_GT(hits, 10000);
}

}  // namespace
