// What a user reads when a scene or a run goes wrong (issue 14, item 7): the time.dt error gives
// both step sizes with their significant digits, and a step that trips several run checks at once
// names every one of them, the energy's first.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>

#include "files.hpp"
#include "libmpm/core/error.hpp"
#include "libmpm/method/run_scene.hpp"
#include "support.hpp"

namespace cleave {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

fs::path test_dir(const std::string& tag) {
  return test::fresh_dir(fs::path(CLEAVE_BINARY_DIR) / "test_run_messages" / tag);
}

// A 6 x 3 mm steel block in 0.6 mm cells: the stable step h / c is about 1.02e-7 s.
json small_cell_block() {
  return json::parse(R"({
    "analysis": {"type": "plane_strain"},
    "grid": {"cell_size": 0.0006},
    "materials": [{"name": "steel", "type": "linear_elastic", "E": 2e11, "nu": 0.3, "density": 7800}],
    "bodies": [{"name": "block", "material": "steel",
                "shape": {"type": "rectangle", "min": [0, 0], "max": [0.006, 0.003]}}],
    "time": {"end": 1e-5, "dt": 2e-7}
  })");
}

// The SceneError of building `scene`; fails the test when there is none.
SceneError scene_error(const json& scene) {
  try {
    (void)build_model<2>(scene);
  } catch (const SceneError& e) {
    return e;
  }
  ADD_FAILURE() << "no SceneError for " << scene.dump();
  return SceneError("", "");
}

// Checks "dt = A s > LIMIT-FORMULA = B s" in `reason`: A and B equal `dt` and `limit` to the six
// significant digits printed.
void expect_dt_numbers(const std::string& reason, double dt, double limit) {
  EXPECT_EQ(reason.find("0.000000"), std::string::npos) << reason;
  std::smatch m;
  const std::regex form(R"(dt = ([-+0-9.eE]+) s > .* = ([-+0-9.eE]+) s;)");
  ASSERT_TRUE(std::regex_search(reason, m, form)) << reason;
  const double a = std::stod(m[1].str()), b = std::stod(m[2].str());
  EXPECT_NEAR(a, dt, 5e-6 * dt) << "dt as printed: " << m[1] << " in: " << reason;
  EXPECT_NEAR(b, limit, 5e-6 * limit) << "limit as printed: " << m[2] << " in: " << reason;
  EXPECT_NE(m[1].str(), m[2].str()) << reason;
}

TEST(RunMessages, DtJustAboveASmallStableLimitPrintsBothStepsWithTheirSignificantDigits) {
  const json s = small_cell_block();
  // The limit as the MPM reader computes it: cell / (P-wave speed + particle speed), at rest.
  const double E = 2e11, nu = 0.3, rho = 7800;
  const double c = std::sqrt(E * (1 - nu) / ((1 + nu) * (1 - 2 * nu)) / rho);
  const double limit = 0.0006 / c;
  ASSERT_GT(2e-7, limit);
  ASSERT_LT(2e-7, 2.5 * limit) << "the test wants a dt a little above the limit";
  const SceneError e = scene_error(s);
  EXPECT_EQ(e.key_path(), "time.dt");
  expect_dt_numbers(e.reason(), 2e-7, limit);
  EXPECT_NE(e.reason().find("dt = 2e-07 s"), std::string::npos) << e.reason();
}

TEST(RunMessages, DtErrorInSceneUnitsPrintsBothStepsInSecondsWithTheirSignificantDigits) {
  // The same block in mm and ms: dt = 2e-4 ms is 2e-7 s, and the message speaks SI.
  json s = small_cell_block();
  s["units"] = {{"length", "mm"}, {"time", "ms"}, {"stress", "Pa"}, {"density", "kg/m3"}};
  s["grid"]["cell_size"] = 0.6;
  s["bodies"][0]["shape"] = {{"type", "rectangle"}, {"min", {0, 0}}, {"max", {6, 3}}};
  s["time"] = {{"end", 0.01}, {"dt", 2e-4}};
  const double c = std::sqrt(2e11 * 0.7 / (1.3 * 0.4) / 7800);
  const SceneError e = scene_error(s);
  EXPECT_EQ(e.key_path(), "time.dt");
  expect_dt_numbers(e.reason(), 2e-7, 0.0006 / c);
}

