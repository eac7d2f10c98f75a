// 2D crack geometry (seed 002 Appendix A, line crossing): the signed-area sign rules of every
// appendix pattern and their mirror images, degenerate cases (node on a segment, on its start and
// end point, a line through an end point, collinear lines), odd/even crossing counts on zig-zag
// cracks, interior polyline vertices, crack-extent screening against the unscreened answer, and
// parse_cracks (both forms, units, and the exact key path of every error).
#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "libmpm/core/error.hpp"
#include "libmpm/crack/crack2d.hpp"
#include "libmpm/crack/crossing.hpp"
#include "libmpm/crack/surface.hpp"
#include "libmpm/mpm/crack_fields/line_weight.hpp"

namespace {

using cleave::SceneError;
using cleave::Vec;
using cleave::crack::area_sign;
using cleave::crack::classify_signs;
using cleave::crack::Crack2D;
using cleave::crack::crack_crossing;
using cleave::crack::crack_crossing_unscreened;
using cleave::crack::parse_cracks;
using cleave::crack::segment_crossing;
using cleave::crack::Side;
using cleave::crack::segment_crosses;
using cleave::crack::signed_area;
using json = nlohmann::json;

Vec<2> v(double x, double y) { return Vec<2>(x, y); }

const char* name(Side s) { return s == Side::Above ? "Above" : s == Side::Below ? "Below" : "None"; }

// The four appendix signs (123), (124), (341), (342) as a string like "-++-".
std::string signs(const Vec<2>& p, const Vec<2>& n, const Vec<2>& x3, const Vec<2>& x4) {
  auto c = [](int s) { return s > 0 ? '+' : s < 0 ? '-' : '0'; };
  return {c(area_sign(p, n, x3)), c(area_sign(p, n, x4)), c(area_sign(x3, x4, p)), c(area_sign(x3, x4, n))};
}

Side flip(Side s) { return s == Side::Above ? Side::Below : s == Side::Below ? Side::Above : Side::None; }
Vec<2> mirror(const Vec<2>& x) { return v(x.x(), -x.y()); }  // reflection: reverses orientation

Crack2D make_crack(std::vector<Vec<2>> pts) {
  Crack2D c;
  c.name = "c";
  c.points = std::move(pts);
  c.update_extent();
  return c;
}

// One segment case: expected side and appendix sign string, and the mirror images: reflecting
// everything flips the side; reversing the crack direction flips the side; swapping particle and
// node of a proper crossing flips the side.
void expect_segment(const Vec<2>& p, const Vec<2>& n, const Vec<2>& x3, const Vec<2>& x4, Side want,
                    const std::string& want_signs) {
  SCOPED_TRACE("particle " + std::to_string(p.x()) + "," + std::to_string(p.y()) + " node " +
               std::to_string(n.x()) + "," + std::to_string(n.y()));
  EXPECT_EQ(signs(p, n, x3, x4), want_signs);
  EXPECT_EQ(segment_crossing(p, n, x3, x4), want) << name(segment_crossing(p, n, x3, x4));
  EXPECT_EQ(segment_crossing(mirror(p), mirror(n), mirror(x3), mirror(x4)), flip(want));
  EXPECT_EQ(segment_crossing(p, n, x4, x3), flip(want));
  // A one-segment crack gives the same answer (screened and unscreened).
  const Crack2D c = make_crack({x3, x4});
  EXPECT_EQ(crack_crossing(c, p, n), want);
  EXPECT_EQ(crack_crossing_unscreened(c, p, n), want);
}

// ----------------------------------------------------------------------------------------------
// Signed area and its sign.

TEST(CrackSignedArea, MatchesEquation33) {
  const Vec<2> a = v(0.3, -1.2), b = v(2.5, 0.7), c = v(-0.4, 1.9);
  const double eq33 = a.x() * (b.y() - c.y()) + b.x() * (c.y() - a.y()) + c.x() * (a.y() - b.y());
  EXPECT_NEAR(signed_area(a, b, c), eq33, 1e-14);
  EXPECT_GT(signed_area(v(0, 0), v(1, 0), v(0, 1)), 0.0);  // counter-clockwise
  EXPECT_LT(signed_area(v(0, 0), v(0, 1), v(1, 0)), 0.0);  // clockwise
  EXPECT_EQ(signed_area(v(0, 0), v(1, 1), v(2, 2)), 0.0);
  EXPECT_EQ(area_sign(v(0, 0), v(1, 0), v(0, 1)), 1);
  EXPECT_EQ(area_sign(v(0, 0), v(0, 1), v(1, 0)), -1);
  EXPECT_EQ(area_sign(v(0, 0), v(1, 1), v(2, 2)), 0);
  EXPECT_EQ(area_sign(v(1, 2), v(1, 2), v(5, 7)), 0);  // repeated point
}

// Shewchuk's classic failure of the naive formula: points a hair off the line y = x. The exact
// sign is known in closed form (-sign(dx - dy)), and area_sign must always get it.
TEST(CrackSignedArea, SignIsExactNearDegenerate) {
  const Vec<2> q = v(12, 12), r = v(24, 24);
  for (int i = -40; i <= 40; ++i) {
    for (int j = -40; j <= 40; ++j) {
      const double px = std::nextafter(0.5, 0.0) + i * std::ldexp(1.0, -53);
      const double py = 0.5 + j * std::ldexp(1.0, -53);
      const int want = px > py ? -1 : px < py ? 1 : 0;  // (p, q, r): left of q -> r iff py > px
      ASSERT_EQ(area_sign(v(px, py), q, r), want) << i << " " << j;
      ASSERT_EQ(area_sign(q, r, v(px, py)), want);  // cyclic permutations agree exactly
      ASSERT_EQ(area_sign(r, v(px, py), q), want);
      ASSERT_EQ(area_sign(q, v(px, py), r), -want);
    }
  }
}

// ----------------------------------------------------------------------------------------------
// One segment: every appendix pattern.

const Vec<2> kX3 = v(0, 0), kX4 = v(1, 0);  // crack pointing +x: "above" (left) is +y

TEST(CrackSegmentCrossing, WorkedExampleConvention) {
  // The hand-worked example in crossing.hpp: particle left of x3 -> x4 is above.
  expect_segment(v(0.5, 1), v(0.5, -1), kX3, kX4, Side::Above, "-++-");
  expect_segment(v(0.5, -1), v(0.5, 1), kX3, kX4, Side::Below, "+--+");
  // Oblique lines and an oblique crack.
  expect_segment(v(0.1, 0.3), v(0.9, -0.2), kX3, kX4, Side::Above, "-++-");
  expect_segment(v(0.9, -0.2), v(0.1, 0.3), kX3, kX4, Side::Below, "+--+");
  expect_segment(v(-1, 1), v(1, 0), v(0, -1), v(1, 2), Side::Above, "-++-");
}

TEST(CrackSegmentCrossing, NoCrossingCases) {
  expect_segment(v(0.5, 1), v(0.5, 0.5), kX3, kX4, Side::None, "-+++");     // same side
  expect_segment(v(0.5, -1), v(0.5, -0.2), kX3, kX4, Side::None, "+---");
  expect_segment(v(2, 1), v(2, -1), kX3, kX4, Side::None, "--+-");          // past the end
  expect_segment(v(-1, 1), v(-1, -1), kX3, kX4, Side::None, "+++-");        // before the start
  expect_segment(v(3, 1), v(2, 0), kX3, kX4, Side::None, "--+0");           // node on the extension
}

TEST(CrackSegmentCrossing, NodeOnSegment) {
  // (-++0): node on the crack segment, particle above; (+--0) below.
  expect_segment(v(0.5, 1), v(0.5, 0), kX3, kX4, Side::Above, "-++0");
  expect_segment(v(0.2, 0.7), v(0.75, 0), kX3, kX4, Side::Above, "-++0");
  expect_segment(v(0.5, -1), v(0.5, 0), kX3, kX4, Side::Below, "+--0");
  // Oblique crack with exactly representable points on it.
  expect_segment(v(0.25, 2), v(0.5, 1), v(0, 0), v(1, 2), Side::Above, "-++0");
  expect_segment(v(0.75, 0), v(0.5, 1), v(0, 0), v(1, 2), Side::Below, "+--0");
}

TEST(CrackSegmentCrossing, NodeOnStartAndEndPoint) {
  expect_segment(v(0.3, 1), kX3, kX3, kX4, Side::Above, "0++0");   // on the start point
  expect_segment(v(-0.5, 1), kX3, kX3, kX4, Side::Above, "0++0");  // from behind the start
  expect_segment(v(0.3, -1), kX3, kX3, kX4, Side::Below, "0--0");
  expect_segment(v(0.3, 1), kX4, kX3, kX4, Side::Above, "-0+0");   // on the end point
  expect_segment(v(1.5, 1), kX4, kX3, kX4, Side::Above, "-0+0");   // from beyond the end
  expect_segment(v(0.3, -1), kX4, kX3, kX4, Side::Below, "+0-0");
}

TEST(CrackSegmentCrossing, LineThroughEndPointFromOutsideDoesNotCount) {
  // The particle-node line passes exactly through x3 or x4 with the node off the segment:
  // (0++-) / (-0+-) and mirrors are not among the appendix's patterns, so no crossing.
  expect_segment(v(0, 1), v(0, -1), kX3, kX4, Side::None, "0++-");
  expect_segment(v(-1, 1), v(1, -1), kX3, kX4, Side::None, "0++-");
  expect_segment(v(1, 1), v(1, -1), kX3, kX4, Side::None, "-0+-");
  expect_segment(v(2, 1), v(0, -1), kX3, kX4, Side::None, "-0+-");
  expect_segment(v(0, -1), v(0, 1), kX3, kX4, Side::None, "0--+");
}

TEST(CrackSegmentCrossing, ParticleOnCrackIsIgnored) {
  expect_segment(v(0.5, 0), v(0.5, 1), kX3, kX4, Side::None, "+-0+");
  expect_segment(v(0.5, 0), v(0.5, -1), kX3, kX4, Side::None, "-+0-");
  expect_segment(v(0, 0), v(0.5, 1), kX3, kX4, Side::None, "0-0+");
}

TEST(CrackSegmentCrossing, CollinearLineAndCrack) {
  expect_segment(v(-1, 0), v(2, 0), kX3, kX4, Side::None, "0000");      // covers the crack
  expect_segment(v(0.2, 0), v(0.8, 0), kX3, kX4, Side::None, "0000");   // inside it
  expect_segment(v(2, 0), v(3, 0), kX3, kX4, Side::None, "0000");       // beyond it
  expect_segment(v(-1, 0), v(0.5, 0), kX3, kX4, Side::None, "0000");    // node on it
  expect_segment(v(-1, 0), v(0, 0), kX3, kX4, Side::None, "0000");      // node on the start
}

// Every one of the 81 sign combinations: exactly the appendix's eight give a side.
TEST(CrackSegmentCrossing, ClassifyAllSignPatterns) {
  int hits = 0;
  for (int a = -1; a <= 1; ++a)
    for (int b = -1; b <= 1; ++b)
      for (int c = -1; c <= 1; ++c)
        for (int e = -1; e <= 1; ++e) {
          auto ch = [](int s) { return s > 0 ? '+' : s < 0 ? '-' : '0'; };
          const std::string pat{ch(a), ch(b), ch(c), ch(e)};
          Side want = Side::None;
          if (pat == "-++-" || pat == "-++0" || pat == "0++0" || pat == "-0+0") want = Side::Above;
          if (pat == "+--+" || pat == "+--0" || pat == "0--0" || pat == "+0-0") want = Side::Below;
          EXPECT_EQ(classify_signs(a, b, c, e), want) << pat;
          hits += want != Side::None;
        }
  EXPECT_EQ(hits, 8);
}

// The appendix's robustness claim: with a node very close to (or on) a crack, two particles on
// the same side are never put on opposite sides. Random oblique segments, node on a rounded point
// of the segment; particles well off the crack on either side.
TEST(CrackSegmentCrossing, NodeNearCrackIsConsistentAcrossParticles) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> u(-1.0, 1.0), t01(0.05, 0.95);
  int on_crack = 0;
  for (int k = 0; k < 2000; ++k) {
    const Vec<2> x3 = v(u(rng), u(rng)), x4 = v(u(rng), u(rng));
    const Vec<2> d = x4 - x3;
    if (d.norm() < 0.2) continue;
    const Vec<2> nrm = v(-d.y(), d.x()) / d.norm();  // left normal
    const Vec<2> node = x3 + t01(rng) * d;           // on the segment up to rounding
    Side left = Side::None, right = Side::None;
    for (int m = 0; m < 20; ++m) {
      const Vec<2> along = x3 + t01(rng) * d;
      const double off = 0.01 + 0.1 * (u(rng) + 1.0);
      const Side l = segment_crossing(along + off * nrm, node, x3, x4);
      const Side r = segment_crossing(along - off * nrm, node, x3, x4);
      if (m == 0) {
        left = l;
        right = r;
      }
      ASSERT_EQ(l, left) << "left particles split at k=" << k;
      ASSERT_EQ(r, right) << "right particles split at k=" << k;
    }
    // The node is on one side (or on the crack): exactly the other side's particles are separated.
    EXPECT_TRUE(left == Side::Above || left == Side::None);
    EXPECT_TRUE(right == Side::Below || right == Side::None);
    EXPECT_FALSE(left == Side::None && right == Side::None);
    on_crack += left == Side::Above && right == Side::Below;
  }
  EXPECT_GE(on_crack, 0);
}

