// Photoelasticity (no VTK): what a polariscope shows of an in-plane stress state, in monochromatic
// and in white light, and the Brazilian-disk closed form used to check it. Formulas:
// /work/shared/reference/validation.md section 7 (docs/validation.md in the repository).
//
// Conventions
//  - Stresses in Pa, lengths in m, angles in rad measured from +x towards +y.
//  - Fringe order N = t (s1 - s2) / f_sigma, relative retardation delta = 2 pi N (phase) and
//    Gamma = N lambda (path difference, m). f_sigma is `fringe_constant` when > 0, else
//    wavelength / stress_optic (C); with neither set the functions that need f_sigma throw
//    std::invalid_argument.
//  - Intensities are relative to I0 = 1, the light leaving the polariser.
//  - Polariscope::Seed002 is the form of seed 002, eq. 23: I = (1 + cos(k_f (s1 - s2))) / 2, i.e.
//    cos^2(delta / 2) with delta = k_f (s1 - s2): a light-field picture (zero stress is bright,
//    the dark fringes are at k_f (s1 - s2) = pi, 3 pi, ...), with 2 pi t / f_sigma folded into
//    k_f. In this mode thickness, fringe_constant and stress_optic are not used: N is
//    k_f (s1 - s2) / (2 pi), Gamma = N * wavelength, and white light shows light-field colours.
//  - Non-finite stresses give NaN from the scalar functions (fringe_order, intensity,
//    retardation) and the neutral gray (0.5, 0.5, 0.5) from white_light_rgb.
#pragma once
#include <array>
#include <optional>
#include <string>
#include <string_view>

namespace cleave::viz {

enum class Polariscope { CircularDark, CircularLight, PlaneCrossed, PlaneParallel, Seed002 };

// "dark", "light", "crossed", "parallel", "seed002" (ASCII case-insensitive); nullopt otherwise.
std::optional<Polariscope> polariscope_from_name(const std::string& name);
// The name polariscope_from_name accepts for `mode`.
std::string_view polariscope_name(Polariscope mode);

struct PhotoelasticSettings {
  Polariscope mode = Polariscope::CircularDark;
  double thickness = 1e-3;       // m
  double fringe_constant = 0.0;  // f_sigma in Pa*m/fringe at `wavelength` (0 = use stress_optic)
  double stress_optic = 0.0;     // C in 1/Pa (f_sigma = wavelength / C)
  double wavelength = 546e-9;    // m, monochromatic light
  double polarizer_angle = 0.0;  // rad, plane polariscope axis from x
  double k_f = 0.0889e-6;        // 1/Pa, seed 002 eq. 23 (0.0889 /MPa)
  bool white_light = false;
};

// f_sigma used by the settings (Pa*m/fringe): fringe_constant if > 0, else wavelength /
// stress_optic if stress_optic > 0; otherwise throws std::invalid_argument.
double effective_fringe_constant(const PhotoelasticSettings& s);

// Principal stress difference s1 - s2 >= 0 and the angle theta in (-pi/2, pi/2] of sigma1 from x.
struct InPlane {
  double diff, theta;
};
InPlane in_plane(double sxx, double syy, double sxy);

// N = t (s1 - s2) / f_sigma at the set wavelength (Seed002: k_f (s1 - s2) / (2 pi)).
double fringe_order(double sxx, double syy, double sxy, const PhotoelasticSettings& s);

// Monochromatic intensity in [0, 1], I0 = 1, with delta = 2 pi N and
// phi = theta - polarizer_angle (theta: direction of sigma1):
//   CircularDark  sin^2(delta/2)              CircularLight  cos^2(delta/2)
//   PlaneCrossed  sin^2(2 phi) sin^2(delta/2) PlaneParallel  1 - sin^2(2 phi) sin^2(delta/2)
//   Seed002       (1 + cos(k_f (s1 - s2))) / 2   (light-field form, zero stress bright)
double intensity(double sxx, double syy, double sxy, const PhotoelasticSettings& s);

// Retardation (path difference, m): Gamma = t C (s1 - s2) with C = wavelength / f_sigma, i.e.
// Gamma = N * wavelength (Seed002: k_f (s1 - s2) wavelength / (2 pi)).
double retardation(double sxx, double syy, double sxy, const PhotoelasticSettings& s);

// White-light colour (sRGB, gamma-encoded, [0, 1]) of the stress state in the set polariscope:
// the retardation's colour from a precomputed table (below), dark field for CircularDark, light
// field for CircularLight and Seed002; the plane polariscopes mix in linear light with the
// isoclinic factor q = sin^2(2 phi): crossed q * dark, parallel white - q * dark.
std::array<double, 3> white_light_rgb(double sxx, double syy, double sxy,
                                      const PhotoelasticSettings& s);

// Colour of retardation Gamma (m; |Gamma| is used) between crossed circular polarisers
// (dark_field) or parallel ones (light field), computed directly (no table):
//   XYZ = k * sum over lambda = 380..780 nm in 1 nm steps of D65(lambda) cmf(lambda) I(lambda),
//   I = sin^2(pi Gamma / lambda) (dark) or cos^2 (light),
// with the CIE 1931 2-degree colour-matching functions and the D65 power distribution tabulated at
// 5 nm (CIE 15:2004) and interpolated linearly, and k such that Y = 1 for I = 1. The oscillating
// part of I is averaged over each 1 nm band (a sinc factor), which only matters at high orders
// (>~ 20 um), where it turns the sum into the true high-order white instead of aliasing.
// XYZ -> linear sRGB (IEC 61966-2-1) -> divided per channel by the linear sRGB of the D65 sum
// itself (a white balance of < 0.5 %, so Gamma = 0 in light field is exactly (1, 1, 1)) ->
// clamped to [0, 1] -> sRGB gamma. Gamma = 0 in dark field is exactly black. Non-finite Gamma:
// the neutral gray (0.5, 0.5, 0.5).
std::array<double, 3> white_light_colour(double Gamma, bool dark_field);

// The white_light_rgb table: kWhiteLightTableSize entries of the dark-field linear colour evenly
// over Gamma in [0, kWhiteLightTableMax], interpolated linearly (0.73 nm per entry; largest
// difference from white_light_colour measured 9e-5 per encoded channel). Larger retardations are
// computed directly. Built once, on first use (about 0.15 s), thread-safe.
inline constexpr int kWhiteLightTableSize = 8192;
inline constexpr double kWhiteLightTableMax = 6000e-9;  // m

// Brazilian disk (validation.md section 7): disk of radius R and thickness t, diametral
// compression P (N) applied at (0, +R) and (0, -R); stress at (x, y) from the centre. Singular (inf
// or NaN) at the two load points.
struct Stress2 {
  double xx, yy, xy;
};
Stress2 brazilian_disk_stress(double x, double y, double R, double P, double t);

}  // namespace cleave::viz
