#include "viz/job/render_job.hpp"

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkNew.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include "libmpm/io/pvd_writer.hpp"
#include "viz/optics/colormap.hpp"

namespace cleave::viz {
namespace fs = std::filesystem;

namespace {

std::array<uint8_t, 3> to_rgb8(const std::array<double, 3>& c) {
  std::array<uint8_t, 3> r;
  for (int k = 0; k < 3; ++k) r[k] = static_cast<uint8_t>(std::lround(std::clamp(c[k], 0.0, 1.0) * 255.0));
  return r;
}

std::string format_time(double t) {
  char b[64];
  if (std::fabs(t) < 1e-3) std::snprintf(b, sizeof b, "t = %.2f us", t * 1e6);
  else if (std::fabs(t) < 1.0) std::snprintf(b, sizeof b, "t = %.4f ms", t * 1e3);
  else std::snprintf(b, sizeof b, "t = %.4f s", t);
  return b;
}

// Units shown on the colour bar for the fields Cleave writes.
std::string field_units(const std::string& f) {
  static const char* stress[] = {"sxx", "syy", "szz", "sxy", "von_mises", "principal_stress_difference", "s1-s2"};
  for (const char* s : stress)
    if (f == s || f.rfind("stress", 0) == 0) return "MPa";
  if (f[0] == 'u' || f.rfind("displacement", 0) == 0 || f == "|u|") return "mm";
  if (f[0] == 'v' || f.rfind("velocity", 0) == 0 || f == "|v|") return "m/s";
  return "";
}
// Display scale matching field_units (SI inside, engineering units on screen).
double field_scale(const std::string& units) { return units == "MPa" ? 1e-6 : units == "mm" ? 1e3 : 1.0; }

// Maps a field's values (SI) to colours: display units, automatic range (symmetric about zero with
// a diverging map for signed fields) or the fixed --range, log scale, colour map; fills the bar.
class ColourScale {
 public:
  ColourScale(const RenderOptions& o, const std::vector<double>& values, ColorBar& bar) : log_(o.log_scale) {
    const std::string units = field_units(o.field);
    scale_ = field_scale(units);
    // Automatic range: the 0.5 % and 99.5 % quantiles, so that a few singular particles (load points,
    // supports, crack tips) do not wash out the rest of the image; --range overrides.
    std::vector<double> v;
    v.reserve(values.size());
    for (double x : values)
      if (std::isfinite(x)) v.push_back(x * scale_);
    lo_ = 0, hi_ = 1;
    if (!v.empty()) {
      const std::size_t a = std::size_t(0.005 * (v.size() - 1)), b = std::size_t(0.995 * (v.size() - 1));
      std::nth_element(v.begin(), v.begin() + a, v.end());
      lo_ = v[a];
      std::nth_element(v.begin(), v.begin() + b, v.end());
      hi_ = v[b];
    }
    const bool is_signed = lo_ < 0 && hi_ > 0;
    if (o.range) lo_ = (*o.range)[0], hi_ = (*o.range)[1];
    else if (is_signed) lo_ = -std::max(-lo_, hi_), hi_ = -lo_;
    if (log_) {
      if (hi_ <= 0) throw std::invalid_argument("--log needs positive values of " + o.field);
      if (lo_ <= 0) lo_ = hi_ * 1e-4;
    }
    if (hi_ == lo_) hi_ = lo_ + (lo_ == 0 ? 1.0 : std::fabs(lo_) * 1e-6);
    const std::string name = o.colormap.empty() ? (is_signed && !log_ ? "coolwarm" : "viridis") : o.colormap;
    const auto cm = colormap_from_name(name);
    if (!cm) throw std::invalid_argument("unknown colour map '" + name + "'; valid: viridis, cividis, coolwarm, gray");
    map_ = *cm;
    bar.show = o.colorbar;
    bar.min = lo_, bar.max = hi_, bar.log = log_;
    bar.title = o.field + (units.empty() ? "" : " (" + units + ")");
    bar.table = colormap_table(map_, 256);
  }
  std::array<uint8_t, 3> operator()(double v_si) const {
    const double v = v_si * scale_;
    const double t = log_ ? (std::log10(std::max(v, lo_)) - std::log10(lo_)) / (std::log10(hi_) - std::log10(lo_))
                          : (v - lo_) / (hi_ - lo_);
    return to_rgb8(colormap(map_, std::clamp(t, 0.0, 1.0)));
  }

