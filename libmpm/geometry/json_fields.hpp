// Small JSON readers for the shape parser. Each checks one value and throws a SceneError that
// names the exact scene key path of the offending value, with a reason a user can act on.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace cleave::geom::detail {

// "parent.key" (or just "key" at the root) and "parent[i]".
std::string key_path(const std::string& parent, const std::string& key);
std::string index_path(const std::string& parent, std::size_t i);

// "a, b, c"
std::string join(const std::vector<std::string>& items);

// What a JSON value is, for "got ..." in messages: "the string \"abc\"", "an object", ...
std::string describe(const nlohmann::json& v);

// Throws for the first key of `obj` not in `valid` ("unknown key 'radus'; valid keys: ...").
void reject_unknown_keys(const nlohmann::json& obj, const std::string& path,
                         const std::vector<std::string>& valid);

// obj[key]; throws at path.key if absent.
const nlohmann::json& require(const nlohmann::json& obj, const std::string& key, const std::string& path);

// A finite JSON number (booleans are not numbers).
double read_number(const nlohmann::json& v, const std::string& path);

// An array of exactly labels.size() finite numbers, e.g. labels {"x", "y"} gives the reason
// "expected 2 numbers [x, y]". Element errors name path[i].
std::vector<double> read_numbers(const nlohmann::json& v, const std::string& path,
                                 const std::vector<std::string>& labels);

}  // namespace cleave::geom::detail
