// Scene reader validation: every bad value must be rejected with a SceneError that names the exact
// key path and gives a reason a user can act on; and the good values must arrive in SI, with the
// derived grid and the traction faces built as docs/scenes.md describes.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>

#include "libmpm/core/error.hpp"
#include "libmpm/mpm/mpm_scene.hpp"

namespace {

using nlohmann::json;
using cleave::SceneError;

// A small valid plane-strain scene in SI: a 0.1 x 0.05 m steel block, 1 cm cells, derived grid.
json scene2d() {
  return json::parse(R"({
    "title": "block 2D",
    "analysis": {"type": "plane_strain"},
    "grid": {"cell_size": 0.01},
    "materials": [{"name": "steel", "type": "linear_elastic", "E": 2e11, "nu": 0.3, "density": 7800}],
    "bodies": [{"name": "block", "material": "steel",
                "shape": {"type": "rectangle", "min": [0, 0], "max": [0.1, 0.05]}}],
    "time": {"end": 1e-5}
  })");
}

// A small valid 3D scene: a 4 cm steel cube, 1 cm cells, derived grid.
json scene3d() {
  return json::parse(R"({
    "analysis": {"type": "3d"},
    "grid": {"cell_size": 0.01},
    "materials": [{"name": "steel", "type": "linear_elastic", "E": 2e11, "nu": 0.3, "density": 7800}],
    "bodies": [{"name": "cube", "material": "steel",
                "shape": {"type": "box", "min": [0, 0, 0], "max": [0.04, 0.04, 0.04]}}],
    "time": {"end": 1e-5}
  })");
}

// The explicit grid used by tests that need fixed grid lines: 20 x 15 cells from (-0.05, -0.05).
json explicit_grid2d() { return json::parse(R"({"cell_size": 0.01, "min": [-0.05, -0.05], "max": [0.15, 0.10]})"); }

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

// Builds the scene and checks that it fails with exactly `path` and a reason containing `word`
// (case-insensitive).
template <int Dim>
void expect_error(const json& scene, const std::string& path, const std::string& word) {
  try {
    (void)cleave::build_model<Dim>(scene);
    ADD_FAILURE() << "no error; expected a SceneError at '" << path << "'\nscene: " << scene.dump();
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key_path(), path) << "message: " << e.what();
    EXPECT_NE(lower(e.reason()).find(lower(word)), std::string::npos)
        << "reason '" << e.reason() << "' should mention '" << word << "'";
    EXPECT_FALSE(e.reason().empty());
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected a SceneError at '" << path << "', got another exception: " << e.what();
  }
}

#define EXPECT_SCENE_ERROR_2D(scene, path, word) \
  do {                                           \
    SCOPED_TRACE(path);                          \
    expect_error<2>(scene, path, word);          \
  } while (0)
#define EXPECT_SCENE_ERROR_3D(scene, path, word) \
  do {                                           \
    SCOPED_TRACE(path);                          \
    expect_error<3>(scene, path, word);          \
  } while (0)

// ------------------------------------------------------------------------------------------------
// The base scenes are valid (otherwise every error test below would prove nothing).

TEST(SceneBase, BaseScenesAreValid) {
  const auto m2 = cleave::build_model<2>(scene2d());
  EXPECT_EQ(m2.particles.size(), 20u * 10u);  // 10 x 5 cells, 2 x 2 particles per cell
  EXPECT_EQ(m2.title, "block 2D");
  const auto m3 = cleave::build_model<3>(scene3d());
  EXPECT_EQ(m3.particles.size(), 8u * 8u * 8u);
  EXPECT_EQ(cleave::scene_dimension(scene2d()), 2);
  EXPECT_EQ(cleave::scene_dimension(scene3d()), 3);
  auto s = scene2d();
  s["grid"] = explicit_grid2d();
  EXPECT_NO_THROW(cleave::build_model<2>(s));
}

// ------------------------------------------------------------------------------------------------
// Top level, units, analysis, method

TEST(SceneErrors, UnknownTopLevelKey) {
  auto s = scene2d();
  s["solver"] = json::object();
  EXPECT_SCENE_ERROR_2D(s, "solver", "unknown");
  auto s3 = scene3d();
  s3["materal"] = json::array();
  EXPECT_SCENE_ERROR_3D(s3, "materal", "unknown");
}

TEST(SceneErrors, MissingRequiredSections) {
  for (const char* key : {"materials", "bodies", "time", "analysis"}) {
    auto s = scene2d();
    s.erase(key);
    EXPECT_SCENE_ERROR_2D(s, key, "missing");
  }
  auto s = scene2d();  // the discretisation length: "resolution" or the method's own grid.cell_size
  s.erase("grid");
  EXPECT_SCENE_ERROR_2D(s, "resolution", "missing");
}

// "resolution" is the one discretisation key of every method: MPM's cell size, read in the scene's
// unit; the method's own spelling is accepted in its place but not beside it.
TEST(SceneErrors, ResolutionIsTheCellSizeAndExcludesGridCellSize) {
  auto s = scene2d();
  const double h = s["grid"]["cell_size"];
  s["grid"].erase("cell_size");
  s["resolution"] = h;
  EXPECT_EQ(cleave::build_model<2>(s).grid.h, h);
  s["grid"]["cell_size"] = h;
  EXPECT_SCENE_ERROR_2D(s, "grid.cell_size", "not both");
  s["grid"].erase("cell_size");
  s["resolution"] = -h;
  EXPECT_SCENE_ERROR_2D(s, "resolution", "positive");
  s["resolution"] = "fine";
  EXPECT_SCENE_ERROR_2D(s, "resolution", "number");
}

