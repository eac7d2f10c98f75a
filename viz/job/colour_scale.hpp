// How values and times are shown: display units and the quantity's name for a colour bar, the
// colour of a value, and the time stamp of a frame.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "viz/optics/colormap.hpp"
#include "viz/render/headless.hpp"

namespace cleave::viz {

struct RenderOptions;

std::array<uint8_t, 3> to_rgb8(const std::array<double, 3>& c);

// "t = 30.0 µs" (UTF-8 µ) below 1 ms, "t = 1.2345 ms" below 1 s, then seconds.
std::string format_time(double t);

// Display units of a field Cleave writes ("MPa" for stresses, "mm" for displacements, "m/s" for
// velocities, "" otherwise) and the factor from SI to them.
std::string field_units(const std::string& field);
double field_scale(const std::string& units);

// The colour bar's title: the quantity's name and unit, "von Mises stress (MPa)",
// "normal stress xx (MPa)", "speed (m/s)"; names Cleave does not know as they are ("mass").
std::string field_label(const std::string& field);

// Maps a field's values (SI) to colours: display units, automatic range (symmetric about zero with
// a diverging map for signed fields) or the fixed --range, log scale, colour map; fills the bar.
class ColourScale {
 public:
  ColourScale(const RenderOptions& o, const std::vector<double>& values, ColorBar& bar);
  std::array<uint8_t, 3> operator()(double v_si) const;

 private:
  bool log_;
  double scale_ = 1, lo_ = 0, hi_ = 1;
  ColorMapKind map_ = ColorMapKind::Viridis;
};

}  // namespace cleave::viz
