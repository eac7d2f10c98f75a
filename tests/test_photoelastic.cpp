// Photoelasticity and colour maps (viz/optics, no VTK): the Brazilian-disk closed form, the
// stress-optic law, every polariscope formula of validation.md section 7 at hand-computed points,
// the seed 002 light-field form, the white-light (Michel-Levy) colours and the colour maps.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "viz/optics/colormap.hpp"
#include "viz/optics/photoelastic.hpp"

namespace {

using namespace cleave::viz;
constexpr double kPi = std::numbers::pi;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double nm = 1e-9;

// HSV of a gamma-encoded sRGB colour: hue in degrees [0, 360) (NaN for a gray), saturation and
// value in [0, 1].
struct Hsv {
  double h, s, v;
};
Hsv hsv(const Rgb& c) {
  const double mx = std::max({c[0], c[1], c[2]});
  const double mn = std::min({c[0], c[1], c[2]});
  const double d = mx - mn;
  double h = kNaN;
  if (d > 0) {
    if (mx == c[0]) h = std::fmod((c[1] - c[2]) / d + 6, 6);
    else if (mx == c[1]) h = (c[2] - c[0]) / d + 2;
    else h = (c[0] - c[1]) / d + 4;
    h *= 60;
  }
  return {h, mx > 0 ? d / mx : 0, mx};
}

// Angular distance between two hues in degrees.
double hue_distance(double a, double b) {
  const double d = std::fmod(std::abs(a - b), 360.0);
  return std::min(d, 360 - d);
}

// Settings with f_sigma = 1 Pa*m/fringe and t = 1 m, so the fringe order equals s1 - s2 in Pa:
// stresses below are given directly as fringe orders.
PhotoelasticSettings unit_settings(Polariscope mode, double polarizer = 0) {
  PhotoelasticSettings s;
  s.mode = mode;
  s.thickness = 1;
  s.fringe_constant = 1;
  s.polarizer_angle = polarizer;
  return s;
}

// ---- Brazilian disk ---------------------------------------------------------------------------

constexpr double R = 0.025, P = 1000, T = 0.005, D = 2 * R;

TEST(BrazilianDisk, CentreValues) {
  const Stress2 c = brazilian_disk_stress(0, 0, R, P, T);
  EXPECT_NEAR(c.xx, 2 * P / (kPi * D * T), 1e-9 * P / (D * T));
  EXPECT_NEAR(c.yy, -6 * P / (kPi * D * T), 1e-9 * P / (D * T));
  EXPECT_NEAR(c.xy, 0, 1e-12 * P / (D * T));
}

TEST(BrazilianDisk, Symmetry) {
  for (double x : {0.003, 0.011, 0.019})
    for (double y : {0.002, 0.009, 0.017}) {
      const Stress2 s = brazilian_disk_stress(x, y, R, P, T);
      const Stress2 mx = brazilian_disk_stress(-x, y, R, P, T);
      const Stress2 my = brazilian_disk_stress(x, -y, R, P, T);
      const double tol = 1e-9 * std::abs(s.yy) + 1e-6;
      EXPECT_NEAR(mx.xx, s.xx, tol);
      EXPECT_NEAR(mx.yy, s.yy, tol);
      EXPECT_NEAR(mx.xy, -s.xy, tol);
      EXPECT_NEAR(my.xx, s.xx, tol);
      EXPECT_NEAR(my.yy, s.yy, tol);
      EXPECT_NEAR(my.xy, -s.xy, tol);
    }
}

// The rim is free of traction away from the two load points: sigma . n = 0 with n = (x, y) / R.
TEST(BrazilianDisk, TractionFreeRim) {
  const double scale = P / (kPi * R * T);
  for (int k = 0; k < 72; ++k) {
    const double a = 2 * kPi * (k + 0.5) / 72;  // avoids the load points at a = pi/2, 3 pi/2
    const double nx = std::cos(a), ny = std::sin(a);
    const Stress2 s = brazilian_disk_stress(R * nx, R * ny, R, P, T);
    EXPECT_NEAR(s.xx * nx + s.xy * ny, 0, 1e-9 * scale) << "angle " << a;
    EXPECT_NEAR(s.xy * nx + s.yy * ny, 0, 1e-9 * scale) << "angle " << a;
  }
}

// Along the loaded diameter sigma_x is the uniform splitting tension 2P/(pi D t); across the
// horizontal diameter sigma_y carries the load: t * integral of sigma_y dx = -P.
TEST(BrazilianDisk, LoadedDiameterAndEquilibrium) {
  for (double y : {-0.02, -0.01, 0.0, 0.005, 0.015, 0.024})
    EXPECT_NEAR(brazilian_disk_stress(0, y, R, P, T).xx, 2 * P / (kPi * D * T), 1e-6);
  const int n = 20000;  // midpoint rule, smooth integrand
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const double x = -R + (i + 0.5) * (2 * R / n);
    sum += brazilian_disk_stress(x, 0, R, P, T).yy * (2 * R / n);
  }
  EXPECT_NEAR(sum * T, -P, 1e-6 * P);
}

