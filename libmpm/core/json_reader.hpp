// Small helpers that read scene JSON with precise error messages: every failure names the key
// path ("time.dt") and the reason, and unknown keys are rejected rather than silently ignored.
#pragma once
#include <algorithm>
#include <cmath>
#include <iterator>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <span>
#include <cstdint>
#include <string>
#include <utility>

#include "libmpm/core/error.hpp"
#include "libmpm/core/types.hpp"

namespace cleave {

class ObjectReader {
 public:
  ObjectReader(const nlohmann::json& j, std::string path, std::initializer_list<const char*> allowed)
      : ObjectReader(j, std::move(path), std::span<const char* const>(allowed.begin(), allowed.size())) {}
  ObjectReader(const nlohmann::json& j, std::string path, std::span<const char* const> allowed)
      : j_(j), path_(std::move(path)) {
    if (!j.is_object()) throw SceneError(path_, "expected an object");
    for (auto it = j.begin(); it != j.end(); ++it) {
      bool ok = false;
      std::string valid;
      for (const char* a : allowed) {
        ok = ok || it.key() == a;
        valid += (valid.empty() ? "" : ", ") + std::string(a);
      }
      if (!ok) throw SceneError(at(it.key()), "unknown key; valid keys: " + valid);
    }
  }
  std::string at(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  const std::string& path() const { return path_; }
  bool has(const char* key) const { return j_.contains(key) && !j_[key].is_null(); }
  const nlohmann::json& operator[](const char* key) const { return j_[key]; }

  double number(const char* key, double scale = 1.0) const {
    if (!has(key)) throw SceneError(at(key), "missing");
    const double v = number_of(j_[key], at(key)) * scale;
    if (!std::isfinite(v)) throw SceneError(at(key), "overflows after unit scaling (got " + j_[key].dump() + ")");
    return v;
  }
  double number_or(const char* key, double fallback, double scale = 1.0) const {
    return has(key) ? number(key, scale) : fallback;
  }
  double positive(const char* key, double scale = 1.0) const {
    const double v = number(key, scale);
    if (!(v > 0.0)) throw SceneError(at(key), "must be positive (got " + j_[key].dump() + ")");
    return v;
  }
  double positive_or(const char* key, double fallback, double scale = 1.0) const {
    return has(key) ? positive(key, scale) : fallback;
  }
  int integer_or(const char* key, int fallback, int lo, int hi) const {
    if (!has(key)) return fallback;
    const auto& v = j_[key];
    if (!v.is_number_integer()) throw SceneError(at(key), "expected an integer");
    const auto i = integer_within(v, lo, hi);
    if (!i)
      throw SceneError(at(key), "must be between " + std::to_string(lo) + " and " + std::to_string(hi) +
                                    " (got " + v.dump() + ")");
    return static_cast<int>(*i);
  }
  // The JSON integer `v` when it lies in [lo, hi], else nothing (also for a non-integer). The one
  // place scene integers are range-checked: nlohmann keeps a non-negative integer as unsigned, and
  // one above 2^63 - 1 (18446744073709551615) read as a signed type wraps to a negative value that
  // could pass a lower bound or be printed as the value given (an error must print v.dump()).
  static std::optional<long long> integer_within(const nlohmann::json& v, long long lo, long long hi) {
    if (v.is_number_unsigned()) {
      const uint64_t u = v.get<uint64_t>();
      if (hi < 0 || u > static_cast<uint64_t>(hi) || (lo > 0 && u < static_cast<uint64_t>(lo))) return std::nullopt;
      return static_cast<long long>(u);
    }
    if (!v.is_number_integer()) return std::nullopt;
    const long long i = v.get<long long>();
    if (i < lo || i > hi) return std::nullopt;
    return i;
  }
  std::string string(const char* key) const {
    if (!has(key)) throw SceneError(at(key), "missing");
    if (!j_[key].is_string()) throw SceneError(at(key), "expected a string");
    return j_[key].get<std::string>();
  }
  std::string string_or(const char* key, const std::string& fallback) const {
    return has(key) ? string(key) : fallback;
  }
  bool boolean_or(const char* key, bool fallback) const {
    if (!has(key)) return fallback;
    if (!j_[key].is_boolean()) throw SceneError(at(key), "expected true or false (got " + j_[key].dump() + ")");
    return j_[key].get<bool>();
  }
  template <int Dim>
  Vec<Dim> vec(const char* key, double scale = 1.0) const {
    if (!has(key)) throw SceneError(at(key), "missing");
    return vec_of<Dim>(j_[key], at(key), scale);
  }

  // A vector whose components may be null (free): returns the bit mask of the given components and
  // their values (times scale). Errors name the key: not Dim entries, a non-number, all null.
  template <int Dim>
  std::pair<uint8_t, Vec<Dim>> partial_vec(const char* key, double scale) const {
    const nlohmann::json& vj = j_[key];
    if (!has(key) || !vj.is_array() || vj.size() != Dim)
      throw SceneError(at(key), "expected " + std::to_string(Dim) + " entries, each a number or null (free)");
    uint8_t mask = 0;
    Vec<Dim> v = Vec<Dim>::Zero();
    for (int d = 0; d < Dim; ++d) {
      if (vj[d].is_null()) continue;
      mask |= uint8_t(1u << d);
      const std::string p = at(key) + "[" + std::to_string(d) + "]";
      v[d] = number_of(vj[d], p) * scale;
      if (!std::isfinite(v[d])) throw SceneError(p, "overflows after unit scaling (got " + vj[d].dump() + ")");
    }
    if (!mask) throw SceneError(at(key), "every component is null: the condition does nothing");
    return {mask, v};
  }

  static double number_of(const nlohmann::json& v, const std::string& path) {
    if (!v.is_number()) throw SceneError(path, "expected a number (got " + v.dump() + ")");
    const double d = v.get<double>();
    if (!std::isfinite(d)) throw SceneError(path, "must be finite");
    return d;
  }
  template <int Dim>
  static Vec<Dim> vec_of(const nlohmann::json& v, const std::string& path, double scale = 1.0) {
    if (!v.is_array() || v.size() != static_cast<std::size_t>(Dim))
      throw SceneError(path, "expected " + std::to_string(Dim) + " numbers (" +
                                 (Dim == 2 ? "[x, y]" : "[x, y, z]") + ") for this " +
                                 std::to_string(Dim) + "D scene");
    Vec<Dim> r;
    for (int d = 0; d < Dim; ++d) {
      const std::string p = path + "[" + std::to_string(d) + "]";
      r[d] = number_of(v[d], p) * scale;
      if (!std::isfinite(r[d])) throw SceneError(p, "overflows after unit scaling (got " + v[d].dump() + ")");
    }
    return r;
  }

 private:
  const nlohmann::json& j_;
  std::string path_;
};

// Key path of element i of the array at `base`: "bodies[2]".
inline std::string index_path(const std::string& base, std::size_t i) { return base + "[" + std::to_string(i) + "]"; }

// Reads "output.fields" (an array of field names, each one of `valid`); `qualifier` is added to the
// unknown-name error (" for peridynamics").
template <class Names>
std::set<std::string> read_field_names(const nlohmann::json& f, const Names& valid, const std::string& qualifier = "") {
  if (!f.is_array()) throw SceneError("output.fields", "expected an array of field names");
  std::set<std::string> out;
  for (std::size_t i = 0; i < f.size(); ++i) {
    const std::string p = index_path("output.fields", i);
    if (!f[i].is_string()) throw SceneError(p, "expected a field name");
    const std::string name = f[i].get<std::string>();
    if (std::find(std::begin(valid), std::end(valid), name) == std::end(valid)) {
      std::string list;
      for (const char* n : valid) list += (list.empty() ? "" : ", ") + std::string(n);
      throw SceneError(p, "unknown field '" + name + "'" + qualifier + "; valid: " + list);
    }
    out.insert(name);
  }
  return out;
}

}  // namespace cleave
