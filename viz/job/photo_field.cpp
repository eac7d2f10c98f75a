#include "viz/job/photo_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace cleave::viz {
namespace {

std::array<double, 2> model_of(const PhotoMap& map, double u, double v) {
  const double ca = std::cos(map.angle), sa = std::sin(map.angle);
  const double dx = (u + 0.5) * map.scale, dy = -(v + 0.5) * map.scale;
  return {map.x0 + ca * dx - sa * dy, map.y0 + sa * dx + ca * dy};
}

double luminance(const uint8_t* c) { return (0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]) / 255.0; }

// 3 x 5 pixel digits, rows top to bottom, bit 2 the left column: enough to label fringe orders.
constexpr uint8_t kDigits[10][5] = {{7, 5, 5, 5, 7}, {2, 6, 2, 2, 7}, {7, 1, 7, 4, 7}, {7, 1, 7, 1, 7}, {5, 5, 7, 1, 1},
                                    {7, 4, 7, 1, 7}, {7, 4, 7, 5, 7}, {7, 1, 1, 1, 1}, {7, 5, 7, 5, 7}, {7, 5, 7, 1, 7}};

void stamp_number(Image& img, int x, int y, int value, int size, const uint8_t rgb[3]) {
  const std::string text = std::to_string(value);
  // On a white box one glyph pixel wider all round, readable on dark and light fringes alike.
  for (int py = y - size; py < y + 6 * size; ++py)
    for (int px = x - size; px < x + int(text.size()) * 4 * size; ++px)
      if (px >= 0 && py >= 0 && px < img.width && py < img.height) std::fill_n(&img.rgb[3 * (std::size_t(py) * img.width + px)], 3, 255);
  for (std::size_t k = 0; k < text.size(); ++k)
    for (int r = 0; r < 5; ++r)
      for (int c = 0; c < 3; ++c) {
        if (!(kDigits[text[k] - '0'][r] & (4 >> c))) continue;
        for (int a = 0; a < size; ++a)
          for (int b = 0; b < size; ++b) {
            const int px = x + (int(k) * 4 + c) * size + b, py = y + r * size + a;
            if (px < 0 || py < 0 || px >= img.width || py >= img.height) continue;
            std::copy_n(rgb, 3, &img.rgb[3 * (std::size_t(py) * img.width + px)]);
          }
      }
}

}  // namespace

PhotoField photo_field(const ParticleFrame& f, int width, int height, const PhotoMap& map) {
  if (f.dim != 2) throw std::invalid_argument("photo comparisons need a 2D frame");
  double bx0 = 1e300, bx1 = -1e300, by0 = 1e300, by1 = -1e300;
  for (double u : {0.0, double(width)})
    for (double v : {0.0, double(height)}) {
      const auto p = model_of(map, u - 0.5, v - 0.5);
      bx0 = std::min(bx0, p[0]), bx1 = std::max(bx1, p[0]), by0 = std::min(by0, p[1]), by1 = std::max(by1, p[1]);
    }
  // The model over the photo's footprint at the photo's resolution, sampled per photo pixel.
  const int W = std::max(1, int(std::ceil((bx1 - bx0) / map.scale))), H = std::max(1, int(std::ceil((by1 - by0) / map.scale)));
  const View v{bx0, by0, bx1, by1, W, H};
  const Raster r = stress_raster(f, v);
  PhotoField m{width, height, std::vector<double>(std::size_t(width) * height, std::numeric_limits<double>::quiet_NaN())};
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const auto p = model_of(map, i, j);
      const int mi = int((p[0] - v.x0) / (v.x1 - v.x0) * v.width), mj = int((v.y1 - p[1]) / (v.y1 - v.y0) * v.height);
      if (mi < 0 || mj < 0 || mi >= v.width || mj >= v.height) continue;
      const std::size_t q = std::size_t(mj) * v.width + mi;
      if (!r.covered[q]) continue;
      m.diff[std::size_t(j) * width + i] = in_plane(r.values[3 * q], r.values[3 * q + 1], r.values[3 * q + 2]).diff;
    }
  return m;
}

std::vector<uint8_t> compared_pixels(const PhotoField& m, const PhotoMap& map, const Image* mask,
                                     const std::optional<std::array<double, 4>>& roi) {
  if (mask && (mask->width != m.width || mask->height != m.height))
    throw std::invalid_argument("the mask is " + std::to_string(mask->width) + "x" + std::to_string(mask->height) +
                                " pixels, the photo " + std::to_string(m.width) + "x" + std::to_string(m.height));
  std::vector<uint8_t> use(m.diff.size(), 0);
  for (int j = 0; j < m.height; ++j)
    for (int i = 0; i < m.width; ++i) {
      const std::size_t t = std::size_t(j) * m.width + i;
      if (!std::isfinite(m.diff[t])) continue;
      if (mask && luminance(&mask->rgb[3 * t]) <= 0.5) continue;
      if (roi) {
        const auto p = model_of(map, i, j);
        const auto& b = *roi;
        if (p[0] < b[0] || p[0] > b[2] || p[1] < b[1] || p[1] > b[3]) continue;
      }
      use[t] = 1;
    }
  return use;
}

