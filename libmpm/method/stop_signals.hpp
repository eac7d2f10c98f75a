// SIGINT and SIGTERM during a run: the handler only records the signal (the one async-signal-safe
// thing to do); the run loop looks at it after each step, finishes that step, writes a checkpoint
// there and stops (RunStopped). A second signal of either kind gets the default action (the
// process dies at once: the checkpoint of the last frame is still there). SIGXFSZ is ignored
// while a run goes, so that a write past `ulimit -f` fails with EFBIG and is reported like a full
// disk instead of killing the process.
#pragma once

namespace cleave {

// Installs the handlers for its lifetime. Nested or concurrent guards share one installation:
// the first installs (and clears any recorded signal), the last restores the earlier handlers.
class StopSignals {
 public:
  StopSignals();
  ~StopSignals();
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;
};

// The signal that asked the run to stop (SIGINT or SIGTERM), 0 if none.
int stop_requested();

// "SIGINT", "SIGTERM", or "a signal" for any other.
const char* signal_name(int sig);

}  // namespace cleave