 private:
  bool log_;
  double scale_ = 1, lo_ = 0, hi_ = 1;
  ColorMapKind map_ = ColorMapKind::Viridis;
};

// The frame of OUT/cracks.pvd nearest to time t; null when the run has no crack series.
struct CrackFrame {
  vtkSmartPointer<vtkUnstructuredGrid> grid;
  double time = 0;
  fs::path file;
};
CrackFrame nearest_crack_frame(const fs::path& dir, double t) {
  CrackFrame cf;
  const fs::path pvd = dir / "cracks.pvd";
  if (!fs::exists(pvd)) return cf;
  const auto idx = io::PvdIndex::load(pvd);
  if (idx.entries().empty()) return cf;
  auto best = idx.entries().front();
  for (const auto& e : idx.entries())
    if (std::fabs(e.first - t) < std::fabs(best.first - t)) best = e;
  vtkNew<vtkXMLUnstructuredGridReader> r;
  cf.file = dir / best.second;
  r->SetFileName(cf.file.c_str());
  r->Update();
  cf.grid = r->GetOutput();
  cf.time = best.first;
  return cf;
}

// The crack polylines of the crack frame nearest to time t (none when the series has no cracks).
std::vector<Polyline2D> crack_overlays(const fs::path& dir, double t) {
  std::vector<Polyline2D> out;
  const CrackFrame cf = nearest_crack_frame(dir, t);
  if (!cf.grid) return out;
  vtkUnstructuredGrid* g = cf.grid;
  for (vtkIdType c = 0; c < g->GetNumberOfCells(); ++c) {
    vtkCell* cell = g->GetCell(c);
    Polyline2D pl;
    pl.colour = {0.9, 0.1, 0.1};
    for (vtkIdType k = 0; k < cell->GetNumberOfPoints(); ++k) {
      double x[3];
      g->GetPoint(cell->GetPointId(k), x);
      pl.points.push_back({x[0], x[1]});
    }
    out.push_back(std::move(pl));
  }
  return out;
}

fs::path series_dir(const fs::path& p) { return fs::is_directory(p) ? p : p.parent_path(); }

}  // namespace

Raster stress_raster(const ParticleFrame& f, const View& v) {
  const auto it = f.arrays.find("stress");
  if (it == f.arrays.end() || it->second.components != 6)
    throw std::invalid_argument(f.file + ": no 6-component 'stress' array: fringes need stresses (output.fields)");
  const auto& s = it->second.values;
  std::vector<double> per(3 * f.x.size());
  for (std::size_t p = 0; p < f.x.size(); ++p) {
    per[3 * p] = s[6 * p];
    per[3 * p + 1] = s[6 * p + 1];
    per[3 * p + 2] = s[6 * p + 3];
  }
  return rasterize_2d(f, v, per, 3);
}

Image field_image(const ParticleFrame& f, const View& v, const RenderOptions& o, ColorBar& bar) {
  Image img;
  img.width = v.width;
  img.height = v.height;
  img.rgb.resize(3 * std::size_t(v.width) * v.height);
  const auto bg = to_rgb8(o.background);
  const std::size_t npix = std::size_t(v.width) * v.height;
  if (o.fringes) {
    const Raster r = stress_raster(f, v);
    bar.show = false;
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < npix; ++i) {
      std::array<uint8_t, 3> c = bg;
      if (r.covered[i]) {
        const double* s = &r.values[3 * i];
        if (o.photo.white_light) {
          c = to_rgb8(white_light_rgb(s[0], s[1], s[2], o.photo));
        } else {
          const double I = intensity(s[0], s[1], s[2], o.photo);
          c = to_rgb8({I, I, I});
        }
      }
      std::copy(c.begin(), c.end(), &img.rgb[3 * i]);
    }
    return img;
  }
  const std::vector<double> per = scalar_field(f, o.field);
  const Raster r = rasterize_2d(f, v, per, 1);
  std::vector<double> shown;
  for (std::size_t i = 0; i < npix; ++i)
    if (r.covered[i]) shown.push_back(r.values[i]);
  const ColourScale cs(o, shown, bar);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < npix; ++i) {
    const std::array<uint8_t, 3> c = r.covered[i] ? cs(r.values[i]) : bg;
    std::copy(c.begin(), c.end(), &img.rgb[3 * i]);
  }
  return img;
}