// ----------------------------------------------------------------------------------------------
// Whole cracks.

TEST(CrackCrossing, ZigZagEvenIsNoneOddIsNetSide) {
  // Segments 0 and 2 point up-right, segment 1 down-right; y = 0.5 crosses them at x = 0.5, 1.5, 2.5.
  const Crack2D c = make_crack({v(0, 0), v(1, 1), v(2, 0), v(3, 1)});
  EXPECT_EQ(crack_crossing(c, v(0.2, 0.5), v(1.8, 0.5)), Side::None);  // two crossings
  EXPECT_EQ(crack_crossing(c, v(1.2, 0.5), v(2.8, 0.5)), Side::None);
  // Three crossings with sides above, below, above: the particle (upper left of segment 0) is above.
  EXPECT_EQ(segment_crossing(v(0.2, 0.5), v(2.8, 0.5), c.points[0], c.points[1]), Side::Above);
  EXPECT_EQ(segment_crossing(v(0.2, 0.5), v(2.8, 0.5), c.points[1], c.points[2]), Side::Below);
  EXPECT_EQ(segment_crossing(v(0.2, 0.5), v(2.8, 0.5), c.points[2], c.points[3]), Side::Above);
  EXPECT_EQ(crack_crossing(c, v(0.2, 0.5), v(2.8, 0.5)), Side::Above);
  EXPECT_EQ(crack_crossing(c, v(2.8, 0.5), v(0.2, 0.5)), Side::Below);
  // One crossing.
  EXPECT_EQ(crack_crossing(c, v(0.2, 0.5), v(0.8, 0.5)), Side::Above);
  EXPECT_EQ(crack_crossing(c, v(1.2, 0.5), v(1.8, 0.5)), Side::Below);
}

