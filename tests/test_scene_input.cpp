// Bad input that once got past the scene reader (issue 15): counts beyond a long, numbers beyond a
// double, a directory as the scene, duplicate keys, a --set that another replaces, and scenes too
// big for the machine. Each is a SceneError naming the key and the reason, before anything is built
// or written. The CLI's side (exit 2, nothing written) is in test_cli_input.cpp.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "files.hpp"
#include "libmpm/core/error.hpp"
#include "libmpm/core/resources.hpp"
#include "libmpm/method/run_scene.hpp"
#include "libmpm/mpm/mpm_scene.hpp"
#include "libmpm/pd/pd_scene.hpp"
#include "libmpm/scene/json_text.hpp"
#include "support.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using cleave::SceneError;
using cleave::test::error_of;

// A valid plane-strain scene: a 0.1 x 0.05 m steel block, 1 cm cells.
json block() {
  return json::parse(R"({
    "analysis": {"type": "plane_strain"},
    "resolution": 0.01,
    "materials": [{"name": "steel", "type": "linear_elastic", "E": 2e11, "nu": 0.3, "density": 7800}],
    "bodies": [{"name": "block", "material": "steel",
                "shape": {"type": "rectangle", "min": [0, 0], "max": [0.1, 0.05]}}],
    "time": {"end": 1e-5}
  })");
}

bool has(const std::string& text, const std::string& word) { return text.find(word) != std::string::npos; }

// A temporary directory removed at the end of the test.
struct TempDir {
  fs::path path = cleave::test::fresh_dir(cleave::test::per_test_path("cleave_input_"));
  ~TempDir() { fs::remove_all(path); }
};

// --- counts --------------------------------------------------------------------------------------

TEST(SceneErrors, ATimeEndThatNeedsMoreStepsThanALongHoldsIsRefused) {
  json s = block();
  s["time"]["end"] = 1e300;  // `check` printed -9223372036854775808 steps and the run never ended
  const SceneError e = error_of([&] { cleave::build_model<2>(s); });
  EXPECT_EQ(e.key_path(), "time.end");
  EXPECT_TRUE(has(e.reason(), "steps")) << e.reason();
  s["time"]["end"] = 1e5;  // 6e10 steps: fits a long, but no run could finish
  EXPECT_EQ(error_of([&] { cleave::build_model<2>(s); }).key_path(), "time.end");
  s["time"]["end"] = 1e-3;
  EXPECT_NO_THROW(cleave::build_model<2>(s));
}

TEST(SceneErrors, AValueThatOverflowsAfterUnitScalingIsRefused) {
  json s = block();
  s["units"] = {{"velocity", "mm/us"}};
  s["bodies"][0]["velocity"] = {1e306, 0};  // finite as written, infinite in m/s
  const SceneError e = error_of([&] { cleave::build_model<2>(s); });
  EXPECT_EQ(e.key_path(), "bodies[0].velocity[0]");
  EXPECT_TRUE(has(e.reason(), "overflows")) << e.reason();
  s["bodies"][0]["velocity"] = {1, 0};
  s["units"] = {{"length", "cm"}};
  s["resolution"] = 1e-300;  // finite and positive, but no grid holds the cells it makes
  EXPECT_EQ(error_of([&] { cleave::build_model<2>(s); }).key_path(), "resolution");
}

TEST(SceneErrors, AnOutputIntervalThatWritesMoreFramesThanAFolderShouldHoldIsRefused) {
  json s = block();
  s["time"]["end"] = 1.0;  // 7e5 steps: allowed
  s["output"] = {{"interval", 1e-30}};
  const SceneError e = error_of([&] { cleave::build_model<2>(s); });
  EXPECT_EQ(e.key_path(), "output.interval");
  EXPECT_TRUE(has(e.reason(), "frames")) << e.reason();
  // A frame at every step of a short run is allowed: the run writes at most one per step.
  s["time"]["end"] = 1e-5;
  EXPECT_NO_THROW(cleave::build_model<2>(s));
}

