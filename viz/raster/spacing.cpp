// Particle spacing and the view that fits the bodies (viz/raster/rasterize.hpp).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>

#include "viz/raster/footprints.hpp"
#include "viz/raster/rasterize.hpp"

namespace cleave::viz {

using detail::array_with;
using detail::finite3;

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

double median_spacing(const ParticleFrame& f) {
  const int D = f.dim == 3 ? 3 : 2;
  std::vector<std::size_t> pts;
  pts.reserve(f.x.size());
  for (std::size_t p = 0; p < f.x.size(); ++p)
    if (finite3(f.x[p])) pts.push_back(p);
  const std::size_t m = pts.size();
  if (m < 2) return 0.0;

  double lo[3] = {kInf, kInf, kInf}, hi[3] = {-kInf, -kInf, -kInf};
  for (std::size_t p : pts)
    for (int d = 0; d < D; ++d) {
      lo[d] = std::min(lo[d], f.x[p][d]);
      hi[d] = std::max(hi[d], f.x[p][d]);
    }
  int deff = 0;
  double vol = 1.0, ext[3] = {0, 0, 0};
  for (int d = 0; d < D; ++d) {
    ext[d] = hi[d] - lo[d];
    if (ext[d] > 0) { ++deff; vol *= ext[d]; }
  }
  if (deff == 0) return 0.0;
  // Uniform cubic cells of edge h, about one particle per cell, at most ~4 m cells in all.
  double h = std::pow(vol / static_cast<double>(m), 1.0 / deff);
  long long nc[3] = {1, 1, 1}, total = 1;
  for (int iter = 0; iter < 200; ++iter) {
    total = 1;
    for (int d = 0; d < D; ++d) {
      const double c = ext[d] > 0 ? std::floor(ext[d] / h) + 1.0 : 1.0;
      nc[d] = static_cast<long long>(std::min(c, 1e7));
      total *= nc[d];
    }
    if (total <= 4 * static_cast<long long>(m) + 8) break;
    h *= 1.25;
  }
  auto cell_of = [&](std::size_t p, long long c[3]) {
    for (int d = 0; d < 3; ++d) {
      c[d] = 0;
      if (d < D && ext[d] > 0)
        c[d] = std::min(nc[d] - 1, static_cast<long long>((f.x[p][d] - lo[d]) / h));
    }
  };
  auto flat = [&](const long long c[3]) { return c[0] + nc[0] * (c[1] + nc[1] * c[2]); };
  std::vector<std::size_t> start(static_cast<std::size_t>(total) + 1, 0), order(m);
  std::vector<long long> cell(m);
  for (std::size_t i = 0; i < m; ++i) {
    long long c[3];
    cell_of(pts[i], c);
    cell[i] = flat(c);
    ++start[static_cast<std::size_t>(cell[i]) + 1];
  }
  for (std::size_t c = 0; c < static_cast<std::size_t>(total); ++c) start[c + 1] += start[c];
  {
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < m; ++i) order[fill[static_cast<std::size_t>(cell[i])]++] = pts[i];
  }

  const std::size_t stride = std::max<std::size_t>(1, m / 20000);
  const long long rmax = std::max({nc[0], nc[1], nc[2]});
  std::vector<double> nn;
  nn.reserve(m / stride + 1);
  for (std::size_t i = 0; i < m; i += stride) {
    const std::size_t p = pts[i];
    long long c[3];
    cell_of(p, c);
    double best = kInf;
    for (long long r = 0; r <= rmax; ++r) {
      long long a[3], b[3];
      for (int d = 0; d < 3; ++d) {
        a[d] = std::max(0LL, c[d] - r);
        b[d] = std::min(nc[d] - 1, c[d] + r);
      }
      for (long long z = a[2]; z <= b[2]; ++z)
        for (long long y = a[1]; y <= b[1]; ++y)
          for (long long x = a[0]; x <= b[0]; ++x) {
            const long long cheb = std::max({std::abs(x - c[0]), std::abs(y - c[1]), std::abs(z - c[2])});
            if (cheb != r) continue;
            const long long q[3] = {x, y, z};
            const std::size_t k = static_cast<std::size_t>(flat(q));
            for (std::size_t t = start[k]; t < start[k + 1]; ++t) {
              const std::size_t o = order[t];
              double d2 = 0;
              for (int d = 0; d < D; ++d) d2 += (f.x[o][d] - f.x[p][d]) * (f.x[o][d] - f.x[p][d]);
              if (d2 > 0 && d2 < best) best = d2;
            }
          }
      if (best < kInf && std::sqrt(best) <= static_cast<double>(r) * h) break;
    }
    if (best < kInf) nn.push_back(std::sqrt(best));
  }
  if (nn.empty()) return 0.0;
  auto mid = nn.begin() + static_cast<std::ptrdiff_t>(nn.size() / 2);
  std::nth_element(nn.begin(), mid, nn.end());
  return *mid;
}

