#include "study/study_spec.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <set>

#include "libmpm/core/json_reader.hpp"
#include "libmpm/reference/closed_form.hpp"
#include "libmpm/scene/scene.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace cleave::study {
namespace {

std::string index_key(const std::string& base, std::size_t i) { return base + "[" + std::to_string(i) + "]"; }

const json& array_at(const ObjectReader& r, const char* key, bool non_empty) {
  const json& a = r[key];
  if (!a.is_array()) throw SceneError(r.at(key), "expected an array");
  if (non_empty && a.empty()) throw SceneError(r.at(key), "is empty: nothing to run");
  return a;
}

std::vector<Setting> read_settings(const json& j, const std::string& key) {
  if (!j.is_object()) throw SceneError(key, "expected an object of scene keys and values ({\"time.end\": 0.1})");
  std::vector<Setting> s;
  for (auto it = j.begin(); it != j.end(); ++it) s.push_back({it.key(), it.value()});
  return s;
}

double finite_number(const json& v, const std::string& key) {
  if (!v.is_number()) throw SceneError(key, "expected a number");
  const double d = v.get<double>();
  if (!std::isfinite(d)) throw SceneError(key, "must be finite");
  return d;
}

Expectation read_expectation(const json& j, const std::string& key) {
  Expectation e;
  if (j.is_string()) {
    e.outcome = j.get<std::string>();
  } else {
    ObjectReader r(j, key, {"outcome", "energy_drift", "cause"});
    e.outcome = r.string("outcome");
    if (r.has("energy_drift")) e.energy_drift = r.positive("energy_drift");
    e.cause = r.string_or("cause", "");
  }
  static const std::set<std::string> kOutcomes{"complete", "stop", "refuse", "complete_or_stop"};
  if (!kOutcomes.count(e.outcome))
    throw SceneError(key + (j.is_string() ? "" : ".outcome"),
                     "unknown outcome '" + e.outcome + "'; valid: complete, stop, refuse, complete_or_stop");
  return e;
}

Reference read_reference(const json& j, const std::string& key, const fs::path& dir) {
  Reference ref;
  ref.key = key;
  ObjectReader r(j, key, {"closed_form", "values", "finest", "value", "file", "points", "time_column", "column",
                          "image", "map", "field", "mask"});
  int kinds = r.has("closed_form") + r.has("finest") + r.has("value") + r.has("file") + r.has("points") + r.has("image");
  if (kinds != 1)
    throw SceneError(key, "give exactly one of closed_form, finest, value, file, points or image");
  if (!r.has("image"))
    for (const char* k : {"map", "field", "mask"})
      if (r.has(k)) throw SceneError(r.at(k), "only for an image reference");
  if (r.has("closed_form")) {
    ref.kind = Reference::Kind::ClosedForm;
    ref.closed_form = r.string("closed_form");
    std::unique_ptr<reference::ClosedForm> form;
    try {
      form = reference::make_closed_form(ref.closed_form);
    } catch (const std::invalid_argument& e) {
      throw SceneError(r.at("closed_form"), e.what());
    }
    if (r.has("values")) {
      const json& v = r["values"];
      if (!v.is_object()) throw SceneError(r.at("values"), "expected an object");
      std::set<std::string> known;
      for (const auto& p : form->parameters()) known.insert(p.name);
      for (auto it = v.begin(); it != v.end(); ++it) {
        const std::string k = r.at("values") + "." + it.key();
        if (!known.count(it.key())) {
          std::string names;
          for (const auto& p : form->parameters()) names += (names.empty() ? "" : ", ") + p.name;
          throw SceneError(k, "'" + ref.closed_form + "' takes no value of that name; it takes " + names);
        }
        if (!(it.value().is_number() || it.value().is_string()))
          throw SceneError(k, "expected a number (SI) or a scene key path (\"materials[0].E\")");
        if (it.value().is_number()) finite_number(it.value(), k);
        ref.values[it.key()] = it.value();
      }
    }
  } else if (r.has("finest")) {
    if (!r["finest"].is_boolean() || !r["finest"].get<bool>()) throw SceneError(r.at("finest"), "expected true");
    ref.kind = Reference::Kind::Finest;
  } else if (r.has("value")) {
    ref.kind = Reference::Kind::Value;
    ref.value = r.number("value");
  } else if (r.has("file")) {
    ref.kind = Reference::Kind::File;
    ref.file = dir / r.string("file");
    ref.column = r.string("column");
    ref.time_column = r.string_or("time_column", "time_s");
  } else if (r.has("points")) {
    ref.kind = Reference::Kind::Points;
    ref.file = dir / r.string("points");
  } else {
    ref.kind = Reference::Kind::Image;
    ref.file = dir / r.string("image");
    const json& m = r["map"];
    if (!m.is_array() || m.size() < 3 || m.size() > 4)
      throw SceneError(r.at("map"), "expected [x0, y0, metres per pixel(, angle in degrees)]: the model coordinates of "
                                    "the photo's top-left corner, as cleave compare --map (in metres)");
    for (std::size_t i = 0; i < m.size(); ++i) ref.map[i] = finite_number(m[i], index_key(r.at("map"), i));
    if (!(ref.map[2] > 0)) throw SceneError(index_key(r.at("map"), 2), "must be positive");
    ref.map[3] *= M_PI / 180;
    const std::string field = r.string_or("field", "dark");
    if (field != "dark" && field != "light") throw SceneError(r.at("field"), "expected dark or light");
    ref.light_field = field == "light";
    if (r.has("mask")) {
      ref.mask = dir / r.string("mask");
      if (!fs::is_regular_file(ref.mask)) throw SceneError(r.at("mask"), "cannot open " + ref.mask.string());
    }
  }
  for (const char* k : {"file", "points", "image"})
    if (r.has(k) && !fs::is_regular_file(ref.file)) throw SceneError(r.at(k), "cannot open " + ref.file.string());
  if (ref.kind != Reference::Kind::File && (r.has("column") || r.has("time_column")))
    throw SceneError(r.at(r.has("column") ? "column" : "time_column"), "only for a reference file");
  if (ref.kind != Reference::Kind::ClosedForm && r.has("values"))
    throw SceneError(r.at("values"), "only for a closed form");
  return ref;
}

QuantitySpec read_quantity(const json& j, const std::string& key, const fs::path& dir) {
  ObjectReader r(j, key, {"name", "kind", "file", "column", "where", "at", "window", "max", "reference", "tolerances",
                          "fringe_constant", "thickness", "grid", "centre", "radius", "key"});
  QuantitySpec q;
  q.key = key;
  q.name = r.string("name");
  const std::string kind = r.string_or("kind", "column");
  if (kind == "column") q.kind = QuantitySpec::Kind::Column;
  else if (kind == "energy_drift") q.kind = QuantitySpec::Kind::EnergyDrift;
  else if (kind == "fringe_rms") q.kind = QuantitySpec::Kind::FringeRms;
  else if (kind == "run_info") q.kind = QuantitySpec::Kind::RunInfo;
  else throw SceneError(r.at("kind"), "unknown quantity kind '" + kind + "'; valid: column, energy_drift, fringe_rms, "
                                      "run_info");
  if (q.kind == QuantitySpec::Kind::RunInfo) q.info_key = r.string("key");
  else if (r.has("key")) throw SceneError(r.at("key"), "only for a quantity of kind run_info");
  if (q.kind == QuantitySpec::Kind::Column) {
    q.column = r.string("column");
    q.file = r.string_or("file", "crack_tips.csv");
    static const std::set<std::string> kFiles{"crack_tips.csv", "crack_fronts.csv", "global.csv"};
    if (!kFiles.count(q.file))
      throw SceneError(r.at("file"), "'" + q.file + "' is not a table a run writes; valid: global.csv, crack_tips.csv, "
                                     "crack_fronts.csv");
    if (r.has("where")) {
      const json& w = r["where"];
      if (!w.is_object()) throw SceneError(r.at("where"), "expected an object ({\"tip\": 1})");
      for (auto it = w.begin(); it != w.end(); ++it) q.where[it.key()] = finite_number(it.value(), r.at("where") + "." + it.key());
    }
    const int whens = r.has("at") + r.has("window") + r.has("max");
    if (whens > 1) throw SceneError(key, "give at most one of at, window and max");
    if (r.has("at")) q.when = QuantitySpec::When::At, q.at = r.number("at");
    if (r.has("max")) {
      if (!r["max"].is_boolean() || !r["max"].get<bool>()) throw SceneError(r.at("max"), "expected true");
      q.when = QuantitySpec::When::Max;
    }
    if (r.has("window")) {
      const json& w = r["window"];
      if (!w.is_array() || w.size() != 2) throw SceneError(r.at("window"), "expected [t0, t1] in seconds");
      q.t0 = finite_number(w[0], r.at("window") + "[0]"), q.t1 = finite_number(w[1], r.at("window") + "[1]");
      if (!(q.t1 > q.t0)) throw SceneError(r.at("window"), "t1 must be after t0");
      q.when = QuantitySpec::When::Window;
    }
  } else {
    for (const char* k : {"column", "file", "where", "window", "max"})
      if (r.has(k)) throw SceneError(r.at(k), "not for a quantity of kind " + kind);
  }
  if (q.kind == QuantitySpec::Kind::FringeRms) {
    q.at = r.number("at");
    q.fringe_constant = r.positive("fringe_constant");
    q.thickness = r.positive("thickness");
    if (r.has("grid") || r.has("radius") || r.has("centre")) {
      q.grid = r.positive("grid"), q.radius = r.positive("radius");
      const json& c = r["centre"];
      if (!c.is_array() || c.size() != 2) throw SceneError(r.at("centre"), "expected [x, y] in metres");
      q.centre = {finite_number(c[0], r.at("centre") + "[0]"), finite_number(c[1], r.at("centre") + "[1]")};
    }
  }
  if (r.has("reference")) q.reference = read_reference(r["reference"], r.at("reference"), dir);
  using RK = Reference::Kind;
  if (q.kind == QuantitySpec::Kind::FringeRms) {
    const RK k = q.reference.kind;
    if ((k == RK::Points || k == RK::Image) ? q.grid > 0 : k != RK::ClosedForm)
      throw SceneError(r.at("reference"), "a fringe_rms quantity takes a field closed form with grid, centre and "
                                          "radius, or digitised points (x, y, N) or a photo without them");
    if (k == RK::ClosedForm && !reference::make_closed_form(q.reference.closed_form)->field())
      throw SceneError(r.at("reference") + ".closed_form", "'" + q.reference.closed_form + "' is not a stress field");
    if (k == RK::ClosedForm && !(q.grid > 0)) throw SceneError(r.at("grid"), "missing (points of the closed form)");
  } else if (q.reference.kind == RK::Points || q.reference.kind == RK::Image) {
    throw SceneError(r.at("reference") + (q.reference.kind == RK::Points ? ".points" : ".image"),
                     "only for a fringe_rms quantity");
  } else if (q.reference.kind == RK::ClosedForm && reference::make_closed_form(q.reference.closed_form)->field()) {
    throw SceneError(r.at("reference") + ".closed_form",
                     "'" + q.reference.closed_form + "' is a stress field: measure it with a fringe_rms quantity");
  }
  if (r.has("tolerances")) {
    const json& t = r["tolerances"];
    if (!t.is_array()) throw SceneError(r.at("tolerances"), "expected an array of relative errors ([0.05, 0.02])");
    for (std::size_t i = 0; i < t.size(); ++i) {
      const double v = finite_number(t[i], index_key(r.at("tolerances"), i));
      if (!(v > 0)) throw SceneError(index_key(r.at("tolerances"), i), "must be positive");
      q.tolerances.push_back(v);
    }
    if ((q.kind == QuantitySpec::Kind::Column || q.kind == QuantitySpec::Kind::RunInfo) && q.reference.kind == RK::None)
      throw SceneError(r.at("tolerances"), "need a reference to measure errors against");
  }
  return q;
}

std::string safe_label(const std::string& s) {
  std::string o;
  for (char c : s) o += (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_') ? c : '_';
  return o;
}

}  // namespace

std::string value_text(const json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number()) {
    char b[64];
    std::snprintf(b, sizeof b, "%g", v.get<double>());
    return b;
  }
  return v.dump();
}