TEST(SceneErrors, PeridynamicCountsAreCheckedToo) {
  json s = json::parse(R"({
    "method": "peridynamics", "analysis": {"type": "plane_stress", "thickness": 0.001}, "resolution": 0.005,
    "materials": [{"name": "glass", "type": "linear_elastic", "E": 65e9, "density": 2235, "fracture_energy": 204}],
    "bodies": [{"name": "block", "material": "glass", "shape": {"type": "rectangle", "min": [0, 0], "max": [0.1, 0.05]}}],
    "time": {"end": 1e300}
  })");
  EXPECT_EQ(error_of([&] { cleave::pd::build_pd_system<2>(s); }).key_path(), "time.end");
  s["time"]["end"] = 10.0;  // 1e7 steps, a frame at each
  s["output"] = {{"interval", 1e-30}};
  EXPECT_EQ(error_of([&] { cleave::pd::build_pd_system<2>(s); }).key_path(), "output.interval");
}

// --- the scene text --------------------------------------------------------------------------------

TEST(SceneErrors, ANumberBeyondADoubleNamesTheKeyTheLineAndTheColumn) {
  const SceneError e = error_of([] { cleave::scene::parse_scene_text("{\n  \"resolution\": 1e400\n}\n"); });
  EXPECT_EQ(e.key_path(), "resolution");
  EXPECT_TRUE(has(e.reason(), "1e400")) << e.reason();
  EXPECT_TRUE(has(e.reason(), "out of range")) << e.reason();
  EXPECT_TRUE(has(e.reason(), "line 2, column 17")) << e.reason();
  const SceneError g = error_of([] {
    cleave::scene::parse_scene_text(R"({"grid": {"cell_size": 1e400}, "bodies": [{}, {"velocity": [0, -1e999]}]})");
  });
  EXPECT_EQ(g.key_path(), "grid.cell_size");
  const SceneError b = error_of([] { cleave::scene::parse_scene_text(R"({"bodies": [{}, {"velocity": [0, -1e999]}]})"); });
  EXPECT_EQ(b.key_path(), "bodies[1].velocity[1]");
}

TEST(SceneErrors, ADuplicateKeyIsRefusedNamingTheKeyAndBothPlaces) {
  const std::string text = "{\n  \"time\": {\"end\": 1},\n  \"bodies\": [],\n  \"time\": {\"end\": 2}\n}\n";
  const SceneError e = error_of([&] { cleave::scene::parse_scene_text(text); });
  EXPECT_EQ(e.key_path(), "time");
  EXPECT_TRUE(has(e.reason(), "duplicate key")) << e.reason();
  EXPECT_TRUE(has(e.reason(), "line 2, column 3")) << e.reason();
  EXPECT_TRUE(has(e.reason(), "line 4, column 3")) << e.reason();
  // Nested, inside an array, and with an escaped quote before the key.
  const SceneError n = error_of([] {
    cleave::scene::parse_scene_text(R"({"bodies": [{"name": "a\"", "shape": {"radius": 1, "radius": 2}}]})");
  });
  EXPECT_EQ(n.key_path(), "bodies[0].shape.radius");
  // The same key in two different objects is no duplicate.
  const json ok = cleave::scene::parse_scene_text(R"({"a": {"x": 1}, "b": {"x": 2}, "c": [{"x": 3}, {"x": 4}]})");
  EXPECT_EQ(ok["c"][1]["x"], 4);
}

TEST(SceneErrors, SyntaxErrorsNameTheKeyAndThePosition) {
  const SceneError e = error_of([] { cleave::scene::parse_scene_text("{\"analysis\": {\"type\": \"3d\"},\n \"grid\": \n"); });
  EXPECT_EQ(e.key_path(), "grid");
  EXPECT_TRUE(has(e.reason(), "not valid JSON")) << e.reason();
  EXPECT_TRUE(has(e.reason(), "line 3")) << e.reason();
  EXPECT_EQ(error_of([] { cleave::scene::parse_scene_text(""); }).key_path(), "(scene)");
  // Comments stay allowed, as in the example scenes.
  EXPECT_EQ(cleave::scene::parse_scene_text("{\"a\": 1 // one\n}")["a"], 1);
}

TEST(SceneErrors, ADirectoryOrAMissingFileAsTheSceneCannotBeOpened) {
  TempDir dir;
  const SceneError d = error_of([&] { cleave::load_scene_file(dir.path); });
  EXPECT_EQ(d.key_path(), "");  // the file itself: the CLI prints the reason alone
  EXPECT_EQ(d.reason(), "cannot open " + dir.path.string() + ": is a directory");
  const SceneError m = error_of([&] { cleave::load_scene_file(dir.path / "none.json"); });
  EXPECT_TRUE(has(m.reason(), "cannot open")) << m.reason();
  EXPECT_TRUE(has(m.reason(), "no such file")) << m.reason();
}

