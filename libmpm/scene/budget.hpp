// What a scene asks of the machine, checked before anything is allocated or written: step and
// frame counts (a long must hold them and a run must be able to finish), the points the bodies
// will hold, and the memory they need against what the machine has (core/resources.hpp). Each
// refusal is a SceneError naming the key that sets the figure, so `cleave check` shows it too.
#pragma once
#include <string>

#include "libmpm/core/run_settings.hpp"
#include "libmpm/geometry/shape.hpp"

namespace cleave::scene {

// The most steps a run may take (hours at a microsecond a step even for one point; a long holds
// 9.2e18) and the most frames it may write (one file per frame and series in one folder).
inline constexpr double kMaxSteps = 1e10, kMaxFrames = 1e6;

// SceneError at time.end when the run needs more than kMaxSteps steps, or a count no double holds.
void check_step_count(const RunSettings& s);
// SceneError at output.interval when the run would write more than kMaxFrames frames.
void check_frame_count(const RunSettings& s);

// The points a shape will hold on a lattice of `spacing` (per axis), before any is made: the
// lattice sites of its bounding box times the share of sample points (at most 32 per axis) inside.
template <int Dim>
double estimate_points(const geom::Shape<Dim>& shape, double spacing);

// Refuses a build needing more memory than the machine has available (core/resources.hpp), unless
// `cleave run --force`: SceneError at `key`, with both figures and `what` ("4e9 particles").
void check_memory(double bytes, const std::string& key, const std::string& what);

}  // namespace cleave::scene