std::string settings_text(const std::vector<Setting>& s) {
  std::string t;
  for (const auto& x : s) t += (t.empty() ? "" : ", ") + x.key + "=" + value_text(x.value);
  return t;
}

Study read_study(const fs::path& file) {
  try {
    const json j = load_scene_file(file);
    ObjectReader r(j, "", {"title", "description", "scene", "set", "vary", "runs", "cell_size", "series", "quantities",
                           "threads"});
    Study st;
    st.file = fs::absolute(file);
    const fs::path dir = st.file.parent_path();
    st.title = r.string_or("title", file.stem().string());
    st.description = r.string_or("description", "");
    st.threads = r.integer_or("threads", 0, 1, 4096);
    const fs::path base_scene = r.has("scene") ? (dir / r.string("scene")).lexically_normal() : fs::path();
    const std::vector<Setting> common = r.has("set") ? read_settings(r["set"], "set") : std::vector<Setting>{};
    if (!r.has("vary") && !r.has("runs")) throw SceneError("vary", "missing: give the settings to vary, or runs");

    // vary: the Cartesian product, the first key outermost.
    std::vector<std::vector<Setting>> combos{{}};
    if (r.has("vary")) {
      const json& v = array_at(r, "vary", true);
      for (std::size_t i = 0; i < v.size(); ++i) {
        const std::string k = index_key("vary", i);
        ObjectReader vr(v[i], k, {"key", "values"});
        const std::string key = vr.string("key");
        for (const auto& other : st.varied_keys)
          if (other == key) throw SceneError(vr.at("key"), "'" + key + "' is varied twice");
        const json& vals = array_at(vr, "values", true);
        st.varied_keys.push_back(key);
        std::vector<std::vector<Setting>> next;
        for (const auto& c : combos)
          for (const auto& val : vals) {
            auto n = c;
            n.push_back({key, val});
            next.push_back(std::move(n));
          }
        combos = std::move(next);
      }
      if (base_scene.empty()) throw SceneError("scene", "missing: the base scene whose keys vary");
      for (const auto& c : combos) {
        RunPlan p;
        p.scene = base_scene;
        p.settings = common;
        p.settings.insert(p.settings.end(), c.begin(), c.end());
        p.varied = c;
        std::string label;
        for (const auto& s : c) label += (label.empty() ? "" : "__") + s.key + "_" + value_text(s.value);
        p.label = safe_label(label);
        st.runs.push_back(std::move(p));
      }
    }
    if (r.has("runs")) {
      const json& runs = array_at(r, "runs", true);
      for (std::size_t i = 0; i < runs.size(); ++i) {
        const std::string k = index_key("runs", i);
        ObjectReader rr(runs[i], k, {"label", "scene", "set", "expect"});
        RunPlan p;
        p.label = safe_label(rr.string("label"));
        p.named = true;
        if (rr.has("scene")) p.scene = (dir / rr.string("scene")).lexically_normal();
        else if (!base_scene.empty()) p.scene = base_scene;
        else throw SceneError(rr.at("scene"), "missing (and the study names no base scene)");
        p.settings = common;
        if (rr.has("set")) {
          p.varied = read_settings(rr["set"], rr.at("set"));
          p.settings.insert(p.settings.end(), p.varied.begin(), p.varied.end());
        }
        if (rr.has("expect")) p.expect = read_expectation(rr["expect"], rr.at("expect"));
        for (const auto& s : p.varied)  // a run's own keys are the study's columns too
          if (std::find(st.varied_keys.begin(), st.varied_keys.end(), s.key) == st.varied_keys.end())
            st.varied_keys.push_back(s.key);
        st.runs.push_back(std::move(p));
      }
    }
    std::set<std::string> labels;
    const std::size_t from_vary = r.has("vary") ? combos.size() : 0;
    for (std::size_t i = 0; i < st.runs.size(); ++i)
      if (!labels.insert(st.runs[i].label).second)
        throw SceneError(i >= from_vary ? index_key("runs", i - from_vary) + ".label" : "vary",
                         "two runs share the folder name '" + st.runs[i].label + "'");

    if (r.has("cell_size")) {
      st.cell_key = r.string("cell_size");
      if (std::find(st.varied_keys.begin(), st.varied_keys.end(), st.cell_key) == st.varied_keys.end())
        throw SceneError("cell_size", "'" + st.cell_key + "' is not one of the varied keys");
    } else {
      for (const char* k : {"resolution", "grid.cell_size", "horizon.spacing", "pd.spacing"})
        if (std::find(st.varied_keys.begin(), st.varied_keys.end(), k) != st.varied_keys.end()) st.cell_key = k;
    }
    if (r.has("series")) {
      const json& s = array_at(r, "series", false);
      for (std::size_t i = 0; i < s.size(); ++i) {
        if (!s[i].is_string()) throw SceneError(index_key("series", i), "expected a varied key");
        const std::string key = s[i].get<std::string>();
        if (std::find(st.varied_keys.begin(), st.varied_keys.end(), key) == st.varied_keys.end())
          throw SceneError(index_key("series", i), "'" + key + "' is not one of the varied keys");
        st.series_keys.push_back(key);
      }
    } else {
      for (const auto& k : st.varied_keys)
        if (k != st.cell_key) st.series_keys.push_back(k);
    }
    if (r.has("quantities")) {
      const json& q = array_at(r, "quantities", false);
      std::set<std::string> names;
      for (std::size_t i = 0; i < q.size(); ++i) {
        st.quantities.push_back(read_quantity(q[i], index_key("quantities", i), dir));
        if (!names.insert(st.quantities.back().name).second)
          throw SceneError(index_key("quantities", i) + ".name", "'" + st.quantities.back().name + "' is named twice");
        if (st.quantities.back().reference.kind == Reference::Kind::Finest && st.cell_key.empty())
          throw SceneError(index_key("quantities", i) + ".reference.finest",
                           "needs a varied cell size (resolution or grid.cell_size, or cell_size naming the key)");
      }
    }
    return st;
  } catch (const SceneError& e) {
    throw StudyError(e.key_path().empty() ? file.string() : e.key_path(), e.reason());
  }
}

}  // namespace cleave::study