TEST(SceneErrors, UnknownUnitsKind) {
  auto s = scene2d();
  s["units"] = {{"temperature", "K"}};
  EXPECT_SCENE_ERROR_2D(s, "units.temperature", "unknown");
}

TEST(SceneErrors, UnknownUnit) {
  auto s = scene2d();
  s["units"] = {{"length", "inch"}};
  EXPECT_SCENE_ERROR_2D(s, "units.length", "unknown unit");
  // The reason lists the valid units.
  try {
    (void)cleave::build_model<2>(s);
  } catch (const SceneError& e) {
    EXPECT_NE(e.reason().find("mm"), std::string::npos) << e.reason();
  }
  s["units"] = {{"stress", "psi"}};
  EXPECT_SCENE_ERROR_2D(s, "units.stress", "MPa");
  s["units"] = {{"time", 1}};
  EXPECT_SCENE_ERROR_2D(s, "units.time", "string");
}

TEST(SceneErrors, UnknownAnalysisType) {
  auto s = scene2d();
  s["analysis"]["type"] = "axisymmetric";
  EXPECT_SCENE_ERROR_2D(s, "analysis.type", "unknown");
}

TEST(SceneErrors, PlaneStressWithoutThickness) {
  auto s = scene2d();
  s["analysis"] = {{"type", "plane_stress"}};
  EXPECT_SCENE_ERROR_2D(s, "analysis.thickness", "thickness");
}

TEST(SceneErrors, ThicknessIn3D) {
  auto s = scene3d();
  s["analysis"]["thickness"] = 0.01;
  EXPECT_SCENE_ERROR_3D(s, "analysis.thickness", "3D");
  auto b = scene3d();
  b["bodies"][0]["thickness"] = 0.01;
  EXPECT_SCENE_ERROR_3D(b, "bodies[0].thickness", "3D");
}

TEST(SceneErrors, NonPositiveThickness) {
  auto s = scene2d();
  s["analysis"] = {{"type", "plane_stress"}, {"thickness", -1}};
  EXPECT_SCENE_ERROR_2D(s, "analysis.thickness", "positive");
}

TEST(SceneErrors, UnknownShapeFunction) {
  auto s = scene2d();
  s["mpm"] = {{"shape_function", "cubic_bspline"}};
  EXPECT_SCENE_ERROR_2D(s, "mpm.shape_function", "unknown");
}

TEST(SceneErrors, UnknownStressUpdate) {
  auto s = scene2d();
  s["mpm"] = {{"stress_update", "RK4"}};
  EXPECT_SCENE_ERROR_2D(s, "mpm.stress_update", "unknown");
  auto t = scene2d();
  t["mpm"] = {{"stres_update", "USL"}};
  EXPECT_SCENE_ERROR_2D(t, "mpm.stres_update", "unknown");
}

// ------------------------------------------------------------------------------------------------
// Materials

TEST(SceneErrors, UnknownMaterialKey) {
  auto s = scene2d();
  s["materials"][0]["yield_stress"] = 3e8;
  EXPECT_SCENE_ERROR_2D(s, "materials[0].yield_stress", "unknown");
}

TEST(SceneErrors, NegativeModulus) {
  auto s = scene2d();
  s["materials"][0]["E"] = -2e11;
  EXPECT_SCENE_ERROR_2D(s, "materials[0].E", "positive");
  s["materials"][0]["E"] = 0;
  EXPECT_SCENE_ERROR_2D(s, "materials[0].E", "positive");
  s["materials"][0]["E"] = "2e11";
  EXPECT_SCENE_ERROR_2D(s, "materials[0].E", "number");
}

TEST(SceneErrors, PoissonRatioOutOfRange) {
  for (double nu : {0.5, 0.7, -1.0, -1.5}) {
    SCOPED_TRACE(nu);
    auto s = scene2d();
    s["materials"][0]["nu"] = nu;
    EXPECT_SCENE_ERROR_2D(s, "materials[0].nu", "Poisson");
    auto s3 = scene3d();
    s3["materials"][0]["nu"] = nu;
    EXPECT_SCENE_ERROR_3D(s3, "materials[0].nu", "Poisson");
  }
  auto s = scene2d();
  s["materials"][0].erase("nu");
  EXPECT_SCENE_ERROR_2D(s, "materials[0].nu", "missing");
}

TEST(SceneErrors, MissingDensity) {
  auto s = scene2d();
  s["materials"][0].erase("density");
  EXPECT_SCENE_ERROR_2D(s, "materials[0].density", "missing");
  auto s3 = scene3d();
  s3["materials"][0].erase("density");
  EXPECT_SCENE_ERROR_3D(s3, "materials[0].density", "missing");
}

TEST(SceneErrors, UnknownMaterialType) {
  auto s = scene2d();
  s["materials"][0]["type"] = "johnson_cook";
  EXPECT_SCENE_ERROR_2D(s, "materials[0].type", "unknown");
  try {
    (void)cleave::build_model<2>(s);
  } catch (const SceneError& e) {
    EXPECT_NE(e.reason().find("linear_elastic"), std::string::npos) << "should list the valid types";
  }
}

