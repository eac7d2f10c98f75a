// Pieces shared by the pictures of viz/render (2D frames, 3D particles, plots): not part of the
// renderer's interface (viz/render/headless.hpp is). The layout of the bands around a picture
// (title and time stamp on top, colour bar on the right, scale bar below) and the VTK actors
// that draw them.
#pragma once

#include "viz/render/headless.hpp"

#include <vtkRenderer.h>
#include <vtkSmartPointer.h>

#include <array>
#include <string>
#include <vector>

class vtkImageData;
class vtkTextProperty;

namespace cleave::viz::detail {

// Throws std::invalid_argument unless the image holds 3 bytes per pixel.
void check_image(const Image& image, const char* what);
// Image (top row first) -> vtkImageData (row 0 at the bottom), 3 unsigned chars per point.
vtkSmartPointer<vtkImageData> to_vtk(const Image& image);
// Near-black text on light backgrounds, near-white on dark ones.
std::array<double, 3> text_colour_on(const std::array<double, 3>& background);
void configure_text(vtkTextProperty* p, int size, const std::array<double, 3>& colour);
void set_viewport_pixels(vtkRenderer* ren, int W, int H, int x, int y_bottom, int w, int h);

// Pixel layout of a picture. Fonts scale with `text_size` (the height the fonts are made for:
// the window's height unless a caller fixes it, so that a frame cropped to its bodies keeps the
// lettering of the size asked for), the margin with the fonts.
struct Layout {
  int width = 0, height = 0;
  int margin = 0;
  int title_font = 0, label_font = 0;
  int title_band = 0;   // pixels at the top (title, time stamp)
  int cbar_band = 0;    // pixels at the right (colour bar)
  int bottom_band = 0;  // pixels at the bottom (scale bar)
  int bar_width = 0, label_width = 0, cbar_title_width = 0;
};
Layout make_layout(int width, int height, bool title_band, const ColorBar& cb, int text_size = 0,
                   bool bottom_band = false);
bool has_title_band(const std::string& title, const std::string& time_stamp);

// The colour bar's tick values: round 1-2-5 steps inside [min, max] (decades on a log scale).
std::vector<double> colour_bar_ticks(const ColorBar& cb);

// Adds renderers to the context's window for one picture and takes them out again afterwards, with
// the context current, so their GL resources are freed in the right context.
class Scene {
 public:
  explicit Scene(HeadlessContext& context);
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;
  // layer 0 renderers clear their viewport to the background; layer 1 draws over everything.
  vtkRenderer* add(int layer, const std::array<double, 3>& background);

 private:
  HeadlessContext& context_;
  std::vector<vtkSmartPointer<vtkRenderer>> renderers_;
};

// Title (centred) and time stamp (right) in the top band, colour bar in the right band, all in the
// full-window overlay renderer `ren`.
void add_annotations(vtkRenderer* ren, const Layout& l, const std::string& title, const std::string& time_stamp,
                     const ColorBar& cb, const std::array<double, 3>& background);

// A scale bar in the bottom band, starting at pixel column x0 (from the left): a bar `pixels` long
// and its label to its right.
void add_scale_bar(vtkRenderer* ren, const Layout& l, int x0, double pixels, const std::string& label,
                   const std::array<double, 3>& background);

}  // namespace cleave::viz::detail
