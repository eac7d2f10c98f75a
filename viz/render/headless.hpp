// Headless rendering backend: an OSMesa OpenGL context driving a VTK render window (no X server, no
// DISPLAY), and the three kinds of picture the renderer makes with it: a 2D field frame, 3D
// particles as cubes, and a line plot. VTK stays out of this header (window() hands out the VTK
// window for code that wants to add its own renderers).
//
// Programs that use this must be built with cleave_viz_executable() (viz/CMakeLists.txt).
// A context is current on one thread at a time; use each from the thread that made it.
#pragma once

#include "viz/render/image.hpp"

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

class vtkRenderWindow;

namespace cleave::viz {

// PNG through vtkPNGWriter. Throws std::invalid_argument for an inconsistent image and
// std::runtime_error naming the file when it cannot be written.
void write_png(const std::filesystem::path& file, const Image& image);

// PNG or JPEG (by extension: .png, .jpg, .jpeg, any case), converted to 8-bit RGB (grey is
// replicated, alpha dropped, 16-bit samples reduced to their high byte). Throws std::runtime_error
// naming the file when it is missing, unreadable or of another type.
Image read_image(const std::filesystem::path& file);

// An OSMesa context (core profile 3.2 or later, RGBA, 24-bit depth, 8-bit stencil) rendering into
// a buffer it owns, and a vtkGenericOpenGLRenderWindow of the same size drawing through it. Made
// current on construction and again by every render. Several may exist (one per frame size, say)
// and may be created, resized and destroyed any number of times in one process.
class HeadlessContext {
 public:
  HeadlessContext(int width, int height);
  ~HeadlessContext();
  HeadlessContext(HeadlessContext&&) noexcept;
  HeadlessContext& operator=(HeadlessContext&&) noexcept;
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  int width() const;
  int height() const;
  // New pixel size for the buffer and the window; renderers already in the window stay.
  void resize(int width, int height);
  // Makes this context current on the calling thread (renders do it themselves).
  void make_current();

