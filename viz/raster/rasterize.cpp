// Two passes over horizontal bands of pixel rows, each band owned by one thread: particles are
// listed (in index order) under every band their footprint or tent support touches, so a band's
// pixels are written by one thread in a fixed order and the result does not depend on the thread
// count. Pass 1 finds each pixel's owner (coverage); pass 2 scatters tent weights from the
// particles near each pixel that are connected to its owner.
#include "viz/raster/rasterize.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>

#include "viz/raster/footprints.hpp"

namespace cleave::viz {

using detail::Foot;
using detail::kInsideTol;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kConnectTol = 0.25;    // gap (in spacings) up to which footprints are connected
constexpr int kBandRows = 8;

}  // namespace

Raster rasterize_2d(const ParticleFrame& f, const View& v, const std::vector<double>& per_particle, int k,
                    const RasterOptions& options) {
  const std::size_t n = f.x.size();
  if (f.dim != 2)
    throw std::invalid_argument("rasterize_2d: frame" + (f.file.empty() ? std::string() : " " + f.file) +
                                " is 3D; take a cut_plane first");
  if (k < 0) throw std::invalid_argument("rasterize_2d: k must be >= 0");
  if (per_particle.size() != n * static_cast<std::size_t>(k))
    throw std::invalid_argument("rasterize_2d: " + std::to_string(per_particle.size()) +
                                " values for " + std::to_string(n) + " particles x " +
                                std::to_string(k) + " per particle");
  if (v.width < 1 || v.height < 1 || !(v.x1 > v.x0) || !(v.y1 > v.y0))
    throw std::invalid_argument("rasterize_2d: empty view");
  if (n > static_cast<std::size_t>(std::numeric_limits<int32_t>::max()))
    throw std::invalid_argument("rasterize_2d: too many particles");

  const int W = v.width, H = v.height;
  const std::size_t npix = static_cast<std::size_t>(W) * static_cast<std::size_t>(H);
  const std::size_t K = static_cast<std::size_t>(k);
  const double pw = v.pixel_width(), ph = v.pixel_height();
  const double X0 = v.x0, Y1 = v.y1;  // locals: stores into the raster cannot alias them
  auto px = [X0, pw](int i) { return X0 + (i + 0.5) * pw; };
  auto py = [Y1, ph](int j) { return Y1 - (j + 0.5) * ph; };

  Raster R;
  R.view = v;
  R.k = k;
  R.values.assign(npix * K, kNaN);
  R.covered.assign(npix, 0);
  R.owner.assign(npix, -1);

  // Footprints: centre, spacing, bounding half-extents and (I + eps)^-1 / s.
  std::vector<Foot> foot;
  std::vector<uint8_t> valid;
  detail::footprints(f, foot, valid);

  // Index ranges of the pixel centres within [c - e, c + e] (slightly widened, so that the
  // footprint test with its tolerance decides on the edges), clamped to the image.
  constexpr double kRangeSlack = 4 * kInsideTol;
  auto col_range = [&](double c, double e, int& a, int& b) {
    e *= 1 + kRangeSlack;
    const double lo = (c - e - X0) / pw - 0.5 - 1e-9, hi = (c + e - X0) / pw - 0.5 + 1e-9;
    if (!(hi >= 0.0) || !(lo <= W - 1.0)) return false;  // also rejects NaN
    a = static_cast<int>(std::max(0.0, std::ceil(lo)));
    b = static_cast<int>(std::min(W - 1.0, std::floor(hi)));
    return a <= b;
  };
  auto row_range = [&](double c, double e, int& a, int& b) {
    e *= 1 + kRangeSlack;
    const double lo = (Y1 - (c + e)) / ph - 0.5 - 1e-9, hi = (Y1 - (c - e)) / ph - 0.5 + 1e-9;
    if (!(hi >= 0.0) || !(lo <= H - 1.0)) return false;
    a = static_cast<int>(std::max(0.0, std::ceil(lo)));
    b = static_cast<int>(std::min(H - 1.0, std::floor(hi)));
    return a <= b;
  };

  // Particles under each band of rows, in index order (counting sort).
  const int nb = (H + kBandRows - 1) / kBandRows;
  std::vector<std::size_t> bstart(static_cast<std::size_t>(nb) + 1, 0);
  std::vector<int> pb0(n, 0), pb1(n, -1);
  for (std::size_t p = 0; p < n; ++p) {
    if (!valid[p]) continue;
    const Foot& F = foot[p];
    int i0, i1, j0, j1;
    const double ex = std::max(F.hx, F.s), ey = std::max(F.hy, F.s);
    if (!col_range(F.x, ex, i0, i1) || !row_range(F.y, ey, j0, j1)) continue;
    pb0[p] = j0 / kBandRows;
    pb1[p] = j1 / kBandRows;
    for (int b = pb0[p]; b <= pb1[p]; ++b) ++bstart[static_cast<std::size_t>(b) + 1];
  }
  for (int b = 0; b < nb; ++b) bstart[static_cast<std::size_t>(b) + 1] += bstart[static_cast<std::size_t>(b)];
  std::vector<int32_t> blist(bstart.back());
  {
    std::vector<std::size_t> fill(bstart.begin(), bstart.end() - 1);
    for (std::size_t p = 0; p < n; ++p)
      for (int b = pb0[p]; b <= pb1[p]; ++b) blist[fill[static_cast<std::size_t>(b)]++] = static_cast<int32_t>(p);
  }
  std::vector<int>().swap(pb0);
  std::vector<int>().swap(pb1);

  // Pass 1: coverage and owners.
  std::vector<double> best(npix, kInf);
  CLEAVE_OMP("omp parallel for schedule(dynamic, 1)")
  for (int b = 0; b < nb; ++b) {
    const int rb0 = b * kBandRows, rb1 = std::min(H - 1, rb0 + kBandRows - 1);
    for (std::size_t t = bstart[static_cast<std::size_t>(b)]; t < bstart[static_cast<std::size_t>(b) + 1]; ++t) {
      const int32_t p = blist[t];
      const Foot& F = foot[static_cast<std::size_t>(p)];
      int i0, i1, j0, j1;
      if (!col_range(F.x, F.hx, i0, i1) || !row_range(F.y, F.hy, j0, j1)) continue;
      j0 = std::max(j0, rb0);
      j1 = std::min(j1, rb1);
      for (int j = j0; j <= j1; ++j) {
        const double dy = py(j) - F.y;
        const std::size_t row = static_cast<std::size_t>(j) * static_cast<std::size_t>(W);
        for (int i = i0; i <= i1; ++i) {
          const double dx = px(i) - F.x;
          const double a = std::abs(F.a00 * dx + F.a01 * dy), c = std::abs(F.a10 * dx + F.a11 * dy);
          if (a > 0.5 + kInsideTol || c > 0.5 + kInsideTol) continue;
          const double key = std::max(a, c);
          const std::size_t pix = row + static_cast<std::size_t>(i);
          if (key < best[pix]) {  // index order within the band: ties keep the lower index
            best[pix] = key;
            R.owner[pix] = p;
          }
        }
      }
    }
  }
  std::vector<double>().swap(best);
  if (options.smooth_outline) detail::smooth_outline(foot, valid, X0, Y1, pw, ph, W, H, R.owner, R.edge);

  // Pass 2: tent-weighted sums from particles connected to each pixel's owner.
  std::vector<double> wsum(npix, 0.0), acc(npix * K, 0.0);
  if (K > 0) {
    CLEAVE_OMP("omp parallel for schedule(dynamic, 1)")
    for (int b = 0; b < nb; ++b) {
      const int rb0 = b * kBandRows, rb1 = std::min(H - 1, rb0 + kBandRows - 1);
      for (std::size_t t = bstart[static_cast<std::size_t>(b)]; t < bstart[static_cast<std::size_t>(b) + 1]; ++t) {
        const int32_t q = blist[t];
        const Foot& Q = foot[static_cast<std::size_t>(q)];
        int i0, i1, j0, j1;
        if (!col_range(Q.x, Q.s, i0, i1) || !row_range(Q.y, Q.s, j0, j1)) continue;
        j0 = std::max(j0, rb0);
        j1 = std::min(j1, rb1);
        const double* fq = &per_particle[static_cast<std::size_t>(q) * K];
        for (int j = j0; j <= j1; ++j) {
          const double wy = 1.0 - std::abs(py(j) - Q.y) * Q.inv_s;
          if (wy <= 0) continue;
          const std::size_t row = static_cast<std::size_t>(j) * static_cast<std::size_t>(W);
          for (int i = i0; i <= i1; ++i) {
            const std::size_t pix = row + static_cast<std::size_t>(i);
            const int32_t o = R.owner[pix];
            if (o < 0) continue;
            const double wx = 1.0 - std::abs(px(i) - Q.x) * Q.inv_s;
            if (wx <= 0) continue;
            if (o != q) {
              const Foot& O = foot[static_cast<std::size_t>(o)];
              const double tol = kConnectTol * std::min(O.s, Q.s);
              if (std::abs(Q.x - O.x) > O.hx + Q.hx + tol || std::abs(Q.y - O.y) > O.hy + Q.hy + tol) continue;
            }
            const double w = wx * wy;
            wsum[pix] += w;
            double* ap = &acc[pix * K];
            for (std::size_t c = 0; c < K; ++c) ap[c] += w * fq[c];
          }
        }
      }
    }
  }

  CLEAVE_OMP("omp parallel for schedule(static)")
  for (std::ptrdiff_t ipix = 0; ipix < static_cast<std::ptrdiff_t>(npix); ++ipix) {
    const std::size_t pix = static_cast<std::size_t>(ipix);
    const int32_t o = R.owner[pix];
    if (o < 0) continue;
    R.covered[pix] = 1;
    if (K == 0) continue;
    double* out = &R.values[pix * K];
    if (wsum[pix] > 0) {
      const double inv = 1.0 / wsum[pix];
      for (std::size_t c = 0; c < K; ++c) out[c] = acc[pix * K + c] * inv;
    } else {
      for (std::size_t c = 0; c < K; ++c) out[c] = per_particle[static_cast<std::size_t>(o) * K + c];
    }
  }
  return R;
}

}  // namespace cleave::viz