// Calibration formula of the Brazilian disk: N at the centre = 8 P / (pi D f_sigma).
TEST(BrazilianDisk, CentreFringeOrder) {
  PhotoelasticSettings s;
  s.thickness = T;
  s.fringe_constant = 7e3;  // polycarbonate, ~7 N/mm/fringe
  const Stress2 c = brazilian_disk_stress(0, 0, R, P, T);
  EXPECT_NEAR(fringe_order(c.xx, c.yy, c.xy, s), 8 * P / (kPi * D * s.fringe_constant), 1e-9);
}

// ---- stress-optic law -------------------------------------------------------------------------

TEST(Photoelastic, Names) {
  EXPECT_EQ(polariscope_from_name("dark"), Polariscope::CircularDark);
  EXPECT_EQ(polariscope_from_name("light"), Polariscope::CircularLight);
  EXPECT_EQ(polariscope_from_name("crossed"), Polariscope::PlaneCrossed);
  EXPECT_EQ(polariscope_from_name("parallel"), Polariscope::PlaneParallel);
  EXPECT_EQ(polariscope_from_name("seed002"), Polariscope::Seed002);
  EXPECT_EQ(polariscope_from_name("Dark"), Polariscope::CircularDark);
  EXPECT_FALSE(polariscope_from_name("circular").has_value());
  EXPECT_FALSE(polariscope_from_name("").has_value());
  for (Polariscope p :
       {Polariscope::CircularDark, Polariscope::CircularLight, Polariscope::PlaneCrossed,
        Polariscope::PlaneParallel, Polariscope::Seed002})
    EXPECT_EQ(polariscope_from_name(std::string(polariscope_name(p))), p);
}

TEST(Photoelastic, InPlanePrincipalStresses) {
  // Uniaxial x: sigma1 along x.
  InPlane p = in_plane(5, 0, 0);
  EXPECT_DOUBLE_EQ(p.diff, 5);
  EXPECT_DOUBLE_EQ(p.theta, 0);
  // Uniaxial y: sigma1 along y.
  p = in_plane(0, 5, 0);
  EXPECT_DOUBLE_EQ(p.diff, 5);
  EXPECT_NEAR(p.theta, kPi / 2, 1e-15);
  // Pure shear tau: s1,2 = +-tau at 45 degrees.
  p = in_plane(0, 0, 3);
  EXPECT_DOUBLE_EQ(p.diff, 6);
  EXPECT_NEAR(p.theta, kPi / 4, 1e-15);
  // General: (sxx, syy, sxy) = (3, -1, 2): s1,2 = 1 +- sqrt(8).
  p = in_plane(3, -1, 2);
  EXPECT_NEAR(p.diff, 2 * std::sqrt(8.0), 1e-14);
  EXPECT_NEAR(p.theta, 0.5 * std::atan2(4.0, 4.0), 1e-15);
  // Rotating a uniaxial stress sigma by beta: theta = beta, diff = sigma.
  for (double beta : {0.1, 0.7, 1.3, -0.4}) {
    const double c = std::cos(beta), s = std::sin(beta), sig = 2.5;
    p = in_plane(sig * c * c, sig * s * s, sig * s * c);
    EXPECT_NEAR(p.diff, sig, 1e-14);
    EXPECT_NEAR(p.theta, beta, 1e-14);
  }
}

