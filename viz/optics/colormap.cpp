#include "viz/optics/colormap.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>
#include <span>

namespace cleave::viz {

namespace {

// A control point: position t in [0, 1] and its gamma-encoded sRGB colour.
struct Stop {
  double t, r, g, b;
};

constexpr double idx(int i) { return i / 255.0; }

// Viridis (van der Walt & Smith, matplotlib 2.0 default): entries 0, 8, ..., 248, 255 of the
// published 256-entry table.
constexpr Stop kViridis[] = {
    {idx(0), 0.267004, 0.004874, 0.329415},   {idx(8), 0.277018, 0.050344, 0.375715},
    {idx(16), 0.282327, 0.094955, 0.417331},  {idx(24), 0.282884, 0.135920, 0.453427},
    {idx(32), 0.278826, 0.175490, 0.483397},  {idx(40), 0.270595, 0.214069, 0.507052},
    {idx(48), 0.258965, 0.251537, 0.524736},  {idx(56), 0.244972, 0.287675, 0.537260},
    {idx(64), 0.229739, 0.322361, 0.545706},  {idx(72), 0.214298, 0.355619, 0.551184},
    {idx(80), 0.199430, 0.387607, 0.554642},  {idx(88), 0.185556, 0.418570, 0.556753},
    {idx(96), 0.172719, 0.448791, 0.557885},  {idx(104), 0.160665, 0.478540, 0.558115},
    {idx(112), 0.149039, 0.508051, 0.557250}, {idx(120), 0.137770, 0.537492, 0.554906},
    {idx(128), 0.127568, 0.566949, 0.550556}, {idx(136), 0.120565, 0.596422, 0.543611},
    {idx(144), 0.120638, 0.625828, 0.533488}, {idx(152), 0.132268, 0.655014, 0.519661},
    {idx(160), 0.157851, 0.683765, 0.501686}, {idx(168), 0.196571, 0.711827, 0.479221},
    {idx(176), 0.246070, 0.738910, 0.452024}, {idx(184), 0.304148, 0.764704, 0.419943},
    {idx(192), 0.369214, 0.788888, 0.382914}, {idx(200), 0.440137, 0.811138, 0.340967},
    {idx(208), 0.515992, 0.831158, 0.294279}, {idx(216), 0.595839, 0.848717, 0.243329},
    {idx(224), 0.678489, 0.863742, 0.189503}, {idx(232), 0.762373, 0.876424, 0.137064},
    {idx(240), 0.845561, 0.887322, 0.099702}, {idx(248), 0.926106, 0.897330, 0.104071},
    {idx(255), 0.993248, 0.906157, 0.143936},
};

// Cividis (Nuñez, Anderton & Renslow 2018, as tabulated in matplotlib): entries 0, 8, ..., 248,
// 252, 255.
constexpr Stop kCividis[] = {
    {idx(0), 0.000000, 0.135112, 0.304751},   {idx(8), 0.000000, 0.157932, 0.357521},
    {idx(16), 0.000000, 0.178802, 0.414764},  {idx(24), 0.017852, 0.198528, 0.441248},
    {idx(32), 0.103401, 0.220406, 0.435790},  {idx(40), 0.154261, 0.242475, 0.430120},
    {idx(48), 0.195057, 0.264372, 0.425924},  {idx(56), 0.230871, 0.286134, 0.423498},
    {idx(64), 0.263738, 0.307831, 0.422789},  {idx(72), 0.294669, 0.329531, 0.423716},
    {idx(80), 0.324250, 0.351289, 0.426250},  {idx(88), 0.352892, 0.373153, 0.430226},
    {idx(96), 0.380830, 0.395164, 0.435653},  {idx(104), 0.408226, 0.417357, 0.442570},
    {idx(112), 0.435168, 0.439763, 0.451134}, {idx(120), 0.461616, 0.462405, 0.461969},
    {idx(128), 0.488697, 0.485318, 0.471008}, {idx(136), 0.517920, 0.508454, 0.472707},
    {idx(144), 0.547840, 0.531895, 0.471704}, {idx(152), 0.578236, 0.555673, 0.468724},
    {idx(160), 0.609105, 0.579816, 0.463638}, {idx(168), 0.640352, 0.604354, 0.456791},
    {idx(176), 0.671991, 0.629316, 0.448018}, {idx(184), 0.704037, 0.654731, 0.437147},
    {idx(192), 0.736488, 0.680629, 0.424028}, {idx(200), 0.769353, 0.707035, 0.408516},
    {idx(208), 0.802667, 0.733978, 0.390153}, {idx(216), 0.836429, 0.761483, 0.368747},
    {idx(224), 0.870717, 0.789572, 0.343333}, {idx(232), 0.905589, 0.818257, 0.312889},
    {idx(240), 0.941147, 0.847530, 0.275815}, {idx(248), 0.977780, 0.877281, 0.227954},
    {idx(252), 0.994847, 0.892954, 0.203445}, {idx(255), 0.995737, 0.909344, 0.217772},
};

Rgb interpolate(std::span<const Stop> stops, double t) {
  // First stop with position >= t (t already in [0, 1]; the tables start at 0 and end at 1).
  const auto hi = std::lower_bound(stops.begin(), stops.end(), t,
                                   [](const Stop& s, double v) { return s.t < v; });
  if (hi == stops.begin()) return {hi->r, hi->g, hi->b};
  if (hi == stops.end()) return {stops.back().r, stops.back().g, stops.back().b};
  const Stop& a = *(hi - 1);
  const Stop& b = *hi;
  const double w = (t - a.t) / (b.t - a.t);
  return {a.r + w * (b.r - a.r), a.g + w * (b.g - a.g), a.b + w * (b.b - a.b)};
}

// ---- CIELAB / Msh (Moreland 2009) -----------------------------------------------------------
constexpr std::array<double, 3> kD65White = {0.95047, 1.0, 1.08883};

double lab_f(double r) {
  constexpr double d = 6.0 / 29.0;
  return r > d * d * d ? std::cbrt(r) : r / (3 * d * d) + 4.0 / 29.0;
}
double lab_finv(double f) {
  constexpr double d = 6.0 / 29.0;
  return f > d ? f * f * f : 3 * d * d * (f - 4.0 / 29.0);
}

std::array<double, 3> lab_from_srgb(const Rgb& c) {
  const Rgb lin = {srgb_decode(c[0]), srgb_decode(c[1]), srgb_decode(c[2])};
  const auto xyz = xyz_from_linear_srgb(lin);
  const double fx = lab_f(xyz[0] / kD65White[0]);
  const double fy = lab_f(xyz[1] / kD65White[1]);
  const double fz = lab_f(xyz[2] / kD65White[2]);
  return {116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz)};
}

Rgb srgb_from_lab(const std::array<double, 3>& lab) {
  const double fy = (lab[0] + 16) / 116;
  const double fx = fy + lab[1] / 500;
  const double fz = fy - lab[2] / 200;
  const std::array<double, 3> xyz = {kD65White[0] * lab_finv(fx), kD65White[1] * lab_finv(fy),
                                     kD65White[2] * lab_finv(fz)};
  const Rgb lin = linear_srgb_from_xyz(xyz);
  Rgb out{};
  for (int i = 0; i < 3; ++i) out[i] = std::clamp(srgb_encode(std::max(lin[i], 0.0)), 0.0, 1.0);
  return out;
}

struct Msh {
  double m, s, h;
};

Msh msh_from_lab(const std::array<double, 3>& lab) {
  const double m = std::sqrt(lab[0] * lab[0] + lab[1] * lab[1] + lab[2] * lab[2]);
  return {m, m > 0 ? std::acos(std::clamp(lab[0] / m, -1.0, 1.0)) : 0.0,
          std::atan2(lab[2], lab[1])};
}

std::array<double, 3> lab_from_msh(const Msh& c) {
  return {c.m * std::cos(c.s), c.m * std::sin(c.s) * std::cos(c.h),
          c.m * std::sin(c.s) * std::sin(c.h)};
}

// Hue for the unsaturated end of a segment, spun away from the saturated colour so the segment
// does not pass through a perceptual hue jump (Moreland's AdjustHue).
double adjust_hue(const Msh& sat, double m_unsat) {
  if (sat.m >= m_unsat) return sat.h;
  const double spin =
      sat.s * std::sqrt(m_unsat * m_unsat - sat.m * sat.m) / (sat.m * std::sin(sat.s));
  return sat.h > -std::numbers::pi / 3 ? sat.h + spin : sat.h - spin;
}

// Moreland's interpolation between two end points given in Msh.
Rgb diverging(Msh a, Msh b, double t) {
  constexpr double kSat = 0.05;
  // Distinct saturated end points: pass through a neutral white in the middle.
  if (a.s > kSat && b.s > kSat && std::abs(a.h - b.h) > std::numbers::pi / 3) {
    const double mid = std::max({a.m, b.m, 88.0});
    if (t < 0.5) {
      b = {mid, 0, 0};
      t = 2 * t;
    } else {
      a = {mid, 0, 0};
      t = 2 * t - 1;
    }
  }
  if (a.s < kSat && b.s > kSat) a.h = adjust_hue(b, a.m);
  if (b.s < kSat && a.s > kSat) b.h = adjust_hue(a, b.m);
  const Msh c = {(1 - t) * a.m + t * b.m, (1 - t) * a.s + t * b.s, (1 - t) * a.h + t * b.h};
  return srgb_from_lab(lab_from_msh(c));
}

// The cool-warm end points, (59, 76, 192) and (180, 4, 38), in Msh (computed once).
Rgb cool_warm(double t) {
  static const Msh cool = msh_from_lab(lab_from_srgb({59 / 255.0, 76 / 255.0, 192 / 255.0}));
  static const Msh warm = msh_from_lab(lab_from_srgb({180 / 255.0, 4 / 255.0, 38 / 255.0}));
  return diverging(cool, warm, t);
}

}  // namespace

