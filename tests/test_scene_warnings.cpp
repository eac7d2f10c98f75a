// Doubts that are not errors reach the user as warnings: a strong particle-mass contrast between
// bodies with linear shape functions (the beam impact is unstable at CFL 0.5 that way), bodies
// that overlap, and crack contact detected by nodal volume in a damped run.
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

// Two bodies that overlap both fill the shared region, and their particles share grid nodes, so
// they stick together: a warning names both. Disks that only touch (five_disks.json) get none.
TEST(SceneWarnings, TwoBodiesThatOverlapAreNamedInAWarning) {
  nlohmann::json s = nlohmann::json::parse(R"({
    "analysis": {"type": "plane_strain"}, "resolution": 0.01,
    "materials": [{"name": "steel", "type": "linear_elastic", "E": 2e11, "nu": 0.3, "density": 7800}],
    "bodies": [{"name": "left", "material": "steel", "shape": {"type": "rectangle", "min": [0, 0], "max": [0.1, 0.05]}},
               {"name": "right", "material": "steel", "shape": {"type": "disk", "center": [0.1, 0.025], "radius": 0.02}}],
    "time": {"end": 1e-5}
  })");
  const Model<2> m = build_model<2>(s);
  ASSERT_EQ(m.warnings.size(), 1u);
  const std::string& w = m.warnings[0];
  for (const char* word : {"'left' (bodies[0])", "'right' (bodies[1])", "overlap", "stick together"})
    EXPECT_NE(w.find(word), std::string::npos) << word << " missing in: " << w;
  // Side by side, sharing the face x = 0.1: no warning.
  s["bodies"][1]["shape"] = {{"type", "rectangle"}, {"min", {0.1, 0}}, {"max", {0.2, 0.05}}};
  EXPECT_TRUE(build_model<2>(s).warnings.empty());
  EXPECT_TRUE(build_model<2>(load_scene_file(CLEAVE_SOURCE_DIR "/data/scenes/five_disks.json")).warnings.empty());
}

// Crack contact detected by nodal volume (seed 002, the default) in a damped or static run ratchets the
// faces open (the static DCB's J +25 %, docs/validation.md): a warning per crack names the key and the
// cure. Undamped runs (impact, where volume detection keeps its energy) get none.
TEST(SceneWarnings, VolumeDetectionOfACrackInADampedRunIsNamedInAWarning) {
  nlohmann::json s = load_scene_file(CLEAVE_SOURCE_DIR "/data/scenes/dcb_crack.json");
  EXPECT_TRUE(build_model<2>(s).warnings.empty());  // displacement detection, as shipped
  s["cracks"][0].erase("contact");                    // the default: frictionless, volume
  const Model<2> dcb = build_model<2>(s);
  ASSERT_EQ(dcb.warnings.size(), 1u);
  for (const char* word : {"cracks[0].contact.detection", "damped run", "crack 'midplane'", "\"displacement\""})
    EXPECT_NE(dcb.warnings[0].find(word), std::string::npos) << word << " missing in: " << dcb.warnings[0];
  s["cracks"][0]["contact"] = {{"law", "none"}};  // no contact: nothing to detect
  EXPECT_TRUE(build_model<2>(s).warnings.empty());
  EXPECT_TRUE(build_model<2>(load_scene_file(CLEAVE_SOURCE_DIR "/data/scenes/colliding_disks.json")).warnings.empty());
}

}  // namespace
}  // namespace cleave
