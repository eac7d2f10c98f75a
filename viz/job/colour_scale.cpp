#include "viz/job/colour_scale.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

#include "viz/job/render_job.hpp"

namespace cleave::viz {

std::array<uint8_t, 3> to_rgb8(const std::array<double, 3>& c) {
  std::array<uint8_t, 3> r;
  for (int k = 0; k < 3; ++k) r[k] = static_cast<uint8_t>(std::lround(std::clamp(c[k], 0.0, 1.0) * 255.0));
  return r;
}

std::string format_time(double t) {
  char b[64];
  if (std::fabs(t) < 1e-3) std::snprintf(b, sizeof b, "t = %.1f \xC2\xB5s", t * 1e6);
  else if (std::fabs(t) < 1.0) std::snprintf(b, sizeof b, "t = %.4f ms", t * 1e3);
  else std::snprintf(b, sizeof b, "t = %.4f s", t);
  return b;
}

std::string field_units(const std::string& f) {
  static const char* stress[] = {"sxx", "syy", "szz", "sxy", "syz", "sxz", "von_mises", "principal_stress_difference", "s1-s2"};
  for (const char* s : stress)
    if (f == s || f.rfind("stress", 0) == 0) return "MPa";
  if (f.empty()) return "";
  if (f == "ux" || f == "uy" || f == "uz" || f.rfind("displacement", 0) == 0 || f == "|u|") return "mm";
  if (f == "vx" || f == "vy" || f == "vz" || f.rfind("velocity", 0) == 0 || f == "|v|") return "m/s";
  return "";
}

double field_scale(const std::string& units) { return units == "MPa" ? 1e-6 : units == "mm" ? 1e3 : 1.0; }

std::string field_label(const std::string& f) {
  // Words rather than symbols: the renderer's font has no Greek letters.
  static const std::map<std::string, std::string> names = {
      {"von_mises", "von Mises stress"}, {"principal_stress_difference", "principal stress difference"},
      {"s1-s2", "principal stress difference"}, {"sxx", "normal stress xx"}, {"syy", "normal stress yy"},
      {"szz", "normal stress zz"}, {"sxy", "shear stress xy"}, {"syz", "shear stress yz"}, {"sxz", "shear stress xz"},
      {"exx", "normal strain xx"}, {"eyy", "normal strain yy"}, {"ezz", "normal strain zz"},
      {"exy", "shear strain xy"}, {"eyz", "shear strain yz"}, {"exz", "shear strain xz"},
      {"ux", "displacement x"}, {"uy", "displacement y"}, {"uz", "displacement z"}, {"|u|", "displacement"},
      {"vx", "velocity x"}, {"vy", "velocity y"}, {"vz", "velocity z"}, {"|v|", "speed"}, {"damage", "damage"}};
  const auto it = names.find(f);
  const std::string units = field_units(f);
  return (it != names.end() ? it->second : f) + (units.empty() ? "" : " (" + units + ")");
}

ColourScale::ColourScale(const RenderOptions& o, const std::vector<double>& values, ColorBar& bar) : log_(o.log_scale) {
  const std::string units = field_units(o.field);
  scale_ = field_scale(units);
  // Automatic range: the 0.5 % and 99.5 % quantiles, so that a few singular particles (load points,
  // supports, crack tips) do not wash out the rest of the image; --range overrides.
  std::vector<double> v;
  v.reserve(values.size());
  for (double x : values)
    if (std::isfinite(x)) v.push_back(x * scale_);
  lo_ = 0, hi_ = 1;
  if (!v.empty()) {
    const std::size_t a = std::size_t(0.005 * (v.size() - 1)), b = std::size_t(0.995 * (v.size() - 1));
    std::nth_element(v.begin(), v.begin() + a, v.end());
    lo_ = v[a];
    std::nth_element(v.begin(), v.begin() + b, v.end());
    hi_ = v[b];
  }
  const bool is_signed = lo_ < 0 && hi_ > 0;
  if (o.range) lo_ = (*o.range)[0], hi_ = (*o.range)[1];
  else if (is_signed) lo_ = -std::max(-lo_, hi_), hi_ = -lo_;
  if (log_) {
    if (hi_ <= 0) throw std::invalid_argument("--log needs positive values of " + o.field);
    if (lo_ <= 0) lo_ = hi_ * 1e-4;
  }
  if (hi_ == lo_) hi_ = lo_ + (lo_ == 0 ? 1.0 : std::fabs(lo_) * 1e-6);
  const std::string name = o.colormap.empty() ? (is_signed && !log_ ? "coolwarm" : "viridis") : o.colormap;
  const auto cm = colormap_from_name(name);
  if (!cm) throw std::invalid_argument("unknown colour map '" + name + "'; valid: viridis, cividis, coolwarm, gray");
  map_ = *cm;
  bar.show = o.colorbar;
  bar.min = lo_, bar.max = hi_, bar.log = log_;
  bar.title = field_label(o.field);
  bar.table = colormap_table(map_, 256);
}

std::array<uint8_t, 3> ColourScale::operator()(double v_si) const {
  const double v = v_si * scale_;
  const double t = log_ ? (std::log10(std::max(v, lo_)) - std::log10(lo_)) / (std::log10(hi_) - std::log10(lo_))
                        : (v - lo_) / (hi_ - lo_);
  return to_rgb8(colormap(map_, std::clamp(t, 0.0, 1.0)));
}

}  // namespace cleave::viz