Image centre_line_overlay(const Image& photo, const PhotoField& m, const PhotoelasticSettings& s, double scale) {
  Image out = photo;
  const double k = scale * s.thickness / effective_fringe_constant(s);
  auto N = [&](int i, int j) { return k * m.diff[std::size_t(j) * m.width + i]; };
  const uint8_t red[3] = {220, 30, 30}, blue[3] = {40, 80, 230};
  std::vector<int> labelled;                 // integer orders already labelled
  std::vector<std::pair<int, int>> spots;  // and where
  const int glyph = std::max(2, std::max(photo.width, photo.height) / 300);
  for (int j = 0; j + 1 < m.height; ++j)
    for (int i = 0; i + 1 < m.width; ++i) {
      const double a = N(i, j), b = N(i + 1, j), c = N(i, j + 1);
      if (!std::isfinite(a)) continue;
      // A half-order level between this pixel and its right or lower neighbour.
      for (double nb : {b, c}) {
        if (!std::isfinite(nb) || std::floor(2 * a) == std::floor(2 * nb)) continue;
        const int level = int(std::floor(2 * std::max(a, nb)));  // twice the order crossed
        const bool whole = level % 2 == 0;
        std::copy_n(whole ? red : blue, 3, &out.rgb[3 * (std::size_t(j) * m.width + i)]);
        if (whole && level > 0 && std::find(labelled.begin(), labelled.end(), level) == labelled.end()) {
          // One label per order, clear of the others (near a tip the lines crowd: label further out).
          bool clear = true;
          for (const auto& [x, y] : spots) clear = clear && std::max(std::abs(x - i), std::abs(y - j)) > 10 * glyph;
          if (clear) {
            labelled.push_back(level), spots.push_back({i, j});
            stamp_number(out, i + 3, j - 6 * glyph, level / 2, glyph, red);
          }
        }
      }
    }
  return out;
}

FoldedOrderAgreement folded_order_agreement(const Image& photo, const PhotoField& m, const std::vector<uint8_t>& use,
                                            const PhotoelasticSettings& s, double scale) {
  std::vector<double> lum;
  for (std::size_t t = 0; t < use.size(); ++t)
    if (use[t]) lum.push_back(luminance(&photo.rgb[3 * t]));
  FoldedOrderAgreement r;
  if (lum.size() < 2) throw std::invalid_argument("no photo pixel to compare: check --map, --mask and --roi");
  std::vector<double> sorted = lum;
  std::sort(sorted.begin(), sorted.end());
  const double lo = sorted[sorted.size() / 100], hi = sorted[sorted.size() - 1 - sorted.size() / 100];
  const bool light = s.mode == Polariscope::CircularLight || s.mode == Polariscope::Seed002;
  const double k = scale * s.thickness / effective_fringe_constant(s);
  double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0, d2 = 0;
  std::size_t q = 0;
  for (std::size_t t = 0; t < use.size(); ++t) {
    if (!use[t]) continue;
    double I = hi > lo ? std::clamp((lum[q++] - lo) / (hi - lo), 0.0, 1.0) : 0.5;
    if (light) I = 1 - I;
    const double a = std::acos(1 - 2 * I) / (2 * std::numbers::pi);  // photo: folded order in [0, 1/2]
    const double n = k * m.diff[t], b = std::fabs(n - std::round(n));
    sa += a, sb += b, saa += a * a, sbb += b * b, sab += a * b, d2 += (a - b) * (a - b);
    ++r.pixels;
  }
  const double n = double(r.pixels), cov = sab / n - sa * sb / (n * n), va = saa / n - sa * sa / (n * n),
               vb = sbb / n - sb * sb / (n * n);
  r.ncc = va > 0 && vb > 0 ? cov / std::sqrt(va * vb) : 0.0;
  r.rms = std::sqrt(d2 / n);
  return r;
}

