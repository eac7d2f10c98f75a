#include "viz/optics/photoelastic.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "viz/optics/colormap.hpp"

namespace cleave::viz {

namespace {

constexpr double kPi = std::numbers::pi;

// ---- spectral data, 380..780 nm every 5 nm (81 values), CIE 15:2004 -------------------------
constexpr int kSpectral5 = 81;
constexpr double kLambda0 = 380.0;  // nm
constexpr double kStep5 = 5.0;      // nm

// CIE 1931 2-degree standard observer.
constexpr double kXBar[kSpectral5] = {
    0.001368, 0.002236, 0.004243, 0.007650, 0.014310, 0.023190, 0.043510, 0.077630, 0.134380,
    0.214770, 0.283900, 0.328500, 0.348280, 0.348060, 0.336200, 0.318700, 0.290800, 0.251100,
    0.195360, 0.142100, 0.095640, 0.057950, 0.032010, 0.014700, 0.004900, 0.002400, 0.009300,
    0.029100, 0.063270, 0.109600, 0.165500, 0.225750, 0.290400, 0.359700, 0.433450, 0.512050,
    0.594500, 0.678400, 0.762100, 0.842500, 0.916300, 0.978600, 1.026300, 1.056700, 1.062200,
    1.045600, 1.002600, 0.938400, 0.854450, 0.751400, 0.642400, 0.541900, 0.447900, 0.360800,
    0.283500, 0.218700, 0.164900, 0.121200, 0.087400, 0.063600, 0.046770, 0.032900, 0.022700,
    0.015840, 0.011359, 0.008111, 0.005790, 0.004109, 0.002899, 0.002049, 0.001440, 0.001000,
    0.000690, 0.000476, 0.000332, 0.000235, 0.000166, 0.000117, 0.000083, 0.000059, 0.000042,
};
constexpr double kYBar[kSpectral5] = {
    0.000039, 0.000064, 0.000120, 0.000217, 0.000396, 0.000640, 0.001210, 0.002180, 0.004000,
    0.007300, 0.011600, 0.016840, 0.023000, 0.029800, 0.038000, 0.048000, 0.060000, 0.073900,
    0.090980, 0.112600, 0.139020, 0.169300, 0.208020, 0.258600, 0.323000, 0.407300, 0.503000,
    0.608200, 0.710000, 0.793200, 0.862000, 0.914850, 0.954000, 0.980300, 0.994950, 1.000000,
    0.995000, 0.978600, 0.952000, 0.915400, 0.870000, 0.816300, 0.757000, 0.694900, 0.631000,
    0.566800, 0.503000, 0.441200, 0.381000, 0.321000, 0.265000, 0.217000, 0.175000, 0.138200,
    0.107000, 0.081600, 0.061000, 0.044580, 0.032000, 0.023200, 0.017000, 0.011920, 0.008210,
    0.005723, 0.004102, 0.002929, 0.002091, 0.001484, 0.001047, 0.000740, 0.000520, 0.000361,
    0.000249, 0.000172, 0.000120, 0.000085, 0.000060, 0.000042, 0.000030, 0.000021, 0.000015,
};
constexpr double kZBar[kSpectral5] = {
    0.006450, 0.010550, 0.020050, 0.036210, 0.067850, 0.110200, 0.207400, 0.371300, 0.645600,
    1.039050, 1.385600, 1.622960, 1.747060, 1.782600, 1.772110, 1.744100, 1.669200, 1.528100,
    1.287640, 1.041900, 0.812950, 0.616200, 0.465180, 0.353300, 0.272000, 0.212300, 0.158200,
    0.111700, 0.078250, 0.057250, 0.042160, 0.029840, 0.020300, 0.013400, 0.008750, 0.005750,
    0.003900, 0.002750, 0.002100, 0.001800, 0.001650, 0.001400, 0.001100, 0.001000, 0.000800,
    0.000600, 0.000340, 0.000240, 0.000190, 0.000100, 0.000050, 0.000030, 0.000020, 0.000010,
    0.000000, 0.000000, 0.000000, 0.000000, 0.000000, 0.000000, 0.000000, 0.000000, 0.000000,
    0.000000, 0.000000, 0.000000, 0.000000, 0.000000, 0.000000, 0.000000, 0.000000, 0.000000,
    0.000000, 0.000000, 0.000000, 0.000000, 0.000000, 0.000000, 0.000000, 0.000000, 0.000000,
};
// CIE standard illuminant D65, relative spectral power (100 at 560 nm).
constexpr double kD65[kSpectral5] = {
    49.9755, 52.3118, 54.6482, 68.7015, 82.7549, 87.1204, 91.4860, 92.4589, 93.4318, 90.0570,
    86.6823, 95.7736, 104.865, 110.936, 117.008, 117.410, 117.812, 116.336, 114.861, 115.392,
    115.923, 112.367, 108.811, 109.082, 109.354, 108.578, 107.802, 106.296, 104.790, 106.239,
    107.689, 106.047, 104.405, 104.225, 104.046, 102.023, 100.000, 98.1671, 96.3342, 96.0611,
    95.7880, 92.2368, 88.6856, 89.3459, 90.0062, 89.8026, 89.5991, 88.6489, 87.6987, 85.4936,
    83.2886, 83.4939, 83.6992, 81.8630, 80.0268, 80.1207, 80.2146, 81.2462, 82.2778, 80.2810,
    78.2842, 74.0027, 69.7213, 70.6652, 71.6091, 72.9790, 74.3490, 67.9765, 61.6040, 65.7448,
    69.8856, 72.4863, 75.0870, 69.3398, 63.5927, 55.0054, 46.4182, 56.6118, 66.8054, 65.0941,
    63.3828,
};

// Integration grid: 380..780 nm every 1 nm, the 5 nm tables interpolated linearly.
constexpr int kGrid = 401;
constexpr double kGridStep = 1.0;  // nm

struct Spectral {
  std::array<double, kGrid> lambda{};              // nm
  std::array<std::array<double, 3>, kGrid> w{};   // D65 * (xbar, ybar, zbar) / sum(D65 * ybar)
  std::array<double, 3> balance{};                 // linear sRGB of the D65 white (sum of w)
};

double lerp5(const double (&table)[kSpectral5], double lambda) {
  const double u = (lambda - kLambda0) / kStep5;
  const int i = std::clamp(static_cast<int>(u), 0, kSpectral5 - 2);
  const double f = u - i;
  return (1 - f) * table[i] + f * table[i + 1];
}

const Spectral& spectral() {
  static const Spectral sp = [] {
    Spectral s;
    double ysum = 0;
    for (int i = 0; i < kGrid; ++i) {
      const double l = kLambda0 + i * kGridStep;
      const double d = lerp5(kD65, l);
      s.lambda[i] = l;
      s.w[i] = {d * lerp5(kXBar, l), d * lerp5(kYBar, l), d * lerp5(kZBar, l)};
      ysum += s.w[i][1];
    }
    std::array<double, 3> white{};
    for (auto& wi : s.w)
      for (int c = 0; c < 3; ++c) {
        wi[c] /= ysum;
        white[c] += wi[c];
      }
    s.balance = linear_srgb_from_xyz(white);
    return s;
  }();
  return sp;
}

// Dark-field (crossed circular) colour of retardation Gamma (m) in white-balanced linear sRGB,
// not clamped; the light-field colour is (1, 1, 1) minus this.
std::array<double, 3> dark_linear_direct(double gamma) {
  const Spectral& sp = spectral();
  const double g_nm = std::abs(gamma) * 1e9;
  std::array<double, 3> xyz{};
  for (int i = 0; i < kGrid; ++i) {
    const double l = sp.lambda[i];
    const double phase = 2 * kPi * g_nm / l;  // 2 pi Gamma / lambda
    // Average of cos(phase) over the 1 nm band around l: d(phase)/d(lambda) = -phase / l.
    const double half = 0.5 * phase * kGridStep / l;
    const double sinc = half > 1e-8 ? std::sin(half) / half : 1.0;
    const double i_dark = 0.5 * (1 - std::cos(phase) * sinc);  // sin^2(pi Gamma / lambda)
    for (int c = 0; c < 3; ++c) xyz[c] += sp.w[i][c] * i_dark;
  }
  std::array<double, 3> rgb = linear_srgb_from_xyz(xyz);
  for (int c = 0; c < 3; ++c) rgb[c] /= sp.balance[c];
  return rgb;
}

const std::vector<std::array<double, 3>>& dark_table() {
  static const std::vector<std::array<double, 3>> table = [] {
    std::vector<std::array<double, 3>> t(kWhiteLightTableSize);
    for (int i = 0; i < kWhiteLightTableSize; ++i)
      t[i] = dark_linear_direct(kWhiteLightTableMax * i / (kWhiteLightTableSize - 1));
    return t;
  }();
  return table;
}

std::array<double, 3> dark_linear(double gamma) {
  const double g = std::abs(gamma);
  if (!(g < kWhiteLightTableMax)) return dark_linear_direct(g);
  const auto& t = dark_table();
  const double u = g / kWhiteLightTableMax * (kWhiteLightTableSize - 1);
  const int i = std::min(static_cast<int>(u), kWhiteLightTableSize - 2);
  const double f = u - i;
  return {(1 - f) * t[i][0] + f * t[i + 1][0], (1 - f) * t[i][1] + f * t[i + 1][1],
          (1 - f) * t[i][2] + f * t[i + 1][2]};
}

std::array<double, 3> encode(const std::array<double, 3>& lin) {
  return {srgb_encode(std::clamp(lin[0], 0.0, 1.0)), srgb_encode(std::clamp(lin[1], 0.0, 1.0)),
          srgb_encode(std::clamp(lin[2], 0.0, 1.0))};
}

std::string lower(const std::string& s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

double sq(double v) { return v * v; }

}  // namespace

std::optional<Polariscope> polariscope_from_name(const std::string& name) {
  const std::string n = lower(name);
  for (Polariscope p :
       {Polariscope::CircularDark, Polariscope::CircularLight, Polariscope::PlaneCrossed,
        Polariscope::PlaneParallel, Polariscope::Seed002})
    if (n == polariscope_name(p)) return p;
  return std::nullopt;
}

std::string_view polariscope_name(Polariscope mode) {
  switch (mode) {
    case Polariscope::CircularDark: return "dark";
    case Polariscope::CircularLight: return "light";
    case Polariscope::PlaneCrossed: return "crossed";
    case Polariscope::PlaneParallel: return "parallel";
    case Polariscope::Seed002: return "seed002";
  }
  return "dark";
}

double effective_fringe_constant(const PhotoelasticSettings& s) {
  if (s.fringe_constant > 0) return s.fringe_constant;
  if (s.stress_optic > 0 && s.wavelength > 0) return s.wavelength / s.stress_optic;
  throw std::invalid_argument(
      "photoelastic settings: set fringe_constant (Pa*m/fringe) or stress_optic (1/Pa) > 0");
}

InPlane in_plane(double sxx, double syy, double sxy) {
  const double half = 0.5 * (sxx - syy);
  return {2 * std::hypot(half, sxy), 0.5 * std::atan2(2 * sxy, sxx - syy)};
}

double fringe_order(double sxx, double syy, double sxy, const PhotoelasticSettings& s) {
  const double diff = in_plane(sxx, syy, sxy).diff;
  if (s.mode == Polariscope::Seed002) return s.k_f * diff / (2 * kPi);
  return s.thickness * diff / effective_fringe_constant(s);
}

double intensity(double sxx, double syy, double sxy, const PhotoelasticSettings& s) {
  const InPlane p = in_plane(sxx, syy, sxy);
  switch (s.mode) {
    case Polariscope::Seed002: return 0.5 * (1 + std::cos(s.k_f * p.diff));
    case Polariscope::CircularDark: return sq(std::sin(kPi * fringe_order(sxx, syy, sxy, s)));
    case Polariscope::CircularLight: return sq(std::cos(kPi * fringe_order(sxx, syy, sxy, s)));
    case Polariscope::PlaneCrossed:
    case Polariscope::PlaneParallel: {
      const double crossed = sq(std::sin(2 * (p.theta - s.polarizer_angle))) *
                             sq(std::sin(kPi * fringe_order(sxx, syy, sxy, s)));
      return s.mode == Polariscope::PlaneCrossed ? crossed : 1 - crossed;
    }
  }
  return 0;
}

double retardation(double sxx, double syy, double sxy, const PhotoelasticSettings& s) {
  return fringe_order(sxx, syy, sxy, s) * s.wavelength;
}

std::array<double, 3> white_light_rgb(double sxx, double syy, double sxy,
                                      const PhotoelasticSettings& s) {
  if (!std::isfinite(sxx) || !std::isfinite(syy) || !std::isfinite(sxy)) return {0.5, 0.5, 0.5};
  const std::array<double, 3> dark = dark_linear(retardation(sxx, syy, sxy, s));
  std::array<double, 3> lin{};
  switch (s.mode) {
    case Polariscope::CircularDark: lin = dark; break;
    case Polariscope::CircularLight:
    case Polariscope::Seed002:
      for (int c = 0; c < 3; ++c) lin[c] = 1 - dark[c];
      break;
    case Polariscope::PlaneCrossed:
    case Polariscope::PlaneParallel: {
      const double q = sq(std::sin(2 * (in_plane(sxx, syy, sxy).theta - s.polarizer_angle)));
      for (int c = 0; c < 3; ++c)
        lin[c] = s.mode == Polariscope::PlaneCrossed ? q * dark[c] : 1 - q * dark[c];
      break;
    }
  }
  return encode(lin);
}

std::array<double, 3> white_light_colour(double Gamma, bool dark_field) {
  if (!std::isfinite(Gamma)) return {0.5, 0.5, 0.5};
  std::array<double, 3> lin = dark_linear_direct(Gamma);
  if (!dark_field)
    for (double& c : lin) c = 1 - c;
  return encode(lin);
}

Stress2 brazilian_disk_stress(double x, double y, double R, double P, double t) {
  const double a = R - y, b = R + y;
  const double r1_4 = sq(x * x + a * a), r2_4 = sq(x * x + b * b);
  const double k = 2 * P / (kPi * t);
  return {-k * (x * x * a / r1_4 + x * x * b / r2_4 - 1 / (2 * R)),
          -k * (a * a * a / r1_4 + b * b * b / r2_4 - 1 / (2 * R)),
          k * (x * a * a / r1_4 - x * b * b / r2_4)};
}

}  // namespace cleave::viz