RenderResult render_series(const RenderOptions& o, const std::function<void(std::size_t, std::size_t)>& progress) {
  const auto entries = read_series(o.series);
  const auto sel = select_frames(entries, o.frames);
  if (sel.empty()) throw std::invalid_argument("frame selection '" + o.frames + "' selects no frame");
  const fs::path dir = series_dir(o.series);
  const fs::path images = o.image_dir.empty() ? dir / "render" : o.image_dir;
  fs::create_directories(images);
  HeadlessContext ctx(o.width, o.height);
  RenderResult res;
  std::string prefix = o.fringes ? (o.photo.white_light ? "fringes_white" : "fringes") : o.field;
  for (char& c : prefix)  // a file name: "|v|" -> "_v_", "stress:1" -> "stress_1"
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') c = '_';
  for (std::size_t k = 0; k < sel.size(); ++k) {
    const auto& e = entries[sel[k]];
    ParticleFrame f = read_particle_frame(e.file, e.time);
    if (f.dim == 3 && o.cut_plane) {
      const auto& c = *o.cut_plane;
      f = cut_plane(f, {c[0], c[1], c[2]}, {c[3], c[4], c[5]});
    }
    Image out;
    const std::string stamp = o.time_stamp ? format_time(e.time) : "";
    if (f.dim == 3) {
      if (o.fringes) throw std::invalid_argument("fringes of a 3D series need a cut plane (--cut-plane)");
      ColorBar bar;
      const std::vector<double> per = scalar_field(f, o.field);
      const ColourScale cs(o, per, bar);
      std::vector<std::array<double, 3>> centres(f.x.begin(), f.x.end());
      const std::vector<double> edge = particle_sizes(f);  // "size", else the median spacing
      std::vector<std::array<uint8_t, 3>> colours(f.x.size());
      for (std::size_t p = 0; p < f.x.size(); ++p) colours[p] = cs(per[p]);
      Camera3D cam;
      cam.preset = o.camera;
      cam.explicit_view = o.view;
      // Crack surfaces (triangle cells of the crack frame nearest in time) over the particles.
      std::vector<std::array<std::array<double, 3>, 3>> tris;
      if (const CrackFrame cf = nearest_crack_frame(dir, e.time); cf.grid)
        for (vtkIdType c = 0; c < cf.grid->GetNumberOfCells(); ++c) {
          vtkCell* cell = cf.grid->GetCell(c);
          if (cell->GetNumberOfPoints() != 3) continue;
          std::array<std::array<double, 3>, 3> t;
          for (int k = 0; k < 3; ++k) cf.grid->GetPoint(cell->GetPointId(k), t[k].data());
          tris.push_back(t);
        }
      out = render_particles_3d(ctx, centres, edge, colours, cam, o.title, stamp, bar, o.background, tris);
    } else {
      Frame2D fr;
      fr.title = o.title;
      fr.time_stamp = stamp;
      fr.background = o.background;
      fr.colorbar.show = o.colorbar && !o.fringes;
      // The field viewport depends on the window's aspect ratio: fit once to the whole image, ask the
      // layout for the field's rectangle, and fit again to exactly that many pixels.
      const View v0 = fit_view(f, o.width, o.height, o.roi, o.zoom);
      fr.x0 = v0.x0, fr.y0 = v0.y0, fr.x1 = v0.x1, fr.y1 = v0.y1;
      const PixelRect rect = frame_2d_field_viewport(o.width, o.height, fr);
      const View v = fit_view(f, std::max(1, rect.width), std::max(1, rect.height), o.roi, o.zoom);
      fr.field = field_image(f, v, o, fr.colorbar);
      fr.x0 = v.x0, fr.y0 = v.y0, fr.x1 = v.x1, fr.y1 = v.y1;
      if (!o.cut_plane) fr.overlays = crack_overlays(dir, e.time);
      out = render_frame_2d(ctx, fr);
    }
    char name[256];
    std::snprintf(name, sizeof name, "%s_%06zu.png", prefix.c_str(), k);
    const fs::path file = images / name;
    write_png(file, out);
    res.images.push_back(file);
    if (progress) progress(k + 1, sel.size());
  }
  if (o.movie) {
    if (std::system("command -v ffmpeg >/dev/null 2>&1") != 0)
      throw std::runtime_error("--movie needs Debian's ffmpeg (apt-get install ffmpeg; the README's set-up command installs it)");
    fs::path movie = *o.movie;
    if (movie.is_relative() && movie.parent_path().empty()) movie = images / movie;
    std::ostringstream cmd;
    cmd << "ffmpeg -loglevel error -y -framerate " << o.fps << " -i '" << (images / (prefix + "_%06d.png")).string()
        << "' -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' -c:v libx264 -pix_fmt yuv420p '" << movie.string() << "'";
    if (std::system(cmd.str().c_str()) != 0) throw std::runtime_error("ffmpeg failed to encode " + movie.string());
    res.movie = movie;
  }
  return res;
}

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
  // One raster over the points' bounding box, fine enough that a pixel is well below a particle.
  double x0 = pts[0][0], x1 = x0, y0 = pts[0][1], y1 = y0;
  for (const auto& p : pts) x0 = std::min(x0, p[0]), x1 = std::max(x1, p[0]), y0 = std::min(y0, p[1]), y1 = std::max(y1, p[1]);
  const double pad = 1e-6 + 0.01 * std::max(x1 - x0, y1 - y0);
  x0 -= pad, x1 += pad, y0 -= pad, y1 += pad;
  const int n = 1024;
  const double w = x1 - x0, h = y1 - y0;
  View v{x0, y0, x1, y1, w >= h ? n : std::max(1, int(n * w / h)), h >= w ? n : std::max(1, int(n * h / w))};
  const Raster r = stress_raster(f, v);
  double sum = 0;
  std::size_t k = 0;
  for (const auto& p : pts) {
    const int i = std::clamp(int((p[0] - v.x0) / (v.x1 - v.x0) * v.width), 0, v.width - 1);
    const int j = std::clamp(int((v.y1 - p[1]) / (v.y1 - v.y0) * v.height), 0, v.height - 1);
    const std::size_t q = std::size_t(j) * v.width + i;
    if (!r.covered[q]) continue;
    const double N = fringe_order(r.values[3 * q], r.values[3 * q + 1], r.values[3 * q + 2], s);
    sum += (N - p[2]) * (N - p[2]);
    ++k;
  }
  if (used) *used = k;
  if (!k) throw std::runtime_error("no digitised point lies on the body");
  return std::sqrt(sum / k);
}