PhotoCalibration calibrate_to_photo(const Image& photo, const PhotoField& m, const std::vector<uint8_t>& use,
                                    const PhotoelasticSettings& s) {
  std::vector<double> b, d;
  for (std::size_t t = 0; t < use.size(); ++t)
    if (use[t]) b.push_back(luminance(&photo.rgb[3 * t])), d.push_back(m.diff[t]);
  if (b.size() < 16) throw std::invalid_argument("fewer than 16 photo pixels on the bodies: check --map, --mask and --roi");
  auto ncc = [&](double c) {
    double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
    for (std::size_t i = 0; i < b.size(); ++i) {
      const double a = intensity(c * d[i], 0, 0, s);
      sa += a, sb += b[i], saa += a * a, sbb += b[i] * b[i], sab += a * b[i];
    }
    const double n = double(b.size()), cov = sab / n - sa * sb / (n * n), va = saa / n - sa * sa / (n * n),
                 vb = sbb / n - sb * sb / (n * n);
    return va > 0 && vb > 0 ? cov / std::sqrt(va * vb) : -1.0;
  };
  PhotoCalibration r;
  r.pixels = b.size();
  r.ncc_at_one = ncc(1.0);
  // Scan, then refine round the best: the correlation has a peak per fringe-count alias.
  const int n = 240;
  double best = 1, best_v = -2;
  for (int k = 0; k <= n; ++k) {
    const double c = 0.2 * std::pow(25.0, double(k) / n), v = ncc(c);
    if (v > best_v) best_v = v, best = c;
  }
  const double step = std::pow(25.0, 1.0 / n);
  double lo = best / step, hi = best * step;
  const double g = (std::sqrt(5.0) - 1) / 2;
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo), f1 = ncc(x1), f2 = ncc(x2);
  for (int it = 0; it < 60; ++it) {
    if (f1 > f2) hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo), f1 = ncc(x1);
    else lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo), f2 = ncc(x2);
  }
  r.scale = 0.5 * (lo + hi);
  r.ncc = ncc(r.scale);
  return r;
}

std::vector<FringePoint> extract_fringe_points(const Image& photo, const PhotoField& m, const PhotoMap& map,
                                               const std::vector<uint8_t>& use, const PhotoelasticSettings& s, double scale,
                                               double x0, double y0, double r0, double r1, std::size_t max_points) {
  const int W = m.width, H = m.height;
  std::vector<double> I(use.size(), std::numeric_limits<double>::quiet_NaN()), on;
  for (std::size_t t = 0; t < use.size(); ++t)
    if (use[t]) on.push_back(I[t] = luminance(&photo.rgb[3 * t]));
  if (on.size() < 16) throw std::invalid_argument("fewer than 16 photo pixels on the bodies: check --map, --mask and --roi");
  std::sort(on.begin(), on.end());
  const double lo = on[on.size() / 100], hi = on[on.size() - 1 - on.size() / 100];
  const bool light = s.mode == Polariscope::CircularLight;
  const double k = scale * s.thickness / effective_fringe_constant(s);
  auto at = [&](int i, int j) { return I[std::size_t(j) * W + i]; };
  std::vector<FringePoint> pts;
  for (int j = 1; j + 1 < H; ++j)
    for (int i = 1; i + 1 < W; ++i) {
      const double c = at(i, j);
      if (!std::isfinite(c)) continue;
      const double l = at(i - 1, j), r = at(i + 1, j), u = at(i, j - 1), d = at(i, j + 1);
      if (!std::isfinite(l) || !std::isfinite(r) || !std::isfinite(u) || !std::isfinite(d)) continue;
      const double n = hi > lo ? (c - lo) / (hi - lo) : 0.5;
      const bool dark = n <= 0.25 && ((c <= l && c <= r && (c < l || c < r)) || (c <= u && c <= d && (c < u || c < d)));
      const bool bright = n >= 0.75 && ((c >= l && c >= r && (c > l || c > r)) || (c >= u && c >= d && (c > u || c > d)));
      if (!dark && !bright) continue;
      const auto p = model_of(map, i, j);
      const double rr = std::hypot(p[0] - x0, p[1] - y0);
      if (rr < r0 || rr > r1) continue;
      // Whole orders on dark lines of a dark field (bright lines of a light one), half orders on the others.
      const bool whole = dark != light;
      const double N = k * m.diff[std::size_t(j) * W + i], order = whole ? std::round(N) : std::round(N - 0.5) + 0.5;
      if (std::fabs(N - order) > 0.3 || order < 0) continue;
      pts.push_back({p[0], p[1], order});
    }
  if (pts.size() > max_points) {
    std::vector<FringePoint> thin;
    const double step = double(pts.size()) / double(max_points);
    for (std::size_t q = 0; q < max_points; ++q) thin.push_back(pts[std::size_t(q * step)]);
    pts.swap(thin);
  }
  return pts;
}

}  // namespace cleave::viz