// The seed-002 beam impact, coarse, with linear shape functions at CFL 1 under USL: it blows up at
// first contact, and the blow-up throws beam particles out of the grid. global.csv (and so the
// energy check) is due only at the end: the step that loses the first particle is the first check.
json blowing_up_beam_impact() {
  return json::parse(R"({
    "units": {"length": "mm", "stress": "MPa", "density": "g/cm3", "velocity": "m/s", "time": "ms"},
    "analysis": {"type": "plane_stress", "thickness": 12.95},
    "grid": {"cell_size": 1.0, "min": [-50, -10], "max": [50, 25]},
    "mpm": {"shape_function": "linear", "stress_update": "USL"},
    "materials": [
      {"name": "delrin", "type": "linear_elastic", "E": 2900, "nu": 0.33, "density": 1.5},
      {"name": "impactor", "type": "linear_elastic", "E": 29000, "nu": 0.33, "density": 7.8}
    ],
    "bodies": [
      {"name": "beam", "material": "delrin", "shape": {"type": "rectangle", "min": [-44, 0], "max": [44, 6]},
       "particles_per_cell": 2},
      {"name": "impactor", "material": "impactor", "shape": {"type": "disk", "center": [0, 12], "radius": 5},
       "particles_per_cell": 2, "thickness": 599.1, "velocity": [0, -2.43]}
    ],
    "loads": [
      {"type": "velocity", "region": {"min": [-35, 0], "max": [-33, 0]}, "velocity": [null, 0]},
      {"type": "velocity", "region": {"min": [33, 0], "max": [35, 0]}, "velocity": [null, 0]}
    ],
    "time": {"end": 3.0, "cfl": 1.0},
    "output": {"interval": 0.1, "global_interval": 3.0}
  })");
}

std::string run_message(const fs::path& out) {
  std::ifstream in(out / "run.json");
  const json status = json::parse(in);
  EXPECT_EQ(status["status"], "aborted");
  return status.value("message", std::string());
}

TEST(RunMessages, EnergyBlowUpAndAParticleLeavingTheGridInOneStepAreBothReportedEnergyFirst) {
  const fs::path out = test_dir("blowup");
  RunOptions opt;
  opt.out = out;
  std::string thrown;
  try {
    (void)run_scene(blowing_up_beam_impact(), {}, opt);
    FAIL() << "the run should stop";
  } catch (const RunAborted& e) {
    thrown = e.what();
  }
  EXPECT_EQ(run_message(out), thrown);
  // "step N, time T s: energy blow-up, ...; fastest particle P at (x, y) m, speed v m/s; also
  //  particle Q at (x, y) m left the grid"
  const std::regex form(
      R"(^step \d+, time [0-9.e+-]+ s: energy blow-up, total energy [0-9.e+-]+ J exceeds 10 x the reference )"
      R"([0-9.e+-]+ J; fastest particle \d+ at \([0-9.e+-]+, [0-9.e+-]+\) m, speed [0-9.e+-]+ m/s; )"
      R"(also particle \d+ at \([0-9.e+-]+, [0-9.e+-]+\) m left the grid$)");
  EXPECT_TRUE(std::regex_search(thrown, form)) << thrown;
  const std::size_t energy = thrown.find("energy blow-up"), grid = thrown.find("left the grid");
  ASSERT_NE(energy, std::string::npos) << thrown;
  ASSERT_NE(grid, std::string::npos) << thrown;
  EXPECT_LT(energy, grid) << "the energy check comes first: " << thrown;
}

TEST(RunMessages, ANonFiniteVelocityAndAParticleLeavingTheGridInOneStepAreAllReported) {
  // Two blocks far apart: one particle of the first (particle 0) gets a NaN velocity, the whole
  // second block a speed that carries it out of the grid in one step.
  json s = json::parse(R"({
    "analysis": {"type": "plane_strain"},
    "grid": {"cell_size": 0.01, "min": [-0.05, -0.05], "max": [0.45, 0.1]},
    "materials": [{"name": "steel", "type": "linear_elastic", "E": 2e11, "nu": 0.3, "density": 7800}],
    "bodies": [{"name": "a", "material": "steel", "shape": {"type": "rectangle", "min": [0, 0], "max": [0.05, 0.05]}},
               {"name": "b", "material": "steel", "shape": {"type": "rectangle", "min": [0.3, 0], "max": [0.35, 0.05]}}],
    "time": {"end": 1e-4},
    "output": {"interval": 1e-4}
  })");
  Model<2> m = build_model<2>(s);
  auto& P = m.particles;
  long first_b = -1;
  for (std::size_t p = 0; p < P.size(); ++p)
    if (P.x[p].x() > 0.2) {
      if (first_b < 0) first_b = static_cast<long>(p);
      P.v[p] = Vec<2>(0.0, 10.0 * 0.15 / m.dt);  // 10 grid heights in one step
    }
  ASSERT_GT(first_b, 0);
  P.v[0] = Vec<2>(std::numeric_limits<double>::quiet_NaN(), 0.0);
  const fs::path out = test_dir("nan");
  RunOptions opt;
  opt.out = out;
  std::string thrown;
  try {
    (void)run_model<2>(m, opt);
    FAIL() << "the run should stop";
  } catch (const RunAborted& e) {
    thrown = e.what();
  }
  EXPECT_EQ(run_message(out), thrown);
  // The energy is NaN too; then particle 0's velocity, then block b's first particle.
  const std::regex form(R"(^step 1, time [0-9.e+-]+ s: energy is not finite; also particle 0 at \(.*\) m velocity is )"
                        R"(not finite \(NaN/Inf\); also particle (\d+) at \(.*\) m left the grid$)");
  std::smatch match;
  ASSERT_TRUE(std::regex_search(thrown, match, form)) << thrown;
  EXPECT_EQ(std::stol(match[1].str()), first_b) << thrown;
}

}  // namespace
}  // namespace cleave