TEST(Photoelastic, FringeOrderFormula) {
  PhotoelasticSettings s;
  s.thickness = 6e-3;
  s.fringe_constant = 7e3;  // Pa*m/fringe
  // sxx = 10 MPa, syy = -2 MPa, sxy = 8 MPa: s1 - s2 = sqrt(12^2 + 16^2) MPa = 20 MPa.
  EXPECT_NEAR(fringe_order(10e6, -2e6, 8e6, s), 6e-3 * 20e6 / 7e3, 1e-9);
  EXPECT_NEAR(retardation(10e6, -2e6, 8e6, s), 6e-3 * 20e6 / 7e3 * 546e-9, 1e-18);
  // The same material given by its stress-optic coefficient C = lambda / f_sigma.
  PhotoelasticSettings c;
  c.thickness = 6e-3;
  c.stress_optic = 546e-9 / 7e3;
  EXPECT_NEAR(effective_fringe_constant(c), 7e3, 1e-9);
  EXPECT_NEAR(fringe_order(10e6, -2e6, 8e6, c), fringe_order(10e6, -2e6, 8e6, s), 1e-12);
  // Gamma = t C (s1 - s2).
  EXPECT_NEAR(retardation(10e6, -2e6, 8e6, c), 6e-3 * c.stress_optic * 20e6, 1e-18);
  // fringe_constant wins when both are set.
  c.fringe_constant = 14e3;
  EXPECT_NEAR(fringe_order(10e6, -2e6, 8e6, c), 0.5 * fringe_order(10e6, -2e6, 8e6, s), 1e-12);
  // Neither set: an error, not a silent default.
  PhotoelasticSettings none;
  EXPECT_THROW(fringe_order(1, 0, 0, none), std::invalid_argument);
  EXPECT_THROW(intensity(1, 0, 0, none), std::invalid_argument);
}

// Hand-computed intensities. Uniaxial sxx = N (so theta = 0) with unit settings.
TEST(Photoelastic, CircularPolariscopes) {
  const auto dark = unit_settings(Polariscope::CircularDark);
  const auto light = unit_settings(Polariscope::CircularLight);
  // N = 0: dark 0, light 1. N = 1/4: both 1/2. N = 1/2: dark 1. N = 1: dark 0 (first fringe).
  EXPECT_NEAR(intensity(0, 0, 0, dark), 0, 1e-15);
  EXPECT_NEAR(intensity(0, 0, 0, light), 1, 1e-15);
  EXPECT_NEAR(intensity(0.25, 0, 0, dark), 0.5, 1e-15);
  EXPECT_NEAR(intensity(0.25, 0, 0, light), 0.5, 1e-15);
  EXPECT_NEAR(intensity(0.5, 0, 0, dark), 1, 1e-15);
  EXPECT_NEAR(intensity(1.0, 0, 0, dark), 0, 1e-15);
  EXPECT_NEAR(intensity(1.5, 0, 0, light), 0, 1e-15);
  // N = 1/6: sin^2(pi/6) = 1/4.
  EXPECT_NEAR(intensity(1.0 / 6, 0, 0, dark), 0.25, 1e-15);
  // Circular polariscopes do not see the principal direction.
  EXPECT_NEAR(intensity(0, 0, 1.0 / 12, dark), 0.25, 1e-15);  // pure shear, diff = 1/6
  // dark + light = 1 everywhere.
  for (double sxx : {-0.7, 0.0, 0.3, 1.9})
    for (double sxy : {-0.4, 0.2, 1.1})
      EXPECT_NEAR(intensity(sxx, 0.2, sxy, dark) + intensity(sxx, 0.2, sxy, light), 1, 1e-14);
}

