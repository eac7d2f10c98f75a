// Colour maps for scalar fields (no VTK): perceptually uniform sequential maps (viridis, cividis),
// Moreland's diverging cool-warm map for signed fields and a gray ramp; plus the few sRGB / CIE
// conversions the maps and the photoelastic white-light colours share.
//
// Every colour is sRGB, gamma-encoded (what goes into an 8-bit image), components in [0, 1].
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cleave::viz {

using Rgb = std::array<double, 3>;

enum class ColorMapKind { Viridis, Cividis, CoolWarm, Gray };

// "viridis", "cividis", "coolwarm", "gray" (ASCII case-insensitive); nullopt for anything else.
std::optional<ColorMapKind> colormap_from_name(const std::string& name);
// The name colormap_from_name accepts for `kind` (lower case).
std::string_view colormap_name(ColorMapKind kind);

// Colour of t in [0, 1]: t is clamped to [0, 1]; NaN gives the neutral gray (0.5, 0.5, 0.5).
//  - Viridis, Cividis: linear interpolation (in gamma-encoded sRGB, as matplotlib's ListedColormap
//    does between its 256 entries) between 33 control points of the published 256-entry tables
//    (entries 0, 8, ..., 248 and 255; cividis also 252, where its blue turns back up).
//  - CoolWarm: Moreland's diverging map (K. Moreland, "Diverging color maps for scientific
//    visualization", ISVC 2009): the end points (59, 76, 192) and (180, 4, 38) interpolated in his
//    Msh space (polar CIELAB, D65 white) through the white point M = 88, so t = 0.5 is the light
//    neutral (221, 221, 221) and the two halves have equal, monotone lightness ramps.
//  - Gray: (t, t, t) in encoded sRGB.
Rgb colormap(ColorMapKind kind, double t);

// n entries at t = i / (n - 1), i = 0..n-1 (n == 1: t = 0.5; n <= 0: empty), rounded to 8 bits.
std::vector<std::array<std::uint8_t, 3>> colormap_table(ColorMapKind kind, int n);

// ---- shared colour conversions (IEC 61966-2-1 sRGB, D65) ------------------------------------
// sRGB transfer function on one component: linear light <-> gamma-encoded value. No clamping.
double srgb_encode(double linear);
double srgb_decode(double encoded);
// CIE XYZ (Y = 1 for the reference white) <-> linear sRGB with the IEC 61966-2-1 matrices.
Rgb linear_srgb_from_xyz(const std::array<double, 3>& xyz);
std::array<double, 3> xyz_from_linear_srgb(const Rgb& rgb);
// CIE L* (0 black .. 100 white) of a gamma-encoded sRGB colour.
double cie_lightness(const Rgb& srgb);

}  // namespace cleave::viz