TEST(CrackCrossing, NodeOnInteriorVertexIsSeparatedOnce) {
  // Left turn at (1, 0). Literally per segment the node would be on the end of segment 0 (-0+0)
  // and on the start of segment 1 (0++0): two crossings, i.e. none; the vertex is decided once.
  const Crack2D c = make_crack({v(0, 0), v(1, 0), v(2, 1)});
  const Vec<2> node = v(1, 0);
  EXPECT_EQ(segment_crossing(v(1, 0.5), node, c.points[0], c.points[1]), Side::Above);
  EXPECT_EQ(segment_crossing(v(1, 0.5), node, c.points[1], c.points[2]), Side::Above);
  EXPECT_EQ(crack_crossing(c, v(1, 0.5), node), Side::Above);     // in the left sector
  EXPECT_EQ(crack_crossing(c, v(0.5, 0.2), node), Side::Above);
  EXPECT_EQ(crack_crossing(c, v(1, -0.5), node), Side::Below);
  EXPECT_EQ(crack_crossing(c, v(1.5, 0.2), node), Side::Below);   // right of segment 1
  EXPECT_EQ(crack_crossing(c, v(2, 0), node), Side::Below);       // on segment 0's extension
  EXPECT_EQ(crack_crossing(c, v(0.5, 0), node), Side::None);      // particle on the crack
  EXPECT_EQ(crack_crossing(c, v(1.5, 0.5), node), Side::None);
  // Right turn at (1, 0): the left sector is the large one.
  const Crack2D r = make_crack({v(0, 0), v(1, 0), v(2, -1)});
  EXPECT_EQ(crack_crossing(r, v(1.5, -0.2), node), Side::Above);
  EXPECT_EQ(crack_crossing(r, v(1, 0.5), node), Side::Above);
  EXPECT_EQ(crack_crossing(r, v(1.1, -0.5), node), Side::Below);
  EXPECT_EQ(crack_crossing(r, v(0.5, -0.5), node), Side::Below);
  // Straight through.
  const Crack2D s = make_crack({v(0, 0), v(1, 0), v(2, 0)});
  EXPECT_EQ(crack_crossing(s, v(1.3, 0.5), node), Side::Above);
  EXPECT_EQ(crack_crossing(s, v(0.7, -0.5), node), Side::Below);
}

