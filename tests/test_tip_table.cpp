// crack_tips.csv has one schema for every method (method/tip_table.hpp).
#include <gtest/gtest.h>

#include <cmath>

#include "libmpm/method/tip_table.hpp"
#include "libmpm/core/error.hpp"
#include "libmpm/mpm/mpm_scene.hpp"
#include "libmpm/scene/scene.hpp"

using namespace cleave;

// Column names end in their SI unit (docs/scenes.md, "Output files"); indices have none.
TEST(TipTable, LeadingColumnsAreTheSameForEveryMethodThenTheMethodsQuantities) {
  const TipTable<2> mpm(1, 2, {"J1_J_per_m2", "J2_J_per_m2", "KI_Pa_sqrt_m", "KII_Pa_sqrt_m"});
  const TipTable<3> pd3(1, 1, {});
  EXPECT_EQ(mpm.columns(), (std::vector<std::string>{"time_s", "crack", "tip", "x_m", "y_m", "speed_m_per_s",
                                                     "J1_J_per_m2", "J2_J_per_m2", "KI_Pa_sqrt_m", "KII_Pa_sqrt_m"}));
  EXPECT_EQ(pd3.columns(), (std::vector<std::string>{"time_s", "crack", "tip", "x_m", "y_m", "z_m", "speed_m_per_s"}));
}

TEST(TipTable, SpeedIsTheDistanceFromTheSameTipsPreviousRowOverTheTimeBetween) {
  TipTable<2> t(2, 2, {"J1"});
  const auto r0 = t.row(0.0, 1, 1, Vec<2>(0, 0), {5.0});
  EXPECT_EQ(r0, (std::vector<double>{0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 5.0}));  // first row of the tip: speed 0
  t.row(0.5, 0, 0, Vec<2>(9, 9), {0.0});                                    // another tip: its own history
  const auto r1 = t.row(2.0, 1, 1, Vec<2>(3, 4), {6.0});
  EXPECT_DOUBLE_EQ(r1[5], 2.5);  // 5 m in 2 s
}

// The cadence of crack_tips.csv is output.tip_interval in every method; MPM's crack_tips.interval is
// its older spelling, not to be given beside it; without a crack-tip table the key is an error.
TEST(TipTable, OutputTipIntervalIsTheCadenceAndExcludesCrackTipsInterval) {
  auto s = load_scene_file(CLEAVE_SOURCE_DIR "/data/scenes/dcb_crack.json");
  s["crack_tips"] = nlohmann::json::object();
  EXPECT_DOUBLE_EQ(build_model<2>(s).output.tip_interval, 0.005);  // default: output.global_interval
  s["output"]["tip_interval"] = 0.02;  // s (the scene's time unit)
  EXPECT_DOUBLE_EQ(build_model<2>(s).output.tip_interval, 0.02);
  auto error_key = [](const nlohmann::json& scene) {
    try {
      build_model<2>(scene);
    } catch (const SceneError& e) {
      return e.key_path();
    }
    return std::string("no error");
  };
  s["crack_tips"]["interval"] = 0.02;
  EXPECT_EQ(error_key(s), "crack_tips.interval");
  s.erase("crack_tips");
  EXPECT_EQ(error_key(s), "output.tip_interval");
}