std::vector<double> particle_sizes(const ParticleFrame& f) {
  const std::size_t n = f.x.size();
  std::vector<double> s(n, 0.0);
  bool need_fallback = true;
  if (const PointArray* a = array_with(f, "size", 1)) {
    need_fallback = false;
    const std::size_t c = static_cast<std::size_t>(a->components);
    for (std::size_t p = 0; p < n; ++p) {
      s[p] = a->values[p * c];
      if (!(std::isfinite(s[p]) && s[p] > 0)) need_fallback = true;
    }
  }
  if (need_fallback && n > 0) {
    double m = median_spacing(f);
    if (!(m > 0 && std::isfinite(m))) m = 1.0;
    for (double& v : s)
      if (!(std::isfinite(v) && v > 0)) v = m;
  }
  return s;
}

std::array<double, 4> bodies_box(const ParticleFrame& f, std::optional<std::array<double, 4>> roi, double margin) {
  if (!(margin >= 0) || !std::isfinite(margin))
    throw std::invalid_argument("fit_view: margin must be >= 0, got " + std::to_string(margin));
  double bx0, by0, bx1, by1;
  if (roi) {
    const auto& r = *roi;
    if (!(std::isfinite(r[0]) && std::isfinite(r[1]) && std::isfinite(r[2]) && std::isfinite(r[3])) ||
        !(r[2] > r[0]) || !(r[3] > r[1]))
      throw std::invalid_argument("fit_view: region of interest {x0, y0, x1, y1} needs x1 > x0 and y1 > y0");
    bx0 = r[0]; by0 = r[1]; bx1 = r[2]; by1 = r[3];
  } else {
    const std::vector<double> s = particle_sizes(f);
    bx0 = by0 = kInf;
    bx1 = by1 = -kInf;
    for (std::size_t p = 0; p < f.x.size(); ++p) {
      if (!finite3(f.x[p])) continue;
      const double h = 0.5 * s[p];
      bx0 = std::min(bx0, f.x[p][0] - h);
      bx1 = std::max(bx1, f.x[p][0] + h);
      by0 = std::min(by0, f.x[p][1] - h);
      by1 = std::max(by1, f.x[p][1] + h);
    }
    if (!(bx1 >= bx0))
      throw std::invalid_argument("fit_view: the frame" + (f.file.empty() ? std::string() : " " + f.file) +
                                  " has no particles to fit");
    double big = std::max(bx1 - bx0, by1 - by0);
    if (!(big > 0)) big = 1.0;
    const double pad = margin * big;
    bx0 -= pad; bx1 += pad; by0 -= pad; by1 += pad;
    if (!(bx1 > bx0)) { bx0 -= 0.5 * big; bx1 += 0.5 * big; }
    if (!(by1 > by0)) { by0 -= 0.5 * big; by1 += 0.5 * big; }
  }
  return {bx0, by0, bx1, by1};
}

View fit_view(const ParticleFrame& f, int width, int height,
              std::optional<std::array<double, 4>> roi, double zoom, double margin) {
  if (width < 1 || height < 1)
    throw std::invalid_argument("fit_view: image size " + std::to_string(width) + "x" +
                                std::to_string(height) + " is not positive");
  if (!(zoom > 0) || !std::isfinite(zoom))
    throw std::invalid_argument("fit_view: zoom must be a positive number, got " + std::to_string(zoom));
  const auto [bx0, by0, bx1, by1] = bodies_box(f, roi, margin);
  const double cx = 0.5 * (bx0 + bx1), cy = 0.5 * (by0 + by1);
  const double scale = std::max((bx1 - bx0) / width, (by1 - by0) / height) / zoom;  // model per pixel
  const double hw = 0.5 * scale * width, hh = 0.5 * scale * height;
  return View{cx - hw, cy - hh, cx + hw, cy + hh, width, height};
}

}  // namespace cleave::viz
