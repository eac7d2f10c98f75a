// Units a scene may declare once, per kind of quantity ("units": {"length": "mm", "stress": "MPa"}).
// Every value read from the scene is multiplied by its kind's factor, so the library works in SI only.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

namespace cleave {

enum class Quantity { Length, Time, Mass, Stress, Density, Velocity, Acceleration, Force, InverseTime };

class UnitSystem {
 public:
  UnitSystem();  // all SI
  // Reads the scene's "units" object; throws SceneError("units.<kind>", ...) for unknown kinds or units.
  static UnitSystem from_json(const nlohmann::json& units, const std::string& key_path);
  double factor(Quantity q) const { return factor_[static_cast<int>(q)]; }
  double to_si(double v, Quantity q) const { return v * factor(q); }
  const std::string& name(Quantity q) const { return name_[static_cast<int>(q)]; }

 private:
  static constexpr int kKinds = 9;
  double factor_[kKinds];
  std::string name_[kKinds];
};

}  // namespace cleave
