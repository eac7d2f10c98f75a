#include "study/measure.hpp"

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "libmpm/core/error.hpp"
#include "viz/job/fringe_fit_job.hpp"
#include "viz/job/photo_field.hpp"
#include "viz/render/headless.hpp"
#include "viz/optics/photoelastic.hpp"
#include "viz/raster/series.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace cleave::study {
namespace {


// "materials[0].E" in a scene: nullptr when a step is missing.
const json* find_key(const json& scene, const std::string& path) {
  const json* j = &scene;
  std::size_t i = 0;
  while (i < path.size()) {
    if (path[i] == '.') ++i;
    if (path[i] == '[') {
      const std::size_t close = path.find(']', i);
      if (close == std::string::npos || !j->is_array()) return nullptr;
      const std::size_t k = std::stoul(path.substr(i + 1, close - i - 1));
      if (k >= j->size()) return nullptr;
      j = &(*j)[k], i = close + 1;
      continue;
    }
    const std::size_t end = path.find_first_of(".[", i);
    const std::string name = path.substr(i, end == std::string::npos ? std::string::npos : end - i);
    if (!j->is_object() || !j->contains(name)) return nullptr;
    j = &(*j)[name], i = end == std::string::npos ? path.size() : end;
  }
  return j;
}

Measurement failed(std::string why) {
  Measurement m;
  m.problem = std::move(why);
  return m;
}

Measurement column_quantity(const QuantitySpec& q, const fs::path& dir) {
  const fs::path file = dir / q.file;
  if (!fs::exists(file)) return failed(q.file + " not written (the scene writes no such table)");
  const Series s = column_series(read_table(file), file, q.column, q.where);
  Measurement m;
  switch (q.when) {
    case QuantitySpec::When::Last: m.value = s.y.back(), m.time = s.t.back(); break;
    case QuantitySpec::When::At:
      if (q.at > s.t.back() * (1 + 1e-9) || q.at < s.t.front()) {
        std::ostringstream o;
        o << "the run's " << q.file << " ends at t = " << s.t.back() << " s, before " << q.at << " s";
        return failed(o.str());
      }
      m.value = interpolate(s, q.at), m.time = q.at;
      break;
    case QuantitySpec::When::Max:
      m.value = 0;
      for (std::size_t i = 0; i < s.y.size(); ++i)
        if (std::fabs(s.y[i]) > m.value) m.value = std::fabs(s.y[i]), m.time = s.t[i];
      break;
    case QuantitySpec::When::Window: {
      double ss = 0;
      for (std::size_t i = 0; i < s.t.size(); ++i)
        if (s.t[i] >= q.t0 && s.t[i] <= q.t1) m.series.t.push_back(s.t[i]), m.series.y.push_back(s.y[i]), ss += s.y[i] * s.y[i];
      if (m.series.t.empty()) return failed("no row of " + q.file + " lies in the window");
      m.value = std::sqrt(ss / m.series.t.size());
      break;
    }
  }
  if (!std::isfinite(m.value)) return failed(q.column + " is not a finite number");
  return m;
}

// The energy that external work does not account for, largest over the run, as a fraction of the
// largest energy the run held (kinetic + strain, or the work done): 0 for an exact integrator of an
// undamped body; damping and contact losses count in it.
Measurement energy_drift(const fs::path& dir) {
  const fs::path file = dir / "global.csv";
  if (!fs::exists(file)) return failed("global.csv not written");
  const Table t = read_table(file);
  const int e = t.column("total_energy_J"), w = t.column("external_work_J");
  if (e < 0 || w < 0 || t.rows.empty()) return failed("global.csv has no total_energy_J / external_work_J rows");
  const double base = t.rows.front()[e] - t.rows.front()[w];
  double drift = 0, scale = 0;
  for (const auto& r : t.rows) {
    if (!std::isfinite(r[e]) || !std::isfinite(r[w])) return failed("global.csv holds a non-finite energy");
    drift = std::max(drift, std::fabs(r[e] - r[w] - base));
    scale = std::max({scale, std::fabs(r[e]), std::fabs(r[w])});
  }
  Measurement m;
  m.value = scale > 0 ? drift / scale : 0.0;
  return m;
}

std::vector<viz::FringePoint> read_points(const fs::path& file) {
  const Table t = read_table(file);
  if (t.header.size() < 3) throw std::runtime_error(file.string() + ": expected columns x, y, N (m, m, fringes)");
  std::vector<viz::FringePoint> p;
  for (const auto& r : t.rows)
    if (std::isfinite(r[0]) && std::isfinite(r[1]) && std::isfinite(r[2])) p.push_back({r[0], r[1], r[2]});
  if (p.empty()) throw std::runtime_error(file.string() + ": no points");
  return p;
}

Measurement fringe_rms(const QuantitySpec& q, const fs::path& dir, const json& scene) {
  if (!fs::exists(dir / "particles.pvd")) return failed("particles.pvd not written");
  const auto series = viz::read_series(dir);
  const auto idx = viz::select_frames(series, "time:" + std::to_string(q.at));
  const auto frame = viz::read_particle_frame(series[idx.at(0)].file, series[idx.at(0)].time);
  if (q.reference.kind == Reference::Kind::Image) {
    // The photo's folded fringe order (distance to the nearest whole order, from its intensity)
    // against the frame's, over the pixels on the bodies (viz/job/photo_field.hpp).
    const viz::Image photo = viz::read_image(q.reference.file);
    const viz::PhotoMap map{q.reference.map[0], q.reference.map[1], q.reference.map[2], q.reference.map[3]};
    const auto field = viz::photo_field(frame, photo.width, photo.height, map);
    viz::PhotoelasticSettings s;
    s.mode = q.reference.light_field ? viz::Polariscope::CircularLight : viz::Polariscope::CircularDark;
    s.thickness = q.thickness, s.fringe_constant = q.fringe_constant;
    std::optional<viz::Image> mask;
    if (!q.reference.mask.empty()) mask = viz::read_image(q.reference.mask);
    if (mask && (mask->width != photo.width || mask->height != photo.height))
      return failed("the mask is " + std::to_string(mask->width) + " x " + std::to_string(mask->height) +
                    " pixels, the photo " + std::to_string(photo.width) + " x " + std::to_string(photo.height));
    const auto use = viz::compared_pixels(field, map, mask ? &*mask : nullptr, std::nullopt);
    const auto a = viz::folded_order_agreement(photo, field, use, s);
    if (a.pixels == 0) return failed("no pixel of the photo lies on the bodies");
    Measurement m;
    m.value = a.rms;
    return m;
  }
  std::vector<viz::FringePoint> pts;
  if (q.reference.kind == Reference::Kind::Points) {
    pts = read_points(q.reference.file);
  } else {
    const auto form = reference::make_closed_form(q.reference.closed_form);
    const auto v = reference::complete_values(*form, closed_form_values(q.reference, scene));
    const int n = static_cast<int>(std::floor(q.radius / q.grid));
    for (int i = -n; i <= n; ++i)
      for (int j = -n; j <= n; ++j) {
        const double x = q.centre[0] + i * q.grid, y = q.centre[1] + j * q.grid;
        if ((x - q.centre[0]) * (x - q.centre[0]) + (y - q.centre[1]) * (y - q.centre[1]) > q.radius * q.radius) continue;
        const auto s = form->stress(v, x, y);
        pts.push_back({x, y, q.thickness * viz::in_plane(s[0], s[1], s[2]).diff / q.fringe_constant});
      }
  }
  const auto diff = viz::stress_difference_at(frame, pts);
  double ss = 0;
  std::size_t n = 0;
  for (std::size_t k = 0; k < pts.size(); ++k)
    if (std::isfinite(diff[k])) {
      const double r = q.thickness * diff[k] / q.fringe_constant - pts[k].N;
      ss += r * r, ++n;
    }
  if (n == 0) return failed("no point of the fringe comparison lies on the bodies");
  Measurement m;
  m.value = std::sqrt(ss / n);
  return m;
}

// A number that run.json holds (the peridynamics fork: branching.time, branching.x).
Measurement run_info(const QuantitySpec& q, const fs::path& dir) {
  std::ifstream in(dir / "run.json");
  const json j = json::parse(in, nullptr, false);
  if (j.is_discarded()) return failed("run.json cannot be read");
  const json* v = find_key(j, q.info_key);
  if (!v || !v->is_number()) return failed("run.json has no number at '" + q.info_key + "'");
  Measurement m;
  m.value = v->get<double>();
  m.time = j.value("time", 0.0);
  return m;
}

}  // namespace

