#include "viz/job/render_job.hpp"

#include <fstream>
#include <nlohmann/json.hpp>

#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkNew.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include "viz/job/colour_scale.hpp"
#include "viz/job/crack_frames.hpp"
#include "viz/job/movie.hpp"
#include "viz/optics/colormap.hpp"
#include "viz/raster/slice.hpp"
#include "viz/raster/smooth.hpp"

namespace cleave::viz {
namespace fs = std::filesystem;

namespace {

fs::path series_dir(const fs::path& p) { return fs::is_directory(p) ? p : p.parent_path(); }

// The options of 3D cracks and slices, named as the command line names them.
void check_crack_options(const RenderOptions& o) {
  if (!(o.opening_scale > 0) || !std::isfinite(o.opening_scale))
    throw std::invalid_argument("--opening-scale must be a positive number (1: the opening as it is)");
  if (o.slice) {
    if (!(*o.slice > 0) || !std::isfinite(*o.slice)) throw std::invalid_argument("--slice must be a positive thickness");
    if (!o.cut_plane) throw std::invalid_argument("--slice needs --cut-plane (the slice is centred on that plane)");
  }
}

// Space around the bodies, of the box's larger side: a figure's tight frame, or the room an image of
// a given size has anyway.
constexpr double kTightMargin = 0.015, kMargin = 0.03;

}  // namespace

Raster stress_raster(const ParticleFrame& f, const View& v, const RasterOptions& ro) {
  // A section of a 3D frame carries its in-plane stress (cut_plane); a 2D frame its own xx, yy, xy.
  if (const auto uv = f.arrays.find("stress_uv"); uv != f.arrays.end() && uv->second.components == 3)
    return rasterize_2d(f, v, uv->second.values, 3, ro);
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
  return rasterize_2d(f, v, per, 3, ro);
}

std::string run_length_unit(const fs::path& dir_or_pvd) {
  const fs::path dir = fs::is_directory(dir_or_pvd) ? dir_or_pvd : dir_or_pvd.parent_path();
  std::ifstream in(dir / "run.json");
  if (!in) return "m";
  try {
    return nlohmann::json::parse(in).value("length_unit", std::string("m"));
  } catch (const std::exception&) {
    return "m";
  }
}

ParticleFrame drawn_frame(const ParticleFrame& frame, const RenderOptions& o) {
  ParticleFrame scaled;
  if (o.load_scale != 1.0) {
    scaled = frame;
    for (const char* name : {"stress", "strain", "von_mises", "principal_stress_difference", "displacement", "velocity"})
      if (auto it = scaled.arrays.find(name); it != scaled.arrays.end())
        for (double& v : it->second.values) v *= o.load_scale;
  }
  const ParticleFrame& f = o.load_scale != 1.0 ? scaled : frame;
  if (!(o.smooth > 0) || f.dim != 2) return f;
  SmoothSettings s;
  s.sigma = o.smooth;
  // Cracks are barriers: the stress is not averaged from one face of a crack to the other. A 2D
  // frame has crack paths; a section of a 3D frame the traces of the crack faces where they are.
  if (!o.series.empty()) {
    const fs::path dir = series_dir(o.series);
    if (const CrackFrame cf = nearest_crack_frame(dir, f.time); o.cut_plane && cf.grid && has_crack_surfaces(cf.grid)) {
      const auto& c = *o.cut_plane;
      s.barriers = section_barriers(crack_surfaces(cf.grid), {c[0], c[1], c[2]}, {c[3], c[4], c[5]});
    } else if (cf.grid) {
      for (const Polyline2D& pl : crack_overlays(cf.grid))
        for (std::size_t i = 0; i + 1 < pl.points.size(); ++i)
          s.barriers.push_back({pl.points[i][0], pl.points[i][1], pl.points[i + 1][0], pl.points[i + 1][1]});
    }
  }
  return smooth_stress(f, s);
}

namespace {
// The bodies' outline over a field image: dark grey (light grey on a dark background), about 1.5
// pixels wide and more on large images, antialiased from the signed edge distance of the raster.
void draw_outline(Image& img, const Raster& r, const std::array<double, 3>& background) {
  if (r.edge.empty()) return;
  const double lum = 0.299 * background[0] + 0.587 * background[1] + 0.114 * background[2];
  const double ink = lum > 0.5 ? 0.2 * 255 : 0.8 * 255;
  const double half = 0.5 * std::max(1.5, img.width / 1000.0);
  for (std::size_t i = 0; i < r.edge.size(); ++i) {
    const double a = std::clamp(half + 0.5 - std::fabs(double(r.edge[i])), 0.0, 1.0);
    if (a <= 0) continue;
    for (int c = 0; c < 3; ++c) img.rgb[3 * i + c] = uint8_t(std::lround((1 - a) * img.rgb[3 * i + c] + a * ink));
  }
}
}  // namespace

Image field_image(const ParticleFrame& frame, const View& v, const RenderOptions& o, ColorBar& bar) {
  const ParticleFrame f = drawn_frame(frame, o);
  RasterOptions ro;
  ro.smooth_outline = o.outline;
  Image img;
  img.width = v.width;
  img.height = v.height;
  img.rgb.resize(3 * std::size_t(v.width) * v.height);
  const auto bg = to_rgb8(o.background);
  const std::size_t npix = std::size_t(v.width) * v.height;
  if (o.fringes) {
    const Raster r = stress_raster(f, v, ro);
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
    draw_outline(img, r, o.background);
    return img;
  }
  const std::vector<double> per = scalar_field(f, o.field);
  const Raster r = rasterize_2d(f, v, per, 1, ro);
  std::vector<double> shown;
  for (std::size_t i = 0; i < npix; ++i)
    if (r.covered[i]) shown.push_back(r.values[i]);
  const ColourScale cs(o, shown, bar);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < npix; ++i) {
    const std::array<uint8_t, 3> c = r.covered[i] ? cs(r.values[i]) : bg;
    std::copy(c.begin(), c.end(), &img.rgb[3 * i]);
  }
  draw_outline(img, r, o.background);
  return img;
}

