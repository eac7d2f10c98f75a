#include "apps/cleave/progress.hpp"

#include <unistd.h>

#include <cstdio>
#include <string>

namespace cleave::app {

std::string format_seconds(double s) {
  char b[64];
  if (s < 60) std::snprintf(b, sizeof b, "%.1f s", s);
  else if (s < 3600) std::snprintf(b, sizeof b, "%dm%02ds", int(s) / 60, int(s) % 60);
  else std::snprintf(b, sizeof b, "%dh%02dm", int(s) / 3600, (int(s) % 3600) / 60);
  return b;
}

ProgressPrinter::ProgressPrinter() : tty_(isatty(fileno(stderr))) {}

void ProgressPrinter::operator()(const RunProgress& p) {
  const double pct = 100.0 * p.time / p.end_time;
  std::fprintf(stderr, "%sstep %ld  t = %.4g / %.4g s (%.1f%%)  wall %s  ETA %s%s", tty_ ? "\r\033[K" : "", p.step,
               p.time, p.end_time, pct, format_seconds(p.wall_s).c_str(), format_seconds(p.eta_s).c_str(),
               tty_ ? "" : "\n");
  std::fflush(stderr);
  dirty_ = tty_;
}

void ProgressPrinter::finish() {
  if (dirty_) std::fprintf(stderr, "\n");
  dirty_ = false;
}

}  // namespace cleave::app
