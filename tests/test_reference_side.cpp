// A particle a hair from a 2D crack's line is sorted by its side in the reference configuration
// (libmpm/crack/reference_side.hpp).
#include <gtest/gtest.h>

#include "libmpm/crack/crack2d.hpp"
#include "libmpm/crack/reference_side.hpp"

namespace cleave::crack {
namespace {

// A crack along y = 0 from x = -2 to x = 2 (left to right: above is +y), its reference line the same
// moved up by `up`, as if the current line had drifted down against the material by that much.
Crack2D straight_crack(double up) {
  Crack2D c;
  c.points = {Vec<2>(-2, 0), Vec<2>(0, 0), Vec<2>(2, 0)};
  c.reference = {Vec<2>(-2, up), Vec<2>(0, up), Vec<2>(2, up)};
  set_polyline_segments(c);
  c.update_extent();
  return c;
}

const double kHair = 1e-3;

TEST(ReferenceSide, AParticleAHairAboveTheLineThatStoodBelowItIsTakenAtTheSameDistanceBelow) {
  const Crack2D c = straight_crack(2e-4);  // the particle stands 1e-4 below the reference line
  const Vec<2> x(0.5, 1e-4), X(0.5, 1e-4);
  double dist = 0;
  Vec<2> out;
  bool moved = false;
  ASSERT_TRUE(reference_side(c, 0, 1, x, X, kHair, dist, out, moved));
  EXPECT_TRUE(moved);
  EXPECT_NEAR(dist, 1e-4, 1e-15);
  EXPECT_NEAR(out.x(), 0.5, 1e-15);
  EXPECT_NEAR(out.y(), -1e-4, 1e-15);
  EXPECT_EQ(sorting_position(std::vector<Crack2D>{c}, x, X, kHair), out);
}

TEST(ReferenceSide, AParticleOnTheSameSideOfBothLinesOrBeyondTheHairKeepsItsPlace) {
  const Crack2D c = straight_crack(2e-4);
  double dist = 0;
  Vec<2> out(9, 9);
  bool moved = true;
  // above both lines
  EXPECT_TRUE(reference_side(c, 0, 1, Vec<2>(0.5, 5e-4), Vec<2>(0.5, 5e-4), kHair, dist, out, moved));
  EXPECT_FALSE(moved);
  // beyond the hair of the current line, whatever its reference side
  EXPECT_FALSE(reference_side(c, 0, 1, Vec<2>(0.5, 2e-3), Vec<2>(0.5, -1.0), kHair, dist, out, moved));
  EXPECT_FALSE(moved);
  // beside no segment (past the crack's end)
  EXPECT_FALSE(reference_side(c, 0, 1, Vec<2>(2.5, 1e-4), Vec<2>(2.5, -1.0), kHair, dist, out, moved));
  const Vec<2> x(0.5, 5e-4);
  EXPECT_EQ(sorting_position(std::vector<Crack2D>{c}, x, x, kHair), x);
}

TEST(ReferenceSide, AParticleOnTheLineGoesToItsReferenceSide) {
  const Crack2D c = straight_crack(0.0);
  double dist = 0;
  Vec<2> out;
  bool moved = false;
  ASSERT_TRUE(reference_side(c, 0, 1, Vec<2>(-1, 0), Vec<2>(-1, 3e-4), kHair, dist, out, moved));
  EXPECT_TRUE(moved);
  EXPECT_GT(out.y(), 0.0);  // above, where it stood
  EXPECT_LT(out.y(), kHair);
}

TEST(ReferenceSide, AParticleOnTheReferenceLineToRoundOffIsSortedByTheCurrentLine) {
  const Crack2D c = straight_crack(0.0);
  double dist = 0;
  Vec<2> out;
  bool moved = true;
  EXPECT_TRUE(reference_side(c, 0, 1, Vec<2>(-1, -1e-4), Vec<2>(-1, 1e-18), kHair, dist, out, moved));
  EXPECT_FALSE(moved);
}

TEST(ReferenceSide, ACrackWithoutReferencePointsSortsByItsCurrentLine) {
  Crack2D c = straight_crack(2e-4);
  c.reference.clear();
  const Vec<2> x(0.5, 1e-4);
  EXPECT_EQ(sorting_position(std::vector<Crack2D>{c}, x, Vec<2>(0.5, -1.0), kHair), x);
}

// What the sorting changes in the line crossing (seed 002 Appendix A): the line from a particle a hair
// above the current line to a node below it crosses the crack, and selects the above field, for the
// particle as it stands; taken on its reference side, below, the same line crosses nothing.
TEST(ReferenceSide, TheLineToANodeAcrossTheCrackCrossesNothingForAParticleThatStoodOnTheNodesSide) {
  const Crack2D c = straight_crack(2e-4);
  const std::vector<Crack2D> cracks{c};
  const Vec<2> x(0.5, 1e-4), X(0.5, 1e-4), node(0.0, -1.0);
  EXPECT_NE(field_key(cracks, x, node), 0u);
  EXPECT_EQ(field_key(cracks, sorting_position(cracks, x, X, kHair), node), 0u);
  // and a node above it is now across the crack
  EXPECT_EQ(field_key(cracks, x, Vec<2>(0.0, 1.0)), 0u);
  EXPECT_NE(field_key(cracks, sorting_position(cracks, x, X, kHair), Vec<2>(0.0, 1.0)), 0u);
}

}  // namespace
}  // namespace cleave::crack