TEST(Photoelastic, PlanePolariscopes) {
  const auto crossed = unit_settings(Polariscope::PlaneCrossed);
  const auto parallel = unit_settings(Polariscope::PlaneParallel);
  // sigma1 along the polariser (theta = 0): isoclinic, dark whatever the fringe order.
  for (double n : {0.1, 0.5, 1.3}) {
    EXPECT_NEAR(intensity(n, 0, 0, crossed), 0, 1e-15);
    EXPECT_NEAR(intensity(n, 0, 0, parallel), 1, 1e-15);
    EXPECT_NEAR(intensity(0, n, 0, crossed), 0, 1e-15);  // theta = 90 degrees: also isoclinic
  }
  // Pure shear: theta = 45 degrees, sin^2(2 theta) = 1: crossed = circular dark field.
  // diff = 2 tau = 1/2 fringe: I = sin^2(pi/2) = 1; diff = 1/6: I = 1/4.
  EXPECT_NEAR(intensity(0, 0, 0.25, crossed), 1, 1e-15);
  EXPECT_NEAR(intensity(0, 0, 1.0 / 12, crossed), 0.25, 1e-15);
  EXPECT_NEAR(intensity(0, 0, 1.0 / 12, parallel), 0.75, 1e-15);
  // Polariser at 22.5 degrees to sigma1: sin^2(2 * 22.5 deg) = 1/2; N = 1/2: I = 1/2.
  auto c22 = unit_settings(Polariscope::PlaneCrossed, kPi / 8);
  EXPECT_NEAR(intensity(0.5, 0, 0, c22), 0.5, 1e-15);
  // N = 1/4 and 22.5 degrees: (1/2)(1/2) = 1/4.
  EXPECT_NEAR(intensity(0.25, 0, 0, c22), 0.25, 1e-15);
  // Rotating the polariser onto the principal direction of a general state makes it isoclinic.
  const InPlane p = in_plane(0.3, -0.4, 0.25);
  for (double a : {p.theta, p.theta + kPi / 2, p.theta - kPi / 2})
    EXPECT_NEAR(intensity(0.3, -0.4, 0.25, unit_settings(Polariscope::PlaneCrossed, a)), 0, 1e-14);
  // parallel = 1 - crossed for any state and polariser angle.
  for (double a : {0.0, 0.3, 1.0})
    for (double sxy : {-0.3, 0.1, 0.8}) {
      const double ic = intensity(0.6, -0.1, sxy, unit_settings(Polariscope::PlaneCrossed, a));
      const double ip = intensity(0.6, -0.1, sxy, unit_settings(Polariscope::PlaneParallel, a));
      EXPECT_NEAR(ic + ip, 1, 1e-14);
      EXPECT_GE(ic, 0);
      EXPECT_LE(ic, 1);
    }
}

// Seed 002 eq. 23: I = (1 + cos(k_f (s1 - s2))) / 2 with k_f = 0.0889 /MPa, light field.
TEST(Photoelastic, Seed002Form) {
  PhotoelasticSettings s;
  s.mode = Polariscope::Seed002;  // thickness / f_sigma / C unused (both left at 0: no throw)
  EXPECT_DOUBLE_EQ(intensity(0, 0, 0, s), 1);  // zero stress is bright
  // 1 MPa: (1 + cos(0.0889)) / 2 = 0.99802549... (cos 0.0889 = 1 - 0.0889^2/2 + 0.0889^4/24).
  EXPECT_NEAR(intensity(1e6, 0, 0, s), 0.998025494, 1e-8);
  // First dark fringe at k_f diff = pi: diff = pi / 0.0889 MPa = 35.338 MPa.
  const double d1 = kPi / 0.0889e-6;
  EXPECT_NEAR(intensity(d1, 0, 0, s), 0, 1e-15);
  EXPECT_NEAR(intensity(0, 0, d1 / 2, s), 0, 1e-15);  // as pure shear: theta does not matter
  EXPECT_NEAR(intensity(2 * d1, 0, 0, s), 1, 1e-15);
  // Same as the circular light field with N = k_f diff / (2 pi).
  EXPECT_NEAR(fringe_order(d1, 0, 0, s), 0.5, 1e-14);
  EXPECT_NEAR(retardation(d1, 0, 0, s), 0.5 * s.wavelength, 1e-20);
  for (double diff : {3e6, 17e6, 52e6}) {
    const double n = fringe_order(diff, 0, 0, s);
    EXPECT_NEAR(intensity(diff, 0, 0, s), std::pow(std::cos(kPi * n), 2), 1e-14);
  }
}

TEST(Photoelastic, NonFiniteStress) {
  const auto dark = unit_settings(Polariscope::CircularDark);
  EXPECT_TRUE(std::isnan(intensity(kNaN, 0, 0, dark)));
  EXPECT_TRUE(std::isnan(fringe_order(0, kNaN, 0, dark)));
  const Rgb g = white_light_rgb(0, 0, kNaN, dark);
  EXPECT_EQ(g, (Rgb{0.5, 0.5, 0.5}));
  EXPECT_EQ(white_light_colour(kNaN, true), (Rgb{0.5, 0.5, 0.5}));
}

// ---- white light --------------------------------------------------------------------------------

