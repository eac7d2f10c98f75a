// Comparing a run's fringes with a photograph, with digitised fringe orders, or with another run
// of the same scene (render_job.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "viz/job/fringe_fit_job.hpp"
#include "viz/job/photo_field.hpp"
#include "viz/job/render_job.hpp"
#include "viz/optics/photoelastic.hpp"
#include "viz/render/headless.hpp"

namespace cleave::viz {
namespace fs = std::filesystem;

std::vector<std::array<double, 3>> read_fringe_points(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.string() + ": cannot open the points file");
  std::vector<std::array<double, 3>> pts;
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    for (char& c : line)
      if (c == ',') c = ' ';
    std::istringstream ss(line);
    std::array<double, 3> p;
    if (!(ss >> p[0])) continue;  // blank line
    if (!(ss >> p[1] >> p[2]))
      throw std::runtime_error(file.string() + ":" + std::to_string(n) + ": expected 'x y N' (three numbers)");
    pts.push_back(p);
  }
  if (pts.empty()) throw std::runtime_error(file.string() + ": no points");
  return pts;
}

double fringe_order_rms(const ParticleFrame& f, const PhotoelasticSettings& s, const std::vector<std::array<double, 3>>& pts,
                        std::size_t* used) {
  std::vector<FringePoint> at;
  for (const auto& p : pts) at.push_back({p[0], p[1], p[2]});
  const auto ds = stress_difference_at(f, at);
  double sum = 0;
  std::size_t k = 0;
  for (std::size_t i = 0; i < at.size(); ++i) {
    if (!std::isfinite(ds[i])) continue;
    const double N = fringe_order(ds[i], 0, 0, s);  // N depends on s1 - s2 alone
    sum += (N - at[i].N) * (N - at[i].N);
    ++k;
  }
  if (used) *used = k;
  if (!k) throw std::runtime_error("no digitised point lies on the body");
  return std::sqrt(sum / k);
}

CompareResult compare_with_photo(const RenderOptions& o, const fs::path& photo_file, const PhotoMap& map,
                                 const std::optional<std::vector<std::array<double, 3>>>& points,
                                 const fs::path& out_prefix, const std::optional<fs::path>& mask_file) {
  // A photo or mask that cannot be read is bad input (exit 2), not a failure of the comparison.
  auto read_input = [](const fs::path& file) {
    try {
      return read_image(file);
    } catch (const std::runtime_error& e) {
      throw std::invalid_argument(e.what());
    }
  };
  const Image photo = read_input(photo_file);
  std::optional<Image> mask_image;
  if (mask_file) mask_image = read_input(*mask_file);
  const auto entries = read_series(o.series);
  const auto sel = select_frames(entries, o.frames);
  if (sel.size() != 1) throw std::invalid_argument("compare needs exactly one frame (--frame time:T, last, index:I)");
  const auto& e = entries[sel[0]];
  const ParticleFrame f = drawn_frame(read_particle_frame(e.file, e.time), o);
  RenderOptions model_opts = o;
  model_opts.smooth = 0;         // f is smoothed already
  model_opts.outline = false;    // the photo has its own edges: compare the field alone
  // Model position of each photo pixel centre.
  const double ca = std::cos(map.angle), sa = std::sin(map.angle);
  auto model_of = [&](double u, double v) {
    const double dx = (u + 0.5) * map.scale, dy = -(v + 0.5) * map.scale;
    return std::array<double, 2>{map.x0 + ca * dx - sa * dy, map.y0 + sa * dx + ca * dy};
  };
  double bx0 = 1e300, bx1 = -1e300, by0 = 1e300, by1 = -1e300;
  for (double u : {0.0, double(photo.width)})
    for (double v : {0.0, double(photo.height)}) {
      const auto p = model_of(u - 0.5, v - 0.5);
      bx0 = std::min(bx0, p[0]), bx1 = std::max(bx1, p[0]), by0 = std::min(by0, p[1]), by1 = std::max(by1, p[1]);
    }
  // Render the model over the photo's footprint at the photo's resolution, then sample per photo pixel.
  const int W = std::max(1, int(std::ceil((bx1 - bx0) / map.scale))), H = std::max(1, int(std::ceil((by1 - by0) / map.scale)));
  View v{bx0, by0, bx1, by1, W, H};
  ColorBar bar;
  const Image model = field_image(f, v, model_opts, bar);
  const Raster cov = rasterize_2d(f, v, std::vector<double>(f.x.size(), 1.0), 1);
  Image aligned{photo.width, photo.height, std::vector<uint8_t>(photo.rgb.size(), 0)};
  std::vector<uint8_t> mask(std::size_t(photo.width) * photo.height, 0);
  for (int j = 0; j < photo.height; ++j)
    for (int i = 0; i < photo.width; ++i) {
      const auto p = model_of(i, j);
      const int mi = int((p[0] - v.x0) / (v.x1 - v.x0) * v.width), mj = int((v.y1 - p[1]) / (v.y1 - v.y0) * v.height);
      if (mi < 0 || mj < 0 || mi >= v.width || mj >= v.height) continue;
      const std::size_t q = std::size_t(mj) * v.width + mi, t = std::size_t(j) * photo.width + i;
      if (!cov.covered[q]) continue;
      mask[t] = 1;
      std::copy_n(&model.rgb[3 * q], 3, &aligned.rgb[3 * t]);
    }
  // The pixels compared: on the bodies, in the mask and the region of interest.
  const PhotoField field = photo_field(f, photo.width, photo.height, map);
  const std::vector<uint8_t> use = compared_pixels(field, map, mask_image ? &*mask_image : nullptr, o.roi);
  CompareResult res;
  double sa_ = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
  for (std::size_t t = 0; t < mask.size(); ++t) {
    if (!mask[t] || !use[t]) continue;
    auto lum = [](const uint8_t* c) { return (0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]) / 255.0; };
    const double a = lum(&aligned.rgb[3 * t]), b = lum(&photo.rgb[3 * t]);
    sa_ += a, sb += b, saa += a * a, sbb += b * b, sab += a * b;
    ++res.pixels;
  }
  if (!res.pixels) throw std::invalid_argument("the mapped photo does not overlap the body: check --map (and --mask, --roi)");
  const double n = double(res.pixels);
  const double cov_ab = sab / n - sa_ / n * sb / n, va = saa / n - sa_ * sa_ / n / n, vb = sbb / n - sb * sb / n / n;
  res.ncc = va > 0 && vb > 0 ? cov_ab / std::sqrt(va * vb) : 0.0;
  if (o.photo.mode != Polariscope::Seed002) {
    const FoldedOrderAgreement a = folded_order_agreement(photo, field, use, o.photo);
    res.folded_ncc = a.ncc, res.folded_rms = a.rms;
  }
  // Side by side, and the model's fringe centre-lines over the photo.
  Image side{2 * photo.width, photo.height, std::vector<uint8_t>(6 * std::size_t(photo.width) * photo.height)};
  for (int j = 0; j < photo.height; ++j)
    for (int i = 0; i < photo.width; ++i) {
      const std::size_t t = std::size_t(j) * photo.width + i;
      std::copy_n(&photo.rgb[3 * t], 3, &side.rgb[3 * (std::size_t(j) * side.width + i)]);
      std::copy_n(&aligned.rgb[3 * t], 3, &side.rgb[3 * (std::size_t(j) * side.width + photo.width + i)]);
    }
  write_png(out_prefix.string() + "_side_by_side.png", side);
  write_png(out_prefix.string() + "_overlay.png", o.photo.mode == Polariscope::Seed002 ? photo : centre_line_overlay(photo, field, o.photo));
  if (points) res.fringe_rms = fringe_order_rms(f, o.photo, *points, &res.points_used);
  return res;
}

