// Sections of 3D frames: a cutting plane's axes and the particles whose domains it meets, as a 2D
// frame (viz/raster/rasterize.hpp).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>

#include "viz/raster/footprints.hpp"
#include "viz/raster/rasterize.hpp"

namespace cleave::viz {

using detail::array_with;
using detail::finite3;

namespace {
constexpr double kFaceShift = 0.1;  // of the half-thickness: see cut_plane
}  // namespace

std::pair<std::array<double, 3>, std::array<double, 3>> plane_axes(std::array<double, 3> n) {
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(len > 0) || !std::isfinite(len))
    throw std::invalid_argument("plane normal must be a non-zero finite vector");
  for (double& c : n) c /= len;
  const double ax = std::abs(n[0]), ay = std::abs(n[1]), az = std::abs(n[2]);
  constexpr double kAxis = 1e-12;
  if (az >= 1 - kAxis) return {{1, 0, 0}, {0, 1, 0}};
  if (ax >= 1 - kAxis) return {{0, 1, 0}, {0, 0, 1}};
  if (ay >= 1 - kAxis) return {{1, 0, 0}, {0, 0, 1}};
  const std::array<double, 3> e = (ax >= ay && ax >= az) ? std::array<double, 3>{0, 1, 0}
                                                         : std::array<double, 3>{1, 0, 0};
  const double en = e[0] * n[0] + e[1] * n[1] + e[2] * n[2];
  std::array<double, 3> u = {e[0] - en * n[0], e[1] - en * n[1], e[2] - en * n[2]};
  const double ul = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  for (double& c : u) c /= ul;
  std::array<double, 3> w = {n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0]};
  if (w[2] < -kAxis || (std::abs(w[2]) <= kAxis && w[1] < 0))
    for (double& c : w) c = -c;
  return {u, w};
}

ParticleFrame cut_plane(const ParticleFrame& f, std::array<double, 3> point, std::array<double, 3> normal) {
  const auto [u, w] = plane_axes(normal);
  const double len = std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
  std::array<double, 3> nn;
  for (int d = 0; d < 3; ++d) nn[static_cast<std::size_t>(d)] = normal[static_cast<std::size_t>(d)] / len;
  // Half-thickness of an axis-aligned cube of edge s along nn: s/2 (|nx| + |ny| + |nz|).
  const double reach = 0.5 * (std::abs(nn[0]) + std::abs(nn[1]) + std::abs(nn[2]));
  const std::vector<double> s = particle_sizes(f);
  const bool had_size = array_with(f, "size", 1) != nullptr;

  std::vector<std::size_t> keep;
  for (std::size_t p = 0; p < f.x.size(); ++p) {
    if (!finite3(f.x[p])) continue;
    const double d = nn[0] * (f.x[p][0] - point[0]) + nn[1] * (f.x[p][1] - point[1]) + nn[2] * (f.x[p][2] - point[2]);
    // A plane on a lattice face (the middle of a body a whole number of cells long: where one cuts)
    // has the layers beside it at d = -r and d = +r only up to rounding and the particles' small
    // displacements, so the exact test -r <= d < r took parts of both layers or of neither (a strip
    // one particle tall, or no particle). The window shifted by r/10 towards -n takes the layer
    // below whole while its particles are off the face by less than that.
    const double r = reach * s[p], shift = kFaceShift * r;
    if (d >= -r - shift && d < r - shift) keep.push_back(p);
  }

  ParticleFrame out;
  out.time = f.time;
  out.dim = 2;
  out.file = f.file;
  out.x.resize(keep.size());
  auto dot = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  };
  for (std::size_t i = 0; i < keep.size(); ++i) out.x[i] = {dot(u, f.x[keep[i]]), dot(w, f.x[keep[i]]), 0.0};
  for (const auto& [name, a] : f.arrays) {
    const std::size_t c = static_cast<std::size_t>(a.components);
    if (a.components < 1 || a.values.size() != f.x.size() * c) continue;  // inconsistent: dropped
    PointArray b;
    b.components = a.components;
    b.values.resize(keep.size() * c);
    for (std::size_t i = 0; i < keep.size(); ++i)
      std::copy_n(&a.values[keep[i] * c], c, &b.values[i * c]);
    out.arrays[name] = std::move(b);
  }
  // Tensors in the plane's axes: the strain for the footprints, the stress for fringes (the section's
  // in-plane stress, not the global xx, yy, xy).
  for (const char* name : {"strain", "stress"}) {
    const PointArray* t6 = array_with(f, name, 6);
    if (!t6) continue;
    const std::size_t c = static_cast<std::size_t>(t6->components);
    PointArray b;
    b.components = 3;
    b.values.resize(keep.size() * 3);
    for (std::size_t i = 0; i < keep.size(); ++i) {
      const auto t = detail::in_plane_tensor(&t6->values[keep[i] * c], u, w);
      std::copy(t.begin(), t.end(), &b.values[3 * i]);
    }
    out.arrays[std::string(name) + "_uv"] = std::move(b);
  }
  if (!had_size) {
    PointArray b;
    b.values.resize(keep.size());
    for (std::size_t i = 0; i < keep.size(); ++i) b.values[i] = s[keep[i]];
    out.arrays["size"] = std::move(b);
  }
  return out;
}


}  // namespace cleave::viz
