// Registration of the linear elastic material, and the shared number reader.
#include "libmpm/material/linear_elastic.hpp"

namespace cleave {

double read_positive(const nlohmann::json& j, const std::string& key, const std::string& key_path,
                     double factor) {
  const std::string path = key_path + "." + key;
  if (!j.contains(key)) throw SceneError(path, "missing");
  if (!j[key].is_number()) throw SceneError(path, "expected a number");
  const double v = j[key].get<double>();
  if (!std::isfinite(v) || v <= 0.0)
    throw SceneError(path, "must be a positive number (got " + j[key].dump() + ")");
  return v * factor;
}

void register_builtin_materials() {
  static bool done = [] {
    MaterialRegistry<2>::instance().add("linear_elastic", [](const MaterialArgs& a) {
      return std::unique_ptr<Material<2>>(new LinearElastic<2>(a));
    });
    MaterialRegistry<3>::instance().add("linear_elastic", [](const MaterialArgs& a) {
      return std::unique_ptr<Material<3>>(new LinearElastic<3>(a));
    });
    return true;
  }();
  (void)done;
}

}  // namespace cleave