TEST(WhiteLight, ZeroRetardation) {
  const Rgb dark = white_light_colour(0, true);
  const Rgb light = white_light_colour(0, false);
  for (int c = 0; c < 3; ++c) {
    EXPECT_LT(dark[c], 0.02);
    EXPECT_NEAR(light[c], 1, 1e-9);
  }
}

// Colour names of the Michel-Levy chart (crossed polars) and roughly where Newton's colour scale,
// as usually tabulated with it, puts them (nm of retardation): grey-blue ~160, clearer grey ~220,
// white ~260, straw to bright yellow ~270-310, brownish yellow ~330, reddish orange ~430, red ~505,
// deep red ~535, purple ~550, violet ~565, indigo ~575, sky blue ~590, greenish blue ~660,
// green ~730, light green ~750. The rendering uses D65 and clamps out-of-gamut colours (G < 0
// between 520 and 560 nm), so hue boundaries are not sharp; the hue tolerances are about half the
// distance to the neighbouring named colour. This rendering (figures printed below) puts the
// first-order orange-red at 470-490 nm and pure red at 490-500 nm, 15-30 nm before the table's
// 505-536; the red band is therefore tested at 475-500 nm.
TEST(WhiteLight, MichelLevyFirstOrder) {
  struct Probe {
    double gamma_nm;
    const char* name;
  };
  std::printf("Gamma(nm)  dark-field sRGB          HSV hue  sat  value\n");
  auto report = [](double g, const Rgb& c) {
    const Hsv h = hsv(c);
    std::printf("%6.0f  (%.3f, %.3f, %.3f)  %6.1f  %.2f  %.2f\n", g, c[0], c[1], c[2], h.h, h.s,
                h.v);
  };
  for (double g : {0.0, 100.0, 200.0, 225.0, 250.0, 300.0, 400.0, 425.0, 450.0, 475.0, 490.0,
                   500.0, 515.0, 530.0, 550.0, 565.0, 575.0, 600.0, 630.0, 660.0, 700.0, 750.0,
                   800.0})
    report(g, white_light_colour(g * nm, true));

  // Near-white greys (grey-blue -> white): low saturation, bright.
  for (double g : {200.0, 225.0, 250.0}) {
    const Hsv h = hsv(white_light_colour(g * nm, true));
    EXPECT_LT(h.s, 0.2) << g << " nm";
    EXPECT_GT(h.v, 0.8) << g << " nm";
  }
  // Yellow to brownish yellow: R and G high, B low; hue between orange (30) and yellow (60).
  for (double g : {400.0, 425.0, 450.0}) {
    const Rgb c = white_light_colour(g * nm, true);
    const Hsv h = hsv(c);
    EXPECT_GT(c[0], 0.8) << g << " nm";
    EXPECT_GT(c[1], 0.5) << g << " nm";
    EXPECT_LT(c[2], 0.35) << g << " nm";
    EXPECT_GE(h.h, 30) << g << " nm";
    EXPECT_LE(h.h, 60) << g << " nm";
  }
  // Orange-red to red: red dominant, hue within 30 degrees of red (0).
  for (double g : {475.0, 485.0, 495.0, 500.0}) {
    const Rgb c = white_light_colour(g * nm, true);
    EXPECT_GT(c[0], std::max(c[1], c[2])) << g << " nm";
    EXPECT_LT(hue_distance(hsv(c).h, 0), 30) << g << " nm";
  }
  // Sensitive tint (first-order red / purple): R and B above G, hue purple-magenta (260-320).
  for (double g : {530.0, 550.0, 565.0}) {
    const Rgb c = white_light_colour(g * nm, true);
    const Hsv h = hsv(c);
    EXPECT_GT(c[0], c[1]) << g << " nm";
    EXPECT_GT(c[2], c[1]) << g << " nm";
    EXPECT_GE(h.h, 260) << g << " nm";
    EXPECT_LE(h.h, 320) << g << " nm";
  }
  // Sky blue: blue dominant, hue 195-250 (cyan 180 .. blue 240).
  for (double g : {600.0, 630.0, 660.0}) {
    const Rgb c = white_light_colour(g * nm, true);
    EXPECT_GT(c[2], std::max(c[0], c[1])) << g << " nm";
    EXPECT_GE(hsv(c).h, 195) << g << " nm";
    EXPECT_LE(hsv(c).h, 250) << g << " nm";
  }
  // Greenish blue to green: G above R, hue between yellow-green (90) and cyan-blue (200).
  for (double g : {700.0, 725.0, 750.0, 775.0, 800.0}) {
    const Rgb c = white_light_colour(g * nm, true);
    EXPECT_GT(c[1], c[0]) << g << " nm";
    EXPECT_GE(hsv(c).h, 90) << g << " nm";
    EXPECT_LE(hsv(c).h, 200) << g << " nm";
  }

  // Order along the ramp: first Gamma (1 nm steps) at which each colour class appears as a bright
  // (HSV value > 0.5) colour; the dim blue-grey of the lowest retardations is not sky blue.
  auto first = [](auto pred) {
    for (int g = 0; g <= 1000; ++g) {
      const Rgb c = white_light_colour(g * nm, true);
      if (hsv(c).v > 0.5 && pred(c)) return g;
    }
    return -1;
  };
  const int yellow = first([](const Rgb& c) {
    const Hsv h = hsv(c);
    return h.s > 0.5 && h.h >= 30 && h.h <= 65;
  });
  const int red = first([](const Rgb& c) {
    const Hsv h = hsv(c);
    return h.s > 0.5 && hue_distance(h.h, 0) < 15;
  });
  const int purple = first([](const Rgb& c) {
    const Hsv h = hsv(c);
    return h.s > 0.5 && h.h >= 265 && h.h <= 300;
  });
  const int blue = first([](const Rgb& c) {
    const Hsv h = hsv(c);
    return h.s > 0.5 && h.h >= 200 && h.h <= 240 && c[1] > c[0];
  });
  const int green = first([](const Rgb& c) {
    const Hsv h = hsv(c);
    return h.s > 0.3 && h.h >= 90 && h.h <= 170;
  });
  std::printf("first appearance (nm): yellow %d, red %d, purple %d, blue %d, green %d\n", yellow,
              red, purple, blue, green);
  RecordProperty("first_yellow_nm", yellow);
  RecordProperty("first_red_nm", red);
  RecordProperty("first_purple_nm", purple);
  RecordProperty("first_blue_nm", blue);
  RecordProperty("first_green_nm", green);
  EXPECT_GT(yellow, 250);
  EXPECT_LT(yellow, red);
  EXPECT_LT(red, purple);
  EXPECT_LT(purple, blue);
  EXPECT_LT(blue, green);
  EXPECT_LT(green, 800);
}

