// `cleave render`: frames of a particle series → stress-coloured or photoelastic-fringe PNG images
// (and a movie). Every pixel's colour is computed from the stress interpolated to that pixel,
// never by interpolating colours or intensities.
#pragma once
#include <array>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "viz/job/front_plots.hpp"
#include "viz/optics/photoelastic.hpp"
#include "viz/raster/rasterize.hpp"
#include "viz/raster/series.hpp"
#include "viz/render/headless.hpp"

namespace cleave::viz {

struct RenderOptions {
  std::filesystem::path series;                 // OUT directory or a .pvd
  std::filesystem::path image_dir;              // default: OUT/render
  std::string frames = "all";                   // all | every:K | time:T | first | last | index:I
  int width = 1280, height = 720;
  std::optional<std::array<double, 4>> roi;     // x0, y0, x1, y1 (model units, m)
  double zoom = 1.0;
  std::array<double, 3> background{1, 1, 1};
  std::string title;
  bool time_stamp = true;
  bool colorbar = true;
  // Colouring by a field (when `fringes` is false).
  std::string field = "principal_stress_difference";
  std::string colormap;                         // empty: viridis, or coolwarm for signed fields
  std::optional<std::array<double, 2>> range;   // fixed range; default automatic
  bool log_scale = false;
  // Photoelastic fringes.
  bool fringes = false;
  PhotoelasticSettings photo;
  // 3D: cut plane (point, normal) renders a 2D section; otherwise particles as cubes.
  std::optional<std::array<double, 6>> cut_plane;
  // 3D cracks (docs/rendering.md, "3D cracks"): their two faces are drawn with the opening K times
  // what it is (viz/raster/crack_section.hpp), over the cubes and as traces in sections. > 0.
  double opening_scale = 1.0;
  // Stresses, strains, displacements and velocities times this (drawn_frame): an elastic static
  // run serves a whole load sequence (--load-scale).
  double load_scale = 1.0;
  // With cut_plane: a frozen-stress slice of this thickness (m, > 0) centred on the plane instead
  // of the one-particle section (viz/raster/slice.hpp); fringes take it as the specimen thickness
  // (photo.thickness is not used).
  std::optional<double> slice;
  std::string camera = "iso";
  std::optional<std::array<double, 9>> view;   // explicit camera: position, focal point, view-up
  // Movie: encoded with ffmpeg from the PNG frames, which are kept.
  std::optional<std::filesystem::path> movie;
  int fps = 10;
  // Figures of 2D frames and sections (docs/rendering.md, "Figures"), all on by default:
  bool tight = true;      // crop the image to the bodies and its bands (width x height: the most)
  bool outline = true;    // smooth outlines (RasterOptions::smooth_outline), drawn in dark grey
  bool scale_bar = true;  // a round length with its unit below the bodies
  double smooth = 1.5;    // stress smoothing width in particle spacings (smooth.hpp); 0: as written
};

struct RenderResult {
  std::vector<std::filesystem::path> images;
  std::optional<std::filesystem::path> movie;
};

// Renders the selected frames; progress(i, n) after each frame. Throws std::runtime_error /
// std::invalid_argument with a clear message on bad input.
RenderResult render_series(const RenderOptions&, const std::function<void(std::size_t, std::size_t)>& progress = {});

// The field image of one 2D frame (pixel colours over view), and its colour bar: the stress of
// drawn_frame, the smooth outline when o.outline.
Image field_image(const ParticleFrame&, const View&, const RenderOptions&, ColorBar& bar);

// The frame as it is drawn: its fields scaled by o.load_scale, its stress smoothed over o.smooth
// particle spacings, with the cracks of the series at the frame's time as barriers (smooth_stress):
// the crack paths of a 2D frame, the traces of the 3D crack faces in o.cut_plane for a section; not
// smoothed when o.smooth <= 0.
ParticleFrame drawn_frame(const ParticleFrame&, const RenderOptions&);

// Per-pixel in-plane stress (sxx, syy, sxy; a section's "stress_uv") of a frame: Raster with k = 3.
Raster stress_raster(const ParticleFrame&, const View&, const RasterOptions& = {});

// Frames are named PREFIX_NNNNNN.png with NNNNNN the frame's index in the series, so renders of
// different selections into one folder do not overwrite each other's frames.
std::string frame_file_name(const std::string& prefix, std::size_t index);

// Photo comparison (viz/job/compare.cpp).
struct PhotoMap {
  double x0 = 0, y0 = 0;  // model coordinates of the photo's top-left pixel corner
  double scale = 1e-4;    // metres per photo pixel
  double angle = 0;       // rad, rotation of the photo's x axis from the model's x axis
};
struct CompareResult {
  double ncc = 0;              // normalised cross-correlation of intensities over the mapped region
  std::size_t pixels = 0;      // pixels compared
  std::optional<double> fringe_rms;  // with points: RMS of (model fringe order - digitised order)
  std::size_t points_used = 0;
  // Folded fringe orders (photo_field.hpp): correlation and RMS difference; not for seed002.
  std::optional<double> folded_ncc, folded_rms;
};
// `mask`: an image of the photo's size, white where pixels are compared; o.roi (model coordinates)
// restricts them too. PREFIX_overlay.png holds the model's fringe centre-lines over the photo.
CompareResult compare_with_photo(const RenderOptions&, const std::filesystem::path& photo, const PhotoMap&,
                                 const std::optional<std::vector<std::array<double, 3>>>& points,
                                 const std::filesystem::path& out_prefix,
                                 const std::optional<std::filesystem::path>& mask = {});
// Two runs of one scene (at two resolutions, say): the fringe orders of their frames nearest in
// time to the selected frame of a, drawn as o says (drawn_frame), compared pixel by pixel over a
// raster of the bodies of a (1024 pixels along its longer side) where both have material; with
// difference_png, |N_a - N_b| as an image there (white 0, black 1 fringe or more, grey no material).
struct RunComparison {
  double rms = 0;          // RMS of the fringe-order difference
  double mean_abs = 0;     // mean absolute difference
  std::size_t pixels = 0;  // pixels compared
  double time_a = 0, time_b = 0;
};
RunComparison compare_runs(const RenderOptions& a, const std::filesystem::path& b_series,
                           const std::filesystem::path& difference_png = {});
// The length unit of the scene a run was written from (OUT/run.json "length_unit", given the run's
// folder or its .pvd): the default unit of the commands' coordinates (--roi, --map, --points, ...);
// "m" for runs written before it was recorded, or without a run.json.
std::string run_length_unit(const std::filesystem::path& dir_or_pvd);
// Points file: "x y N" per line (model units m, fringe order); '#' comments.
std::vector<std::array<double, 3>> read_fringe_points(const std::filesystem::path&);
// RMS of (model N at (x, y) - N) over the points that fall on the body.
double fringe_order_rms(const ParticleFrame&, const PhotoelasticSettings&, const std::vector<std::array<double, 3>>& pts,
                        std::size_t* used = nullptr);

// Plots: energies from OUT/global.csv, J/K from OUT/crack_tips.csv, and K along 3D crack fronts from
// OUT/crack_fronts.csv (front_plots, with `front`'s options) when present.
std::vector<std::filesystem::path> render_plots(const std::filesystem::path& out_dir, const std::filesystem::path& image_dir,
                                                int width, int height, const FrontPlotOptions& front = {});

// Crack-opening profile of the crack frame nearest to `time`: normal and tangential crack opening
// displacement against the distance along each crack, from OUT/cracks.pvd. Crack VTU files hold
// each crack as line segments in path order (older files: one poly-line cell per crack) with point
// data "cod_normal" and "cod_tangential" (m) and "crack" (id).
std::filesystem::path render_cod_profile(const std::filesystem::path& out_dir, const std::filesystem::path& image_dir,
                                         double time, int width, int height);

}  // namespace cleave::viz