std::string frame_file_name(const std::string& prefix, std::size_t index) {
  char name[256];
  std::snprintf(name, sizeof name, "%s_%06zu.png", prefix.c_str(), index);
  return name;
}

RenderResult render_series(const RenderOptions& options, const std::function<void(std::size_t, std::size_t)>& progress) {
  check_crack_options(options);
  RenderOptions o = options;
  if (o.slice) o.photo.thickness = *o.slice;  // a slice's fringes: its own thickness
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
  std::optional<std::array<int, 2>> canvas;  // image size of the 2D frames
  for (std::size_t k = 0; k < sel.size(); ++k) {
    const auto& e = entries[sel[k]];
    ParticleFrame f = read_particle_frame(e.file, e.time);
    if (o.slice && f.dim != 3)
      throw std::invalid_argument("--slice needs a 3D series; " + e.file.string() + " is 2D");
    const bool section = f.dim == 3 && o.cut_plane;
    if (section) {
      const auto& c = *o.cut_plane;
      f = o.slice ? slice_plane(f, {c[0], c[1], c[2]}, {c[3], c[4], c[5]}, *o.slice)
                  : cut_plane(f, {c[0], c[1], c[2]}, {c[3], c[4], c[5]});
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
      // The crack faces (triangles of the crack frame nearest in time) over the particles.
      CrackSurfaces3D faces;
      if (const CrackFrame cf = nearest_crack_frame(dir, e.time); cf.grid)
        faces = crack_faces_3d(crack_surfaces(cf.grid), o.opening_scale);
      out = render_particles_3d(ctx, centres, edge, colours, cam, o.title, stamp, bar, o.background, faces);
    } else {
      Frame2D fr;
      fr.title = o.title;
      fr.time_stamp = stamp;
      fr.background = o.background;
      fr.colorbar.show = o.colorbar && !o.fringes;
      fr.scale_bar = o.scale_bar;
      // Lettering for the size asked for, also when the image is cropped to the bodies; a wide strip
      // of an image (1280 x 400) gets letters for its width, not only its few rows.
      fr.text_size = std::max(o.height, int(0.45 * o.width));
      const double margin = o.tight ? kTightMargin : kMargin;
      // The layout gives the largest rectangle of the bodies' aspect ratio beside the bands; the view
      // is then fitted to exactly that many pixels.
      const auto box = bodies_box(f, o.roi, margin);
      fr.x0 = box[0], fr.y0 = box[1], fr.x1 = box[2], fr.y1 = box[3];
      if (!canvas) {  // the first frame sizes the image; the others are fitted into it, as a movie needs
        canvas = o.tight ? frame_2d_tight_size(o.width, o.height, fr) : std::array<int, 2>{o.width, o.height};
        ctx.resize((*canvas)[0], (*canvas)[1]);
      }
      const int W = (*canvas)[0], H = (*canvas)[1];
      const PixelRect rect = frame_2d_field_viewport(W, H, fr);
      const View v = fit_view(f, std::max(1, rect.width), std::max(1, rect.height), o.roi, o.zoom, margin);
      fr.field = field_image(f, v, o, fr.colorbar);
      fr.x0 = v.x0, fr.y0 = v.y0, fr.x1 = v.x1, fr.y1 = v.y1;
      if (!section) {
        fr.overlays = crack_overlays(dir, e.time);
      } else if (const CrackFrame cf = nearest_crack_frame(dir, e.time); cf.grid && has_crack_surfaces(cf.grid)) {
        fr.overlays = section_overlays(crack_surfaces(cf.grid), o.opening_scale, *o.cut_plane);
      }
      out = render_frame_2d(ctx, fr);
    }
    const fs::path file = images / frame_file_name(prefix, sel[k]);
    write_png(file, out);
    res.images.push_back(file);
    if (progress) progress(k + 1, sel.size());
  }
  if (o.movie) res.movie = encode_movie(res.images, images, *o.movie, o.fps);
  return res;
}