TEST(SceneErrors, AnEndlessOrHugeSceneFileIsRefusedAfterItsCapNotReadUntilMemoryRunsOut) {
  const SceneError z = error_of([] { cleave::load_scene_file("/dev/zero"); });
  EXPECT_EQ(z.key_path(), "");
  EXPECT_TRUE(has(z.reason(), "cannot read /dev/zero: more than 64 MiB")) << z.reason();
  TempDir dir;  // a sparse file one byte over the cap (no disk used)
  const fs::path big = dir.path / "big.json";
  std::ofstream(big) << "{}";
  fs::resize_file(big, cleave::kMaxSceneFileBytes + 1);
  EXPECT_TRUE(has(error_of([&] { cleave::load_scene_file(big); }).reason(), "more than 64 MiB"));
}

TEST(SceneErrors, AnUnreadableSceneCannotBeOpened) {
  TempDir dir;
  const fs::path locked = dir.path / "locked.json";
  std::ofstream(locked) << block().dump();
  fs::permissions(locked, fs::perms::none);
  if (std::ifstream(locked).good()) GTEST_SKIP() << "running as root: a file without permissions is still readable";
  const SceneError u = error_of([&] { cleave::load_scene_file(locked); });
  EXPECT_TRUE(has(u.reason(), "cannot open " + locked.string() + ": Permission denied")) << u.reason();
}

// --- --set -------------------------------------------------------------------------------------------

TEST(SceneErrors, ASetThatALaterSetReplacesIsRefused) {
  json s = block();
  const SceneError e = error_of([&] { cleave::apply_overrides(s, {"time.end=1", "resolution=0.02", "time.end=2"}); });
  EXPECT_EQ(e.key_path(), "time.end");
  EXPECT_TRUE(has(e.reason(), "--set time.end=1")) << e.reason();
  EXPECT_TRUE(has(e.reason(), "--set time.end=2")) << e.reason();
  // A later --set of the object around it replaces it as well; one inside an earlier one does not.
  EXPECT_EQ(error_of([&] { cleave::apply_overrides(s, {"time.end=1", R"(time={"end": 2})"}); }).key_path(), "time.end");
  EXPECT_NO_THROW(cleave::apply_overrides(s, {R"(time={"end": 2})", "time.end=3", "time.endx=1"}));
  EXPECT_EQ(s["time"]["end"], 3);
}

TEST(SceneErrors, ASetNumberBeyondADoubleIsRefusedNamingTheKey) {
  json s = block();
  const SceneError e = error_of([&] { cleave::apply_override(s, "resolution=1e400"); });
  EXPECT_EQ(e.key_path(), "resolution");
  EXPECT_TRUE(has(e.reason(), "out of range")) << e.reason();
}

// `materials.0.E` reads naturally but JSON arrays have no named keys: the error shows the index form.
TEST(SceneErrors, ASetThatNamesAnArrayElementWithADotShowsTheIndexForm) {
  json s = block();
  const SceneError e = error_of([&] { cleave::apply_override(s, "materials.0.E=1e9"); });
  EXPECT_EQ(e.key_path(), "materials.0");
  EXPECT_TRUE(has(e.reason(), "materials[0]")) << e.reason();
  EXPECT_NO_THROW(cleave::apply_override(s, "materials[0].E=1e9"));
  EXPECT_EQ(s["materials"][0]["E"], 1e9);
}

// --- what the machine has ----------------------------------------------------------------------------

TEST(SceneErrors, ASceneNeedingMoreMemoryThanTheMachineHasIsRefusedBeforeAllocating) {
  // A 1 m square at 33 um: 9e8 grid nodes (below the 2e9 guard) and 3.7e9 particles, about 1.8 TB.
  json s = block();
  s["bodies"][0]["shape"] = {{"type", "rectangle"}, {"min", {0, 0}}, {"max", {1, 1}}};
  s["resolution"] = 3.3e-5;
  if (cleave::available_memory_bytes() > 2e12) GTEST_SKIP() << "this machine has more than 2 TB available";
  const SceneError e = error_of([&] { cleave::build_model<2>(s); });
  EXPECT_EQ(e.key_path(), "resolution");
  EXPECT_TRUE(has(e.reason(), "of memory")) << e.reason();
  EXPECT_TRUE(has(e.reason(), "available")) << e.reason();
  EXPECT_TRUE(has(e.reason(), "--force")) << e.reason();
  // The same for peridynamics, at its spacing.
  json p = json::parse(R"({
    "method": "peridynamics", "analysis": {"type": "plane_stress", "thickness": 0.001},
    "peridynamics": {"spacing": 1e-5},
    "materials": [{"name": "glass", "type": "linear_elastic", "E": 65e9, "density": 2235, "fracture_energy": 204}],
    "bodies": [{"name": "block", "material": "glass", "shape": {"type": "rectangle", "min": [0, 0], "max": [1, 1]}}],
    "time": {"end": 1e-6}
  })");
  EXPECT_EQ(error_of([&] { cleave::pd::build_pd_system<2>(p); }).key_path(), "peridynamics.spacing");
}

