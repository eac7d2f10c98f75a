// Round numbers for figures: colour-bar ticks in 1-2-5 steps, the length of a scale bar, and how
// both are written. Pure functions (no VTK), so the choices are tested without rendering.
#pragma once
#include <string>
#include <vector>

namespace cleave::viz {

// Tick values in [lo, hi] (either order) on a 1-2-5 step (1, 2 or 5 times a power of ten): the
// step whose number of ticks is nearest 5 (more ticks on a tie), at least 3 and at most max_ticks
// (>= 3); the range's ends when no such step exists. Values within 1e-9 of a step of zero are
// exactly 0. Empty for a non-finite or empty range.
std::vector<double> nice_ticks(double lo, double hi, int max_ticks = 7);

// Ticks for a logarithmic scale over [lo, hi] (0 < lo < hi): the powers of ten inside, with 2 and 5
// times them added while fewer than 3 ticks fall inside. Empty when lo <= 0 or the range is empty.
std::vector<double> log_ticks(double lo, double hi);

// A tick label: the shortest "%g"-style text that shows `v` to the step's precision ("0.05",
// "120", "1e+04"); never "-0".
std::string format_tick(double v, double step);

// A scale bar: `length` (m) is the largest 1-2-5 length that spans at most `max_pixels` pixels at
// `metres_per_pixel`, and `label` writes it in the unit that keeps the number between 1 and 500
// ("10 mm", "500 µm", "2 m"; UTF-8 µ). length 0 and an empty label for bad arguments.
struct ScaleBar {
  double length = 0;
  std::string label;
};
ScaleBar nice_scale_bar(double metres_per_pixel, double max_pixels);

}  // namespace cleave::viz
