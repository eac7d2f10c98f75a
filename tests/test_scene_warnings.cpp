// Doubts that are not errors reach the user as warnings: a strong particle-mass contrast between
// bodies with linear shape functions (the beam impact is unstable at CFL 0.5 that way).
#include <gtest/gtest.h>

#include "libmpm/mpm/mpm_scene.hpp"

namespace cleave {
namespace {

TEST(SceneWarnings, MassContrastWithLinearShapeFunctions) {
  nlohmann::json s = load_scene_file(CLEAVE_SOURCE_DIR "/data/scenes/beam_impact.json");
  s["resolution"] = 1.0;
  s["mpm"]["shape_function"] = "linear";
  const Model<2> lin = build_model<2>(s);
  ASSERT_EQ(lin.warnings.size(), 1u);
  EXPECT_NE(lin.warnings[0].find("240x"), std::string::npos) << lin.warnings[0];
  s["mpm"]["shape_function"] = "ugimp";
  EXPECT_TRUE(build_model<2>(s).warnings.empty());
}

}  // namespace
}  // namespace cleave
