#include "libmpm/scene/scene.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "libmpm/core/error.hpp"
#include "libmpm/scene/json_text.hpp"
#include "libmpm/scene/sections.hpp"

namespace cleave {

using nlohmann::json;

json load_scene_file(const std::filesystem::path& file) {
  // The reason names the file: an empty key path tells the CLI to print the reason alone.
  const std::string name = file.string();
  std::error_code ec;
  const auto st = std::filesystem::status(file, ec);
  if (!std::filesystem::exists(st)) throw SceneError("", "cannot open " + name + ": no such file");
  if (std::filesystem::is_directory(st)) throw SceneError("", "cannot open " + name + ": is a directory");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw SceneError("", "cannot open " + name + ": " + std::strerror(errno));
  // Read in blocks up to a cap, so that /dev/zero or an endless pipe is refused instead of read
  // until memory runs out (a scene is text of kilobytes; meshes and photographs are files of their own).
  std::string text;
  char block[1 << 16];
  while (in.read(block, sizeof block) || in.gcount() > 0) {
    text.append(block, static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxSceneFileBytes)
      throw SceneError("", "cannot read " + name + ": more than " + std::to_string(kMaxSceneFileBytes >> 20) +
                               " MiB, not a scene file (a scene is JSON text of kilobytes)");
  }
  if (in.bad()) throw SceneError("", "cannot read " + name + ": " + std::strerror(errno));
  return scene::parse_scene_text(text);
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

// Whether `s` is UTF-8: a scene file's strings are (the parser refuses others), but a --set word is
// taken as typed, and JSON that holds other bytes cannot be printed (dump() throws).
static bool is_utf8(const std::string& s) {
  try {
    (void)json(s).dump();
    return true;
  } catch (const json::type_error&) {
    return false;
  }
}

void apply_override(json& scene, const std::string& kv) {
  const auto eq = kv.find('=');
  if (eq == std::string::npos || eq == 0) throw SceneError(kv, "--set needs KEY=VALUE");
  const std::string key = kv.substr(0, eq), text = kv.substr(eq + 1);
  if (!is_utf8(key)) throw SceneError("(--set)", "--set key is not UTF-8 text");
  if (!is_utf8(text)) throw SceneError(key, "--set value is not UTF-8 text");
  json value;
  std::size_t value_nesting = 0;  // arrays and objects in one another in the value (json_text.hpp)
  const auto nesting = [&](int depth, json::parse_event_t event, json&) {
    if (event == json::parse_event_t::object_start || event == json::parse_event_t::array_start) {
      value_nesting = std::max(value_nesting, static_cast<std::size_t>(depth) + 1);
      if (value_nesting > scene::kMaxNesting)
        throw SceneError(key, "--set value nests arrays and objects more than " + std::to_string(scene::kMaxNesting) +
                                  " levels deep");
    }
    return true;
  };
  try {
    value = json::parse(text, nesting);
  } catch (const json::out_of_range& e) {  // 1e400: a number, but beyond a double's range
    throw SceneError(key, "--set value " + text + " is out of range (a double holds at most 1.8e308)");
  } catch (const json::exception&) {
    value = text;  // a bare word such as USL
    value_nesting = 0;
  }
  json* node = &scene;
  json* parent = nullptr;  // the object holding the last key, for a null that removes it
  std::string last_name;
  std::size_t i = 0, levels = 0;  // the containers the value will sit in
  while (i < key.size()) {
    if (++levels + value_nesting > scene::kMaxNesting)
      throw SceneError(key, "--set key and value nest arrays and objects more than " + std::to_string(scene::kMaxNesting) +
                           " levels deep");
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
      if (node->is_array())
        throw SceneError(key.substr(0, end == std::string::npos ? key.size() : end),
                         "is an array: index it as " + key.substr(0, i > 0 && key[i - 1] == '.' ? i - 1 : i) + "[" +
                             (name.find_first_not_of("0123456789") == std::string::npos ? name : "0") + "]");
      if (!node->is_null() && !node->is_object()) throw SceneError(key, "cannot set a key inside a non-object");
      parent = node, last_name = name;
      node = &(*node)[name];
      i = end == std::string::npos ? key.size() : end;
    }
  }
  // KEY=null removes the key: a scene with "mpm": {...} may run as peridynamics with --set mpm=null.
  if (value.is_null() && parent && i == key.size() && key.back() != ']') {
    parent->erase(last_name);
    return;
  }
  *node = value;
}

void apply_overrides(json& scene, const std::vector<std::string>& key_values) {
  // A later --set of the same key (or of a key above it) would replace an earlier one without a word.
  auto key_of = [](const std::string& kv) { return kv.substr(0, kv.find('=')); };
  for (std::size_t i = 0; i < key_values.size(); ++i)
    for (std::size_t j = i + 1; j < key_values.size(); ++j) {
      const std::string a = key_of(key_values[i]), b = key_of(key_values[j]);
      const bool covers = a.rfind(b, 0) == 0 && (a.size() == b.size() || a[b.size()] == '.' || a[b.size()] == '[');
      if (!b.empty() && covers)
        throw SceneError(a, "--set twice: '--set " + key_values[i] + "' (option " + std::to_string(i + 1) +
                                ") would be overridden by '--set " + key_values[j] + "' (option " +
                                std::to_string(j + 1) + "); give each key once");
    }
  for (const auto& kv : key_values) apply_override(scene, kv);
}

}  // namespace cleave
