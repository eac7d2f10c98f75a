#include "libmpm/scene/sections.hpp"

#include <cmath>
#include <cstdio>

#include "libmpm/scene/budget.hpp"

namespace cleave::scene {

using nlohmann::json;

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

const json& array_at(const json& root, const char* key, bool required) {
  static const json empty = json::array();
  if (!root.contains(key) || root[key].is_null()) {
    if (required) throw SceneError(key, "missing");
    return empty;
  }
  if (!root[key].is_array()) throw SceneError(key, "expected an array");
  return root[key];
}

Analysis read_analysis(const json& scene, double length, double& thickness) {
  if (!scene.contains("analysis")) throw SceneError("analysis", "missing (plane_strain, plane_stress or 3d)");
  ObjectReader r(scene["analysis"], "analysis", {"type", "thickness"});
  const std::string type = r.string("type");
  Analysis a;
  if (type == "plane_strain") a = Analysis::PlaneStrain;
  else if (type == "plane_stress") a = Analysis::PlaneStress;
  else if (type == "3d") a = Analysis::ThreeD;
  else throw SceneError("analysis.type", "unknown analysis '" + type + "'; valid: plane_strain, plane_stress, 3d");
  if (a == Analysis::ThreeD && r.has("thickness"))
    throw SceneError("analysis.thickness", "a 3D analysis has no thickness");
  if (a == Analysis::PlaneStress && !r.has("thickness"))
    throw SceneError("analysis.thickness", "missing: a plane-stress analysis needs the specimen thickness");
  thickness = r.positive_or("thickness", 1.0, length);  // default: unit depth, 1 m
  return a;
}

double read_damping(const json& scene, const UnitSystem& units) {
  if (!scene.contains("damping") || scene["damping"].is_null()) return 0.0;
  ObjectReader r(scene["damping"], "damping", {"kinetic"});
  const double k = r.number_or("kinetic", 0.0, units.factor(Quantity::InverseTime));
  if (k < 0) throw SceneError("damping.kinetic", "must not be negative");
  return k;
}

double read_static(const json& scene, double damping) {
  if (!scene.contains("static") || scene["static"].is_null()) return 0.0;
  ObjectReader r(scene["static"], "static", {"tolerance"});
  const double tol = r.number_or("tolerance", 1e-4, 1.0);
  if (!(tol > 0 && tol < 0.1))
    throw SceneError("static.tolerance", "must be between 0 and 0.1 (the relative change of the strain energy over a "
                                         "period at which the state counts as static; 1e-4 gives K to about 5e-5)");
  if (damping > 0)
    throw SceneError("damping.kinetic", "a static scene sets its damping itself (critical for the lowest mode): leave "
                                        "out damping.kinetic");
  return tol;
}

void read_time(const json& scene, const UnitSystem& units, double stable_dt, const std::string& limit,
               const std::string& no_limit_reason, RunSettings& s) {
  if (!scene.contains("time") || scene["time"].is_null()) throw SceneError("time", "missing (needs at least time.end)");
  ObjectReader r(scene["time"], "time", {"end", "dt", "cfl"});
  const double T = units.factor(Quantity::Time);
  s.stable_dt = stable_dt;
  s.end_time = r.positive("end", T);
  if (r.has("dt") && r.has("cfl")) throw SceneError("time.cfl", "give time.dt or time.cfl, not both");
  if (!std::isfinite(stable_dt)) {
    if (!r.has("dt")) throw SceneError("time.dt", "missing: " + no_limit_reason);
    s.dt = r.positive("dt", T);
  } else if (r.has("dt")) {
    s.dt = r.positive("dt", T);
    if (s.dt > stable_dt)
      throw SceneError("time.dt", "above the stable limit: dt = " + fmt(s.dt) + " s > " + limit + " = " +
                                      fmt(stable_dt) + " s; use a smaller dt or time.cfl");
  } else {
    // A static scene (dynamic relaxation) needs stability, not the transient's accuracy: 0.9.
    const double cfl = r.positive_or("cfl", s.static_tolerance > 0 ? 0.9 : 0.5);
    if (cfl > 1.0) throw SceneError("time.cfl", "must be at most 1 (got " + fmt(cfl) + ")");
    s.dt = cfl * stable_dt;
  }
  check_step_count(s);  // scene/budget.hpp: before anything is built or written
}

void read_checks(const json& scene, RunSettings& s) {
  if (!scene.contains("checks") || scene["checks"].is_null()) return;
  ObjectReader r(scene["checks"], "checks", {"energy_blowup_factor"});
  s.energy_blowup_factor = r.positive_or("energy_blowup_factor", 10.0);
  if (s.energy_blowup_factor <= 1.0)
    throw SceneError("checks.energy_blowup_factor", "must be greater than 1 (a run's energy is compared with this "
                                                    "multiple of its initial energy plus external work)");
}

template int axis_of<2>(const std::string&, const std::string&);
template int axis_of<3>(const std::string&, const std::string&);

}  // namespace cleave::scene
