// Growing 2D cracks (issue 18; seed 000's closing aim, NairnMPM's explicit-crack propagation): at a
// growth check, every tip of a crack with "propagation" asks its initiation criterion with the J
// and K of the current state and the toughness of the material at the tip; where it holds, the
// tip advances by the growth length in the direction its rule gives, as one new segment whose
// faces start together (no opening). Stops: a tip whose ligament ahead is under a cell is carried
// through the free edge (an edge crack, its end a mouth, as the scene reader does with an end near
// an edge); a tip that would meet a crack within a cell joins it there and stops; a tip whose next
// point would leave the grid's inner cells stops with a warning. The growth repeats at later checks
// while the criterion holds, capped at the optional speed. Every event is a row of crack_growth.csv.
//
// The state (crack points, tip flags, grown lengths, last growth times) is restart state, so a
// resumed run grows the same path bit for bit; nothing here depends on the thread count.
#pragma once
#include <string>
#include <vector>

#include "libmpm/crack/propagation.hpp"
#include "libmpm/crack/tip_parameters.hpp"
#include "libmpm/method/state_io.hpp"
#include "libmpm/mpm/model.hpp"

namespace cleave {

// Why a tip stopped growing (crack_growth.csv's "stop" column).
enum class GrowthStop { None = 0, FreeEdge = 1, OtherCrack = 2, GridEdge = 3 };

// One growth event: a row of crack_growth.csv.
struct GrowthEvent {
  double time = 0.0;
  int crack = 0, tip = 0;
  Vec<2> to = Vec<2>::Zero();   // the tip after the growth
  double length = 0.0;          // the advance, m
  double speed = 0.0;           // over the tip's last 4 cells of growth (kSpeedCells; 0 on its first)
  double angle = 0.0;           // the kink from the tip's previous direction, rad
  double J = 0.0, KI = 0.0, KII = 0.0, ratio = 0.0;  // what the criterion saw; ratio >= 1
  GrowthStop stop = GrowthStop::None;
};

class CrackGrowth {
 public:
  // m.propagation says which cracks grow (none: inactive).
  explicit CrackGrowth(Model<2>& m);
  bool active() const { return active_; }
  // Is a check due after step `step` at `time`: a crack's check_interval divides the step, and one of
  // its tips may grow now (the speed cap lets it; a tip that grew less than growth_length / cap ago
  // cannot, so J is not evaluated for it: a running tip is checked every few steps, not every step)?
  bool due(long step, double time) const;
  // Grows the tips whose criterion holds in the state of `tips` (J and K at every tip now); returns
  // whether a crack changed. Warnings (a tip that stopped at the grid's edge) go to `warnings`.
  bool grow(double time, long step, const std::vector<crack::TipRecord>& tips, std::vector<std::string>& warnings);
  // The events since the last call, in order.
  std::vector<GrowthEvent> take_events();
  static std::vector<std::string> columns();
  static std::vector<double> row(const GrowthEvent& e);

  // Restart state: the cracks' points and faces (their counts change as they grow), tip flags, grown
  // lengths and last growth times.
  void save(StateWriter& w) const;
  void load(StateReader& r);

 private:
  // A tip's speed is taken over its last 4 cells of growth, the J contour's diameter at its default
  // radius: a tip grows a step at a time, as soon as J reaches G_c again, so the time between two
  // steps measures the check's cadence more than the speed (one step later read 7 km/s in steel).
  static constexpr double kSpeedCells = 4.0;
  static constexpr int kHistory = 41;  // growths kept: 4 cells at the shortest growth length, 0.1 cell
  struct TipState {
    double grown = 0.0;       // m, for the resistance curve
    double last_time = -1.0;  // of the last growth; < 0 before the first
    double wait = 0.0;        // s after the last growth before the next may come (the speed cap)
    // The last kHistory growths: time and total grown length after each (a ring, newest at
    // (count - 1) % kHistory).
    double t[kHistory] = {}, s[kHistory] = {};
    long count = 0;
  };
  Model<2>& m_;
  bool active_ = false;
  std::vector<TipState> state_;  // crack * 2 + end
  std::vector<GrowthEvent> events_;
  std::vector<double> half_size_;  // half each particle's spacing (from its area), for the ligament
};

}  // namespace cleave
