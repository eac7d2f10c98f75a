#include "libmpm/scene/budget.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "libmpm/core/error.hpp"
#include "libmpm/core/resources.hpp"
#include "libmpm/scene/sections.hpp"

namespace cleave::scene {

void check_step_count(const RunSettings& s) {
  const double steps = steps_to_end(s);
  if (!(steps <= kMaxSteps))  // also NaN and inf
    throw SceneError("time.end", "time.end = " + fmt(s.end_time) + " s at dt = " + fmt(s.dt) + " s needs " +
                                     fmt(steps) + " steps; at most " + fmt(kMaxSteps) +
                                     " can run (hours at a microsecond a step, even for one point)");
}

void check_frame_count(const RunSettings& s) {
  const double frames = records_to_end(s, s.output.interval);
  if (!(frames <= kMaxFrames))
    throw SceneError("output.interval", "output.interval = " + fmt(s.output.interval) + " s writes " + fmt(frames) +
                                            " frames (one file per frame and series); at most " + fmt(kMaxFrames));
}

template <int Dim>
double estimate_points(const geom::Shape<Dim>& shape, double spacing) {
  const auto b = shape.bounds();
  if (b.empty()) return 0.0;
  double sites = 1.0;
  std::array<int, Dim> n;
  for (int d = 0; d < Dim; ++d) {
    const double k = std::max(1.0, std::ceil((b.hi[d] - b.lo[d]) / spacing));
    sites *= k;
    n[d] = static_cast<int>(std::min(k, 32.0));
  }
  long inside = 0, total = 0;
  std::array<int, Dim> q{};
  while (true) {
    Vec<Dim> x;
    for (int d = 0; d < Dim; ++d) x[d] = b.lo[d] + (b.hi[d] - b.lo[d]) * (q[d] + 0.5) / n[d];
    inside += shape.contains(x);
    ++total;
    int d = 0;
    while (d < Dim && ++q[d] == n[d]) q[d++] = 0;
    if (d == Dim) break;
  }
  return sites * double(inside) / double(total);
}

void check_memory(double bytes, const std::string& key, const std::string& what) {
  if (resource_checks_forced()) return;
  const double avail = available_memory_bytes();
  if (bytes > avail)
    throw SceneError(key, "needs about " + format_bytes(bytes) + " of memory (" + what + "), more than the " +
                              format_bytes(avail) + " this machine has available; use a coarser " + key +
                              " (or cleave run --force to try anyway)");
}

template double estimate_points<2>(const geom::Shape<2>&, double);
template double estimate_points<3>(const geom::Shape<3>&, double);

}  // namespace cleave::scene
