// The scene reader's fuzz findings, kept (issue 15): every input under tests/fuzz/regressions/ goes
// through the fuzz target's entry point (tests/fuzz/scene_entry.hpp: the `cleave check` path, scene
// text plus "--set" lines) and must be refused with a SceneError naming the key that
// tests/fuzz/regressions/expected_keys.txt gives (or, for a valid scene that once crashed, build);
// no crash, hang or other exception. The inputs: the fuzzer's crashers (crash-*), what reviewing the
// reader beside the fuzzer found (review-*: run under the fuzz build's sanitizers, they reported
// undefined behaviour or a foreign exception) and hand-made hostile ones (hostile-*: deep nesting,
// huge numbers and counts, NaN spelled as a string).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "tests/fuzz/scene_entry.hpp"

namespace {

namespace fs = std::filesystem;
using cleave::fuzz::check_scene;
using cleave::fuzz::split_input;

const fs::path kDir = fs::path(CLEAVE_SOURCE_DIR) / "tests" / "fuzz" / "regressions";

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

cleave::fuzz::Input input_of(const std::string& bytes) {
  return split_input(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
}

struct Expected {
  std::string key, words;
};

// expected_keys.txt: "FILE KEY_PATH [WORDS]" per line ('#' starts a comment): the key path the
// SceneError names ("KEY*": one that starts with KEY, for the long paths of deep nesting; "(accepted)":
// a valid scene that must build) and, when given, words its reason contains.
std::map<std::string, Expected> expected_keys() {
  std::map<std::string, Expected> out;
  std::istringstream in(read(kDir / "expected_keys.txt"));
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream l(line);
    std::string file;
    Expected e;
    l >> file >> e.key >> std::ws;
    std::getline(l, e.words);
    out[file] = e;
  }
  return out;
}

TEST(FuzzRegressions, EveryKeptInputIsRefusedWithASceneErrorNamingItsKey) {
  const auto keys = expected_keys();
  int n = 0;
  for (const auto& e : fs::directory_iterator(kDir)) {
    const std::string name = e.path().filename().string();
    if (name == "expected_keys.txt") continue;
    SCOPED_TRACE(name);
    ++n;
    const auto it = keys.find(name);
    ASSERT_NE(it, keys.end()) << "add '" << name << " KEY' to expected_keys.txt";
    cleave::fuzz::Outcome o;
    try {
      o = check_scene(input_of(read(e.path())));
    } catch (const std::exception& ex) {
      FAIL() << "not a SceneError: " << ex.what();
    }
    const std::string& key = it->second.key;
    if (key == "(accepted)") {  // a valid scene that once crashed the reader: it must build
      EXPECT_TRUE(o.accepted) << o.key << ": " << o.reason;
      continue;
    }
    EXPECT_FALSE(o.accepted) << "the input was accepted";
    if (!key.empty() && key.back() == '*')
      EXPECT_EQ(o.key.substr(0, key.size() - 1), key.substr(0, key.size() - 1)) << o.reason;
    else
      EXPECT_EQ(o.key, key) << o.reason;
    EXPECT_FALSE(o.reason.empty());
    EXPECT_NE(o.reason.find(it->second.words), std::string::npos) << o.reason;
  }
  EXPECT_EQ(n, static_cast<int>(keys.size())) << "expected_keys.txt names a file that is not there";
  EXPECT_GE(n, 5);
}

TEST(FuzzRegressions, TheSeedScenesPassTheSameEntryPoint) {
  // The entry point is the real check path: the example scenes and the fuzz seeds build, or are
  // too big for the entry point's memory cap (scene_entry.hpp) and refused by the memory check.
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(fs::path(CLEAVE_SOURCE_DIR) / "data" / "scenes")) files.push_back(e.path());
  for (const auto& e : fs::directory_iterator(fs::path(CLEAVE_SOURCE_DIR) / "tests" / "fuzz" / "seeds")) files.push_back(e.path());
  ASSERT_GE(files.size(), 10u);
  for (const auto& f : files) {
    SCOPED_TRACE(f.filename().string());
    const auto o = check_scene(input_of(read(f)));
    const bool too_big = o.reason.find("of memory") != std::string::npos &&
                         o.reason.find("this machine has available") != std::string::npos;
    EXPECT_TRUE(o.accepted || too_big) << o.key << ": " << o.reason;
  }
}

TEST(FuzzInputSplit, SetLinesAfterTheSceneBecomeOverridesInOrder) {
  const auto in = input_of("{\"a\": 1}\n--set time.end=2\n--set mpm={\"x\":\n1}\n--set b=\n");
  EXPECT_EQ(in.scene, "{\"a\": 1}");
  ASSERT_EQ(in.overrides.size(), 3u);
  EXPECT_EQ(in.overrides[0], "time.end=2");
  EXPECT_EQ(in.overrides[1], "mpm={\"x\":\n1}");
  EXPECT_EQ(in.overrides[2], "b=");
  std::string many = "{}";
  for (int i = 0; i < 20; ++i) many += "\n--set k" + std::to_string(i) + "=1";
  EXPECT_EQ(input_of(many).overrides.size(), cleave::fuzz::kMaxOverrides);
}

}  // namespace
