#include "viz/raster/footprints.hpp"

#include <algorithm>

#include "viz/raster/rasterize.hpp"

namespace cleave::viz::detail {

namespace {
constexpr double kMaxStrain = 2.0;  // footprint strain components are clamped to +-this
constexpr double kMinDet = 0.1;     // below this det(I + eps) the footprint stays square
}  // namespace

const PointArray* array_with(const ParticleFrame& f, const char* name, int comps) {
  auto it = f.arrays.find(name);
  if (it == f.arrays.end()) return nullptr;
  const PointArray& a = it->second;
  if (a.components < comps || a.values.size() != f.x.size() * static_cast<std::size_t>(a.components))
    return nullptr;
  return &a;
}

void footprints(const ParticleFrame& f, std::vector<Foot>& foot, std::vector<uint8_t>& valid) {
  const std::size_t n = f.x.size();
  foot.assign(n, Foot{});
  valid.assign(n, 0);
  const std::vector<double> s = particle_sizes(f);
  const PointArray* suv = array_with(f, "strain_uv", 3);
  const PointArray* s6 = suv ? nullptr : array_with(f, "strain", 6);
  // In-plane rotation (2D series): footprints turn with the material, so a bent or spinning body
  // leaves no slivers between its particles.
  const PointArray* rot = suv ? nullptr : array_with(f, "rotation", 1);
  CLEAVE_OMP("omp parallel for schedule(static)")
  for (std::ptrdiff_t ip = 0; ip < static_cast<std::ptrdiff_t>(n); ++ip) {
    const std::size_t p = static_cast<std::size_t>(ip);
    if (!std::isfinite(f.x[p][0]) || !std::isfinite(f.x[p][1])) continue;
    double exx = 0, eyy = 0, exy = 0;
    if (suv) {
      const double* e = &suv->values[p * static_cast<std::size_t>(suv->components)];
      exx = e[0]; eyy = e[1]; exy = e[2];
    } else if (s6) {
      const double* e = &s6->values[p * static_cast<std::size_t>(s6->components)];
      exx = e[0]; eyy = e[1]; exy = e[3];
    }
    auto clampe = [](double e) { return std::isfinite(e) ? std::clamp(e, -kMaxStrain, kMaxStrain) : 0.0; };
    double f00 = 1 + clampe(exx), f11 = 1 + clampe(eyy), f01 = clampe(exy), f10 = f01;
    double det = f00 * f11 - f01 * f10;
    if (!(det >= kMinDet)) { f00 = f11 = 1; f01 = f10 = 0; det = 1; }
    if (rot && std::isfinite(rot->values[p])) {
      const double cw = std::cos(rot->values[p]), sw = std::sin(rot->values[p]);
      const double g00 = cw * f00 - sw * f10, g01 = cw * f01 - sw * f11;
      const double g10 = sw * f00 + cw * f10, g11 = sw * f01 + cw * f11;
      f00 = g00, f01 = g01, f10 = g10, f11 = g11;  // det unchanged by a rotation
    }
    Foot& F = foot[p];
    F.x = f.x[p][0];
    F.y = f.x[p][1];
    F.s = s[p];
    F.inv_s = 1.0 / s[p];
    F.hx = 0.5 * s[p] * (std::abs(f00) + std::abs(f01));
    F.hy = 0.5 * s[p] * (std::abs(f10) + std::abs(f11));
    const double c = 1.0 / (det * s[p]);
    F.a00 = f11 * c;
    F.a01 = -f01 * c;
    F.a10 = -f10 * c;
    F.a11 = f00 * c;
    valid[p] = 1;
  }
}

}  // namespace cleave::viz::detail