CompareResult compare_with_photo(const RenderOptions& o, const fs::path& photo_file, const PhotoMap& map,
                                 const std::optional<std::vector<std::array<double, 3>>>& points,
                                 const fs::path& out_prefix) {
  const Image photo = read_image(photo_file);
  const auto entries = read_series(o.series);
  const auto sel = select_frames(entries, o.frames);
  if (sel.size() != 1) throw std::invalid_argument("compare needs exactly one frame (--frame time:T, last, index:I)");
  const auto& e = entries[sel[0]];
  const ParticleFrame f = read_particle_frame(e.file, e.time);
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
  const Image model = field_image(f, v, o, bar);
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
  CompareResult res;
  double sa_ = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
  for (std::size_t t = 0; t < mask.size(); ++t) {
    if (!mask[t]) continue;
    auto lum = [](const uint8_t* c) { return (0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]) / 255.0; };
    const double a = lum(&aligned.rgb[3 * t]), b = lum(&photo.rgb[3 * t]);
    sa_ += a, sb += b, saa += a * a, sbb += b * b, sab += a * b;
    ++res.pixels;
  }
  if (!res.pixels) throw std::runtime_error("the mapped photo does not overlap the body: check --map");
  const double n = double(res.pixels);
  const double cov_ab = sab / n - sa_ / n * sb / n, va = saa / n - sa_ * sa_ / n / n, vb = sbb / n - sb * sb / n / n;
  res.ncc = va > 0 && vb > 0 ? cov_ab / std::sqrt(va * vb) : 0.0;
  // Side by side and overlay images.
  Image side{2 * photo.width, photo.height, std::vector<uint8_t>(6 * std::size_t(photo.width) * photo.height)};
  Image over = photo;
  for (int j = 0; j < photo.height; ++j)
    for (int i = 0; i < photo.width; ++i) {
      const std::size_t t = std::size_t(j) * photo.width + i;
      std::copy_n(&photo.rgb[3 * t], 3, &side.rgb[3 * (std::size_t(j) * side.width + i)]);
      std::copy_n(&aligned.rgb[3 * t], 3, &side.rgb[3 * (std::size_t(j) * side.width + photo.width + i)]);
      if (mask[t])
        for (int c = 0; c < 3; ++c) over.rgb[3 * t + c] = uint8_t((int(photo.rgb[3 * t + c]) + aligned.rgb[3 * t + c]) / 2);
    }
  write_png(out_prefix.string() + "_side_by_side.png", side);
  write_png(out_prefix.string() + "_overlay.png", over);
  if (points) res.fringe_rms = fringe_order_rms(f, o.photo, *points, &res.points_used);
  return res;
}

