// K from fringes against a run (cleave fit): the model's fringe orders at given points, a crack tip
// as the run left it, points sampled from a frame (to check the fit on a known K), and calibration
// of the fringe constant or the load scale to measured points. The fit itself: viz/fit/fringe_fit.hpp.
#pragma once
#include <filesystem>
#include <optional>
#include <vector>

#include "viz/fit/fringe_fit.hpp"
#include "viz/job/render_job.hpp"

namespace cleave::viz {

// s1 - s2 (Pa) of a (drawn) 2D frame at each point; NaN where the point is off the bodies.
std::vector<double> stress_difference_at(const ParticleFrame&, const std::vector<FringePoint>& pts);

// A crack tip of a 2D run at the crack_tips.csv row nearest time t: its position, the crack's
// direction there (from the crack frame nearest t: the path's end segment of at least 1 mm or two
// segments, pointing out of the crack) and the K the run computed. Throws std::runtime_error naming
// the file when the run has no such crack or tip.
struct RunTip {
  double time = 0, x = 0, y = 0, alpha = 0, KI = 0, KII = 0;
};
RunTip run_tip(const std::filesystem::path& dir, double t, int crack, int tip);

// The model's own fringe orders at points of a polar grid round the tip (radii r0..r1, `rings`
// of them, every `step` radians off the crack faces by at least step/2), those on the bodies.
std::vector<FringePoint> sampled_points(const ParticleFrame&, const PhotoelasticSettings&, double x0, double y0, double alpha,
                                        double r0, double r1, int rings = 9, double step = 10 * 3.14159265358979 / 180);

// Least-squares scale c with N_measured ~ c N_model over the points on the bodies (N_model from the
// frame with the settings' fringe constant): the fringe constant that fits is f_sigma / c, the load
// scale that fits is c. Its standard error, the RMS residual before and after, and the points used.
struct Calibration {
  double scale = 1, std_error = 0, rms_before = 0, rms_after = 0;
  std::size_t points = 0;
};
Calibration calibrate_scale(const ParticleFrame&, const PhotoelasticSettings&, const std::vector<FringePoint>& pts);

}  // namespace cleave::viz