// Continuity: no jumps along a fine ramp. The largest step is where a channel leaves 0, where the
// sRGB curve is steepest (slope 12.92); measured max 0.0171 per 0.2 nm, bound 0.03.
TEST(WhiteLight, ContinuousAlongRamp) {
  for (bool dark : {true, false}) {
    Rgb prev = white_light_colour(0, dark);
    double max_step = 0;
    for (int i = 1; i <= 20000; ++i) {  // 0 .. 4000 nm every 0.2 nm
      const Rgb c = white_light_colour(i * 0.2 * nm, dark);
      for (int k = 0; k < 3; ++k) max_step = std::max(max_step, std::abs(c[k] - prev[k]));
      prev = c;
    }
    std::printf("%s field: max channel step per 0.2 nm = %.4f\n", dark ? "dark" : "light",
                max_step);
    EXPECT_LT(max_step, 0.03);
  }
}

// The table behind white_light_rgb agrees with the direct sum, across the table's end too.
TEST(WhiteLight, TableMatchesDirect) {
  const auto dark = unit_settings(Polariscope::CircularDark);
  const auto light = unit_settings(Polariscope::CircularLight);
  const double per_pa = dark.wavelength;  // unit settings: Gamma = (s1 - s2) * wavelength
  double worst = 0;
  for (int i = 0; i <= 7000; ++i) {
    const double gamma = i * 1.0 * nm + 0.37 * nm;
    const double diff = gamma / per_pa;
    const Rgb a = white_light_rgb(diff, 0, 0, dark), b = white_light_colour(gamma, true);
    const Rgb c = white_light_rgb(diff, 0, 0, light), d = white_light_colour(gamma, false);
    for (int k = 0; k < 3; ++k)
      worst = std::max({worst, std::abs(a[k] - b[k]), std::abs(c[k] - d[k])});
  }
  std::printf("table vs direct: max difference %.2e\n", worst);
  EXPECT_LT(worst, 1e-3);
}

