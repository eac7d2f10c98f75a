// Optional wall-clock timers of the MPM step's tasks, to see where a step's time goes (the crack
// overhead study in docs/performance.md). Compiled in only with -DCLEAVE_STEP_TIMERS=ON; otherwise
// CLEAVE_TIME expands to nothing and the stepper carries no timing code.
#pragma once
#ifdef CLEAVE_STEP_TIMERS
#include <omp.h>
#endif

namespace cleave::step_timers {

// The step's parts, in the order a step runs them.
enum Slot {
  CrackIndex,      // spatial index of the crack segments
  Strips,          // strip order, with the near-crack flags when cracks exist
  NearList,        // near-particle list (when a flag changed)
  Classify,        // particle-node line crossing of the near particles
  Allocate,        // extra-field slots
  Task1,           // nodal masses and momenta
  Contact,         // crack contact (Tasks 2 and 6c)
  Stress,          // stress update (Tasks 2 / 6) and internal force (Task 3)
  Forces,          // tractions, body force, damping, prescribed components
  Task4,           // nodal momenta, velocities and accelerations
  Task5,           // particle velocities and positions (and Task 6c momenta)
  Conditions,      // momentum conditions and nodal velocities
  CrackMotion,     // Task 7
  kSlots
};

inline const char* name(int s) {
  static const char* names[kSlots] = {"crack index", "strip order", "near list", "classification",
                                      "field slots", "task 1",      "contact",   "stresses",
                                      "grid forces", "task 4",      "task 5",    "conditions",
                                      "crack motion"};
  return names[s];
}

#ifdef CLEAVE_STEP_TIMERS
inline constexpr bool kEnabled = true;
inline double seconds[kSlots];
inline void reset() {
  for (double& s : seconds) s = 0.0;
}
struct Scope {
  int slot;
  double t0;
  explicit Scope(int s) : slot(s), t0(omp_get_wtime()) {}
  ~Scope() { seconds[slot] += omp_get_wtime() - t0; }
};
#define CLEAVE_TIME_CAT2(a, b) a##b
#define CLEAVE_TIME_CAT(a, b) CLEAVE_TIME_CAT2(a, b)
#define CLEAVE_TIME(slot) ::cleave::step_timers::Scope CLEAVE_TIME_CAT(cleave_timer_, __LINE__)(::cleave::step_timers::slot)
#else
inline constexpr bool kEnabled = false;
inline double seconds[kSlots];
inline void reset() {}
#define CLEAVE_TIME(slot) \
  do {                    \
  } while (0)
#endif

}  // namespace cleave::step_timers