TEST(CrackCrossing, NodeOnCrackTipsAndSegments) {
  const Crack2D c = make_crack({v(0, 0), v(1, 0), v(2, 1)});
  EXPECT_EQ(crack_crossing(c, v(0.3, 1), v(0, 0)), Side::Above);    // start tip (0++0)
  EXPECT_EQ(crack_crossing(c, v(0.3, -1), v(0, 0)), Side::Below);
  EXPECT_EQ(crack_crossing(c, v(1.5, 1.5), v(2, 1)), Side::Above);  // end tip (-0+0)
  EXPECT_EQ(crack_crossing(c, v(2, 0.5), v(2, 1)), Side::Below);
  EXPECT_EQ(crack_crossing(c, v(0.5, 0.5), v(0.5, 0)), Side::Above);  // on a segment (-++0)
  EXPECT_EQ(crack_crossing(c, v(1, 1), v(1.5, 0.5)), Side::Above);
  EXPECT_EQ(crack_crossing(c, v(0, 1), v(0, -1)), Side::None);      // grazes the start tip
  EXPECT_EQ(crack_crossing(c, v(2, 2), v(2, 0)), Side::None);       // grazes the end tip
}

TEST(CrackCrossing, LineThroughInteriorVertex) {
  const Crack2D c = make_crack({v(0, 0), v(1, 0), v(2, 1)});
  // Per segment the appendix sees only end points (none); the polyline is crossed at the vertex.
  EXPECT_EQ(segment_crossing(v(1, 0.5), v(1, -0.5), c.points[0], c.points[1]), Side::None);
  EXPECT_EQ(segment_crossing(v(1, 0.5), v(1, -0.5), c.points[1], c.points[2]), Side::None);
  EXPECT_EQ(crack_crossing(c, v(1, 0.5), v(1, -0.5)), Side::Above);
  EXPECT_EQ(crack_crossing(c, v(1, -0.5), v(1, 0.5)), Side::Below);
  EXPECT_EQ(crack_crossing(c, v(0.5, 0.5), v(1.5, -0.5)), Side::Above);
  // Touching a peak from outside is no crossing.
  const Crack2D peak = make_crack({v(0, 0), v(1, 1), v(2, 0)});
  EXPECT_EQ(crack_crossing(peak, v(0.5, 1), v(1.5, 1)), Side::None);
  EXPECT_EQ(crack_crossing(peak, v(1, 2), v(1, 1)), Side::Above);   // node on the peak, from above
  EXPECT_EQ(crack_crossing(peak, v(1, 0.5), v(1, 1)), Side::Below);
  // A line stopping on the vertex's far side but not reaching it: no crossing.
  EXPECT_EQ(crack_crossing(c, v(1, 0.5), v(1, 0.25)), Side::None);
}

TEST(CrackCrossing, ExtentIsScreenedAndUpdated) {
  Crack2D c = make_crack({v(0, 0), v(1, 1), v(2, -1)});
  EXPECT_EQ(c.lo, v(0, -1));
  EXPECT_EQ(c.hi, v(2, 1));
  Crack2D fresh;  // never updated: empty extent screens everything out
  fresh.points = c.points;
  EXPECT_EQ(crack_crossing(fresh, v(0.5, 1), v(0.5, 0)), Side::None);
  c.points = {v(10, 0), v(11, 0)};
  c.update_extent();
  EXPECT_EQ(c.lo, v(10, 0));
  EXPECT_EQ(crack_crossing(c, v(10.5, 1), v(10.5, -1)), Side::Above);
  EXPECT_FALSE(cleave::crack::extent_overlaps(c, v(0, 1), v(1, -1)));
  EXPECT_TRUE(cleave::crack::extent_overlaps(c, v(9, 1), v(10, 0)));  // touching corner counts
}

// Subtask 1 never changes an answer: 10^5 random pairs against random polylines, with and
// without screening; half the pairs snapped to a lattice that the crack vertices share, so that
// nodes on vertices and segments and lines through vertices occur often.
TEST(CrackCrossing, ScreeningMatchesCheckingEverySegment) {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> u(0.0, 8.0), step(-1.0, 1.0);
  std::uniform_int_distribution<int> lat(0, 64);
  auto snap = [&] { return v(lat(rng) * 0.125, lat(rng) * 0.125); };
  std::vector<Crack2D> cracks;
  for (int k = 0; k < 20; ++k) {
    std::vector<Vec<2>> pts{k % 2 ? snap() : v(u(rng), u(rng))};
    const int n = 2 + k % 7;
    for (int i = 1; i < n; ++i) {
      Vec<2> next = pts.back() + v(step(rng), step(rng));
      if (k % 2) next = v(std::round(next.x() * 4) / 4, std::round(next.y() * 4) / 4);
      if (next != pts.back()) pts.push_back(next);
    }
    if (pts.size() >= 2) cracks.push_back(make_crack(pts));
  }
  long screened = 0, crossings = 0, agree_generic = 0;
  for (int i = 0; i < 100000; ++i) {
    const Crack2D& c = cracks[static_cast<std::size_t>(i) % cracks.size()];
    Vec<2> p, n;
    if (i % 2) {
      p = snap();
      n = snap();
    } else {
      p = v(u(rng), u(rng));
      n = p + 0.5 * v(step(rng), step(rng));
    }
    const Side a = crack_crossing(c, p, n), b = crack_crossing_unscreened(c, p, n);
    ASSERT_EQ(a, b) << "pair " << i;
    screened += !cleave::crack::extent_overlaps(c, p, n);
    crossings += a != Side::None;
    if (i % 2 == 0) {
      // Generic (random real) pairs never hit a vertex: the polyline answer is then exactly the
      // appendix per-segment rules with the odd/even + net-side rule.
      int count = 0, net = 0;
      for (std::size_t s = 0; s + 1 < c.points.size(); ++s) {
        const Side x = segment_crossing(p, n, c.points[s], c.points[s + 1]);
        count += x != Side::None;
        net += x == Side::Above ? 1 : x == Side::Below ? -1 : 0;
      }
      const Side want = count % 2 == 0 ? Side::None : net > 0 ? Side::Above : Side::Below;
      ASSERT_EQ(b, want) << "pair " << i;
      ++agree_generic;
    }
  }
  EXPECT_GT(screened, 10000);   // the screen does skip pairs
  EXPECT_GT(crossings, 1000);   // and many pairs do cross
  EXPECT_EQ(agree_generic, 50000);
}