std::vector<fs::path> render_plots(const fs::path& dir, const fs::path& images, int width, int height) {
  std::vector<fs::path> out;
  fs::create_directories(images);
  auto read_csv = [](const fs::path& file, std::vector<std::string>& header) {
    std::ifstream in(file);
    std::vector<std::vector<double>> rows;
    std::string line;
    if (!std::getline(in, line)) return rows;
    std::stringstream hs(line);
    for (std::string c; std::getline(hs, c, ',');) header.push_back(c);
    while (std::getline(in, line)) {
      std::stringstream ls(line);
      std::vector<double> r;
      for (std::string c; std::getline(ls, c, ',');) r.push_back(std::strtod(c.c_str(), nullptr));
      if (r.size() == header.size()) rows.push_back(std::move(r));
    }
    return rows;
  };
  HeadlessContext ctx(width, height);
  if (fs::exists(dir / "global.csv")) {
    std::vector<std::string> h;
    const auto rows = read_csv(dir / "global.csv", h);
    std::vector<PlotSeries> series;
    for (const char* name : {"kinetic_energy", "strain_energy", "total_energy", "external_work"}) {
      const auto it = std::find(h.begin(), h.end(), name);
      if (it == h.end()) continue;
      PlotSeries s{name, {}, {}};
      for (const auto& r : rows) s.x.push_back(r[0] * 1e3), s.y.push_back(r[it - h.begin()]);
      series.push_back(std::move(s));
    }
    if (!series.empty()) {
      const fs::path f = images / "energy.png";
      write_png(f, render_plot(ctx, series, "Energies", "time (ms)", "energy (J)"));
      out.push_back(f);
    }
  }
  if (fs::exists(dir / "crack_tips.csv")) {
    std::vector<std::string> h;
    const auto rows = read_csv(dir / "crack_tips.csv", h);
    auto col = [&](const char* n) { return int(std::find(h.begin(), h.end(), n) - h.begin()); };
    const int ct = col("crack"), tp = col("tip");
    for (const char* q : {"J1", "KI"}) {
      const int c = col(q);
      if (c >= int(h.size()) || ct >= int(h.size()) || tp >= int(h.size())) continue;
      std::map<std::pair<int, int>, PlotSeries> by_tip;
      for (const auto& r : rows) {
        auto& s = by_tip[{int(r[ct]), int(r[tp])}];
        s.name = std::string(q) + " crack " + std::to_string(int(r[ct])) + " tip " + std::to_string(int(r[tp]));
        s.x.push_back(r[0] * 1e3);
        s.y.push_back(q[0] == 'K' ? r[c] * 1e-6 : r[c]);
        if (q[0] == 'K') {
          const int c2 = col("KII");
          if (c2 < int(h.size())) {
            auto& s2 = by_tip[{int(r[ct]), int(r[tp]) + 1000}];
            s2.name = "KII crack " + std::to_string(int(r[ct])) + " tip " + std::to_string(int(r[tp]));
            s2.x.push_back(r[0] * 1e3);
            s2.y.push_back(r[c2] * 1e-6);
          }
        }
      }
      std::vector<PlotSeries> series;
      for (auto& [k, s] : by_tip) series.push_back(s);
      const bool K = q[0] == 'K';
      const fs::path f = images / (K ? "K.png" : "J.png");
      write_png(f, render_plot(ctx, series, K ? "Stress intensity factors" : "J-integral", "time (ms)",
                               K ? "K (MPa m^1/2)" : "J (J/m^2)"));
      out.push_back(f);
    }
  }
  return out;
}