reference::Values closed_form_values(const Reference& ref, const json& scene) {
  const auto form = reference::make_closed_form(ref.closed_form);
  const UnitSystem units =
      scene.contains("units") ? UnitSystem::from_json(scene["units"], "units") : UnitSystem();
  reference::Values v;
  for (const auto& p : form->parameters()) {
    const std::string key = ref.key + ".values." + p.name;
    std::string path;
    if (auto it = ref.values.find(p.name); it != ref.values.end()) {
      if (it->second.is_number()) {
        v[p.name] = it->second.get<double>();
        continue;
      }
      path = it->second.get<std::string>();
    } else if (p.name == "E" || p.name == "nu" || p.name == "density") {
      path = "materials[0]." + p.name;
    } else {
      if (!p.default_value) throw StudyError(key, "missing: " + p.meaning + " (a number in SI, or a scene key path)");
      continue;  // complete_values fills in the default
    }
    const json* j = find_key(scene, path);
    if (!j || !j->is_number())
      throw StudyError(key, "the scene has no number at '" + path + "' (" + p.meaning + "); give the value");
    v[p.name] = p.quantity ? units.to_si(j->get<double>(), *p.quantity) : j->get<double>();
  }
  return v;
}

Measurement measure(const QuantitySpec& q, const fs::path& dir, const json& scene) {
  try {
    switch (q.kind) {
      case QuantitySpec::Kind::Column: return column_quantity(q, dir);
      case QuantitySpec::Kind::EnergyDrift: return energy_drift(dir);
      case QuantitySpec::Kind::FringeRms: return fringe_rms(q, dir, scene);
      case QuantitySpec::Kind::RunInfo: return run_info(q, dir);
    }
  } catch (const StudyError&) {
    throw;
  } catch (const std::exception& e) {
    return failed(e.what());
  }
  return failed("unknown quantity kind");
}

}  // namespace cleave::study