// ----------------------------------------------------------------------------------------------
// parse_cracks.

std::vector<Crack2D> parse(const json& j, double scale = 1.0) { return parse_cracks(j, "cracks", scale); }

TEST(ParseCracks, PointsForm) {
  const auto cs = parse(json::parse(R"([
    {"name": "a", "points": [[0, 0], [1, 0], [2, 1]]},
    {"name": "b", "points": [[5, 5], [6, 5]], "contact": {"law": "friction", "mu": 0.3}},
    {"name": "c", "points": [[0, 3], [1, 3]], "contact": {"law": "stick"}}])"));
  ASSERT_EQ(cs.size(), 3u);
  EXPECT_EQ(cs[0].name, "a");
  EXPECT_EQ(cs[0].id, 0);
  EXPECT_EQ(cs[1].id, 1);
  ASSERT_EQ(cs[0].points.size(), 3u);
  EXPECT_EQ(cs[0].points[2], v(2, 1));
  EXPECT_EQ(cs[0].contact_law, cleave::crack::ContactLaw::Frictionless);
  EXPECT_EQ(cs[0].friction, 0.0);
  EXPECT_EQ(cs[0].lo, v(0, 0));
  EXPECT_EQ(cs[0].hi, v(2, 1));
  EXPECT_EQ(cs[1].contact_law, cleave::crack::ContactLaw::Friction);
  EXPECT_EQ(cs[1].friction, 0.3);
  EXPECT_EQ(cs[2].contact_law, cleave::crack::ContactLaw::Stick);
  EXPECT_TRUE(parse(json::array()).empty());
  // Straight-on and non-adjacent but far segments are fine.
  EXPECT_NO_THROW(parse(json::parse(R"([{"name": "s", "points": [[0, 0], [1, 0], [2, 0], [2, 1], [0, 1]]}])")));
}

// MPM's explicit crack is the same geometry type as peridynamics' crack surfaces: a polyline read
// from the scene is a Surface<2> whose simplices are its segments and whose boundary (the fronts)
// is its two end points, and the shared crossing test agrees with the MPM one on it.
TEST(ParseCracks, APolylineCrackIsASurfaceWhoseFrontsAreItsEnds) {
  const Crack2D c = parse(json::parse(R"([{"name": "a", "points": [[0, 0], [1, 0], [2, 1], [3, 1]]}])"), 1.0).at(0);
  const cleave::crack::Surface<2>& s = c;
  ASSERT_EQ(s.simplices.size(), 3u);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(s.simplices[k], (std::array<int32_t, 2>{k, k + 1}));
  auto fronts = s.boundary();
  ASSERT_EQ(fronts.size(), 2u);
  std::sort(fronts.begin(), fronts.end());
  EXPECT_EQ(fronts[0][0], 0);
  EXPECT_EQ(fronts[1][0], 3);
  for (const auto& [a, b] : {std::pair{v(0.5, -1), v(0.5, 1)}, std::pair{v(1.5, 2), v(1.6, -2)},
                             std::pair{v(-1, -1), v(-1, 1)}, std::pair{v(2.5, 0), v(2.5, 0.9)}})
    EXPECT_EQ(segment_crosses(s, a, b), crack_crossing(c, a, b) != Side::None);
}

TEST(ParseCracks, StraightFormSplitsIntoEqualSegments) {
  auto one = [](const std::string& s, double scale = 1.0) { return parse(json::parse(s), scale).at(0); };
  const Crack2D a = one(R"([{"name": "a", "from": [0, 0], "to": [1, 0], "segment_length": 0.3}])");
  ASSERT_EQ(a.points.size(), 5u);  // ceil(1 / 0.3) = 4 segments
  for (std::size_t k = 0; k + 1 < a.points.size(); ++k)
    EXPECT_NEAR((a.points[k + 1] - a.points[k]).norm(), 0.25, 1e-15);
  EXPECT_EQ(a.points.front(), v(0, 0));
  EXPECT_EQ(a.points.back(), v(1, 0));
  // A length that divides evenly up to rounding (1.1 / 0.1 = 11.000000000000002) is not rounded up.
  const Crack2D b = one(R"([{"name": "b", "from": [0, 0], "to": [1.1, 0], "segment_length": 0.1}])");
  EXPECT_EQ(b.points.size(), 12u);
  // Oblique, longer segment than the crack: one segment.
  const Crack2D c = one(R"([{"name": "c", "from": [1, 1], "to": [4, 5], "segment_length": 10}])");
  ASSERT_EQ(c.points.size(), 2u);
  const Crack2D d = one(R"([{"name": "d", "from": [1, 1], "to": [4, 5], "segment_length": 1}])");
  ASSERT_EQ(d.points.size(), 6u);  // |to - from| = 5
  for (std::size_t k = 0; k + 1 < d.points.size(); ++k)
    EXPECT_NEAR((d.points[k + 1] - d.points[k]).norm(), 1.0, 1e-14);
  EXPECT_EQ(d.lo, v(1, 1));
  EXPECT_EQ(d.hi, v(4, 5));
}