TEST(SceneErrors, DuplicateMaterialName) {
  auto s = scene2d();
  s["materials"].push_back(s["materials"][0]);
  EXPECT_SCENE_ERROR_2D(s, "materials[1].name", "duplicate");
}

TEST(SceneErrors, NoMaterials) {
  auto s = scene2d();
  s["materials"] = json::array();
  EXPECT_SCENE_ERROR_2D(s, "materials", "at least one");
}

// ------------------------------------------------------------------------------------------------
// Bodies and shapes

TEST(SceneErrors, BodyNamesMissingMaterial) {
  auto s = scene2d();
  s["bodies"][0]["material"] = "aluminium";
  EXPECT_SCENE_ERROR_2D(s, "bodies[0].material", "no material");
}

TEST(SceneErrors, BodyOutsideExplicitGrid) {
  auto s = scene2d();
  s["grid"] = explicit_grid2d();
  s["bodies"][0]["shape"] = json::parse(R"({"type": "rectangle", "min": [0.1, 0], "max": [0.3, 0.05]})");
  EXPECT_SCENE_ERROR_2D(s, "bodies[0].shape", "outside the grid");
  // A body that touches the grid edge has particles whose stencil would leave the grid.
  s["bodies"][0]["shape"] = json::parse(R"({"type": "rectangle", "min": [-0.05, 0], "max": [0.0, 0.05]})");
  EXPECT_SCENE_ERROR_2D(s, "bodies[0].shape", "outside the grid");
}

TEST(SceneErrors, ThreeDShapeIn2D) {
  auto s = scene2d();
  s["bodies"][0]["shape"] = json::parse(R"({"type": "box", "min": [0, 0, 0], "max": [0.1, 0.05, 0.01]})");
  EXPECT_SCENE_ERROR_2D(s, "bodies[0].shape.type", "3D shape");
  s["bodies"][0]["shape"] = json::parse(R"({"type": "sphere", "center": [0, 0, 0], "radius": 0.02})");
  EXPECT_SCENE_ERROR_2D(s, "bodies[0].shape.type", "3D shape");
}

TEST(SceneErrors, TwoDShapeIn3D) {
  auto s = scene3d();
  s["bodies"][0]["shape"] = json::parse(R"({"type": "rectangle", "min": [0, 0], "max": [0.1, 0.05]})");
  EXPECT_SCENE_ERROR_3D(s, "bodies[0].shape.type", "2D shape");
}

TEST(SceneErrors, UnknownShapeType) {
  auto s = scene2d();
  s["bodies"][0]["shape"] = json::parse(R"({"type": "triangle", "points": [[0, 0], [1, 0], [0, 1]]})");
  EXPECT_SCENE_ERROR_2D(s, "bodies[0].shape.type", "unknown shape type");
}

TEST(SceneErrors, DuplicateBodyNames) {
  auto s = scene2d();
  json second = s["bodies"][0];
  second["shape"] = json::parse(R"({"type": "rectangle", "min": [0, 0.1], "max": [0.1, 0.15]})");
  s["bodies"].push_back(second);
  EXPECT_SCENE_ERROR_2D(s, "bodies[1].name", "duplicate");
}

TEST(SceneErrors, VectorWithWrongComponentCount) {
  auto s = scene2d();
  s["bodies"][0]["velocity"] = {1.0, 0.0, 0.0};
  EXPECT_SCENE_ERROR_2D(s, "bodies[0].velocity", "2 numbers");
  auto s3 = scene3d();
  s3["bodies"][0]["velocity"] = {1.0, 0.0};
  EXPECT_SCENE_ERROR_3D(s3, "bodies[0].velocity", "3 numbers");
  auto g = scene2d();
  g["grid"] = explicit_grid2d();
  g["grid"]["min"] = {-0.05, -0.05, -0.05};
  EXPECT_SCENE_ERROR_2D(g, "grid.min", "2 numbers");
  auto l = scene2d();
  l["loads"] = json::parse(R"([{"type": "body_force", "acceleration": [0, -9.81, 0]}])");
  EXPECT_SCENE_ERROR_2D(l, "loads[0].acceleration", "2 numbers");
  auto c = scene2d();
  c["bodies"][0]["velocity"] = {1.0, "fast"};
  EXPECT_SCENE_ERROR_2D(c, "bodies[0].velocity[1]", "number");
}

TEST(SceneErrors, ParticlesPerCellOutOfRange) {
  auto s = scene2d();
  s["bodies"][0]["particles_per_cell"] = 0;
  EXPECT_SCENE_ERROR_2D(s, "bodies[0].particles_per_cell", "between");
  s["bodies"][0]["particles_per_cell"] = 2.5;
  EXPECT_SCENE_ERROR_2D(s, "bodies[0].particles_per_cell", "integer");
}

TEST(SceneErrors, UnknownBodyKey) {
  auto s = scene2d();
  s["bodies"][0]["colour"] = "red";
  EXPECT_SCENE_ERROR_2D(s, "bodies[0].colour", "unknown");
}

// ------------------------------------------------------------------------------------------------
// Grid

TEST(SceneErrors, GridNotWholeNumberOfCells) {
  auto s = scene2d();
  s["grid"] = explicit_grid2d();
  s["grid"]["max"] = {0.155, 0.10};
  EXPECT_SCENE_ERROR_2D(s, "grid.max", "whole number of cells");
}