TEST(WhiteLight, Polariscopes) {
  const double diff = 150 * nm / 546e-9;  // Gamma = 150 nm: colours inside the sRGB gamut
  const Rgb dark = white_light_colour(150 * nm, true);
  // Plane crossed at 45 degrees to sigma1 is the circular dark field; on an isoclinic it is black.
  const Rgb c45 = white_light_rgb(diff, 0, 0, unit_settings(Polariscope::PlaneCrossed, kPi / 4));
  const Rgb c0 = white_light_rgb(diff, 0, 0, unit_settings(Polariscope::PlaneCrossed, 0));
  const Rgb p45 = white_light_rgb(diff, 0, 0, unit_settings(Polariscope::PlaneParallel, kPi / 4));
  const Rgb p0 = white_light_rgb(diff, 0, 0, unit_settings(Polariscope::PlaneParallel, 0));
  const Rgb c22 = white_light_rgb(diff, 0, 0, unit_settings(Polariscope::PlaneCrossed, kPi / 8));
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(c45[k], dark[k], 1e-3);
    EXPECT_NEAR(c0[k], 0, 1e-12);
    EXPECT_NEAR(p0[k], 1, 1e-12);
    // Crossed + parallel add up to white in linear light.
    EXPECT_NEAR(srgb_decode(c45[k]) + srgb_decode(p45[k]), 1, 1e-3);
    // Isoclinic factor 1/2 at 22.5 degrees, applied in linear light.
    EXPECT_NEAR(srgb_decode(c22[k]), 0.5 * srgb_decode(dark[k]), 1e-3);
  }
  // Light field and seed 002 show the light-field colour of the same retardation.
  PhotoelasticSettings seed;
  seed.mode = Polariscope::Seed002;
  const double seed_diff = 2 * kPi * (400 * nm / seed.wavelength) / seed.k_f;  // Gamma = 400 nm
  const Rgb s400 = white_light_rgb(seed_diff, 0, 0, seed);
  const Rgb l400 = white_light_colour(400 * nm, false);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(s400[k], l400[k], 1e-3);
}

// Far beyond the first orders the fringes of all wavelengths mix: high-order white, which is a
// neutral half-intensity gray in both fields (sRGB 0.735 for linear 0.5).
TEST(WhiteLight, HighOrderWhite) {
  for (double g_um : {40.0, 80.0, 500.0})
    for (bool dark : {true, false}) {
      const Rgb c = white_light_colour(g_um * 1e3 * nm, dark);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], srgb_encode(0.5), 0.03) << g_um << " um";
    }
}

// ---- colour maps --------------------------------------------------------------------------------

TEST(ColorMap, Names) {
  EXPECT_EQ(colormap_from_name("viridis"), ColorMapKind::Viridis);
  EXPECT_EQ(colormap_from_name("cividis"), ColorMapKind::Cividis);
  EXPECT_EQ(colormap_from_name("coolwarm"), ColorMapKind::CoolWarm);
  EXPECT_EQ(colormap_from_name("gray"), ColorMapKind::Gray);
  EXPECT_EQ(colormap_from_name("Viridis"), ColorMapKind::Viridis);
  EXPECT_FALSE(colormap_from_name("jet").has_value());
  for (ColorMapKind k :
       {ColorMapKind::Viridis, ColorMapKind::Cividis, ColorMapKind::CoolWarm, ColorMapKind::Gray})
    EXPECT_EQ(colormap_from_name(std::string(colormap_name(k))), k);
}

TEST(ColorMap, ViridisAndCividisEndpoints) {
  const Rgb v0 = colormap(ColorMapKind::Viridis, 0), v1 = colormap(ColorMapKind::Viridis, 1);
  const Rgb v0_ref = {0.267, 0.005, 0.329}, v1_ref = {0.993, 0.906, 0.144};
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(v0[k], v0_ref[k], 0.002);
    EXPECT_NEAR(v1[k], v1_ref[k], 0.002);
  }
  // Midpoint: matplotlib entry 127.5 of 255, (0.128, 0.565, 0.551).
  const Rgb vm = colormap(ColorMapKind::Viridis, 0.5);
  EXPECT_NEAR(vm[0], 0.128, 0.003);
  EXPECT_NEAR(vm[1], 0.565, 0.003);
  EXPECT_NEAR(vm[2], 0.551, 0.003);
  const Rgb c0 = colormap(ColorMapKind::Cividis, 0), c1 = colormap(ColorMapKind::Cividis, 1);
  const Rgb c0_ref = {0.0, 0.135, 0.305}, c1_ref = {0.996, 0.909, 0.218};
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(c0[k], c0_ref[k], 0.002);
    EXPECT_NEAR(c1[k], c1_ref[k], 0.002);
  }
}