TEST(ParseCracks, LengthScaleMultipliesCoordinatesAndLengths) {
  const auto cs = parse(json::parse(R"([
    {"name": "a", "points": [[0, 0], [10, 20]]},
    {"name": "b", "from": [0, 0], "to": [40, 0], "segment_length": 10}])"), 1e-3);
  EXPECT_NEAR(cs[0].points[1].x(), 0.010, 1e-18);
  EXPECT_NEAR(cs[0].points[1].y(), 0.020, 1e-18);
  EXPECT_NEAR(cs[0].hi.y(), 0.020, 1e-18);
  ASSERT_EQ(cs[1].points.size(), 5u);
  EXPECT_NEAR(cs[1].points[1].x(), 0.010, 1e-18);
  EXPECT_NEAR(cs[1].points[4].x(), 0.040, 1e-18);
  EXPECT_THROW(parse(json::array(), 0.0), std::invalid_argument);
  EXPECT_THROW(parse(json::array(), -1.0), std::invalid_argument);
  EXPECT_THROW(parse(json::array(), std::nan("")), std::invalid_argument);
}

struct ErrorCase {
  const char* scene;   // the value of "cracks"
  std::string path;    // expected SceneError::key_path()
  std::string reason;  // substring expected in SceneError::reason()
};

TEST(ParseCracks, ErrorsNameTheKeyPath) {
  const std::string ok = R"({"name": "ok", "points": [[0, 0], [1, 0]]})";
  const std::vector<ErrorCase> cases = {
      {R"({"name": "a"})", "cracks", "expected an array"},
      {R"([3])", "cracks[0]", "expected an object"},
      {R"([{"points": [[0, 0], [1, 0]]}])", "cracks[0].name", "missing"},
      {R"([{"name": 7, "points": [[0, 0], [1, 0]]}])", "cracks[0].name", "expected a string"},
      {R"([{"name": "", "points": [[0, 0], [1, 0]]}])", "cracks[0].name", "must not be empty"},
      {R"([OK, {"name": "b"}])", "cracks[1].points", "missing"},
      {R"([OK, {"name": "b", "points": [[0, 0]]}])", "cracks[1].points", "at least 2 points"},
      {R"([OK, {"name": "b", "points": []}])", "cracks[1].points", "at least 2 points"},
      {R"([OK, {"name": "b", "points": {"x": 1}}])", "cracks[1].points", "expected an array"},
      {R"([OK, {"name": "b", "points": [[0, 0], [1, 0], [2]]}])", "cracks[1].points[2]", "expected 2 numbers"},
      {R"([OK, {"name": "b", "points": [[0, 0], [1, 0], "x"]}])", "cracks[1].points[2]", "expected 2 numbers"},
      {R"([OK, {"name": "b", "points": [[0, 0], [1, 0], [2, "y"]]}])", "cracks[1].points[2][1]", "expected a number"},
      {R"([OK, {"name": "b", "points": [[0, 0], [1, 0], [1, 0]]}])", "cracks[1].points[2]", "zero-length"},
      {R"([OK, {"name": "b", "points": [[0, 0], [0, 0]]}])", "cracks[1].points[1]", "zero-length"},
      // Two non-adjacent segments cross, touch (end on a segment), share an end point (closed loop).
      {R"([OK, {"name": "b", "points": [[0, 0], [2, 0], [2, 1], [1, -1]]}])", "cracks[1].points",
       "segment 0 (points[0] to points[1]) and segment 2 (points[2] to points[3]) intersect"},
      {R"([OK, {"name": "b", "points": [[0, 0], [2, 0], [2, 1], [1, 0]]}])", "cracks[1].points", "intersect or touch"},
      {R"([OK, {"name": "b", "points": [[0, 0], [1, 0], [1, 1], [0, 0]]}])", "cracks[1].points", "intersect or touch"},
      {R"([OK, {"name": "b", "points": [[0, 0], [3, 0], [3, 1], [4, 1], [4, -1], [5, 0], [2, 0]]}])",
       "cracks[1].points", "segment 0"},
      // Adjacent segments folding back onto each other.
      {R"([OK, {"name": "b", "points": [[0, 0], [2, 0], [1, 0]]}])", "cracks[1].points",
       "segment 1 (points[1] to points[2]) folds back onto segment 0"},
      {R"([OK, {"name": "b", "points": [[0, 0], [1, 1], [3, 3], [2, 2]]}])", "cracks[1].points", "folds back"},
      // Straight form.
      {R"([OK, {"name": "b", "from": [0, 0], "to": [1, 0]}])", "cracks[1].segment_length", "missing"},
      {R"([OK, {"name": "b", "to": [1, 0], "segment_length": 0.1}])", "cracks[1].from", "missing"},
      {R"([OK, {"name": "b", "from": [0, 0], "segment_length": 0.1}])", "cracks[1].to", "missing"},
      {R"([OK, {"name": "b", "from": [0, 0], "to": [1, 0], "segment_length": -1}])", "cracks[1].segment_length", "positive"},
      {R"([OK, {"name": "b", "from": [0, 0], "to": [1, 0], "segment_length": 1e-12}])", "cracks[1].segment_length", "too small"},
      {R"([OK, {"name": "b", "from": [0, 0], "to": [0, 0], "segment_length": 0.1}])", "cracks[1].to", "zero-length"},
      {R"([OK, {"name": "b", "from": [0, "a"], "to": [1, 0], "segment_length": 0.1}])", "cracks[1].from[1]", "expected a number"},
      {R"([OK, {"name": "b", "points": [[0, 0], [1, 0]], "from": [0, 0]}])", "cracks[1].from", "not both"},
      // Contact.
      {R"([OK, {"name": "b", "points": [[0, 0], [1, 0]], "contact": {"law": "glue"}}])", "cracks[1].contact.law",
       "unknown contact law \"glue\"; valid laws: stick, frictionless, friction, none"},
      {R"([OK, {"name": "b", "points": [[0, 0], [1, 0]], "contact": {}}])", "cracks[1].contact.law", "missing"},
      {R"([OK, {"name": "b", "points": [[0, 0], [1, 0]], "contact": "stick"}])", "cracks[1].contact", "expected an object"},
      {R"([OK, {"name": "b", "points": [[0, 0], [1, 0]], "contact": {"law": "friction"}}])", "cracks[1].contact.mu", "missing"},
      {R"([OK, {"name": "b", "points": [[0, 0], [1, 0]], "contact": {"law": "friction", "mu": -0.1}}])", "cracks[1].contact.mu", ">= 0"},
      {R"([OK, {"name": "b", "points": [[0, 0], [1, 0]], "contact": {"law": "friction", "mu": "x"}}])", "cracks[1].contact.mu", "expected a number"},
      {R"([OK, {"name": "b", "points": [[0, 0], [1, 0]], "contact": {"law": "stick", "mu": 0.2}}])", "cracks[1].contact.mu", "only valid with law \"friction\""},
      // Unknown keys and duplicates.
      {R"([OK, {"name": "b", "points": [[0, 0], [1, 0]], "tip": 1}])", "cracks[1].tip", "unknown key"},
      {R"([OK, {"name": "b", "points": [[0, 0], [1, 0]], "contact": {"law": "stick", "k": 1}}])", "cracks[1].contact.k", "unknown key"},
      {R"([OK, {"name": "ok", "points": [[5, 5], [6, 5]]}])", "cracks[1].name", "duplicate crack name \"ok\" (also cracks[0])"},
  };
  for (const ErrorCase& c : cases) {
    std::string text = c.scene;
    if (const auto at = text.find("OK"); at != std::string::npos) text.replace(at, 2, ok);
    SCOPED_TRACE(text);
    try {
      parse(json::parse(text));
      ADD_FAILURE() << "no SceneError";
    } catch (const SceneError& e) {
      EXPECT_EQ(e.key_path(), c.path) << e.what();
      EXPECT_NE(e.reason().find(c.reason), std::string::npos) << e.what();
    }
  }
}

}  // namespace