TEST(SceneErrors, GridMinWithoutMax) {
  auto s = scene2d();
  s["grid"] = {{"cell_size", 0.01}, {"min", {-0.05, -0.05}}};
  EXPECT_SCENE_ERROR_2D(s, "grid.max", "both");
}

TEST(SceneErrors, GridCellSize) {
  auto s = scene2d();
  s["grid"]["cell_size"] = -0.01;
  EXPECT_SCENE_ERROR_2D(s, "grid.cell_size", "positive");
  s["grid"].erase("cell_size");
  EXPECT_SCENE_ERROR_2D(s, "resolution", "missing");
}

TEST(SceneErrors, GridMarginCells) {
  auto s = scene2d();
  s["grid"]["margin_cells"] = 1;
  EXPECT_SCENE_ERROR_2D(s, "grid.margin_cells", "between");
}

// ------------------------------------------------------------------------------------------------
// Time

TEST(SceneErrors, DtAboveStableLimit) {
  // c = sqrt(E (1-nu) / ((1+nu)(1-2nu)) / rho) = 5873 m/s; h / c = 1.70e-6 s.
  auto s = scene2d();
  s["time"]["dt"] = 2e-6;
  EXPECT_SCENE_ERROR_2D(s, "time.dt", "stable");
  s["time"]["dt"] = 1.6e-6;
  EXPECT_NO_THROW(cleave::build_model<2>(s));
  // The particle speed counts too: 1000 m/s lowers the limit to h / 6873 = 1.45e-6 s.
  s["bodies"][0]["velocity"] = {1000.0, 0.0};
  EXPECT_SCENE_ERROR_2D(s, "time.dt", "stable");
}

TEST(SceneErrors, CflAboveOne) {
  auto s = scene2d();
  s["time"]["cfl"] = 1.5;
  EXPECT_SCENE_ERROR_2D(s, "time.cfl", "at most 1");
  s["time"]["cfl"] = 0.0;
  EXPECT_SCENE_ERROR_2D(s, "time.cfl", "positive");
}

TEST(SceneErrors, BothDtAndCfl) {
  auto s = scene2d();
  s["time"]["dt"] = 1e-7;
  s["time"]["cfl"] = 0.5;
  EXPECT_SCENE_ERROR_2D(s, "time.cfl", "not both");
}

TEST(SceneErrors, TimeEnd) {
  auto s = scene2d();
  s["time"]["end"] = -1.0;
  EXPECT_SCENE_ERROR_2D(s, "time.end", "positive");
  s["time"].erase("end");
  EXPECT_SCENE_ERROR_2D(s, "time.end", "missing");
}

// ------------------------------------------------------------------------------------------------
// Loads

TEST(SceneErrors, UnknownLoadType) {
  auto s = scene2d();
  s["loads"] = json::parse(R"([{"type": "pressure"}])");
  EXPECT_SCENE_ERROR_2D(s, "loads[0].type", "unknown load type");
  s["loads"] = json::parse(R"([{"face": "+y"}])");
  EXPECT_SCENE_ERROR_2D(s, "loads[0].type", "missing");
}

TEST(SceneErrors, SymmetryPlaneOffGridLine) {
  auto s = scene2d();
  s["grid"] = explicit_grid2d();
  s["loads"] = json::parse(R"([{"type": "symmetry", "axis": "x", "position": 0.005}])");
  EXPECT_SCENE_ERROR_2D(s, "loads[0].position", "grid line");
  s["loads"][0]["position"] = 0.0;  // on a grid line: fine
  EXPECT_NO_THROW(cleave::build_model<2>(s));
  s["loads"][0]["position"] = 0.5;  // a grid line beyond the grid
  EXPECT_SCENE_ERROR_2D(s, "loads[0].position", "inside the grid");
  s["loads"][0]["position"] = 0.0;
  s["loads"][0]["axis"] = "z";  // no z axis in 2D
  EXPECT_SCENE_ERROR_2D(s, "loads[0].axis", "unknown axis");
}

TEST(SceneErrors, VelocityConditionAllNull) {
  auto s = scene2d();
  s["loads"] = json::parse(
      R"([{"type": "velocity", "region": {"min": [0, 0], "max": [0, 0.05]}, "velocity": [null, null]}])");
  EXPECT_SCENE_ERROR_2D(s, "loads[0].velocity", "null");
  auto s3 = scene3d();
  s3["loads"] = json::parse(
      R"([{"type": "velocity", "region": {"min": [0, 0, 0], "max": [0, 0.04, 0.04]}, "velocity": [null, null, null]}])");
  EXPECT_SCENE_ERROR_3D(s3, "loads[0].velocity", "null");
}

TEST(SceneErrors, VelocityConditionOtherErrors) {
  auto s = scene2d();
  s["loads"] = json::parse(R"([{"type": "velocity", "velocity": [0, 0]}])");
  EXPECT_SCENE_ERROR_2D(s, "loads[0].region", "missing");
  s["loads"] = json::parse(
      R"([{"type": "velocity", "region": {"min": [0, 0], "max": [0, 0.05]}, "velocity": [0, 0, 0]}])");
  EXPECT_SCENE_ERROR_2D(s, "loads[0].velocity", "2 entries");
  s["loads"] = json::parse(
      R"([{"type": "velocity", "region": {"min": [5, 5], "max": [6, 6]}, "velocity": [0, 0]}])");
  EXPECT_SCENE_ERROR_2D(s, "loads[0].region", "no grid node");
  s["loads"] = json::parse(
      R"([{"type": "velocity", "region": {"min": [0.1, 0], "max": [0, 0.05]}, "velocity": [0, 0]}])");
  EXPECT_SCENE_ERROR_2D(s, "loads[0].region.max", "below");
}

