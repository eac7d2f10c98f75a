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

#ifdef _OPENMP
#include <omp.h>
#define CLEAVE_OMP(x) _Pragma(x)
#else
#define CLEAVE_OMP(x)
#endif

namespace cleave::viz {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
// Footprint test slack (in footprint edges): neighbouring footprints deformed by different strains
// leave slivers of order h * (strain difference) between them; 2 % closes those without hiding a
// crack that has opened by more than 2 % of a particle.
constexpr double kInsideTol = 0.02;
constexpr double kConnectTol = 0.25;    // gap (in spacings) up to which footprints are connected
constexpr double kMaxStrain = 2.0;      // footprint strain components are clamped to +-this
constexpr double kMinDet = 0.1;         // below this det(I + eps) the footprint stays square
constexpr int kBandRows = 8;

bool finite3(const std::array<double, 3>& p) {
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

// The array `name` if it has at least `comps` components and one tuple per particle.
const PointArray* array_with(const ParticleFrame& f, const char* name, int comps) {
  auto it = f.arrays.find(name);
  if (it == f.arrays.end()) return nullptr;
  const PointArray& a = it->second;
  if (a.components < comps || a.values.size() != f.x.size() * static_cast<std::size_t>(a.components))
    return nullptr;
  return &a;
}

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

View fit_view(const ParticleFrame& f, int width, int height,
              std::optional<std::array<double, 4>> roi, double zoom, double margin) {
  if (width < 1 || height < 1)
    throw std::invalid_argument("fit_view: image size " + std::to_string(width) + "x" +
                                std::to_string(height) + " is not positive");
  if (!(zoom > 0) || !std::isfinite(zoom))
    throw std::invalid_argument("fit_view: zoom must be a positive number, got " + std::to_string(zoom));
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
  const double cx = 0.5 * (bx0 + bx1), cy = 0.5 * (by0 + by1);
  const double scale = std::max((bx1 - bx0) / width, (by1 - by0) / height) / zoom;  // model per pixel
  const double hw = 0.5 * scale * width, hh = 0.5 * scale * height;
  return View{cx - hw, cy - hh, cx + hw, cy + hh, width, height};
}

Raster rasterize_2d(const ParticleFrame& f, const View& v, const std::vector<double>& per_particle, int k) {
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
  struct Foot {
    double x, y, s, inv_s, hx, hy, a00, a01, a10, a11;
  };
  std::vector<Foot> foot(n);
  std::vector<uint8_t> valid(n, 0);
  {
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
    const double r = reach * s[p];
    if (d >= -r && d < r) keep.push_back(p);
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
  if (const PointArray* e6 = array_with(f, "strain", 6)) {
    const std::size_t c = static_cast<std::size_t>(e6->components);
    PointArray b;
    b.components = 3;
    b.values.resize(keep.size() * 3);
    for (std::size_t i = 0; i < keep.size(); ++i) {
      const double* e = &e6->values[keep[i] * c];
      // VTK order XX, YY, ZZ, XY, YZ, XZ.
      const double E[3][3] = {{e[0], e[3], e[5]}, {e[3], e[1], e[4]}, {e[5], e[4], e[2]}};
      auto quad = [&](const std::array<double, 3>& a, const std::array<double, 3>& bb) {
        double r = 0;
        for (int r0 = 0; r0 < 3; ++r0)
          for (int c0 = 0; c0 < 3; ++c0) r += a[static_cast<std::size_t>(r0)] * E[r0][c0] * bb[static_cast<std::size_t>(c0)];
        return r;
      };
      b.values[3 * i] = quad(u, u);
      b.values[3 * i + 1] = quad(w, w);
      b.values[3 * i + 2] = quad(u, w);
    }
    out.arrays["strain_uv"] = std::move(b);
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
