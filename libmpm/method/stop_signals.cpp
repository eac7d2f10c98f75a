#include "libmpm/method/stop_signals.hpp"

#include <csignal>
#include <mutex>

namespace cleave {
namespace {

volatile std::sig_atomic_t g_signal = 0;

extern "C" void record_stop(int sig) {
  if (g_signal == 0) g_signal = sig;
}

std::mutex g_mutex;
int g_users = 0;
struct sigaction g_old_int, g_old_term, g_old_xfsz;

}  // namespace

StopSignals::StopSignals() {
  std::lock_guard<std::mutex> lock(g_mutex);
  if (g_users++ > 0) return;
  g_signal = 0;
  struct sigaction sa = {};
  sa.sa_handler = record_stop;
  sigemptyset(&sa.sa_mask);
  // SA_RESTART: a write interrupted by the signal goes on; SA_RESETHAND: a second signal kills.
  sa.sa_flags = SA_RESTART | SA_RESETHAND;
  sigaction(SIGINT, &sa, &g_old_int);
  sigaction(SIGTERM, &sa, &g_old_term);
  struct sigaction ignore = {};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  sigaction(SIGXFSZ, &ignore, &g_old_xfsz);
}

StopSignals::~StopSignals() {
  std::lock_guard<std::mutex> lock(g_mutex);
  if (--g_users > 0) return;
  sigaction(SIGINT, &g_old_int, nullptr);
  sigaction(SIGTERM, &g_old_term, nullptr);
  sigaction(SIGXFSZ, &g_old_xfsz, nullptr);
}

int stop_requested() { return g_signal; }

const char* signal_name(int sig) {
  switch (sig) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    default: return "a signal";
  }
}

}  // namespace cleave