TEST(SceneErrors, TractionFaceMalformed) {
  auto s = scene2d();
  s["loads"] = json::parse(R"([{"type": "traction", "face": "y", "traction": [0, -1e6]}])");
  EXPECT_SCENE_ERROR_2D(s, "loads[0].face", "face");
  s["loads"][0]["face"] = "+z";  // no z face in 2D
  EXPECT_SCENE_ERROR_2D(s, "loads[0].face", "unknown axis");
  s["loads"][0]["face"] = "top";
  EXPECT_SCENE_ERROR_2D(s, "loads[0].face", "face");
}

TEST(SceneErrors, TractionSelectsNoParticle) {
  auto s = scene2d();
  s["grid"] = explicit_grid2d();
  // The region lies inside the grid but away from the block.
  s["loads"] = json::parse(R"([{"type": "traction", "face": "+y", "traction": [0, -1e6],
                                "region": {"min": [-0.04, 0.06], "max": [0.14, 0.09]}}])");
  EXPECT_SCENE_ERROR_2D(s, "loads[0]", "no particle");
  // A region that holds the top of the block, but the -y face is not there.
  s["loads"][0]["face"] = "-y";
  s["loads"][0]["region"] = json::parse(R"({"min": [-0.04, 0.04], "max": [0.14, 0.09]})");
  EXPECT_SCENE_ERROR_2D(s, "loads[0]", "no particle");
}

TEST(SceneErrors, TractionNamesMissingBody) {
  auto s = scene2d();
  s["loads"] = json::parse(R"([{"type": "traction", "face": "+y", "traction": [0, -1e6], "body": "nope"}])");
  EXPECT_SCENE_ERROR_2D(s, "loads[0].body", "no body");
}

TEST(SceneErrors, ATotalForceInKgfBecomesTheTractionOfEqualTotalOnTheLoadedFaces) {
  auto s = scene2d();
  s["units"] = {{"force", "kgf"}};
  s["loads"] = json::parse(R"([{"type": "traction", "face": "+y", "force": [0, 100]}])");
  const auto m = cleave::build_model<2>(s);
  ASSERT_EQ(m.tractions.size(), 1u);
  double area = 0;
  for (double a : m.tractions[0].face_area) area += a;
  EXPECT_NEAR(m.tractions[0].traction[1] * area, 980.665, 1e-9);  // 100 kgf
  EXPECT_EQ(m.tractions[0].traction[0], 0.0);
  s["units"] = {{"force", "lbf"}};
  EXPECT_NEAR(cleave::build_model<2>(s).tractions[0].traction[1] * area, 444.82216152605, 1e-9);
}

TEST(SceneErrors, TractionTakesEitherATractionOrATotalForce) {
  auto s = scene2d();
  s["loads"] = json::parse(R"([{"type": "traction", "face": "+y", "traction": [0, -1e6], "force": [0, 1]}])");
  EXPECT_SCENE_ERROR_2D(s, "loads[0]", "either");
  s["loads"] = json::parse(R"([{"type": "traction", "face": "+y"}])");
  EXPECT_SCENE_ERROR_2D(s, "loads[0]", "either");
}

// ------------------------------------------------------------------------------------------------
// Damping, output, checks

TEST(SceneErrors, UnknownOutputField) {
  auto s = scene2d();
  s["output"] = {{"fields", {"velocity", "temperature"}}};
  EXPECT_SCENE_ERROR_2D(s, "output.fields[1]", "unknown field");
  s["output"] = {{"fields", {"stress", 3}}};
  EXPECT_SCENE_ERROR_2D(s, "output.fields[1]", "field name");
  s["output"] = {{"interval", -1}};
  EXPECT_SCENE_ERROR_2D(s, "output.interval", "positive");
}

TEST(SceneErrors, NegativeDamping) {
  auto s = scene2d();
  s["damping"] = {{"kinetic", -1.0}};
  EXPECT_SCENE_ERROR_2D(s, "damping.kinetic", "negative");
}

TEST(SceneErrors, Checks) {
  auto s = scene2d();
  s["checks"] = {{"energy_blowup_factor", 0}};
  EXPECT_SCENE_ERROR_2D(s, "checks.energy_blowup_factor", "positive");
  s["checks"] = {{"nan_check", true}};
  EXPECT_SCENE_ERROR_2D(s, "checks.nan_check", "unknown");
}

// ------------------------------------------------------------------------------------------------
// Positive tests: units, derived grid, defaults, traction faces

