// Fewer OpenMP threads while other processes hold cores. Measured (issue 15, docs/performance.md
// "Threads on a busy machine"): with one of two cores held by another process, two threads ran a
// step 0.70x as fast as one (libgomp's spin-waits at every barrier share the held core), and a
// passive wait policy only brought that to 0.97x while costing 12 % on an idle machine. So the run
// keeps its spin-waits and, between steps, about every second, measures the cores that other
// processes kept busy (/proc/stat less this process's CPU time) and uses only the cores left.
// Results do not depend on the thread count (bit-identical), so changing it mid-run changes no
// number.
#pragma once
#include <functional>

namespace cleave {

// What poll() reads: wall time, the CPU time every core of the machine spent busy, this process's
// CPU time (all its threads), all in seconds, and the machine's cores. ok: false when unreadable.
struct CpuSample {
  double wall_s = 0.0, machine_busy_s = 0.0, own_cpu_s = 0.0;
  int cores = 0;
  bool ok = false;
};
CpuSample sample_cpu();  // /proc/stat, CLOCK_PROCESS_CPUTIME_ID, the affinity mask

class ThreadGovernor {
 public:
  using Sampler = std::function<CpuSample()>;
  // max_threads: the most it will use (OMP_NUM_THREADS or the cores, as OpenMP starts).
  explicit ThreadGovernor(int max_threads, double interval_s = 1.0, Sampler sampler = sample_cpu);

  // Between steps: when interval_s has passed since the last measurement, measures again and sets
  // the thread count (omp_set_num_threads when set_omp). Returns the new count when it changed,
  // else 0.
  int poll(bool set_omp = true);
  int threads() const { return threads_; }
  double other_cores() const { return other_; }  // cores other processes kept busy, last measured

  // The threads to use with `other` cores of `cores` kept busy by other processes: the whole cores
  // left (a core more than 70 % free counts), 1 .. max_threads.
  static int choose(int max_threads, int cores, double other);

 private:
  int max_threads_, threads_;
  double interval_s_, other_ = 0.0;
  Sampler sampler_;
  CpuSample last_;
};

}  // namespace cleave
