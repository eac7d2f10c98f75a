// Turning particles into a continuous per-pixel field. Each particle covers its own footprint (its
// square domain, deformed by its strain), so bodies are solid, gaps and opened cracks stay empty,
// and inside a body the value is a tent-weighted average of nearby particles, which reproduces
// linear fields exactly on a regular lattice.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "viz/raster/series.hpp"

namespace cleave::viz {

// A model-space window mapped onto width x height pixels. Pixel (i, j) has its centre at
// (x0 + (i + 0.5) (x1 - x0) / width, y1 - (j + 0.5) (y1 - y0) / height): row j = 0 is the top.
struct View {
  double x0 = 0, y0 = 0, x1 = 1, y1 = 1;
  int width = 0, height = 0;
  double pixel_width() const { return (x1 - x0) / width; }
  double pixel_height() const { return (y1 - y0) / height; }
  // Pixel centres, computed exactly as rasterize_2d does.
  double pixel_x(int i) const { return x0 + (i + 0.5) * pixel_width(); }
  double pixel_y(int j) const { return y1 - (j + 0.5) * pixel_height(); }
};

// Fits the bodies into width x height with square pixels. The bodies' box is the particles' x/y
// bounds padded by half of each particle's size, then by `margin` x (its larger side) on every
// side; `roi` {x0, y0, x1, y1}, when given, replaces that box (no margin). The box is centred and
// widened along one axis to the image's aspect ratio; `zoom` > 1 then shrinks the window about
// its centre by that factor (zoom < 1 widens it). A 3D frame is fitted by its x/y projection.
// Throws std::invalid_argument for width/height < 1, zoom <= 0, margin < 0, a degenerate roi, or
// an empty frame without roi.
View fit_view(const ParticleFrame& frame, int width, int height,
              std::optional<std::array<double, 4>> roi, double zoom, double margin = 0.03);

// The box fit_view widens to the image's aspect ratio: {x0, y0, x1, y1} of the bodies with their
// margin, or roi. Throws as fit_view does.
std::array<double, 4> bodies_box(const ParticleFrame& frame, std::optional<std::array<double, 4>> roi,
                                 double margin = 0.03);

// Per-pixel field. values: k per pixel, pixel-major (index (j * width + i) * k + c), row 0 at the
// top; uncovered pixels hold quiet NaN. covered: 1/0 per pixel. owner: index (into the frame) of
// the particle whose footprint covers the pixel centre (the one whose centre is nearest in its
// own footprint coordinates, lowest index on a tie), -1 where uncovered.
// edge (only with RasterOptions::smooth_outline): per pixel, the signed distance from its centre to
// the bodies' outline in pixels (positive inside; +-infinity away from the edges), for drawing the
// outline antialiased.
struct Raster {
  View view;
  int k = 0;
  std::vector<double> values;
  std::vector<uint8_t> covered;
  std::vector<int32_t> owner;
  std::vector<float> edge;
};

// smooth_outline: the bodies' outlines follow a smooth curve rather than the particles' square
// footprints, whose union is stair-stepped at the particle scale wherever an edge is not parallel to
// the particle lattice (a disk's rim). Near the edges, coverage becomes the level 1/2 of
// D = sum over particles of their footprint's indicator blurred by a Gaussian of 1.5 spacings: a
// partition of unity inside a body, exactly 1/2 where the squares of a straight edge end, and
// blurred over several steps of a staircase, so its level line runs smoothly through the steps.
// The coverage moves by at most 3/4 of a spacing; it never empties a covered pixel with empty space
// on opposite sides within 1.6 spacings (a thin ligament) nor rounds a corner whose two edges run
// straight for 2.5 spacings (a rectangle's). Gaps narrower than about 1.5 spacings close (the
// slivers a staircase leaves where two disks touch; also a crack opened by less than that, which
// the raw footprints show). Pixels it covers are owned by the particle whose blurred footprint is
// largest there.
struct RasterOptions {
  bool smooth_outline = false;
};

// Interpolates k per-particle values (per_particle.size() == k * frame.size(), point-major) onto
// the view, for a 2D frame (dim == 2; for 3D use cut_plane first).
//  Footprint of particle p: the square of edge s_p (array "size"; where absent or not positive,
//   the median nearest-neighbour spacing) centred on it, its edge vectors multiplied by I + eps
//   (eps = uu, vv, uv of array "strain_uv" if present, else xx, yy, xy of array "strain";
//   components clamped to [-2, 2]; the square stays undeformed if det(I + eps) < 0.1).
//   A pixel is covered when its centre lies inside some footprint.
//  Value at a covered pixel: sum w_q f_q / sum w_q, w_q = max(0, 1 - |dx|/s_q) max(0, 1 - |dy|/s_q)
//   over particles q within one spacing of the pixel centre that are connected to the pixel's
//   owner o (their footprints' bounding boxes are within 0.25 min(s_o, s_q) of touching), so
//   values are never averaged across a crack that has opened by more than a quarter spacing.
//   Where all weights vanish the owner's value is used.
// Deterministic: bit-identical results for any number of OpenMP threads.
// Throws std::invalid_argument for a 3D frame, a bad size of per_particle, k < 0, or an empty view.
Raster rasterize_2d(const ParticleFrame& frame, const View& view,
                    const std::vector<double>& per_particle, int k, const RasterOptions& options = {});

// In-plane axes (u, v) of a cutting plane with this normal (need not be unit length): normal z ->
// (x, y), normal x -> (y, z), normal y -> (x, z) (either sign of the normal). Otherwise u is the
// x axis (the y axis when the normal is mostly along x) projected into the plane and v = n x u,
// flipped to point upwards (positive z, or positive y when it has no z).
std::pair<std::array<double, 3>, std::array<double, 3>> plane_axes(std::array<double, 3> normal);

// The particles whose domain (axis-aligned cube of edge "size", or the median nearest-neighbour
// spacing) meets the plane through `point` with `normal` (half-open and shifted by r/10 towards
// -n: -1.1 r <= n.(x - point) < 0.9 r, so a plane on a lattice face takes the whole layer below it
// even when rounding or small displacements move its particles off the face), as a 2D frame:
// x = (u.x, v.x, 0) with (u, v) from plane_axes, dim = 2, time and file kept, every array kept as
// is (global components), plus
// "strain_uv" (e_uu, e_vv, e_uv, the strain in the plane's axes, for the footprints) when "strain"
// is present, "stress_uv" (s_uu, s_vv, s_uv, the section's in-plane stress, for fringes) when
// "stress" is, and "size" when it was missing. Throws std::invalid_argument for a zero normal.
ParticleFrame cut_plane(const ParticleFrame& frame, std::array<double, 3> point,
                        std::array<double, 3> normal);

// Median distance from a particle to its nearest neighbour (x, y for dim 2; x, y, z for dim 3),
// ignoring coincident particles; sampled over at most 20 000 particles. 0 when undefined (fewer
// than two distinct positions).
double median_spacing(const ParticleFrame& frame);

// Per-particle edge of the domain: array "size" where positive and finite, else median_spacing
// (1 if that is undefined too).
std::vector<double> particle_sizes(const ParticleFrame& frame);

}  // namespace cleave::viz