namespace {
// A crack along y = 0 from x = 0 to 3 in segments of 1, with both ends cut back by `cut`.
Crack2D cut_crack(double cut, bool start, bool end) {
  Crack2D c;
  c.points = {v(0, 0), v(1, 0), v(2, 0), v(3, 0)};
  c.tip_cut = cut;
  c.cut_end = {static_cast<uint8_t>(start), static_cast<uint8_t>(end)};
  c.update_extent();
  return c;
}
}  // namespace

// ExplicitCrack::update_crossing: the crossing test's polyline is the crack less tip_cut at each cut
// end, walking over whole segments; the crack's own points are untouched.
TEST(TipCut, TheCrossingPolylineIsTheCrackCutBackAtItsCutEnds) {
  const Crack2D c = cut_crack(1.25, true, false);
  EXPECT_EQ(c.points[0], v(0, 0));
  EXPECT_EQ(c.cross_first, 1);
  EXPECT_EQ(c.cross_last, 3);
  EXPECT_DOUBLE_EQ(c.cross_points[1].x(), 1.25);
  // A node at x = 1 (on the crack, behind the cut) is no longer split; one at x = 2 still is.
  EXPECT_EQ(crack_crossing(c, v(1, 0.5), v(1, 0)), Side::None);
  EXPECT_EQ(crack_crossing(c, v(2, 0.5), v(2, 0)), Side::Above);
  // Uncut, the same node is split (seed 002's rule).
  EXPECT_EQ(crack_crossing(cut_crack(0.0, true, true), v(1, 0.5), v(1, 0)), Side::Above);
  // Both ends: 0.5 off each, inside the end segments.
  const Crack2D b = cut_crack(0.5, true, true);
  EXPECT_EQ(b.cross_first, 0);
  EXPECT_EQ(b.cross_last, 3);
  EXPECT_DOUBLE_EQ(b.cross_points[0].x(), 0.5);
  EXPECT_DOUBLE_EQ(b.cross_points[3].x(), 2.5);
  EXPECT_EQ(crack_crossing(b, v(0.3, 0.5), v(0.3, -0.5)), Side::None);
  EXPECT_EQ(crack_crossing(b, v(0.7, 0.5), v(0.7, -0.5)), Side::Above);
  EXPECT_EQ(crack_crossing(b, v(2.7, -0.5), v(2.7, 0.5)), Side::None);
  // A crack shorter than its two cuts crosses nothing.
  const Crack2D gone = cut_crack(1.6, true, true);
  EXPECT_LE(gone.cross_last, gone.cross_first);
  EXPECT_EQ(crack_crossing(gone, v(1.5, 0.5), v(1.5, -0.5)), Side::None);
}

