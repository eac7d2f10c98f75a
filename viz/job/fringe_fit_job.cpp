#include "viz/job/fringe_fit_job.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "viz/job/crack_frames.hpp"
#include "viz/optics/photoelastic.hpp"

namespace cleave::viz {
namespace fs = std::filesystem;

std::vector<double> stress_difference_at(const ParticleFrame& f, const std::vector<FringePoint>& pts) {
  std::vector<double> out(pts.size(), std::numeric_limits<double>::quiet_NaN());
  if (pts.empty()) return out;
  // One raster over the points' bounding box, fine enough that a pixel is well below a particle.
  double x0 = pts[0].x, x1 = x0, y0 = pts[0].y, y1 = y0;
  for (const auto& p : pts) x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  const double pad = 1e-6 + 0.01 * std::max(x1 - x0, y1 - y0);
  x0 -= pad, x1 += pad, y0 -= pad, y1 += pad;
  const int n = 1024;
  const double w = x1 - x0, h = y1 - y0;
  View v{x0, y0, x1, y1, w >= h ? n : std::max(1, int(n * w / h)), h >= w ? n : std::max(1, int(n * h / w))};
  const Raster r = stress_raster(f, v);
  for (std::size_t k = 0; k < pts.size(); ++k) {
    const int i = std::clamp(int((pts[k].x - v.x0) / (v.x1 - v.x0) * v.width), 0, v.width - 1);
    const int j = std::clamp(int((v.y1 - pts[k].y) / (v.y1 - v.y0) * v.height), 0, v.height - 1);
    const std::size_t q = std::size_t(j) * v.width + i;
    if (!r.covered[q]) continue;
    out[k] = in_plane(r.values[3 * q], r.values[3 * q + 1], r.values[3 * q + 2]).diff;
  }
  return out;
}

RunTip run_tip(const fs::path& dir, double t, int crack, int tip) {
  const fs::path csv = dir / "crack_tips.csv";
  std::ifstream in(csv);
  if (!in) throw std::runtime_error(csv.string() + ": cannot open (a run whose scene has crack_tips writes it)");
  std::string line;
  std::getline(in, line);
  std::vector<std::string> head;
  for (std::stringstream ss(line); std::getline(ss, line, ',');) head.push_back(line);
  auto col = [&](const std::string& name) {
    const auto it = std::find(head.begin(), head.end(), name);
    if (it == head.end()) throw std::runtime_error(csv.string() + ": no column " + name);
    return std::size_t(it - head.begin());
  };
  const std::size_t ct = col("time_s"), cc = col("crack"), ci = col("tip"), cx = col("x_m"), cy = col("y_m"),
                    ck1 = col("KI_Pa_sqrt_m"), ck2 = col("KII_Pa_sqrt_m");
  std::optional<RunTip> best;
  while (std::getline(in, line)) {
    std::vector<double> v;
    for (std::stringstream ss(line); std::getline(ss, line, ',');) v.push_back(std::strtod(line.c_str(), nullptr));
    if (v.size() < head.size() || int(v[cc]) != crack || int(v[ci]) != tip) continue;
    if (!best || std::abs(v[ct] - t) < std::abs(best->time - t)) best = RunTip{v[ct], v[cx], v[cy], 0, v[ck1], v[ck2]};
  }
  if (!best)
    throw std::runtime_error(csv.string() + ": no row for crack " + std::to_string(crack) + " tip " + std::to_string(tip));
  // The crack's direction at the tip: from the path point 1 mm (or two segments) back to the end nearest the tip.
  const CrackFrame cf = nearest_crack_frame(dir, best->time);
  if (!cf.grid) throw std::runtime_error((dir / "cracks.pvd").string() + ": no crack frames to take the tip's direction from");
  double best_d = std::numeric_limits<double>::infinity();
  for (const auto& path : crack_paths(cf.grid)) {
    if (path.size() < 2) continue;
    for (bool at_end : {false, true}) {
      auto pt = [&](std::size_t k) {
        double p[3];
        cf.grid->GetPoint(path[at_end ? path.size() - 1 - k : k], p);
        return std::array<double, 2>{p[0], p[1]};
      };
      const auto e = pt(0);
      const double d = std::hypot(e[0] - best->x, e[1] - best->y);
      if (d >= best_d) continue;
      std::size_t k = 1;
      while (k + 1 < path.size() && (k < 2 || std::hypot(pt(k)[0] - e[0], pt(k)[1] - e[1]) < 1e-3)) ++k;
      const auto b = pt(k);
      best_d = d, best->alpha = std::atan2(e[1] - b[1], e[0] - b[0]);
    }
  }
  if (!std::isfinite(best_d)) throw std::runtime_error(cf.file.string() + ": no 2D crack path to take the tip's direction from");
  return *best;
}

std::vector<FringePoint> sampled_points(const ParticleFrame& f, const PhotoelasticSettings& s, double x0, double y0,
                                        double alpha, double r0, double r1, int rings, double step) {
  std::vector<FringePoint> pts;
  const double pi = 3.14159265358979323846, lim = pi - 0.5 * step;
  for (int i = 0; i < rings; ++i) {
    const double r = rings == 1 ? r0 : r0 + (r1 - r0) * i / (rings - 1);
    for (double th = -lim; th <= lim + 1e-12; th += step)
      pts.push_back({x0 + r * std::cos(alpha + th), y0 + r * std::sin(alpha + th), 0});
  }
  const auto ds = stress_difference_at(f, pts);
  const double fs = effective_fringe_constant(s);
  std::vector<FringePoint> on;
  for (std::size_t k = 0; k < pts.size(); ++k)
    if (std::isfinite(ds[k])) on.push_back({pts[k].x, pts[k].y, s.thickness * ds[k] / fs});
  return on;
}

Calibration calibrate_scale(const ParticleFrame& f, const PhotoelasticSettings& s, const std::vector<FringePoint>& pts) {
  const auto ds = stress_difference_at(f, pts);
  const double fs = effective_fringe_constant(s);
  double mm = 0, nm = 0, nn = 0;
  Calibration c;
  for (std::size_t k = 0; k < pts.size(); ++k) {
    if (!std::isfinite(ds[k])) continue;
    const double M = s.thickness * ds[k] / fs;
    mm += M * M, nm += pts[k].N * M, nn += pts[k].N * pts[k].N;
    c.rms_before += (M - pts[k].N) * (M - pts[k].N);
    ++c.points;
  }
  if (c.points < 2) throw std::invalid_argument("calibration needs at least two points on the bodies (got " + std::to_string(c.points) + ")");
  if (!(mm > 0)) throw std::invalid_argument("the model has no stress at the points: nothing to scale");
  c.scale = nm / mm;
  const double rss = std::max(0.0, nn - c.scale * nm), n = double(c.points);
  c.std_error = std::sqrt(rss / (n - 1) / mm);
  c.rms_before = std::sqrt(c.rms_before / n);
  c.rms_after = std::sqrt(rss / n);
  return c;
}

}  // namespace cleave::viz
