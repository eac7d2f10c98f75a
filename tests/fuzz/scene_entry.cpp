#include "tests/fuzz/scene_entry.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "libmpm/core/error.hpp"
#include "libmpm/method/run_scene.hpp"
#include "libmpm/scene/json_text.hpp"
#include "libmpm/scene/scene.hpp"

// The memory check's figure, capped (scene_entry.hpp): the linker sends the library's calls of
// cleave::available_memory_bytes() here (--wrap), and __real_ is the library's own function.
extern "C" double __real__ZN6cleave22available_memory_bytesEv();
extern "C" double __wrap__ZN6cleave22available_memory_bytesEv() {
  return std::min(__real__ZN6cleave22available_memory_bytesEv(), cleave::fuzz::kMemoryCapBytes);
}

namespace cleave::fuzz {

Input split_input(const uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  static const std::string sep = "\n--set ";
  Input in;
  std::size_t at = text.find(sep);
  in.scene = text.substr(0, at);
  while (at != std::string::npos && in.overrides.size() < kMaxOverrides) {
    const std::size_t start = at + sep.size();
    at = text.find(sep, start);
    std::string kv = text.substr(start, at == std::string::npos ? std::string::npos : at - start);
    if (!kv.empty() && kv.back() == '\n') kv.pop_back();
    in.overrides.push_back(std::move(kv));
  }
  return in;
}

Outcome check_scene(const Input& in) {
  Outcome o;
  try {
    // apps/cleave/main.cpp: load_scene_file (= parse_scene_text of the file's bytes), the overrides,
    // then run_scene_command's "check" branch.
    nlohmann::json scene = scene::parse_scene_text(in.scene);
    apply_overrides(scene, in.overrides);
    SceneMethod method = SceneMethod::build(scene);
    o.lines = method.settings().warnings;
    for (auto& l : method.describe()) o.lines.push_back(std::move(l));
    const RunEstimate est = method.estimate();
    const std::filesystem::path out = "fuzz_check_out";  // never created: only its disk is looked at
    for (auto& l : describe_estimate(est, out)) o.lines.push_back(std::move(l));
    try {
      check_disk(est, out);
    } catch (const SceneError& e) {
      o.lines.push_back("warning: " + e.key_path() + ": " + e.reason());
    }
    o.accepted = true;
  } catch (const SceneError& e) {
    o.key = e.key_path();
    o.reason = e.reason();
  }
  return o;
}

}  // namespace cleave::fuzz