// ExplicitCrack::node_split (cracks[i].tip_split): a crack a tenth of a cell above the node line y = 0,
// its end x = 3 cut back by 0.45 to x = 2.55. Line by line, a node is split by the lines that meet
// the crack short of x = 2.55; node by node, a node past x = 2.55 stays whole and one behind it is
// split by the whole crack, also for a particle whose line meets it between 2.55 and the tip.
TEST(TipCut, NodeByNodeANodePastTheCutStaysWholeAndOneBehindItIsSplitByTheWholeCrack) {
  Crack2D c;
  c.points = {v(0, 0.1), v(1, 0.1), v(2, 0.1), v(3, 0.1)};
  c.tip_cut = 0.45;
  c.cut_end = {0, 1};
  c.update_extent();
  // Node (3, 0), past the cut; the line from (1.5, 0.25) meets the crack at x = 2.4.
  EXPECT_EQ(crack_crossing(c, v(1.5, 0.25), v(3, 0)), Side::Above);
  // Node (2, 0), behind the cut; the line from (3.4, 0.25) meets the crack at x = 2.56.
  EXPECT_EQ(crack_crossing(c, v(3.4, 0.25), v(2, 0)), Side::None);
  c.node_split = true;
  EXPECT_EQ(crack_crossing(c, v(1.5, 0.25), v(3, 0)), Side::None);
  EXPECT_EQ(crack_crossing(c, v(3.4, 0.25), v(2, 0)), Side::Above);
  // Far from the tip the two agree.
  EXPECT_EQ(crack_crossing(c, v(1.2, 0.25), v(1, 0)), Side::Above);
  EXPECT_EQ(crack_crossing(c, v(1.2, -0.25), v(1, 0)), Side::None);
  // With cut_reach (the scene reader's tip_cut + 2.5 cells) a split node's lines are tested on the
  // crack carried on past its tip (split_points): the particle (3.6, 0.2) ahead of the tip, above
  // the crack's line, whose line to the split node (2.5, 0) meets that line at x = 3.05, beyond the
  // tip, is sorted above; its twin below the line stays on the node's side.
  c.cut_reach = 2.95;
  c.update_extent();
  EXPECT_EQ(crack_crossing(c, v(3.6, 0.2), v(2.5, 0)), Side::Above);
  EXPECT_EQ(crack_crossing(c, v(3.6, 0.0), v(2.5, 0)), Side::None);
  EXPECT_EQ(crack_crossing(c, v(1.5, 0.25), v(3, 0)), Side::None);  // (3, 0) is still past the cut
  c.node_split = false;
  EXPECT_EQ(crack_crossing(c, v(3.6, 0.2), v(2.5, 0)), Side::None);
}

TEST(TipCut, TipSplitIsNodeForAGrowingCrackAndLineOtherwiseAndAnUnknownValueIsRefused) {
  const json line = json::parse(R"([{"name": "c", "points": [[0, 0], [1, 0]]}])");
  EXPECT_FALSE(parse_cracks(line, "cracks", 1.0)[0].node_split);
  const json growing = json::parse(R"([{"name": "c", "points": [[0, 0], [1, 0]], "propagation": {}}])");
  EXPECT_TRUE(parse_cracks(growing, "cracks", 1.0)[0].node_split);
  const json asked = json::parse(R"([{"name": "c", "points": [[0, 0], [1, 0]], "tip_split": "node"}])");
  EXPECT_TRUE(parse_cracks(asked, "cracks", 1.0)[0].node_split);
  const json bad = json::parse(R"([{"name": "c", "points": [[0, 0], [1, 0]], "tip_split": "nodes"}])");
  try {
    parse_cracks(bad, "cracks", 1.0);
    FAIL() << "expected a SceneError";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("cracks[0].tip_split"), std::string::npos) << e.what();
  }
}

TEST(TipCut, OutOfRangeIsRefusedNamingTheKey) {
  const json cracks = json::parse(R"([{"name": "c", "points": [[0, 0], [1, 0]], "tip_cut": 1.5}])");
  try {
    parse_cracks(cracks, "cracks", 1.0);
    FAIL() << "expected a SceneError";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("cracks[0].tip_cut"), std::string::npos) << e.what();
  }
}

// Volume detection's crack weight (mpm/crack_fields/line_weight.hpp): the integral of a node's
// bilinear hat along a segment, against closed forms and a fine midpoint rule.
TEST(CrackLineWeight, TheHatIntegralAlongASegmentMatchesItsClosedFormsAndAFineQuadrature) {
  using cleave::crack_fields::hat_integral_along;
  const double h = 2e-3;
  const Vec<2> node(0.01, -0.004);
  const auto at = [&](double x, double y) { return Vec<2>(node.x() + x * h, node.y() + y * h); };
  // Along the node row through the node, past the support: h; parallel at a distance d: h (1 - d/h).
  EXPECT_NEAR(hat_integral_along(at(-3, 0), at(2.5, 0), node, h), h, 1e-15);
  for (double d : {0.1, 0.25, 0.5, 0.9})
    EXPECT_NEAR(hat_integral_along(at(-1.7, d), at(1.2, d), node, h), h * (1 - d), 1e-15) << d;
  // The diagonal through the node: (1 - s / (sqrt 2 h))^2 over |s| < sqrt 2 h, 2 sqrt 2 h / 3.
  EXPECT_NEAR(hat_integral_along(at(-1.5, -1.5), at(2, 2), node, h), 2 * std::sqrt(2.0) * h / 3, 1e-15);
  // Outside the support, and a segment of no length: nothing.
  EXPECT_EQ(hat_integral_along(at(1.0, -2), at(1.0, 2), node, h), 0.0);
  EXPECT_EQ(hat_integral_along(at(0.2, 0.3), at(0.2, 0.3), node, h), 0.0);
  // Any segment: a fine midpoint rule, and the sum of its two halves.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.6, 1.6);
  for (int k = 0; k < 20; ++k) {
    const Vec<2> a = at(u(rng), u(rng)), b = at(u(rng), u(rng));
    const int n = 20000;
    double sum = 0;
    for (int i = 0; i < n; ++i) {
      const Vec<2> x = a + (i + 0.5) / n * (b - a);
      sum += std::max(0.0, 1 - std::fabs(x.x() - node.x()) / h) * std::max(0.0, 1 - std::fabs(x.y() - node.y()) / h);
    }
    sum *= (b - a).norm() / n;
    const double exact = hat_integral_along(a, b, node, h);
    EXPECT_NEAR(exact, sum, 1e-7 * h) << k;
    EXPECT_NEAR(exact, hat_integral_along(a, 0.5 * (a + b), node, h) + hat_integral_along(0.5 * (a + b), b, node, h),
                1e-15)
        << k;
  }
}
