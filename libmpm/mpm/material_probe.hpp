// The material of a 3D model as a point test, for the scene checks that need it (crack fronts
// inside the material, crack_tips contours that leave it).
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

}  // namespace cleave
