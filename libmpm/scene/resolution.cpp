#include "libmpm/scene/resolution.hpp"

#include <cmath>

#include "libmpm/core/error.hpp"
#include "libmpm/core/json_reader.hpp"

namespace cleave::scene {

Resolution read_resolution(const nlohmann::json& scene, const std::string& section_path, const char* key,
                       const std::string& meaning, double length) {
  const std::string own = section_path + "." + key;
  const bool has_own = scene.contains(section_path) && scene[section_path].is_object() &&
                       scene[section_path].contains(key);
  const bool has_common = scene.contains("resolution");
  if (has_own && has_common)
    throw SceneError(own, "give \"resolution\" or \"" + own + "\" (the same length), not both");
  if (!has_own && !has_common)
    throw SceneError("resolution", "missing: the discretisation length (" + meaning + "), in the scene's length unit");
  const std::string path = has_common ? "resolution" : own;
  const nlohmann::json& v = has_common ? scene["resolution"] : scene[section_path][key];
  const double h = ObjectReader::number_of(v, path) * length;
  if (!(h > 0.0)) throw SceneError(path, "must be positive (got " + v.dump() + ")");
  if (!std::isfinite(h)) throw SceneError(path, "overflows after unit scaling (got " + v.dump() + ")");
  return {h, path};
}

}  // namespace cleave::scene
