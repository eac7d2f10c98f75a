// The module layering of docs/architecture.md, checked on the sources: shared modules include only
// the layers below them, a method (any other folder of libmpm/) includes shared modules and its own
// folder only, and the command-line program reaches the library through the method seam.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const fs::path kRoot = CLEAVE_SOURCE_DIR;

// Shared modules and what each may include (besides itself). Every other folder of libmpm/ is a method.
const std::map<std::string, std::set<std::string>> kShared = {
    {"core", {}},
    {"geometry", {"core"}},
    {"material", {"core"}},
    {"shape", {"core"}},
    {"crack", {"core", "geometry"}},
    {"io", {"core", "crack"}},
    {"scene", {"core", "geometry"}},
    {"method", {"core", "io", "scene"}},
    {"reference", {"core"}},
};

struct Include {
  std::string file, target;  // "libmpm/mpm/model.hpp", "libmpm/core/types.hpp"
};

std::vector<Include> includes_under(const fs::path& dir) {
  std::vector<Include> out;
  const std::regex inc(R"(^\s*#\s*include\s+"([^"]+)\")");
  for (const auto& e : fs::recursive_directory_iterator(kRoot / dir)) {
    const auto ext = e.path().extension();
    if (!e.is_regular_file() || (ext != ".hpp" && ext != ".cpp")) continue;
    std::ifstream in(e.path());
    std::smatch m;
    for (std::string line; std::getline(in, line);)
      if (std::regex_search(line, m, inc)) out.push_back({fs::relative(e.path(), kRoot).string(), m[1]});
  }
  return out;
}

// "libmpm/mpm/x.hpp" -> "mpm"; "" when the path is not below libmpm/.
std::string module_of(const std::string& path) {
  if (path.rfind("libmpm/", 0) != 0) return "";
  const auto slash = path.find('/', 7);
  return slash == std::string::npos ? "" : path.substr(7, slash - 7);
}

}  // namespace

TEST(Architecture, SharedModulesIncludeOnlyTheLayersBelowThem) {
  for (const auto& [file, target] : includes_under("libmpm")) {
    const std::string from = module_of(file), to = module_of(target);
    if (to.empty() || from == to || !kShared.count(from)) continue;
    EXPECT_TRUE(kShared.at(from).count(to)) << file << " includes " << target << ": module '" << from
                                            << "' may not depend on '" << to << "'";
  }
}

TEST(Architecture, NoMethodIncludesAnotherMethodsFolder) {
  std::set<std::string> methods;
  for (const auto& [file, target] : includes_under("libmpm")) {
    const std::string from = module_of(file), to = module_of(target);
    if (kShared.count(from)) continue;
    methods.insert(from);
    if (to.empty() || from == to) continue;
    EXPECT_TRUE(kShared.count(to)) << file << " includes " << target << ": method '" << from
                                   << "' reaches into method '" << to << "'";
  }
  EXPECT_TRUE(methods.count("mpm") && methods.count("pd")) << "expected the mpm and pd method folders";
}

// apps/cleave holds no physics and no scene logic: it reaches the library through the method seam
// (method/run_scene.hpp), the scene file helpers and errors, and the renderer.
TEST(Architecture, TheCommandLineProgramReachesMethodsThroughTheSeamOnly) {
  for (const auto& [file, target] : includes_under("apps/cleave")) {
    const std::string to = module_of(target);
    if (to.empty()) continue;
    EXPECT_TRUE(to == "method" || to == "scene" || to == "core")
        << file << " includes " << target << ": the CLI may use method/, scene/ and core/ only";
  }
}

// The renderer reads what the writers wrote; it knows no method.
TEST(Architecture, TheRendererKnowsNoMethod) {
  for (const auto& [file, target] : includes_under("viz")) {
    const std::string to = module_of(target);
    EXPECT_TRUE(to.empty() || to == "io" || to == "core") << file << " includes " << target;
  }
}

// A study runs scenes as `cleave run` does and reads what the runs wrote: it may read scenes and closed
// forms, and knows no method.
TEST(Architecture, TheStudyKnowsNoMethod) {
  for (const auto& [file, target] : includes_under("study")) {
    const std::string to = module_of(target);
    EXPECT_TRUE(to.empty() || to == "core" || to == "io" || to == "scene" || to == "reference")
        << file << " includes " << target;
  }
}
