// What the rasterizer's parts share (not part of the raster interface, viz/raster/rasterize.hpp):
// each particle's footprint, its domain square deformed by its strain and turned by its rotation.
#pragma once
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "viz/raster/series.hpp"

#ifdef _OPENMP
#define CLEAVE_OMP(x) _Pragma(x)
#else
#define CLEAVE_OMP(x)
#endif

namespace cleave::viz::detail {

// Footprint test slack (in footprint edges): neighbouring footprints deformed by different strains
// leave slivers of order h * (strain difference) between them; 2 % closes those without hiding a
// crack that has opened by more than 2 % of a particle.
constexpr double kInsideTol = 0.02;

inline bool finite3(const std::array<double, 3>& p) {
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

// The array `name` if it has at least `comps` components and one tuple per particle.
const PointArray* array_with(const ParticleFrame& f, const char* name, int comps);

// A symmetric tensor of six components in VTK order (xx, yy, zz, xy, yz, xz) in a plane's axes
// (u, w unit vectors in the plane): {uu, ww, uw}, what a section's "strain_uv" and "stress_uv" hold.
inline std::array<double, 3> in_plane_tensor(const double* e, const std::array<double, 3>& u,
                                             const std::array<double, 3>& w) {
  const double E[3][3] = {{e[0], e[3], e[5]}, {e[3], e[1], e[4]}, {e[5], e[4], e[2]}};
  auto quad = [&](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    double r = 0;
    for (std::size_t i = 0; i < 3; ++i)
      for (std::size_t j = 0; j < 3; ++j) r += a[i] * E[i][j] * b[j];
    return r;
  };
  return {quad(u, u), quad(w, w), quad(u, w)};
}

// Footprint of a particle: centre (x, y), domain edge s, bounding half-extents (hx, hy) and the
// map a = (F s)^-1 from model offsets to footprint coordinates (the footprint is |a (x - c)| <= 1/2
// in both components), F = R(rotation) (I + strain).
struct Foot {
  double x, y, s, inv_s, hx, hy, a00, a01, a10, a11;
};

// Footprints of a 2D frame (rasterize.hpp, rasterize_2d, says how strain and rotation enter);
// valid[p] = 0 where the position is not finite.
void footprints(const ParticleFrame& f, std::vector<Foot>& foot, std::vector<uint8_t>& valid);

// Smooth outline (outline.cpp): moves the coverage of owner (-1: uncovered) to the level 1/2 of a
// smoothed indicator near the bodies' edges, and gives each pixel its signed distance to the
// outline in pixels (positive inside; +-infinity away from edges). RasterOptions says why.
void smooth_outline(const std::vector<Foot>& foot, const std::vector<uint8_t>& valid, double x0, double y1,
                    double pw, double ph, int W, int H, std::vector<int32_t>& owner, std::vector<float>& edge);

}  // namespace cleave::viz::detail