TEST(SceneErrors, AnOutputLargerThanTheFreeDiskIsRefusedUnlessForced) {
  TempDir dir;
  cleave::RunEstimate e;
  e.frames = 1e6;
  e.frame_bytes = 1e15;  // an exabyte: more than any disk
  e.output_key = "output.interval";
  const SceneError err = error_of([&] { cleave::check_disk(e, dir.path / "out"); });
  EXPECT_EQ(err.key_path(), "output.interval");
  EXPECT_TRUE(has(err.reason(), "free in " + (dir.path / "out").string())) << err.reason();
  cleave::set_resource_checks_forced(true);
  EXPECT_NO_THROW(cleave::check_disk(e, dir.path / "out"));
  cleave::set_resource_checks_forced(false);
  e.frame_bytes = 1.0;
  EXPECT_NO_THROW(cleave::check_disk(e, dir.path / "out"));
}

TEST(SceneErrors, TheEstimateCountsFramesPointsAndBytes) {
  json s = block();
  s["output"] = {{"interval", 2.5e-6}};
  cleave::SceneMethod m = cleave::SceneMethod::build(s);
  const cleave::RunEstimate e = m.estimate();
  EXPECT_EQ(e.points, 200);  // 10 x 5 cells, 4 particles each
  EXPECT_EQ(e.frames, 5);    // t = 0 and every 2.5 us to 10 us
  EXPECT_GT(e.frame_bytes, 200 * 8 * 20);  // about 30 doubles a particle
  EXPECT_LT(e.frame_bytes, 200 * 8 * 60);
  EXPECT_GT(e.checkpoint_bytes, 200 * 8 * 10);
  EXPECT_GT(e.memory_bytes, 100e6);
  EXPECT_EQ(e.output_key, "output.interval");
}

// The frame estimate follows io/vtu_writer.cpp's layout: output.precision "float32" takes exactly
// half the field bytes of float64 (the rest of the file unchanged); raw, it is the written frame's
// size to within the allowance for the XML; with zlib it bounds the written frame from above.
TEST(SceneErrors, TheFrameEstimateHalvesTheFieldBytesForFloat32AndBoundsTheWrittenFrame) {
  for (const char* compression : {"none", "zlib"}) {
    SCOPED_TRACE(compression);
    const bool zlib = std::string(compression) == "zlib";
    json s = block();
    s["output"] = {{"interval", 5e-6}, {"compression", compression}, {"precision", "float64"}};
    cleave::SceneMethod m64 = cleave::SceneMethod::build(s);
    s["output"]["precision"] = "float32";
    cleave::SceneMethod m32 = cleave::SceneMethod::build(s);
    const cleave::RunEstimate e64 = m64.estimate(), e32 = m32.estimate();
    EXPECT_EQ(e64.zlib, zlib);
    EXPECT_FALSE(e64.float32);
    EXPECT_TRUE(e32.float32);
    EXPECT_GE(e64.field_bytes, 200 * 3 * 8);  // the coordinates at least
    EXPECT_EQ(e32.field_bytes * 2, e64.field_bytes);
    if (!zlib) {
      EXPECT_EQ(e64.frame_bytes - e32.frame_bytes, e64.field_bytes / 2);
    }
    for (auto* m : {&m64, &m32}) {
      const cleave::RunEstimate e = m->estimate();
      TempDir dir;
      cleave::RunOptions opt;
      opt.out = dir.path / "out";
      m->run(opt);
      const double written = double(fs::file_size(opt.out / "particles_000000.vtu"));
      EXPECT_LE(written, e.frame_bytes);
      if (!zlib) {
        EXPECT_GT(written, e.frame_bytes - 16384.0) << "raw: the XML allowance only";
      }
    }
  }
}

}  // namespace