TEST(SceneUnits, ConvertsDeclaredUnitsToSI) {
  const json s = json::parse(R"({
    "units": {"length": "mm", "stress": "MPa", "density": "g/cm3", "time": "ms", "velocity": "mm/ms",
              "inverse_time": "1/ms"},
    "analysis": {"type": "plane_stress", "thickness": 2},
    "grid": {"cell_size": 0.5},
    "materials": [{"name": "steel", "type": "linear_elastic", "E": 200000, "nu": 0.3, "density": 7.8}],
    "bodies": [{"name": "plate", "material": "steel", "velocity": [1, 0],
                "shape": {"type": "rectangle", "min": [0.3, 0.2], "max": [10.3, 5.2]}}],
    "loads": [{"type": "traction", "face": "+y", "traction": [0, -1], "rise_time": 0.002}],
    "damping": {"kinetic": 2},
    "time": {"end": 0.01, "dt": 1e-5},
    "output": {"interval": 0.001}
  })");
  const auto m = cleave::build_model<2>(s);
  const double h = 0.5e-3;
  EXPECT_DOUBLE_EQ(m.grid.h, h);
  EXPECT_DOUBLE_EQ(m.dt, 1e-8);
  EXPECT_DOUBLE_EQ(m.end_time, 1e-5);
  EXPECT_DOUBLE_EQ(m.output.interval, 1e-6);
  EXPECT_DOUBLE_EQ(m.output.global_interval, 1e-7);  // default: interval / 10
  EXPECT_DOUBLE_EQ(m.damping, 2000.0);
  ASSERT_EQ(m.bodies.size(), 1u);
  EXPECT_DOUBLE_EQ(m.bodies[0].thickness, 2e-3);
  ASSERT_GT(m.particles.size(), 0u);
  // rho * (h / ppc)^2 * thickness = 7800 * (0.25e-3)^2 * 2e-3 = 9.75e-7 kg
  for (std::size_t p = 0; p < m.particles.size(); ++p) {
    ASSERT_NEAR(m.particles.mass[p], 9.75e-7, 1e-18) << "particle " << p;
    ASSERT_NEAR(m.particles.v[p][0], 1.0, 1e-15);
  }
  EXPECT_DOUBLE_EQ(m.materials[0]->density(), 7800.0);
  // Stable limit: h / c with the plane-stress (thin plate) c = sqrt(E / (1 - nu^2) / rho) plus the
  // particle speed (validation.md section 1).
  const double c = std::sqrt(2e11 / (1 - 0.09) / 7800.0);
  EXPECT_NEAR(m.stable_dt, h / (c + 1.0), 1e-12 * h / c);
  ASSERT_EQ(m.tractions.size(), 1u);
  EXPECT_DOUBLE_EQ(m.tractions[0].traction[1], -1e6);
  EXPECT_DOUBLE_EQ(m.tractions[0].time_function.rise_time, 2e-6);

  // Derived grid: bounds [0.3, 10.3] x [0.2, 5.2] mm -> cells [0, 21) x [0, 11) around the body,
  // widened by the 2-cell default margin: origin (-1, -1) mm, 26 x 16 nodes.
  for (int d = 0; d < 2; ++d) {
    const double k = m.grid.origin[d] / h;
    EXPECT_NEAR(k, std::round(k), 1e-9) << "origin is a multiple of the cell size along axis " << d;
  }
  EXPECT_NEAR(m.grid.origin[0], -1e-3, 1e-15);
  EXPECT_NEAR(m.grid.origin[1], -1e-3, 1e-15);
  EXPECT_EQ(m.grid.nodes[0], 26);
  EXPECT_EQ(m.grid.nodes[1], 16);
  // At least margin_cells whole cells between the body's bounds and the grid edge, on every side.
  const auto up = m.grid.upper();
  EXPECT_GE(0.3e-3 - m.grid.origin[0], 2 * h - 1e-12);
  EXPECT_LT(0.3e-3 - m.grid.origin[0], 3 * h);
  EXPECT_GE(up[0] - 10.3e-3, 2 * h - 1e-12);
  EXPECT_LT(up[0] - 10.3e-3, 3 * h);
  EXPECT_NEAR(up[1], 6.5e-3, 1e-15);
}

TEST(SceneUnits, DerivedGridMarginCells) {
  auto s = scene2d();  // body [0, 0.1] x [0, 0.05], h = 0.01: edges on grid lines
  auto m = cleave::build_model<2>(s);
  EXPECT_NEAR(m.grid.origin[0], -0.02, 1e-15);
  EXPECT_NEAR(m.grid.origin[1], -0.02, 1e-15);
  EXPECT_EQ(m.grid.nodes[0], 15);  // 10 body cells + 2 x 2 margin cells + 1
  EXPECT_EQ(m.grid.nodes[1], 10);
  s["grid"]["margin_cells"] = 4;
  m = cleave::build_model<2>(s);
  EXPECT_NEAR(m.grid.origin[0], -0.04, 1e-15);
  EXPECT_EQ(m.grid.nodes[0], 19);
  EXPECT_EQ(m.grid.nodes[1], 14);
  const auto m3 = cleave::build_model<3>(scene3d());
  for (int d = 0; d < 3; ++d) {
    EXPECT_NEAR(m3.grid.origin[d], -0.02, 1e-15);
    EXPECT_EQ(m3.grid.nodes[d], 9);
  }
}

TEST(SceneUnits, ExplicitGrid) {
  auto s = scene2d();
  s["grid"] = explicit_grid2d();
  const auto m = cleave::build_model<2>(s);
  EXPECT_NEAR(m.grid.origin[0], -0.05, 1e-15);
  EXPECT_NEAR(m.grid.origin[1], -0.05, 1e-15);
  EXPECT_EQ(m.grid.nodes[0], 21);
  EXPECT_EQ(m.grid.nodes[1], 16);
}

