// Crack propagation's closed forms and the reader of cracks[i].propagation (propagation.hpp).
#include "libmpm/crack/propagation.hpp"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "libmpm/core/error.hpp"
#include "libmpm/core/json_reader.hpp"

namespace cleave::crack {

double hoop_stress_angle(double KI, double KII) {
  if (KII == 0.0) return 0.0;
  const double k1 = std::max(KI, 0.0);  // a closed tip kinks as in pure mode II
  return 2.0 * std::atan((k1 - std::sqrt(k1 * k1 + 8.0 * KII * KII)) / (4.0 * KII));
}

double hoop_stress_intensity(double KI, double KII, double theta) {
  const double c = std::cos(0.5 * theta);
  return c * (KI * c * c - 1.5 * KII * std::sin(theta));
}

std::pair<double, double> kink_intensities(double KI, double KII, double theta) {
  const double s1 = std::sin(0.5 * theta), s3 = std::sin(1.5 * theta);
  const double c1 = std::cos(0.5 * theta), c3 = std::cos(1.5 * theta);
  return {0.25 * (3.0 * c1 + c3) * KI - 0.75 * (s1 + s3) * KII, 0.25 * (s1 + s3) * KI + 0.25 * (c1 + 3.0 * c3) * KII};
}

double max_energy_release_angle(double KI, double KII) {
  if (KII == 0.0) return 0.0;
  const double k1 = std::max(KI, 0.0);
  auto g = [&](double t) {
    const auto [a, b] = kink_intensities(k1, KII, t);
    return std::max(a, 0.0) * std::max(a, 0.0) + b * b;  // a kink cannot open with k_I < 0
  };
  // A scan at a fifth of a degree, then golden-section refinement around the best: deterministic,
  // and safe where G(theta) has a second, lower hump.
  const double lim = 80.0 * M_PI / 180.0, step = 0.2 * M_PI / 180.0;
  double best = -lim, gbest = g(-lim);
  for (double t = -lim + step; t <= lim + 1e-12; t += step)
    if (const double v = g(t); v > gbest) gbest = v, best = t;
  double a = std::max(-lim, best - step), b = std::min(lim, best + step);
  const double r = 0.5 * (std::sqrt(5.0) - 1.0);
  while (b - a > 1e-7) {
    const double x1 = b - r * (b - a), x2 = a + r * (b - a);
    if (g(x1) >= g(x2)) b = x2;
    else a = x1;
  }
  return 0.5 * (a + b);
}

double rayleigh_speed(double shear_modulus, double density, double nu) {
  // The root x = (c_R / c_s)^2 in (0, 1) of the Rayleigh equation
  // (2 - x)^2 = 4 sqrt(1 - x k) sqrt(1 - x), k = (c_s / c_d)^2 = (1 - 2 nu) / (2 (1 - nu)), by bisection:
  // the left side less the right is x (2 k - 2) < 0 just above the trivial root 0, and 1 at x = 1.
  const double k = (1.0 - 2.0 * nu) / (2.0 * (1.0 - nu));
  auto f = [&](double x) { return (2.0 - x) * (2.0 - x) - 4.0 * std::sqrt(1.0 - x * k) * std::sqrt(1.0 - x); };
  double lo = 1e-6, hi = 1.0;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) < 0.0 ? lo : hi) = mid;
  }
  return std::sqrt(shear_modulus / density * 0.5 * (lo + hi));
}

double Propagation::resistance_factor(double da) const {
  if (resistance.empty()) return 1.0;
  if (da <= resistance.front().first) return resistance.front().second;
  for (std::size_t k = 1; k < resistance.size(); ++k)
    if (da <= resistance[k].first) {
      const auto [a0, f0] = resistance[k - 1];
      const auto [a1, f1] = resistance[k];
      return a1 > a0 ? f0 + (f1 - f0) * (da - a0) / (a1 - a0) : f1;
    }
  return resistance.back().second;
}

Propagation parse_propagation(const nlohmann::json& j, const std::string& key_path, double length_scale) {
  const ObjectReader r(j, key_path,
                       {"criterion", "direction", "growth_length", "max_speed_cR", "check_interval", "resistance_curve"});
  Propagation p;
  p.criterion = r.string_or("criterion", p.criterion);
  if (!InitiationCriteria::instance().has(p.criterion))
    throw SceneError(r.at("criterion"),
                     unknown_name("propagation criterion", p.criterion, InitiationCriteria::instance().names_joined()));
  p.direction = r.string_or("direction", p.direction);
  if (!DirectionRules::instance().has(p.direction))
    throw SceneError(r.at("direction"),
                     unknown_name("direction rule", p.direction, DirectionRules::instance().names_joined()));
  p.growth_length = r.number_or("growth_length", p.growth_length);
  if (!(p.growth_length >= 0.1 && p.growth_length <= 2.0))
    throw SceneError(r.at("growth_length"),
                     "must lie in [0.1, 2] cells (got " + r["growth_length"].dump() +
                         "): below a tenth of a cell the segments are shorter than the crossing test resolves; "
                         "above two cells a step skips the J contour's reach");
  p.max_speed_cR = r.number_or("max_speed_cR", p.max_speed_cR);
  if (!(p.max_speed_cR > 0.0 && p.max_speed_cR <= 2.0))
    throw SceneError(r.at("max_speed_cR"), "must lie in (0, 2]: the tip's speed cap as a multiple of the Rayleigh "
                                           "speed (got " + r["max_speed_cR"].dump() + ")");
  p.check_interval = r.integer_or("check_interval", 1, 1, 1000000);
  if (r.has("resistance_curve")) {
    const auto& rc = r["resistance_curve"];
    const std::string path = r.at("resistance_curve");
    if (!rc.is_array() || rc.empty()) throw SceneError(path, "expected [[da, factor], ...] (at least one point)");
    for (std::size_t k = 0; k < rc.size(); ++k) {
      const std::string pk = path + "[" + std::to_string(k) + "]";
      if (!rc[k].is_array() || rc[k].size() != 2 || !rc[k][0].is_number() || !rc[k][1].is_number())
        throw SceneError(pk, "expected [da, factor] (two numbers)");
      const double da = rc[k][0].get<double>() * length_scale, f = rc[k][1].get<double>();
      if (!(std::isfinite(da) && da >= 0.0)) throw SceneError(pk, "da must be finite and >= 0");
      if (!(std::isfinite(f) && f > 0.0)) throw SceneError(pk, "the toughness factor must be finite and > 0");
      if (!p.resistance.empty() && !(da > p.resistance.back().first))
        throw SceneError(pk, "da must increase along the curve");
      p.resistance.emplace_back(da, f);
    }
  }
  return p;
}

}  // namespace cleave::crack
