// The scene sections every method reads the same way: units, analysis, damping, time, output,
// checks, regions and axes. A method's builder (mpm/mpm_scene.cpp, pd/pd_scene.cpp) reads these
// through here and only its own section ("mpm", "peridynamics") and what it builds from bodies and
// loads itself. Errors name the key path, as everywhere.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "libmpm/core/json_reader.hpp"
#include "libmpm/core/run_settings.hpp"
#include "libmpm/core/types.hpp"
#include "libmpm/core/units.hpp"

namespace cleave::scene {

// The array at root[key]; an empty array when absent and not required.
const nlohmann::json& array_at(const nlohmann::json& root, const char* key, bool required);

// "analysis": the type, and the thickness (in the scene's length unit times `length`; 1 m when absent).
Analysis read_analysis(const nlohmann::json& scene, double length, double& thickness);

// "static.tolerance" (default 1e-4 when "static" is given; 0 when absent: a dynamic run). Refuses a
// damping.kinetic beside it (the relaxation sets the damping).
double read_static(const nlohmann::json& scene, double damping);
// "damping.kinetic" (1/s), 0 when absent.
double read_damping(const nlohmann::json& scene, const UnitSystem& units);

// "time": end, and dt or cfl against the method's stable limit `stable_dt` (s). `limit` names the
// limit in the error message ("cell / (wave speed + particle speed)"). An infinite stable_dt (no
// stiffness anywhere) needs an explicit time.dt; `no_limit_reason` says why in that error.
void read_time(const nlohmann::json& scene, const UnitSystem& units, double stable_dt, const std::string& limit,
               const std::string& no_limit_reason, RunSettings& s);

// "output": interval (default end / 100), global_interval (interval / 10), tip_interval (rows of
// crack_tips.csv, every method; global_interval), fields (each one of `valid`; all by default),
// compression ("none" or "zlib") and precision ("float64" or "float32") of the frames.
// `qualifier` is added to the unknown-field message (" for peridynamics"). `has_tips`: the scene
// asks for a crack-tip table; output.tip_interval without one is an error.
template <class Names>
void read_output(const nlohmann::json& scene, const UnitSystem& units, const Names& valid, const std::string& qualifier,
                 bool has_tips, RunSettings& s);

// "checks.energy_blowup_factor" (> 1, default 10).
void read_checks(const nlohmann::json& scene, RunSettings& s);

// An axis name: x, y (and z in 3D).
template <int Dim>
int axis_of(const std::string& name, const std::string& path);

// r[key] = {"min": [...], "max": [...]} in the scene's length unit.
template <int Dim>
void read_region(const ObjectReader& r, const char* key, double length, Vec<Dim>& lo, Vec<Dim>& hi);

template <int Dim>
inline bool in_box(const Vec<Dim>& x, const Vec<Dim>& lo, const Vec<Dim>& hi, double tol) {
  for (int d = 0; d < Dim; ++d)
    if (x[d] < lo[d] - tol || x[d] > hi[d] + tol) return false;
  return true;
}

// Formats a number as %.6g (error messages print figures, not 0.000000).
std::string fmt(double v);

// ---- template definitions --------------------------------------------------------------------

template <class Names>
void read_output(const nlohmann::json& scene, const UnitSystem& units, const Names& valid, const std::string& qualifier,
                 bool has_tips, RunSettings& s) {
  const double T = units.factor(Quantity::Time);
  auto& o = s.output;
  o.interval = s.end_time / 100;
  o.fields = {std::begin(valid), std::end(valid)};
  o.global_interval = o.interval / 10;
  o.tip_interval = o.global_interval;
  if (!scene.contains("output") || scene["output"].is_null()) return;
  ObjectReader r(scene["output"], "output",
                 {"interval", "global_interval", "tip_interval", "fields", "compression", "precision"});
  if (r.has("tip_interval") && !has_tips)
    throw SceneError(r.at("tip_interval"), "the scene asks for no crack-tip table (MPM: \"crack_tips\"; "
                                           "peridynamics: \"peridynamics.crack_tips\")");
  o.interval = r.positive_or("interval", s.end_time / 100, T);
  if (r.has("fields")) o.fields = read_field_names(r["fields"], valid, qualifier);
  o.global_interval = r.positive_or("global_interval", o.interval / 10, T);
  o.tip_interval = r.positive_or("tip_interval", o.global_interval, T);
  // How frames are encoded (io/vtu_writer.hpp). The defaults keep raw Float64: exact, and the
  // fastest to write (docs/performance.md, "Output formats").
  const std::string comp = r.string_or("compression", "none"), prec = r.string_or("precision", "float64");
  if (comp != "none" && comp != "zlib")
    throw SceneError(r.at("compression"), "unknown compression '" + comp + "'; valid: none, zlib");
  if (prec != "float64" && prec != "float32")
    throw SceneError(r.at("precision"), "unknown precision '" + prec + "'; valid: float64, float32");
  o.zlib = comp == "zlib";
  o.float32 = prec == "float32";
}

template <int Dim>
int axis_of(const std::string& s, const std::string& path) {
  if (s == "x") return 0;
  if (s == "y") return 1;
  if (s == "z" && Dim == 3) return 2;
  throw SceneError(path, "unknown axis '" + s + "'; valid: " + std::string(Dim == 3 ? "x, y, z" : "x, y"));
}

template <int Dim>
void read_region(const ObjectReader& r, const char* key, double length, Vec<Dim>& lo, Vec<Dim>& hi) {
  ObjectReader rr(r[key], r.at(key), {"min", "max"});
  lo = rr.vec<Dim>("min", length);
  hi = rr.vec<Dim>("max", length);
  for (int d = 0; d < Dim; ++d)
    if (!(hi[d] >= lo[d])) throw SceneError(rr.at("max"), "region max is below region min");
}

}  // namespace cleave::scene
