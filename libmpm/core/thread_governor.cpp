#include "libmpm/core/thread_governor.hpp"

#include <omp.h>
#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <fstream>
#include <sstream>
#include <string>

namespace cleave {

CpuSample sample_cpu() {
  CpuSample s;
  s.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  timespec ts{};
  if (clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts) != 0) return s;
  s.own_cpu_s = double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
  std::ifstream in("/proc/stat");
  std::string line;
  if (!std::getline(in, line) || line.rfind("cpu ", 0) != 0) return s;
  // user nice system idle iowait irq softirq steal: busy = all but idle and iowait (steal too: a
  // core the hypervisor gives to another machine is not ours either).
  std::istringstream ls(line.substr(4));
  double f[8] = {};
  for (double& v : f)
    if (!(ls >> v)) return s;
  const double tick = double(sysconf(_SC_CLK_TCK));
  if (!(tick > 0)) return s;
  s.machine_busy_s = (f[0] + f[1] + f[2] + f[5] + f[6] + f[7]) / tick;
  cpu_set_t set;
  const long online = sysconf(_SC_NPROCESSORS_ONLN);
  s.cores = sched_getaffinity(0, sizeof set, &set) == 0 ? CPU_COUNT(&set) : int(online);
  // Other processes on cores outside the affinity mask do not take ours: counted against the
  // machine's cores, their load is spread over all of them (an approximation; exact when the mask
  // is the whole machine, the usual case).
  if (online > s.cores && online > 0) s.machine_busy_s *= double(s.cores) / double(online);
  s.ok = s.cores > 0;
  return s;
}

ThreadGovernor::ThreadGovernor(int max_threads, double interval_s, Sampler sampler)
    : max_threads_(std::max(1, max_threads)),
      threads_(max_threads_),
      interval_s_(interval_s),
      sampler_(std::move(sampler)),
      last_(sampler_ ? sampler_() : CpuSample{}) {}

int ThreadGovernor::choose(int max_threads, int cores, double other) {
  const double free = double(cores) - std::max(0.0, other);
  return std::clamp(static_cast<int>(std::floor(free + 0.3)), 1, std::max(1, max_threads));
}

int ThreadGovernor::poll(bool set_omp) {
  if (max_threads_ <= 1 || !sampler_ || !last_.ok) return 0;
  const double now =
      std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  if (now - last_.wall_s < interval_s_) return 0;
  const CpuSample s = sampler_();
  if (!s.ok || !(s.wall_s > last_.wall_s)) return 0;
  const double dt = s.wall_s - last_.wall_s;
  other_ = std::max(0.0, (s.machine_busy_s - last_.machine_busy_s) - (s.own_cpu_s - last_.own_cpu_s)) / dt;
  last_ = s;
  const int n = choose(max_threads_, s.cores, other_);
  if (n == threads_) return 0;
  threads_ = n;
  if (set_omp) omp_set_num_threads(n);
  return n;
}

}  // namespace cleave