fs::path render_cod_profile(const fs::path& dir, const fs::path& images, double time, int width, int height) {
  const CrackFrame cf = nearest_crack_frame(dir, time);
  if (!cf.grid) throw std::runtime_error((dir / "cracks.pvd").string() + ": no crack series (the scene declares no crack)");
  vtkUnstructuredGrid* g = cf.grid;
  const fs::path& file = cf.file;
  vtkDataArray* cn = g->GetPointData()->GetArray("cod_normal");
  vtkDataArray* ct = g->GetPointData()->GetArray("cod_tangential");
  if (!cn || !ct) throw std::runtime_error(file.string() + ": no cod_normal / cod_tangential point data");
  std::vector<PlotSeries> series;
  for (vtkIdType c = 0; c < g->GetNumberOfCells(); ++c) {
    vtkCell* cell = g->GetCell(c);
    PlotSeries n{"normal COD, crack " + std::to_string(c), {}, {}}, t{"tangential COD, crack " + std::to_string(c), {}, {}};
    double along = 0, prev[3] = {0, 0, 0};
    for (vtkIdType k = 0; k < cell->GetNumberOfPoints(); ++k) {
      const vtkIdType id = cell->GetPointId(k);
      double x[3];
      g->GetPoint(id, x);
      if (k) along += std::sqrt((x[0] - prev[0]) * (x[0] - prev[0]) + (x[1] - prev[1]) * (x[1] - prev[1]) +
                                (x[2] - prev[2]) * (x[2] - prev[2]));
      std::copy(x, x + 3, prev);
      n.x.push_back(along * 1e3), n.y.push_back(cn->GetComponent(id, 0) * 1e3);
      t.x.push_back(along * 1e3), t.y.push_back(ct->GetComponent(id, 0) * 1e3);
    }
    series.push_back(std::move(n));
    series.push_back(std::move(t));
  }
  fs::create_directories(images);
  HeadlessContext ctx(width, height);
  const fs::path out = images / "cod_profile.png";
  write_png(out, render_plot(ctx, series, "Crack opening, " + format_time(cf.time), "distance along the crack (mm)",
                             "opening (mm)"));
  return out;
}

}  // namespace cleave::viz
