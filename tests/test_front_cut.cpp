// The 3D fronts cut back for the crossing test (libmpm/crack/front_cut.hpp): a crossing within
// tip_cut of a front does not count, one beyond it does; edges that are no front are not cut.
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "libmpm/crack/crossing3d.hpp"
#include "libmpm/crack/front_cut.hpp"
#include "libmpm/crack/fronts.hpp"
#include "support.hpp"

namespace {

using cleave::Vec;
using cleave::crack::Side;
using V3 = Vec<3>;

// The square [0, 4] x [0, 4] in z = 0, 4 x 4 unit squares each in two triangles (normals +z), with
// one front: the edge x = 4 (the others taken as outside the material).
struct Square {
  cleave::crack::Surface<3> s;
  std::vector<cleave::crack::CrackFront> fronts;
  cleave::crack::FrontCut cut;
  explicit Square(double tip_cut) {
    auto id = [](int i, int j) { return static_cast<int32_t>(i * 5 + j); };
    for (int i = 0; i <= 4; ++i)
      for (int j = 0; j <= 4; ++j) s.points.emplace_back(i, j, 0.0);
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        s.simplices.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        s.simplices.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    fronts = cleave::crack::crack_fronts(s, [](const V3& x) { return x.x() > 3.9; });
    cut = cleave::crack::make_front_cut(s, fronts, tip_cut, 0.5);
  }
  Side cross(const V3& p, const V3& n) const {
    struct All {
      std::size_t operator[](std::size_t k) const { return k; }
    };
    return cleave::crack::triangle_list_crossing(s.points.data(), s.simplices.data(), All{}, s.simplices.size(), p, n,
                                                 nullptr, cut.dropper(s.points.data(), s.simplices.data()));
  }
};

TEST(FrontCut, TheSquaresOneFrontIsItsEdgeInsideTheMaterial) {
  const Square sq(0.45);
  ASSERT_EQ(sq.fronts.size(), 1u);
  for (const int32_t p : sq.fronts[0].nodes) EXPECT_EQ(sq.s.points[p].x(), 4.0);
  EXPECT_TRUE(sq.cut.active());
}

TEST(FrontCut, ALineCrossingWithinTheCutOfAFrontDoesNotCountAndOneBeyondItDoes) {
  const Square sq(0.45);
  // Lines parallel to z through the crack at x = 3.7 (0.3 from the front) and x = 3.5 (0.5 from it).
  EXPECT_EQ(sq.cross(V3(3.7, 2.2, 0.3), V3(3.7, 2.2, -0.7)), Side::None);
  EXPECT_EQ(sq.cross(V3(3.5, 2.2, 0.3), V3(3.5, 2.2, -0.7)), Side::Above);
  EXPECT_EQ(sq.cross(V3(3.5, 2.2, -0.3), V3(3.5, 2.2, 0.7)), Side::Below);
  // A slanted line is judged where it meets the crack (x = 3.6), not at its ends.
  EXPECT_EQ(sq.cross(V3(3.2, 2.2, 0.4), V3(3.8, 2.2, -0.2)), Side::None);
  EXPECT_EQ(sq.cross(V3(3.0, 2.2, 0.5), V3(3.8, 2.2, -0.3)), Side::Above);  // meets at x = 3.5
}

TEST(FrontCut, ANodeOnTheCrackWithinTheCutSeparatesNothingAndOneBeyondItDoes) {
  const Square sq(0.45);
  EXPECT_EQ(sq.cross(V3(3.7, 2.5, 0.5), V3(4.0, 2.0, 0.0)), Side::None);  // the node on the front
  EXPECT_EQ(sq.cross(V3(3.2, 2.5, 0.5), V3(3.0, 2.0, 0.0)), Side::Above);  // a node a cell behind it
}

TEST(FrontCut, EdgesOutsideTheMaterialAreNotCut) {
  const Square sq(0.45);
  // Near the edge x = 0 (a mouth) and y = 0 the crack still separates.
  EXPECT_EQ(sq.cross(V3(0.2, 2.2, 0.3), V3(0.2, 2.2, -0.7)), Side::Above);
  EXPECT_EQ(sq.cross(V3(2.2, 0.1, 0.3), V3(2.2, 0.1, -0.7)), Side::Above);
}

TEST(FrontCut, ZeroCutsNothing) {
  const Square sq(0.0);
  EXPECT_FALSE(sq.cut.active());
  EXPECT_EQ(sq.cross(V3(3.9, 2.2, 0.3), V3(3.9, 2.2, -0.7)), Side::Above);
}

TEST(FrontCutScene, AThreeDCrackTakesTipCutInCellsAndRefusesOneOutsideZeroToOneNamingTheKey) {
  using cleave::test::error_of;
  nlohmann::json s = cleave::test::penny_block_scene(3);
  s["cracks"][0]["tip_cut"] = 0.3;
  const auto m = cleave::build_model<3>(s);
  EXPECT_DOUBLE_EQ(m.cracks[0].front_cut.cut, 0.3e-3);  // 0.3 of a 1 mm cell
  s["cracks"][0]["tip_cut"] = 1.5;
  const auto e = error_of([&] { cleave::build_model<3>(s); });
  EXPECT_EQ(e.key_path(), "cracks[0].tip_cut");
}

}  // namespace