std::optional<ColorMapKind> colormap_from_name(const std::string& name) {
  std::string lower(name);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (ColorMapKind k :
       {ColorMapKind::Viridis, ColorMapKind::Cividis, ColorMapKind::CoolWarm, ColorMapKind::Gray})
    if (lower == colormap_name(k)) return k;
  return std::nullopt;
}

std::string_view colormap_name(ColorMapKind kind) {
  switch (kind) {
    case ColorMapKind::Viridis: return "viridis";
    case ColorMapKind::Cividis: return "cividis";
    case ColorMapKind::CoolWarm: return "coolwarm";
    case ColorMapKind::Gray: return "gray";
  }
  return "viridis";
}

Rgb colormap(ColorMapKind kind, double t) {
  if (std::isnan(t)) return {0.5, 0.5, 0.5};
  t = std::clamp(t, 0.0, 1.0);
  switch (kind) {
    case ColorMapKind::Viridis: return interpolate(kViridis, t);
    case ColorMapKind::Cividis: return interpolate(kCividis, t);
    case ColorMapKind::CoolWarm: return cool_warm(t);
    case ColorMapKind::Gray: return {t, t, t};
  }
  return {0.5, 0.5, 0.5};
}

std::vector<std::array<std::uint8_t, 3>> colormap_table(ColorMapKind kind, int n) {
  std::vector<std::array<std::uint8_t, 3>> out;
  if (n <= 0) return out;
  out.reserve(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double t = n == 1 ? 0.5 : static_cast<double>(i) / (n - 1);
    const Rgb c = colormap(kind, t);
    std::array<std::uint8_t, 3> px{};
    for (int k = 0; k < 3; ++k)
      px[k] = static_cast<std::uint8_t>(std::lround(std::clamp(c[k], 0.0, 1.0) * 255.0));
    out.push_back(px);
  }
  return out;
}

double srgb_encode(double linear) {
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

double srgb_decode(double encoded) {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

Rgb linear_srgb_from_xyz(const std::array<double, 3>& v) {
  return {3.2406 * v[0] - 1.5372 * v[1] - 0.4986 * v[2],
          -0.9689 * v[0] + 1.8758 * v[1] + 0.0415 * v[2],
          0.0557 * v[0] - 0.2040 * v[1] + 1.0570 * v[2]};
}

std::array<double, 3> xyz_from_linear_srgb(const Rgb& c) {
  return {0.4124 * c[0] + 0.3576 * c[1] + 0.1805 * c[2],
          0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2],
          0.0193 * c[0] + 0.1192 * c[1] + 0.9505 * c[2]};
}

double cie_lightness(const Rgb& c) {
  const double y = 0.2126 * srgb_decode(c[0]) + 0.7152 * srgb_decode(c[1]) +
                   0.0722 * srgb_decode(c[2]);
  return 116 * lab_f(y) - 16;
}

}  // namespace cleave::viz