TEST(ColorMap, MonotoneLightness) {
  for (ColorMapKind k : {ColorMapKind::Viridis, ColorMapKind::Cividis, ColorMapKind::Gray}) {
    double prev = cie_lightness(colormap(k, 0));
    const double first = prev;
    for (int i = 1; i <= 1000; ++i) {
      const double l = cie_lightness(colormap(k, i / 1000.0));
      EXPECT_GT(l, prev) << colormap_name(k) << " t = " << i / 1000.0;
      prev = l;
    }
    EXPECT_GT(prev - first, 50) << colormap_name(k);  // a real ramp, not a flat one
  }
}

TEST(ColorMap, CoolWarm) {
  const Rgb mid = colormap(ColorMapKind::CoolWarm, 0.5);
  // Moreland's neutral (221, 221, 221).
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(mid[k], 221 / 255.0, 0.01);
  const Rgb lo = colormap(ColorMapKind::CoolWarm, 0), hi = colormap(ColorMapKind::CoolWarm, 1);
  const Rgb lo_ref = {59 / 255.0, 76 / 255.0, 192 / 255.0};
  const Rgb hi_ref = {180 / 255.0, 4 / 255.0, 38 / 255.0};
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(lo[k], lo_ref[k], 1.0 / 255);
    EXPECT_NEAR(hi[k], hi_ref[k], 1.0 / 255);
  }
  // Blue below the centre, red above; lightness rises to the centre and falls after it.
  const Rgb q1 = colormap(ColorMapKind::CoolWarm, 0.25);
  const Rgb q3 = colormap(ColorMapKind::CoolWarm, 0.75);
  EXPECT_GT(q1[2], q1[0]);
  EXPECT_GT(q3[0], q3[2]);
  double prev = cie_lightness(lo);
  for (int i = 1; i <= 1000; ++i) {
    const double l = cie_lightness(colormap(ColorMapKind::CoolWarm, i / 1000.0));
    if (i <= 500) EXPECT_GT(l, prev) << i;
    else EXPECT_LT(l, prev) << i;
    prev = l;
  }
}

TEST(ColorMap, ClampNaNAndTable) {
  for (ColorMapKind k :
       {ColorMapKind::Viridis, ColorMapKind::Cividis, ColorMapKind::CoolWarm, ColorMapKind::Gray}) {
    EXPECT_EQ(colormap(k, -3), colormap(k, 0));
    EXPECT_EQ(colormap(k, 7), colormap(k, 1));
    EXPECT_EQ(colormap(k, kNaN), (Rgb{0.5, 0.5, 0.5}));
    const auto table = colormap_table(k, 256);
    ASSERT_EQ(table.size(), 256u);
    for (int i : {0, 100, 255}) {
      const Rgb c = colormap(k, i / 255.0);
      for (int ch = 0; ch < 3; ++ch)
        EXPECT_EQ(table[i][ch], static_cast<int>(std::lround(c[ch] * 255)));
    }
  }
  EXPECT_EQ(colormap_table(ColorMapKind::Gray, 2)[1], (std::array<std::uint8_t, 3>{255, 255, 255}));
  EXPECT_EQ(colormap_table(ColorMapKind::Gray, 1).size(), 1u);
  EXPECT_TRUE(colormap_table(ColorMapKind::Gray, 0).empty());
}

TEST(ColorMap, SrgbConversions) {
  for (double v : {0.0, 0.002, 0.01, 0.2, 0.5, 1.0})
    EXPECT_NEAR(srgb_decode(srgb_encode(v)), v, 1e-12);
  EXPECT_NEAR(srgb_encode(0.5), 0.735357, 1e-6);
  // The two IEC 61966-2-1 matrices are inverses (to their 4 published digits).
  const Rgb c = {0.2, 0.7, 0.4};
  const Rgb back = linear_srgb_from_xyz(xyz_from_linear_srgb(c));
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(back[k], c[k], 1e-3);
  EXPECT_NEAR(cie_lightness({1, 1, 1}), 100, 1e-9);
  EXPECT_NEAR(cie_lightness({0, 0, 0}), 0, 1e-9);
}

}  // namespace
