// Particle smoothing (viz/raster/smooth.hpp): a graph of touching footprints, a bounded walk over it
// from each particle (so that the neighbourhood is the material connected to the particle, not
// whatever lies within a radius across a gap), and a weighted linear least-squares fit.
#include "viz/raster/smooth.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>

#include "viz/raster/footprints.hpp"

namespace cleave::viz {

using detail::Foot;

namespace {

constexpr double kConnectTol = 0.25;  // gap (in spacings) up to which footprints touch, as in rasterize_2d
constexpr double kCutoff = 3.0;       // neighbourhood radius in sigmas (weight exp(-4.5) = 1 % there)

bool segments_cross(double ax, double ay, double bx, double by, const std::array<double, 4>& s) {
  auto orient = [](double px, double py, double qx, double qy, double rx, double ry) {
    const double d = (qx - px) * (ry - py) - (qy - py) * (rx - px);
    return (d > 0) - (d < 0);
  };
  const int o1 = orient(ax, ay, bx, by, s[0], s[1]), o2 = orient(ax, ay, bx, by, s[2], s[3]);
  const int o3 = orient(s[0], s[1], s[2], s[3], ax, ay), o4 = orient(s[0], s[1], s[2], s[3], bx, by);
  return o1 * o2 <= 0 && o3 * o4 <= 0 && !(o1 == 0 && o2 == 0);
}

// Touching footprints (bounding boxes within kConnectTol of each other), of the same material, not
// separated by a barrier: compressed rows, each in index order.
void touch_graph(const ParticleFrame& f, const std::vector<Foot>& foot, const std::vector<uint8_t>& valid,
                 const std::vector<std::array<double, 4>>& barriers, std::vector<std::size_t>& start,
                 std::vector<int32_t>& adj) {
  const std::size_t n = foot.size();
  const PointArray* mat = detail::array_with(f, "material", 1);
  double ext = 0, x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (std::size_t p = 0; p < n; ++p)
    if (valid[p]) {
      ext = std::max({ext, 2 * foot[p].hx, 2 * foot[p].hy});
      x0 = std::min(x0, foot[p].x), x1 = std::max(x1, foot[p].x), y0 = std::min(y0, foot[p].y), y1 = std::max(y1, foot[p].y);
    }
  start.assign(n + 1, 0);
  adj.clear();
  if (!(ext > 0)) return;
  // Bins at least as wide as any touching distance (so the 3 x 3 bins around a particle hold all it
  // touches), widened for scattered particles to at most ~4 bins per particle.
  double cell = ext * (1 + kConnectTol);
  while (((x1 - x0) / cell + 1) * ((y1 - y0) / cell + 1) > 4.0 * double(n) + 16) cell *= 2;
  const long nx = static_cast<long>((x1 - x0) / cell) + 1, ny = static_cast<long>((y1 - y0) / cell) + 1;
  std::vector<std::size_t> bstart(std::size_t(nx * ny) + 1, 0), items;
  auto bin = [&](std::size_t p, long& i, long& j) {
    i = std::min(nx - 1, static_cast<long>((foot[p].x - x0) / cell));
    j = std::min(ny - 1, static_cast<long>((foot[p].y - y0) / cell));
  };
  for (std::size_t p = 0; p < n; ++p)
    if (valid[p]) {
      long i, j;
      bin(p, i, j);
      ++bstart[std::size_t(j * nx + i) + 1];
    }
  for (std::size_t c = 0; c + 1 < bstart.size(); ++c) bstart[c + 1] += bstart[c];
  items.resize(bstart.back());
  {
    std::vector<std::size_t> fill(bstart.begin(), bstart.end() - 1);
    for (std::size_t p = 0; p < n; ++p)
      if (valid[p]) {
        long i, j;
        bin(p, i, j);
        items[fill[std::size_t(j * nx + i)]++] = p;
      }
  }
  // Barriers are few (crack segments): test an edge against them only inside their padded box.
  double bx0 = 1e300, by0 = 1e300, bx1 = -1e300, by1 = -1e300;
  for (const auto& s : barriers)
    bx0 = std::min({bx0, s[0], s[2]}) , bx1 = std::max({bx1, s[0], s[2]}), by0 = std::min({by0, s[1], s[3]}), by1 = std::max({by1, s[1], s[3]});
  bx0 -= ext, by0 -= ext, bx1 += ext, by1 += ext;
  std::vector<std::vector<int32_t>> rows(n);
  CLEAVE_OMP("omp parallel for schedule(dynamic, 256)")
  for (std::ptrdiff_t ip = 0; ip < static_cast<std::ptrdiff_t>(n); ++ip) {
    const std::size_t p = static_cast<std::size_t>(ip);
    if (!valid[p]) continue;
    const Foot& P = foot[p];
    long bi, bj;
    bin(p, bi, bj);
    const bool near_barrier = !barriers.empty() && P.x >= bx0 && P.x <= bx1 && P.y >= by0 && P.y <= by1;
    for (long j = std::max(0L, bj - 1); j <= std::min(ny - 1, bj + 1); ++j)
      for (long i = std::max(0L, bi - 1); i <= std::min(nx - 1, bi + 1); ++i) {
        const std::size_t c = std::size_t(j * nx + i);
        for (std::size_t t = bstart[c]; t < bstart[c + 1]; ++t) {
          const std::size_t q = items[t];
          if (q == p) continue;
          const Foot& Q = foot[q];
          const double tol = kConnectTol * std::min(P.s, Q.s);
          if (std::abs(Q.x - P.x) > P.hx + Q.hx + tol || std::abs(Q.y - P.y) > P.hy + Q.hy + tol) continue;
          if (mat && mat->values[p] != mat->values[q]) continue;
          if (near_barrier) {
            bool cut = false;
            for (const auto& s : barriers)
              if (segments_cross(P.x, P.y, Q.x, Q.y, s)) {
                cut = true;
                break;
              }
            if (cut) continue;
          }
          rows[p].push_back(static_cast<int32_t>(q));
        }
      }
    std::sort(rows[p].begin(), rows[p].end());
  }
  for (std::size_t p = 0; p < n; ++p) start[p + 1] = start[p] + rows[p].size();
  adj.resize(start.back());
  for (std::size_t p = 0; p < n; ++p) std::copy(rows[p].begin(), rows[p].end(), adj.begin() + std::ptrdiff_t(start[p]));
}

}  // namespace

std::vector<double> smooth_particle_values(const ParticleFrame& f, const std::vector<double>& values, int k,
                                           const SmoothSettings& settings) {
  const std::size_t n = f.x.size();
  if (f.dim != 2) throw std::invalid_argument("smooth_particle_values: the frame is 3D; take a cut_plane first");
  if (k < 1 || values.size() != n * std::size_t(k))
    throw std::invalid_argument("smooth_particle_values: " + std::to_string(values.size()) + " values for " +
                                std::to_string(n) + " particles x " + std::to_string(k));
  if (!(settings.sigma > 0) || n == 0) return values;
  std::vector<Foot> foot;
  std::vector<uint8_t> valid;
  detail::footprints(f, foot, valid);
  std::vector<std::size_t> start;
  std::vector<int32_t> adj;
  touch_graph(f, foot, valid, settings.barriers, start, adj);

  const std::size_t K = std::size_t(k);
  std::vector<double> out = values;
  CLEAVE_OMP("omp parallel")
  {
    std::vector<uint32_t> seen(n, 0);  // walk number that last reached each particle
    uint32_t walk = 0;
    std::vector<int32_t> queue;
    std::vector<double> b(3 * K);
    CLEAVE_OMP("omp for schedule(dynamic, 64)")
    for (std::ptrdiff_t ip = 0; ip < static_cast<std::ptrdiff_t>(n); ++ip) {
      const std::size_t p = static_cast<std::size_t>(ip);
      if (!valid[p]) continue;
      const Foot& P = foot[p];
      const double sig = settings.sigma * P.s, r2max = (kCutoff * sig) * (kCutoff * sig);
      ++walk;
      queue.assign(1, static_cast<int32_t>(p));
      seen[p] = walk;
      // Weighted sums for the fit f ~ c0 + c1 u + c2 v, (u, v) = offset / sigma.
      double m[6] = {0, 0, 0, 0, 0, 0};  // symmetric 3x3: 00 01 02 11 12 22
      std::fill(b.begin(), b.end(), 0.0);
      for (std::size_t h = 0; h < queue.size(); ++h) {
        const std::size_t q = std::size_t(queue[h]);
        const double dx = foot[q].x - P.x, dy = foot[q].y - P.y, r2 = dx * dx + dy * dy;
        const double w = std::exp(-0.5 * r2 / (sig * sig)) * foot[q].s * foot[q].s;
        const double u = dx / sig, v = dy / sig;
        m[0] += w, m[1] += w * u, m[2] += w * v, m[3] += w * u * u, m[4] += w * u * v, m[5] += w * v * v;
        const double* fq = &values[q * K];
        for (std::size_t c = 0; c < K; ++c) {
          if (!std::isfinite(fq[c])) continue;
          b[3 * c] += w * fq[c], b[3 * c + 1] += w * u * fq[c], b[3 * c + 2] += w * v * fq[c];
        }
        for (std::size_t e = start[q]; e < start[q + 1]; ++e) {
          const std::size_t o = std::size_t(adj[e]);
          if (seen[o] == walk) continue;
          seen[o] = walk;
          const double ex = foot[o].x - P.x, ey = foot[o].y - P.y;
          if (ex * ex + ey * ey < r2max) queue.push_back(static_cast<int32_t>(o));
        }
      }
      // c0 of the 3x3 solve (first row of the inverse); the weighted mean where the fit is degenerate.
      const double c00 = m[3] * m[5] - m[4] * m[4], c01 = m[2] * m[4] - m[1] * m[5], c02 = m[1] * m[4] - m[2] * m[3];
      const double det = m[0] * c00 + m[1] * c01 + m[2] * c02;
      const bool fit = det > 1e-6 * m[0] * m[0] * m[0];
      for (std::size_t c = 0; c < K; ++c) {
        if (!std::isfinite(values[p * K + c])) continue;
        out[p * K + c] = fit ? (c00 * b[3 * c] + c01 * b[3 * c + 1] + c02 * b[3 * c + 2]) / det : b[3 * c] / m[0];
      }
    }
  }
  return out;
}

ParticleFrame smooth_stress(const ParticleFrame& f, const SmoothSettings& settings) {
  if (!(settings.sigma > 0) || f.dim != 2) return f;
  ParticleFrame g = f;
  bool any = false;
  // The stress, and a section's in-plane stress (cut_plane), which fringes of sections use.
  for (const auto& [name, comps] : {std::pair<const char*, int>{"stress", 6}, {"stress_uv", 3}}) {
    const auto it = f.arrays.find(name);
    if (it == f.arrays.end() || it->second.components != comps || it->second.values.size() != comps * f.x.size())
      continue;
    g.arrays[name].values = smooth_particle_values(f, it->second.values, comps, settings);
    any = true;
  }
  if (!any) return f;
  g.arrays.erase("von_mises");
  g.arrays.erase("principal_stress_difference");
  return g;
}

}  // namespace cleave::viz
