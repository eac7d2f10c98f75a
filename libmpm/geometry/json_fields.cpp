#include "libmpm/geometry/json_fields.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "libmpm/core/error.hpp"

namespace cleave::geom::detail {

std::string key_path(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}

std::string index_path(const std::string& parent, std::size_t i) {
  return parent + "[" + std::to_string(i) + "]";
}

std::string join(const std::vector<std::string>& items) {
  std::string s;
  for (const auto& item : items) s += (s.empty() ? "" : ", ") + item;
  return s;
}

std::string describe(const nlohmann::json& v) {
  switch (v.type()) {
    case nlohmann::json::value_t::null: return "null";
    case nlohmann::json::value_t::boolean: return v.get<bool>() ? "true" : "false";
    case nlohmann::json::value_t::object: return "an object";
    case nlohmann::json::value_t::array: return "an array of " + std::to_string(v.size()) + " elements";
    case nlohmann::json::value_t::string: {
      // Keep one-line messages one line, even for a pasted paragraph.
      std::string s = v.dump();
      if (s.size() > 40) s = s.substr(0, 37) + "...\"";
      return "the string " + s;
    }
    default: {
      // dump() writes NaN and infinity as null, which would hide the actual problem.
      std::ostringstream os;
      os << v.get<double>();
      return "the number " + os.str();
    }
  }
}

void reject_unknown_keys(const nlohmann::json& obj, const std::string& path,
                         const std::vector<std::string>& valid) {
  for (const auto& [key, value] : obj.items()) {
    if (std::find(valid.begin(), valid.end(), key) == valid.end())
      throw SceneError(key_path(path, key), "unknown key '" + key + "'; valid keys: " + join(valid));
  }
}

const nlohmann::json& require(const nlohmann::json& obj, const std::string& key, const std::string& path) {
  auto it = obj.find(key);
  if (it == obj.end()) throw SceneError(key_path(path, key), "missing required key '" + key + "'");
  return *it;
}

double read_number(const nlohmann::json& v, const std::string& path) {
  if (!v.is_number()) throw SceneError(path, "expected a number, got " + describe(v));
  const double x = v.get<double>();
  if (!std::isfinite(x)) throw SceneError(path, "expected a finite number, got " + describe(v));
  return x;
}

std::vector<double> read_numbers(const nlohmann::json& v, const std::string& path,
                                 const std::vector<std::string>& labels) {
  const std::string expected =
      "expected " + std::to_string(labels.size()) + " numbers [" + join(labels) + "]";
  if (!v.is_array()) throw SceneError(path, expected + ", got " + describe(v));
  if (v.size() != labels.size())
    throw SceneError(path, expected + ", got " + std::to_string(v.size()) + " elements");
  std::vector<double> out;
  for (std::size_t i = 0; i < v.size(); ++i) out.push_back(read_number(v[i], index_path(path, i)));
  return out;
}

}  // namespace cleave::geom::detail