std::vector<fs::path> render_plots(const fs::path& dir, const fs::path& images, int width, int height,
                                   const FrontPlotOptions& front) {
  const auto fronts = front_plots(dir, front);  // checks the front options before any image is written
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
  // A column by its name with its unit (docs/scenes.md: "kinetic_energy_J"), or by the bare name
  // that Cleave wrote before the CSV columns carried units, so older runs still plot; h.size() if
  // absent. The first column is the time in s either way.
  auto column = [](const std::vector<std::string>& h, const std::string& name, const std::string& unit) {
    auto it = std::find(h.begin(), h.end(), name + "_" + unit);
    if (it == h.end()) it = std::find(h.begin(), h.end(), name);
    return int(it - h.begin());
  };
  HeadlessContext ctx(width, height);
  if (fs::exists(dir / "global.csv")) {
    std::vector<std::string> h;
    const auto rows = read_csv(dir / "global.csv", h);
    std::vector<PlotSeries> series;
    for (const char* name : {"kinetic_energy", "strain_energy", "total_energy", "external_work"}) {
      const int c = column(h, name, "J");
      if (c >= int(h.size())) continue;
      PlotSeries s{name, {}, {}};
      for (const auto& r : rows) s.x.push_back(r[0] * 1e3), s.y.push_back(r[c]);
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
      const int c = column(h, q, q[0] == 'K' ? "Pa_sqrt_m" : "J_per_m2");
      if (c >= int(h.size()) || ct >= int(h.size()) || tp >= int(h.size())) continue;
      std::map<std::pair<int, int>, PlotSeries> by_tip;
      for (const auto& r : rows) {
        auto& s = by_tip[{int(r[ct]), int(r[tp])}];
        s.name = std::string(q) + " crack " + std::to_string(int(r[ct])) + " tip " + std::to_string(int(r[tp]));
        s.x.push_back(r[0] * 1e3);
        s.y.push_back(q[0] == 'K' ? r[c] * 1e-6 : r[c]);
        if (q[0] == 'K') {
          const int c2 = column(h, "KII", "Pa_sqrt_m");
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
  for (auto& f : write_front_plots(ctx, images, fronts)) out.push_back(std::move(f));
  return out;
}

fs::path render_cod_profile(const fs::path& dir, const fs::path& images, double time, int width, int height) {
  const CrackFrame cf = nearest_crack_frame(dir, time);
  if (!cf.grid) throw std::runtime_error((dir / "cracks.pvd").string() + ": no crack series (the scene declares no crack)");
  vtkUnstructuredGrid* g = cf.grid;
  const fs::path& file = cf.file;
  const auto paths = crack_paths(g);
  if (paths.empty())  // 3D crack frames hold surfaces: their opening is drawn by cleave render
    throw std::runtime_error(file.string() + ": no crack paths: --cod plots the opening along 2D cracks; for a 3D "
                             "crack use cleave render with --opening-scale or a --cut-plane section");
  vtkDataArray* cn = g->GetPointData()->GetArray("cod_normal");
  vtkDataArray* ct = g->GetPointData()->GetArray("cod_tangential");
  if (!cn || !ct) throw std::runtime_error(file.string() + ": no cod_normal / cod_tangential point data");
  std::vector<PlotSeries> series;
  for (std::size_t c = 0; c < paths.size(); ++c) {
    PlotSeries n{"normal COD, crack " + std::to_string(c), {}, {}}, t{"tangential COD, crack " + std::to_string(c), {}, {}};
    double along = 0, prev[3] = {0, 0, 0};
    for (std::size_t k = 0; k < paths[c].size(); ++k) {
      const vtkIdType id = paths[c][k];
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