RunComparison compare_runs(const RenderOptions& o, const fs::path& b_series, const fs::path& difference_png) {
  const auto ea = read_series(o.series);
  const auto sel = select_frames(ea, o.frames);
  if (sel.size() != 1) throw std::invalid_argument("comparing runs needs exactly one frame (--frame time:T, last, index:I)");
  const auto& a = ea[sel[0]];
  const auto eb = read_series(b_series);
  char spec[64];
  std::snprintf(spec, sizeof spec, "time:%.17g", a.time);
  const auto& b = eb[select_frames(eb, spec)[0]];
  RenderOptions ob = o;
  ob.series = b_series;
  const ParticleFrame fa = drawn_frame(read_particle_frame(a.file, a.time), o);
  const ParticleFrame fb = drawn_frame(read_particle_frame(b.file, b.time), ob);
  if (fa.dim != 2 || fb.dim != 2) throw std::invalid_argument("comparing runs needs 2D frames");
  // One raster over the bodies of a, fine enough that a pixel is well below a particle of either.
  const auto box = bodies_box(fa, o.roi, 0.0);
  const double aspect = (box[2] - box[0]) / (box[3] - box[1]);
  const View w = fit_view(fa, aspect >= 1 ? 1024 : std::max(1, int(1024 * aspect)),
                          aspect >= 1 ? std::max(1, int(1024 / aspect)) : 1024, o.roi, 1.0, 0.0);
  const Raster ra = stress_raster(fa, w), rb = stress_raster(fb, w);
  RunComparison r;
  r.time_a = a.time, r.time_b = b.time;
  double sum2 = 0, sum1 = 0;
  // The difference image: |N_a - N_b| from white (0) to black (1 fringe or more), the rest grey.
  Image diff{w.width, w.height, std::vector<uint8_t>(3 * std::size_t(w.width) * w.height, 200)};
  for (std::size_t q = 0; q < ra.covered.size(); ++q) {
    if (!ra.covered[q] || !rb.covered[q]) continue;
    const double na = fringe_order(ra.values[3 * q], ra.values[3 * q + 1], ra.values[3 * q + 2], o.photo);
    const double nb = fringe_order(rb.values[3 * q], rb.values[3 * q + 1], rb.values[3 * q + 2], o.photo);
    if (!std::isfinite(na) || !std::isfinite(nb)) continue;
    sum2 += (na - nb) * (na - nb), sum1 += std::fabs(na - nb);
    ++r.pixels;
    const auto level = uint8_t(std::lround(255 * (1 - std::min(1.0, std::fabs(na - nb)))));
    std::fill_n(&diff.rgb[3 * q], 3, level);
  }
  if (!difference_png.empty()) write_png(difference_png, diff);
  if (!r.pixels) throw std::runtime_error("the two runs have no material in common: are they of the same scene?");
  r.rms = std::sqrt(sum2 / r.pixels);
  r.mean_abs = sum1 / r.pixels;
  return r;
}

}  // namespace cleave::viz
