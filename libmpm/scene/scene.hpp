// A scene file as JSON: reading it, the facts every method needs before it builds (dimension,
// method), and `--set` overrides. The sections shared by every method are in scene/sections.hpp;
// each method reads its own section in its folder (mpm/mpm_scene.cpp, pd/pd_scene.cpp).
#pragma once
#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace cleave {

// Reads and parses the file strictly (scene/json_text.hpp: duplicate keys, numbers out of range,
// syntax errors name the key, line and column). A file that cannot be opened (missing, a directory,
// unreadable, longer than kMaxSceneFileBytes: /dev/zero, an endless pipe) is a SceneError with an
// empty key path whose reason names the file.
inline constexpr std::size_t kMaxSceneFileBytes = std::size_t(64) << 20;
nlohmann::json load_scene_file(const std::filesystem::path& file);

// 2 or 3, from "analysis.type".
int scene_dimension(const nlohmann::json& scene);

// The scene's "method" ("mpm" when absent). Whether it names a registered method is the method
// registry's check (method/method.hpp).
std::string scene_method(const nlohmann::json& scene);

// Applies one KEY=VALUE override; the key path uses '.' and [i] like error messages
// (mpm.stress_update, bodies[1].velocity); VALUE is JSON or else a plain string; null removes the
// key (an object's key; an array element is set to null).
void apply_override(nlohmann::json& scene, const std::string& key_value);

// Applies every override in order; SceneError when one key is set twice (or a key and a key inside
// it, as time and time.end): the earlier one would be lost without a word.
void apply_overrides(nlohmann::json& scene, const std::vector<std::string>& key_values);

}  // namespace cleave
