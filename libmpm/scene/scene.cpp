#include "libmpm/scene/scene.hpp"

#include <fstream>

#include "libmpm/core/error.hpp"
#include "libmpm/scene/sections.hpp"

namespace cleave {

using nlohmann::json;

json load_scene_file(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw SceneError(file.string(), "cannot open the scene file");
  try {
    return json::parse(in, nullptr, true, /*ignore_comments=*/true);
  } catch (const json::parse_error& e) {
    throw SceneError(file.string(), std::string("not valid JSON: ") + e.what());
  }
}

int scene_dimension(const json& scene) {
  if (!scene.is_object()) throw SceneError("(scene)", "the scene must be a JSON object");
  double t = 0;
  return dimension_of(scene::read_analysis(scene, 1.0, t));
}

std::string scene_method(const json& scene) {
  if (!scene.is_object() || !scene.contains("method") || scene["method"].is_null()) return "mpm";
  if (!scene["method"].is_string()) throw SceneError("method", "expected a string naming the method");
  return scene["method"].get<std::string>();
}

void apply_override(json& scene, const std::string& kv) {
  const auto eq = kv.find('=');
  if (eq == std::string::npos || eq == 0) throw SceneError(kv, "--set needs KEY=VALUE");
  const std::string key = kv.substr(0, eq), text = kv.substr(eq + 1);
  json value = json::parse(text, nullptr, false);
  if (value.is_discarded()) value = text;  // a bare word such as USL
  json* node = &scene;
  std::size_t i = 0;
  while (i < key.size()) {
    if (key[i] == '[') {
      const auto close = key.find(']', i);
      if (close == std::string::npos) throw SceneError(key, "unclosed '[' in --set key");
      const std::string digits = key.substr(i + 1, close - i - 1);
      if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 9)
        throw SceneError(key.substr(0, close + 1), "an array index must be a non-negative integer");
      const std::size_t idx = std::stoul(digits);
      if (!node->is_array() || idx >= node->size()) throw SceneError(key.substr(0, close + 1), "no such array element");
      node = &(*node)[idx];
      i = close + 1;
    } else {
      if (key[i] == '.') ++i;
      const auto end = key.find_first_of(".[", i);
      const std::string name = key.substr(i, end == std::string::npos ? std::string::npos : end - i);
      if (name.empty()) throw SceneError(key, "empty key name in --set");
      if (!node->is_null() && !node->is_object()) throw SceneError(key, "cannot set a key inside a non-object");
      node = &(*node)[name];
      i = end == std::string::npos ? key.size() : end;
    }
  }
  *node = value;
}

}  // namespace cleave