  // The vtkGenericOpenGLRenderWindow; valid while this context lives (keep no reference past it).
  vtkRenderWindow* window();
  // Renders the window's renderers and reads the pixels back: width() x height(), top row first.
  Image capture();
  // "OpenGL vendor/renderer/version" as the driver reports them (llvmpipe under OSMesa).
  std::string gl_info();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// --- 2D frames ---------------------------------------------------------------------------------

// table: the colours from low to high (empty: a blue-to-red ramp). log: logarithmic scale (min > 0).
struct ColorBar {
  bool show = true;
  std::string title;
  double min = 0, max = 1;
  bool log = false;
  std::vector<std::array<uint8_t, 3>> table;
};

struct Polyline2D {
  std::vector<std::array<double, 2>> points;  // model coordinates
  std::array<double, 3> colour{1, 1, 1};      // RGB in [0, 1]
  double width = 2;                           // pixels
};

struct Frame2D {
  Image field;  // pixels covering the model window [x0,x1] x [y0,y1] exactly (top row = y1)
  double x0 = 0, y0 = 0, x1 = 1, y1 = 1;
  std::array<double, 3> background{1, 1, 1};  // RGB in [0, 1]
  std::vector<Polyline2D> overlays;            // model coordinates
  std::string title, time_stamp;
  ColorBar colorbar;
  // Scale bar below the field (model coordinates in metres): a round length (1-2-5 steps) of at
  // most a fifth of the field's width, labelled with its unit ("10 mm").
  bool scale_bar = false;
  // Fonts are sized for a window this many pixels high (0: the window's own height), so that a
  // frame cropped to its bodies keeps the lettering of the size asked for.
  int text_size = 0;
};

// A rectangle of image pixels: x from the left, y from the top row.
struct PixelRect {
  int x = 0, y = 0, width = 0, height = 0;
};

// Where render_frame_2d puts the model window [x0,x1] x [y0,y1] in an image of width x height:
// the largest rectangle of the model window's aspect ratio that fits, with a small margin, left of
// the colour bar band (when shown), below the title band (when there is a title or time stamp)
// and above the scale bar band (when shown).
PixelRect frame_2d_field_viewport(int width, int height, const Frame2D& frame);

// The size of an image no larger than width x height that holds the frame's field viewport
// (as frame_2d_field_viewport gives it at width x height) and its bands with nothing to spare: the
// tight frame of a figure. {width, height} of that image.
std::array<int, 2> frame_2d_tight_size(int width, int height, const Frame2D& frame);

// Renders the frame at the context's size: the field image (nearest-pixel, unlit, so its colours
// come through exactly) fills frame_2d_field_viewport(); parallel projection in model units;
// overlays on top; title (centred) and time stamp (right) in the top band; colour bar (round ticks)
// on the right; scale bar below the field's left end.
Image render_frame_2d(HeadlessContext& context, const Frame2D& frame);

// --- 3D particles ------------------------------------------------------------------------------

// preset: "iso" (from azimuth 50 deg off +x towards +y, elevation 30 deg, z up, perspective), "xy" (from +z, y up), "xz" (from -y, z up),
// "yz" (from +x, z up); the axis views are parallel projections. explicit_view, when set, wins:
// {position xyz, focal point xyz, view-up xyz}, perspective.
struct Camera3D {
  std::string preset = "iso";
  std::optional<std::array<double, 9>> explicit_view;
};

// A crack face drawn over 3D particles: a triangle mesh (triangles index points) in one colour.
struct CrackFace3D {
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<std::size_t, 3>> triangles;
  std::array<double, 3> colour{0.9, 0.1, 0.1};  // RGB in [0, 1]
};
// Crack faces in drawing order: where two coincide, the earlier one shows. shaded: lit by the
// headlight (ambient 0.4, diffuse 0.6, smooth normals), so the shape of a face shows; otherwise
// flat, unlit colours.
struct CrackSurfaces3D {
  std::vector<CrackFace3D> faces;
  bool shaded = false;
};

// Particles as cubes of edge edge[i] centred at centres[i] with colour colours[i] (vtkGlyph3DMapper,
// lit by a headlight: faces square to the view show their colour exactly). Presets fit the camera to
// the particles. Title, time stamp and colour bar as in render_frame_2d. Throws
// std::invalid_argument when the three arrays differ in length or a preset is unknown.
// cracks: crack faces, drawn over the particles (always visible, as an overlay layer with the same
// camera; the faces hide each other by depth), so embedded cracks show through the body.
Image render_particles_3d(HeadlessContext& context, const std::vector<std::array<double, 3>>& centres,
                          const std::vector<double>& edge, const std::vector<std::array<uint8_t, 3>>& colours,
                          const Camera3D& camera, const std::string& title, const std::string& time_stamp,
                          const ColorBar& colorbar, std::array<double, 3> background,
                          const CrackSurfaces3D& cracks = {});

// --- plots -------------------------------------------------------------------------------------

struct PlotSeries {
  std::string name;
  std::vector<double> x, y;
  // How the series is drawn. The defaults draw what plots always drew: a solid line 2 pixels wide in
  // the palette colour of the series' place in the list, no markers.
  enum class Line { Solid, Dashed, None };
  Line line = Line::Solid;
  bool markers = false;  // a cross at each point
  // Text beside each point (empty, or one per point; an empty string draws nothing there).
  std::vector<std::string> point_labels = {};
  std::optional<std::array<unsigned char, 3>> colour = std::nullopt;  // default: plot_colour(its place)
};

// The plots' palette (matplotlib's tab10: blue, red, green, orange, purple, ...), cycling.
std::array<unsigned char, 3> plot_colour(std::size_t k);

// Where render_plot puts the legend, and the room around the data; the defaults draw plots as they
// always were.
enum class PlotLegend {
  Inside,  // over the plot's top-right corner
  Right,   // to the right of the axes: the plot narrows so that no curve runs under a long legend
};
struct PlotLayout {
  PlotLegend legend = PlotLegend::Inside;
  // Room around the data on each axis, a fraction of its span (0.05: matplotlib's margins), so that
  // points on the data's edge (markers, a constant reference) are not drawn on the frame; 0: VTK's
  // automatic range (the data's, rounded out to ticks).
  double margin = 0;
  // Logarithmic axes (decades); points with a value <= 0 on such an axis are left out.
  bool log_x = false, log_y = false;
};

// Line plot (vtkChartXY drawn through a vtkContextActor in the context's window), white background,
// one colour per series, legend when any series is named. A point with a non-finite x or y is left
// out and breaks the line there (a point left alone between such gaps is drawn as a cross; a series
// with no finite point draws nothing and is not in the legend). Throws std::invalid_argument when a
// series' x and y differ in length.
Image render_plot(HeadlessContext& context, const std::vector<PlotSeries>& series, const std::string& title,
                  const std::string& xlabel, const std::string& ylabel, const PlotLayout& layout = {});

}  // namespace cleave::viz