TEST(SceneUnits, Defaults) {
  const auto m = cleave::build_model<2>(scene2d());
  EXPECT_EQ(m.analysis, cleave::Analysis::PlaneStrain);
  EXPECT_EQ(m.shape_function, cleave::ShapeFunctionKind::UGimp);
  EXPECT_EQ(m.scheme, cleave::Scheme::USAVG);
  EXPECT_NEAR(m.dt, 0.5 * m.stable_dt, 1e-20);  // cfl 0.5
  EXPECT_DOUBLE_EQ(m.output.interval, 1e-7);    // end / 100
  EXPECT_DOUBLE_EQ(m.output.global_interval, 1e-8);
  EXPECT_EQ(m.output.fields.size(), 11u);  // every field, "size" and "rotation" included
  EXPECT_DOUBLE_EQ(m.energy_blowup_factor, 10.0);
  EXPECT_DOUBLE_EQ(m.damping, 0.0);
  EXPECT_DOUBLE_EQ(m.bodies[0].thickness, 1.0);  // plane strain in SI: per metre of depth
  EXPECT_TRUE(m.tractions.empty());
  EXPECT_TRUE(m.conditions.node.empty());
}

// Regression: with a non-SI length unit and no analysis.thickness, the plane-strain default thickness
// must be 1 m (it was once 1 / L metres, 1000 m for "mm", making masses 1000x too big).
TEST(SceneUnits, PlaneStrainDefaultThicknessIsUnitDepthInAnyUnits) {
  auto s = scene2d();
  s["units"] = {{"length", "mm"}};
  s["grid"]["cell_size"] = 10;
  s["bodies"][0]["shape"] = json::parse(R"({"type": "rectangle", "min": [0, 0], "max": [100, 50]})");
  const auto m = cleave::build_model<2>(s);
  const auto si = cleave::build_model<2>(scene2d());  // the same scene in metres
  ASSERT_EQ(m.particles.size(), si.particles.size());
  EXPECT_DOUBLE_EQ(m.bodies[0].thickness, si.bodies[0].thickness);
  EXPECT_NEAR(m.particles.mass[0], si.particles.mass[0], 1e-12 * si.particles.mass[0]);
}

TEST(SceneLoads, TractionOnTopFaceSelectsTopRow) {
  auto s = scene2d();
  s["analysis"] = {{"type", "plane_stress"}, {"thickness", 0.002}};
  s["loads"] = json::parse(R"([{"type": "traction", "face": "+y", "traction": [0, -1e6]}])");
  const auto m = cleave::build_model<2>(s);
  ASSERT_EQ(m.tractions.size(), 1u);
  const auto& t = m.tractions[0];
  const int ppc = 2;
  const double h = 0.01;
  EXPECT_EQ(t.axis, 1);
  EXPECT_EQ(t.side, 1);
  ASSERT_EQ(t.particles.size(), std::size_t(10 * ppc));  // 10 cells across, 2 particles per cell
  ASSERT_EQ(t.face_area.size(), t.particles.size());
  double ymax = -1e300;
  for (std::size_t p = 0; p < m.particles.size(); ++p) ymax = std::max(ymax, m.particles.x[p][1]);
  EXPECT_NEAR(ymax, 0.05 - h / ppc / 2, 1e-12);
  double total_area = 0;
  for (std::size_t k = 0; k < t.particles.size(); ++k) {
    EXPECT_NEAR(m.particles.x[t.particles[k]][1], ymax, 1e-12) << "particle " << t.particles[k];
    EXPECT_NEAR(t.face_area[k], (h / ppc) * 0.002, 1e-18);
    total_area += t.face_area[k];
  }
  EXPECT_NEAR(total_area, 0.1 * 0.002, 1e-15);  // the loaded edge length times the thickness
}

TEST(SceneLoads, TractionFacesAndRegions) {
  auto s = scene2d();
  s["loads"] = json::parse(R"([
      {"type": "traction", "face": "-x", "traction": [1e6, 0]},
      {"type": "traction", "face": "+y", "traction": [0, -1e6], "region": {"min": [0.0, 0.0], "max": [0.05, 0.05]}},
      {"type": "traction", "face": "-y", "traction": [0, 1e6], "body": "block"}])");
  const auto m = cleave::build_model<2>(s);
  ASSERT_EQ(m.tractions.size(), 3u);
  EXPECT_EQ(m.tractions[0].particles.size(), 10u);  // 5 cells high, 2 per cell
  EXPECT_EQ(m.tractions[0].axis, 0);
  EXPECT_EQ(m.tractions[0].side, -1);
  EXPECT_EQ(m.tractions[1].particles.size(), 10u);  // half the top row
  EXPECT_EQ(m.tractions[2].particles.size(), 20u);
  EXPECT_EQ(m.tractions[0].name, "loads[0]");
  for (auto p : m.tractions[1].particles) EXPECT_LE(m.particles.x[p][0], 0.05);
  // plane strain in SI: unit thickness
  EXPECT_NEAR(m.tractions[0].face_area[0], 0.005 * 1.0, 1e-15);
}

