// Smoothing particle values before they are drawn. MPM particles that cross cell boundaries carry a
// stress noise at the scale of the cells (the "checkerboard" of a fringe image: bright and dark
// patches two particles across); a fringe image of the stress as it is shows that noise as if it
// were fringes. Real fringes are level lines of a stress that varies over many particles, so a
// smoothing that reproduces linear fields exactly keeps them where they are.
#pragma once
#include <array>
#include <vector>

#include "viz/raster/series.hpp"

namespace cleave::viz {

struct SmoothSettings {
  // Gaussian width in particle spacings (each particle's own "size"); <= 0: no smoothing.
  double sigma = 1.5;
  // 2D segments {x0, y0, x1, y1} (model units) that nothing is averaged across: crack paths.
  std::vector<std::array<double, 4>> barriers;
};

// The k values per particle (point-major, values.size() == k * frame.size()) of a 2D frame,
// smoothed: at each particle, the value at its centre of the linear function fitted by weighted
// least squares (weights exp(-r^2 / 2 sigma^2) times the particle's area, r < 3 sigma) to the
// particles around it, which reproduces constant and linear fields exactly, also at a free edge.
// Only particles reached from it through touching footprints (gaps under a quarter spacing, as in
// rasterize_2d), without crossing a barrier, and of the same "material" (when the frame has that
// array) take part: nothing is averaged across an opened crack, a crack path, or from one material
// into another. Where the fit is degenerate (a particle alone, a row of particles) the weighted mean
// is used. Deterministic and independent of the thread count. Throws std::invalid_argument for a 3D
// frame or a bad size of `values`.
std::vector<double> smooth_particle_values(const ParticleFrame& frame, const std::vector<double>& values, int k,
                                           const SmoothSettings& settings);

// The frame with its "stress" array (six components) and a section's "stress_uv" (three) smoothed,
// and the arrays derived from the stress ("von_mises", "principal_stress_difference") removed, so
// that scalar_field computes them from the smoothed stress. The frame as it is when sigma <= 0 or
// it has neither array.
ParticleFrame smooth_stress(const ParticleFrame& frame, const SmoothSettings& settings);

}  // namespace cleave::viz
