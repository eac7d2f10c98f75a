#include "apps/cleave/progress.hpp"

#include <unistd.h>

#include <algorithm>
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

std::string summary_line(const RunSummary& s, double work, const std::string& unit, int threads,
                         const std::string& out) {
  char b[2048];
  const long steps = s.steps - s.first_step;  // this invocation's part
  if (s.resumed && steps == 0) {
    std::snprintf(b, sizeof b, "done: nothing to do: the run in %s was already complete at step %ld (t = %.6g s)",
                  out.c_str(), s.steps, s.time);
    return b;
  }
  const double ns = 1e9 * s.wall_s / std::max(1.0, double(steps) * work);
  char part[96];
  if (s.resumed) std::snprintf(part, sizeof part, "resumed at step %ld, %ld more steps", s.first_step, steps);
  else std::snprintf(part, sizeof part, "%ld steps", steps);
  std::snprintf(b, sizeof b, "done: %s to t = %.6g s, %.0f %ss, %d frames, %s wall (%.*f ns/%s-step, %d threads); output in %s",
                part, s.time, work, unit.c_str(), s.frames, format_seconds(s.wall_s).c_str(), ns < 10 ? 2 : 0, ns,
                unit.c_str(), threads, out.c_str());
  return b;
}

std::string cost_line(const costs::Totals& t) {
  std::string line = "cost:";
  char b[96];
  const char* sep = " ";
  for (int p = 0; p < costs::kParts; ++p) {
    if (!t.on(p)) continue;
    std::snprintf(b, sizeof b, "%s%s %.1f %%", sep, costs::name(p), t.wall_s > 0 ? 100.0 * t.seconds[p] / t.wall_s : 0.0);
    line += b;
    sep = ", ";
  }
  return line + " of " + format_seconds(t.wall_s) + " wall";
}

std::string shell_command(const std::vector<std::string>& args, bool with_resume) {
  std::string cmd;
  auto add = [&](const std::string& a) {
    const bool plain = !a.empty() && a.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                         "0123456789_./=:,+-@%") == std::string::npos;
    if (!cmd.empty()) cmd += ' ';
    if (plain) {
      cmd += a;
      return;
    }
    cmd += '\'';
    for (char c : a) cmd += c == '\'' ? std::string("'\\''") : std::string(1, c);
    cmd += '\'';
  };
  for (const auto& a : args) add(a);
  if (with_resume && std::find(args.begin(), args.end(), "--resume") == args.end()) add("--resume");
  return cmd;
}

}  // namespace cleave::app
