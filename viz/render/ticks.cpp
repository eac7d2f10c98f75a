#include "viz/render/ticks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace cleave::viz {

namespace {

// The 1-2-5 steps from just below x upwards: mantissa index k (0, 1, 2) and decade e.
double step_value(int k, int e) {
  static const double m[3] = {1, 2, 5};
  return m[k] * std::pow(10.0, e);
}

std::vector<double> ticks_with_step(double lo, double hi, double step) {
  std::vector<double> t;
  const double eps = 1e-9 * step;
  for (double n = std::ceil((lo - eps) / step); n * step <= hi + eps; n += 1) {
    double v = n * step;
    if (std::fabs(v) < eps) v = 0;  // no -0 and no 1e-17 for a tick at zero
    t.push_back(v);
    if (t.size() > 1000) break;
  }
  return t;
}

}  // namespace

std::vector<double> nice_ticks(double lo, double hi, int max_ticks) {
  if (lo > hi) std::swap(lo, hi);
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(hi > lo)) return {};
  max_ticks = std::max(3, max_ticks);
  // Walk the steps upwards from below range / max_ticks (the count only falls) and keep the step
  // whose count is nearest 5 among those giving 3 to max_ticks ticks (more ticks on a tie).
  int e = static_cast<int>(std::floor(std::log10((hi - lo) / max_ticks))) - 1, k = 0;
  std::vector<double> best;
  for (int guard = 0; guard < 60; ++guard) {
    auto t = ticks_with_step(lo, hi, step_value(k, e));
    if (t.size() < 3) break;
    const auto n = static_cast<int>(t.size());
    if (n <= max_ticks && (best.empty() || std::abs(n - 5) < std::abs(static_cast<int>(best.size()) - 5)))
      best = std::move(t);
    if (++k == 3) k = 0, ++e;
  }
  if (best.empty()) best = {lo, hi};  // a range too narrow for three round values: its ends
  return best;
}

std::vector<double> log_ticks(double lo, double hi) {
  if (lo > hi) std::swap(lo, hi);
  if (!(lo > 0) || !std::isfinite(hi) || !(hi > lo)) return {};
  const double eps = 1e-9;
  std::vector<double> t;
  for (const std::vector<double>& mantissas : {std::vector<double>{1}, {1, 2, 5}}) {
    t.clear();
    for (int e = static_cast<int>(std::floor(std::log10(lo))); e <= static_cast<int>(std::ceil(std::log10(hi))); ++e)
      for (double m : mantissas) {
        const double v = m * std::pow(10.0, e);
        if (v >= lo * (1 - eps) && v <= hi * (1 + eps)) t.push_back(v);
      }
    if (t.size() >= 3) break;
  }
  return t;
}

std::string format_tick(double v, double step) {
  if (v == 0 || std::fabs(v) < 1e-9 * std::fabs(step)) return "0";
  // Enough significant digits that neighbours one step apart differ, at most 6.
  const double mag = std::floor(std::log10(std::fabs(v))), smag = std::floor(std::log10(std::fabs(step)));
  const int digits = std::clamp(static_cast<int>(mag - smag) + 1, 1, 6);
  char b[64];
  std::snprintf(b, sizeof b, "%.*g", digits, v);
  return b;
}

ScaleBar nice_scale_bar(double metres_per_pixel, double max_pixels) {
  ScaleBar s;
  if (!(metres_per_pixel > 0) || !std::isfinite(metres_per_pixel) || !(max_pixels >= 1)) return s;
  const double max_len = metres_per_pixel * max_pixels;
  int e = static_cast<int>(std::floor(std::log10(max_len)));
  double best = step_value(0, e);
  for (int k = 0; k < 3; ++k)
    if (step_value(k, e) <= max_len * (1 + 1e-12)) best = step_value(k, e);
  s.length = best;
  struct Unit {
    double metres;
    const char* name;
  };
  static const Unit units[] = {{1e3, "km"}, {1, "m"}, {1e-3, "mm"}, {1e-6, "\xC2\xB5m"}, {1e-9, "nm"}};
  const Unit* u = &units[4];
  for (const Unit& c : units)
    if (best >= c.metres * (1 - 1e-9)) {
      u = &c;
      break;
    }
  char b[64];
  std::snprintf(b, sizeof b, "%g %s", best / u->metres, u->name);
  s.label = b;
  return s;
}

}  // namespace cleave::viz
