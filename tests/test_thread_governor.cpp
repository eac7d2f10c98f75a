// The thread governor (core/thread_governor.hpp): how many threads a run uses while other processes
// hold cores. Its decisions are tested on given CPU samples (no timing: a loaded CI machine must not
// change an outcome); that the thread count leaves results unchanged is test_determinism's.
#include <gtest/gtest.h>

#include <vector>

#include "libmpm/core/thread_governor.hpp"

using cleave::CpuSample;
using cleave::ThreadGovernor;

TEST(ThreadGovernor, UsesTheWholeCoresOtherProcessesLeave) {
  EXPECT_EQ(ThreadGovernor::choose(2, 2, 0.0), 2);
  EXPECT_EQ(ThreadGovernor::choose(2, 2, 0.2), 2);   // a little background work: still both cores
  EXPECT_EQ(ThreadGovernor::choose(2, 2, 0.5), 1);   // half a core taken: a barrier would wait on it
  EXPECT_EQ(ThreadGovernor::choose(2, 2, 1.0), 1);   // the case measured in docs/performance.md
  EXPECT_EQ(ThreadGovernor::choose(2, 2, 3.0), 1);   // never fewer than one
  EXPECT_EQ(ThreadGovernor::choose(16, 16, 4.0), 12);
  EXPECT_EQ(ThreadGovernor::choose(4, 16, 0.0), 4);  // never more than asked for
  EXPECT_EQ(ThreadGovernor::choose(2, 2, -1.0), 2);  // a negative reading (counter skew) is none
}

// A two-core machine, this run keeping `own` cores busy and other processes `other`, sampled once a
// second.
struct FakeMachine {
  double t = 0, busy = 0, cpu = 0;
  std::vector<CpuSample> samples;
  void advance(double own, double other) {
    t += 1.0, busy += own + other, cpu += own;
    samples.push_back({t, busy, cpu, 2, true});
  }
};

TEST(ThreadGovernor, DropsToOneThreadWhileAnotherProcessHoldsACoreAndComesBackAfter) {
  FakeMachine m;
  m.samples.push_back({0, 0, 0, 2, true});
  m.advance(2.0, 0.0);   // idle machine: both threads
  m.advance(1.0, 1.0);   // another process takes a core (our threads get one core between them)
  m.advance(1.0, 1.0);   // still there (we now run one thread)
  m.advance(1.0, 0.0);   // gone
  std::size_t next = 0;
  ThreadGovernor g(2, 0.0, [&] { return m.samples[next++]; });
  EXPECT_EQ(g.poll(false), 0);  // unchanged: 2
  EXPECT_EQ(g.threads(), 2);
  EXPECT_EQ(g.poll(false), 1);
  EXPECT_DOUBLE_EQ(g.other_cores(), 1.0);
  EXPECT_EQ(g.poll(false), 0);  // unchanged: 1
  EXPECT_EQ(g.poll(false), 2);
  EXPECT_EQ(g.threads(), 2);
}

TEST(ThreadGovernor, DoesNothingWithOneThreadOrWithoutReadings) {
  int calls = 0;
  ThreadGovernor one(1, 0.0, [&] {
    ++calls;
    return CpuSample{double(calls), 0, 0, 2, true};
  });
  EXPECT_EQ(one.poll(false), 0);
  EXPECT_EQ(one.threads(), 1);
  ThreadGovernor unreadable(2, 0.0, [] { return CpuSample{}; });  // no /proc/stat: ok = false
  EXPECT_EQ(unreadable.poll(false), 0);
  EXPECT_EQ(unreadable.threads(), 2);
}

TEST(ThreadGovernor, ReadsThisMachinesCounters) {
  const CpuSample s = cleave::sample_cpu();
  if (!s.ok) GTEST_SKIP() << "no /proc/stat here";
  EXPECT_GE(s.cores, 1);
  EXPECT_GE(s.machine_busy_s, 0.0);
  EXPECT_GE(s.own_cpu_s, 0.0);
}