TEST(SceneLoads, TractionLooksAtItsOwnBodyOnly) {
  // Two blocks stacked face to face: the lower one's top face still counts as a face of that body.
  auto s = scene2d();
  json upper = s["bodies"][0];
  upper["name"] = "upper";
  upper["shape"] = json::parse(R"({"type": "rectangle", "min": [0, 0.05], "max": [0.1, 0.1]})");
  s["bodies"].push_back(upper);
  s["loads"] = json::parse(R"([{"type": "traction", "face": "+y", "traction": [0, -1e6]},
                               {"type": "traction", "face": "+y", "traction": [0, -1e6], "body": "block"}])");
  const auto m = cleave::build_model<2>(s);
  EXPECT_EQ(m.tractions[0].particles.size(), 40u);
  EXPECT_EQ(m.tractions[1].particles.size(), 20u);
  for (auto p : m.tractions[1].particles) EXPECT_LT(m.particles.x[p][1], 0.05);
}

TEST(SceneLoads, TractionIn3D) {
  auto s = scene3d();
  s["loads"] = json::parse(R"([{"type": "traction", "face": "+z", "traction": [0, 0, -1e6]}])");
  const auto m = cleave::build_model<3>(s);
  ASSERT_EQ(m.tractions.size(), 1u);
  EXPECT_EQ(m.tractions[0].axis, 2);
  EXPECT_EQ(m.tractions[0].particles.size(), 64u);  // 8 x 8 particles on the top face
  EXPECT_NEAR(m.tractions[0].face_area[0], 0.005 * 0.005, 1e-18);
}

TEST(SceneLoads, SymmetryAndVelocityConditions) {
  auto s = scene2d();
  s["grid"] = explicit_grid2d();  // 21 x 16 nodes from (-0.05, -0.05)
  s["loads"] = json::parse(R"([
      {"type": "symmetry", "axis": "x", "position": 0.0},
      {"type": "velocity", "region": {"min": [0.1, 0], "max": [0.1, 0.05]}, "velocity": [null, -1]}])");
  const auto m = cleave::build_model<2>(s);
  // 16 nodes on the plane x = 0 (x fixed), 6 nodes on x = 0.1, 0 <= y <= 0.05 (y prescribed).
  ASSERT_EQ(m.conditions.node.size(), 22u);
  int x_fixed = 0, y_fixed = 0;
  for (std::size_t k = 0; k < m.conditions.node.size(); ++k) {
    if (m.conditions.mask[k] & 1) {
      ++x_fixed;
      EXPECT_EQ(m.conditions.velocity[k][0], 0.0);
    }
    if (m.conditions.mask[k] & 2) {
      ++y_fixed;
      EXPECT_EQ(m.conditions.velocity[k][1], -1.0);
    }
  }
  EXPECT_EQ(x_fixed, 16);
  EXPECT_EQ(y_fixed, 6);
}

// Runs build_model in a child process bounded in time (3 s) and memory (2 GiB): exit 0 when it
// throws a SceneError at `path`, 10 when it succeeds, 11 for another key path, 12 for another
// exception, and killed by SIGALRM when it does not finish.
template <int Dim>
void build_bounded(const json& scene, const std::string& path) {
  ::alarm(3);
#ifndef __SANITIZE_ADDRESS__  // AddressSanitizer reserves terabytes of address space for its shadow memory
  const rlimit lim{2ull << 30, 2ull << 30};
  ::setrlimit(RLIMIT_AS, &lim);
#endif
  try {
    (void)cleave::build_model<Dim>(scene);
    std::_Exit(10);
  } catch (const SceneError& e) {
    std::_Exit(e.key_path() == path ? 0 : 11);
  } catch (...) {
    std::_Exit(12);
  }
}

TEST(SceneGuards, TooManyGridNodes2D) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  auto s = scene2d();
  s["grid"]["cell_size"] = 1e-7;  // 1e6 x 5e5 cells
  EXPECT_EXIT(build_bounded<2>(s, "grid.cell_size"), ::testing::ExitedWithCode(0), "");
  EXPECT_SCENE_ERROR_2D(s, "grid.cell_size", "2e9 nodes");
}

TEST(SceneGuards, TooManyGridNodes3D) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  auto s = scene3d();
  s["grid"]["cell_size"] = 1e-5;  // 4000 cells per axis: 6.4e10 nodes
  EXPECT_EXIT(build_bounded<3>(s, "grid.cell_size"), ::testing::ExitedWithCode(0), "");
}

// Regression: a cell count beyond int range must be rejected at grid.cell_size before any int
// conversion (it once overflowed, made 3D node counts negative and hung `cleave check`).
TEST(SceneGuards, CellCountOverflowingIntIsRejected3D) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  auto s = scene3d();
  s["grid"]["cell_size"] = 1e-13;  // 4e11 cells per axis
  EXPECT_EXIT(build_bounded<3>(s, "grid.cell_size"), ::testing::ExitedWithCode(0), "");
  auto e = scene3d();
  e["grid"] = json::parse(R"({"cell_size": 1e-13, "min": [-0.01, -0.01, -0.01], "max": [0.05, 0.05, 0.05]})");
  EXPECT_EXIT(build_bounded<3>(e, "grid.cell_size"), ::testing::ExitedWithCode(0), "");
}

TEST(SceneErrors, SceneDimension) {
  EXPECT_THROW(cleave::scene_dimension(json::array()), SceneError);
  auto s = scene2d();
  s["analysis"]["type"] = "2d";
  try {
    (void)cleave::scene_dimension(s);
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key_path(), "analysis.type");
  }
}

}  // namespace
