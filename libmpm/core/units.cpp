#include "libmpm/core/units.hpp"

#include <map>
#include <utility>
#include <vector>

#include "libmpm/core/error.hpp"

namespace cleave {
namespace {

struct Kind {
  const char* key;
  Quantity q;
  std::vector<std::pair<const char*, double>> units;  // first entry is the SI unit
};

const std::vector<Kind>& kinds() {
  static const std::vector<Kind> k = {
      {"length", Quantity::Length, {{"m", 1.0}, {"cm", 1e-2}, {"mm", 1e-3}, {"um", 1e-6}}},
      {"time", Quantity::Time, {{"s", 1.0}, {"ms", 1e-3}, {"us", 1e-6}, {"ns", 1e-9}}},
      {"mass", Quantity::Mass, {{"kg", 1.0}, {"g", 1e-3}}},
      {"stress", Quantity::Stress, {{"Pa", 1.0}, {"kPa", 1e3}, {"MPa", 1e6}, {"GPa", 1e9}}},
      {"density", Quantity::Density, {{"kg/m3", 1.0}, {"g/cm3", 1e3}, {"g/mm3", 1e6}}},
      {"velocity", Quantity::Velocity, {{"m/s", 1.0}, {"mm/s", 1e-3}, {"mm/ms", 1.0}, {"mm/us", 1e3}}},
      {"acceleration", Quantity::Acceleration, {{"m/s2", 1.0}, {"mm/s2", 1e-3}, {"g0", 9.80665}}},
      {"force", Quantity::Force, {{"N", 1.0}, {"mN", 1e-3}, {"kN", 1e3}, {"kgf", 9.80665}, {"lbf", 4.4482216152605}}},
      {"inverse_time", Quantity::InverseTime, {{"1/s", 1.0}, {"1/ms", 1e3}, {"1/us", 1e6}}},
  };
  return k;
}

}  // namespace

UnitSystem::UnitSystem() {
  for (const auto& k : kinds()) {
    factor_[static_cast<int>(k.q)] = 1.0;
    name_[static_cast<int>(k.q)] = k.units.front().first;
  }
}

UnitSystem UnitSystem::from_json(const nlohmann::json& units, const std::string& key_path) {
  UnitSystem u;
  if (units.is_null()) return u;
  if (!units.is_object()) throw SceneError(key_path, "expected an object such as {\"length\": \"mm\"}");
  for (auto it = units.begin(); it != units.end(); ++it) {
    const Kind* kind = nullptr;
    std::string valid_kinds;
    for (const auto& k : kinds()) {
      valid_kinds += (valid_kinds.empty() ? "" : ", ") + std::string(k.key);
      if (it.key() == k.key) kind = &k;
    }
    const std::string path = key_path + "." + it.key();
    if (!kind) throw SceneError(path, "unknown quantity; valid: " + valid_kinds);
    if (!it->is_string()) throw SceneError(path, "expected a unit name (string)");
    const std::string unit = it->get<std::string>();
    std::string valid_units;
    bool found = false;
    for (const auto& [n, f] : kind->units) {
      valid_units += (valid_units.empty() ? "" : ", ") + std::string(n);
      if (unit == n) {
        u.factor_[static_cast<int>(kind->q)] = f;
        u.name_[static_cast<int>(kind->q)] = n;
        found = true;
      }
    }
    if (!found) throw SceneError(path, "unknown unit '" + unit + "'; valid: " + valid_units);
  }
  return u;
}

}  // namespace cleave
