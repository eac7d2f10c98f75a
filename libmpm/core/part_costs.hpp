// What each part of a run costs in wall time: the step itself, MPM's crack fields and contact, J/K,
// peridynamics' tip tracking, output. `cleave run` prints it as shares of the wall time and run.json
// records it ("costs"), so that a user sees what each feature the scene switched on costs them.
//
// The run loop makes a Ledger active on its thread for the run (Activate); a Scope anywhere below
// it, in serial code, charges the time until it ends to its part instead of the enclosing one.
// Scopes nest exclusively: J/K evaluated inside a frame write is J/K, not output. Time no scope
// claims is the step's. A scope is two clock reads, so it goes around a pass, never inside a
// parallel region (a worker thread has no active ledger, and the scope does nothing there); the
// clock reads change no arithmetic of the run. Without an active ledger (a benchmark stepping a
// model directly) a Scope does nothing.
//
// The ledger sums integer clock ticks, so the parts add up to the wall time exactly (up to the
// rounding of each to seconds).
#pragma once
#include <array>
#include <chrono>

namespace cleave::costs {

enum Part : int {
  Step,           // the step itself: all that no other part claims
  CrackFields,    // MPM: crack index, near list, classification, field slots, extra fields, crack motion
  Contact,        // MPM: crack contact
  TipParameters,  // MPM: J and K at crack tips and fronts
  TipTracking,    // peridynamics: finding the tracked tips in the damage field
  CrackGrowth,    // MPM: growth checks (J and K at the growing tips) and the new crack segments
  Output,         // frames, CSV rows, checkpoints, run.json, the progress line
  kParts
};

// As printed in the `cost:` line.
inline const char* name(int part) {
  static const char* names[kParts] = {"step", "crack fields", "contact", "J/K", "tip tracking", "crack growth", "output"};
  return names[part];
}
// As keyed in run.json's "costs"."parts".
inline const char* key(int part) {
  static const char* keys[kParts] = {"step", "crack_fields", "contact", "J_K", "tip_tracking", "crack_growth", "output"};
  return keys[part];
}

// A run's parts: seconds and scopes entered per part, and the wall time they share.
struct Totals {
  double wall_s = 0.0;
  std::array<double, kParts> seconds{};
  std::array<long, kParts> calls{};
  // Whether the run switched the part on: the step and output always, any other once entered.
  bool on(int part) const { return part == Step || part == Output || calls[part] > 0; }
};

class Ledger {
 public:
  using clock = std::chrono::steady_clock;
  Ledger() : start_(clock::now()), since_(start_) {}

  // Makes `part` current (the time since the last switch goes to the part that was); returns the
  // part it replaced, for leave().
  int enter(int part) {
    ++calls_[part];
    return switch_to(part);
  }
  void leave(int previous) { switch_to(previous); }

  // Up to now.
  Totals totals() const {
    const clock::time_point now = clock::now();
    auto spent = spent_;
    spent[current_] += now - since_;
    Totals t;
    t.wall_s = seconds(now - start_);
    for (int p = 0; p < kParts; ++p) t.seconds[p] = seconds(spent[p]);
    t.calls = calls_;
    return t;
  }

 private:
  static double seconds(clock::duration d) { return std::chrono::duration<double>(d).count(); }
  int switch_to(int part) {
    const clock::time_point now = clock::now();
    spent_[current_] += now - since_;
    since_ = now;
    const int was = current_;
    current_ = part;
    return was;
  }

  clock::time_point start_, since_;
  std::array<clock::duration, kParts> spent_{};
  std::array<long, kParts> calls_{};
  int current_ = Step;
};

// The ledger of the run going on this thread (null outside a run, and on worker threads).
inline thread_local Ledger* active = nullptr;

// Makes `l` the thread's active ledger for its lifetime.
class Activate {
 public:
  explicit Activate(Ledger& l) : was_(active) { active = &l; }
  ~Activate() { active = was_; }
  Activate(const Activate&) = delete;
  Activate& operator=(const Activate&) = delete;

 private:
  Ledger* was_;
};

// The same as a Scope, as two calls compiled out of line (part_costs.cpp), with nothing to destroy,
// for code whose machine code must stay as it was: in the MPM crack fields (crack_fields.hpp), a
// Scope's inlined clock reads and unwinding path changed what GCC inlines elsewhere in the
// translation unit, and with it which multiplies it fuses into adds and the last bits of the
// results. enter() returns what leave() takes.
int enter(int part) noexcept;
void leave(int was) noexcept;

// Charges the time until its end to `part` (serial code only, see above).
class Scope {
 public:
  explicit Scope(int part) : l_(active) {
    if (l_) was_ = l_->enter(part);
  }
  ~Scope() {
    if (l_) l_->leave(was_);
  }
  Scope(const Scope&) = delete;
  Scope& operator=(const Scope&) = delete;

 private:
  Ledger* l_;
  int was_ = Step;
};

}  // namespace cleave::costs
