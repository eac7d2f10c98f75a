// The material of a model as the checks on cracks see it: in 3D a point test (crack fronts inside
// the material, crack_tips contours that leave it); in 2D how far it reaches ahead of a crack end
// (an end near a free edge, read from the scene or grown there).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "libmpm/mpm/model.hpp"

namespace cleave {

// From the particles' domains (the cube of each
// particle's spacing about it, from its volume), binned by grid cell; a point on the body's face
// (a surface crack's edge placed on it) is outside.
class MaterialProbe {
 public:
  explicit MaterialProbe(const Model<3>& m) : m_(m), half_(m.particles.size()) {
    const auto& P = m.particles;
    for (std::size_t p = 0; p < P.size(); ++p) {
      half_[p] = 0.5 * std::cbrt(P.volume0[p]);
      bins_.push_back({cell(P.x[p]), static_cast<int32_t>(p)});
    }
    std::sort(bins_.begin(), bins_.end());
  }
  // x is inside when the material surrounds it: each of the eight points x + eps (+-1, +-1, +-1)
  // lies in a particle's open domain (so a point on the face shared by two particles' domains is
  // inside, one on the body's face is not).
  bool operator()(const Vec<3>& x) const {
    const double eps = 1e-6 * m_.grid.h;
    for (int k = 0; k < 8; ++k)
      if (!within(x + eps * Vec<3>(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1), 0.0)) return false;
    return true;
  }
  // Is x within `reach` (max-norm) of the material?
  bool near(const Vec<3>& x, double reach) const { return within(x, reach); }

 private:
  // Does some particle's open domain grown by reach hold x?
  bool within(const Vec<3>& x, double reach) const {
    const auto& P = m_.particles;
    const double h = m_.grid.h;
    const int r = 1 + static_cast<int>(std::ceil(reach / h));
    for (int di = -r; di <= r; ++di)
      for (int dj = -r; dj <= r; ++dj)
        for (int dk = -r; dk <= r; ++dk) {
          const int64_t c = cell(x + h * Vec<3>(di, dj, dk));
          auto it = std::lower_bound(bins_.begin(), bins_.end(), std::pair<int64_t, int32_t>{c, -1});
          for (; it != bins_.end() && it->first == c; ++it)
            if (((x - P.x[it->second]).cwiseAbs().array() < half_[it->second] + reach).all()) return true;
        }
    return false;
  }
  int64_t cell(const Vec<3>& x) const {
    int64_t c = 0;
    for (int d = 0; d < 3; ++d) {
      const int64_t n = m_.grid.nodes[d] + 2;  // one cell of room either side of the grid
      const int64_t i = std::clamp<int64_t>(static_cast<int64_t>(std::floor((x[d] - m_.grid.origin[d]) / m_.grid.h)) + 1, 0, n - 1);
      c = c * n + i;
    }
    return c;
  }
  const Model<3>& m_;
  std::vector<double> half_;
  std::vector<std::pair<int64_t, int32_t>> bins_;
};

// Half each particle's spacing (from its area and its body's thickness): its domain about its centre.
inline std::vector<double> particle_half_sizes(const Model<2>& m) {
  std::vector<double> half(m.particles.size());
  for (const auto& b : m.bodies)
    for (std::size_t p = b.first; p < b.first + b.count; ++p) half[p] = 0.5 * std::sqrt(m.particles.volume0[p] / b.thickness);
  return half;
}

// The material ahead of x along the unit direction e1 (e2 its normal), within `reach`: the distance
// from x to where it ends, 0 when none lies ahead. A particle counts when its domain (half_size
// about it) reaches the ray; tol widens that test (rows exactly half a spacing off the ray).
inline double material_ahead(const Model<2>& m, const std::vector<double>& half_size, const Vec<2>& x, const Vec<2>& e1,
                             const Vec<2>& e2, double reach, double tol) {
  const auto& P = m.particles;
  double edge = 0.0;
  for (std::size_t p = 0; p < P.size(); ++p) {
    const Vec<2> d = P.x[p] - x;
    const double s = d.dot(e1);
    if (s <= 0.0 || s > reach || std::abs(d.dot(e2)) > half_size[p] + tol) continue;
    edge = std::max(edge, s + half_size[p]);
  }
  return edge;
}

}  // namespace cleave
