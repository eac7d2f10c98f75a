// One MPM time step as the named tasks of seed 002, Appendix A (single velocity field; the crack
// module adds fields). Templated on the dimension and the shape function: one code path for 2D/3D.
#pragma once
#include <memory>
#include <string>

#include <vector>

#include "libmpm/crack/front_parameters.hpp"
#include "libmpm/crack/tip_parameters.hpp"
#include "libmpm/method/method.hpp"  // StepProblem
#include "libmpm/mpm/model.hpp"

namespace cleave {

// Global quantities for global.csv and the run's sanity checks.
template <int Dim>
struct GlobalState {
  double time = 0.0;
  long step = 0;
  double kinetic = 0.0, strain = 0.0, external_work = 0.0;
  Vec<Dim> momentum = Vec<Dim>::Zero();
  double total() const { return kinetic + strain; }
};

template <int Dim>
class Stepper {
 public:
  virtual ~Stepper() = default;
  // Advances the model by model.dt. Returns a problem if one was detected (state is then the
  // state after the step, for writing).
  virtual StepProblem step() = 0;
  virtual GlobalState<Dim> global_state() const = 0;
  virtual double time() const = 0;
  virtual double external_work() const = 0;
  virtual long step_count() const = 0;
  // A message for the log (empty when there is none), e.g. a node that needed more velocity
  // fields than it holds.
  virtual std::string take_warning() { return {}; }
  // J and K at every crack tip of a 2D cracked model, from the current state (empty otherwise).
  virtual std::vector<crack::TipRecord> crack_tip_parameters(const crack::TipSettings&) { return {}; }
  // J and K_I, K_II, K_III at every node of the fronts of a 3D cracked model (empty otherwise).
  virtual std::vector<crack::FrontRecord> crack_front_parameters(const crack::TipSettings&) { return {}; }
  // Brings every particle's stored strain up to date where the stepper takes it from the stress rather
  // than carrying it (Particles::strain_derived): before the array itself is written (checkpoints).
  // Readers of single particles use StrainOf (particle_strain.hpp) instead.
  virtual void sync_strain() {}
  // Restores counters when resuming from a checkpoint.
  virtual void restore(double time, long step, double external_work) = 0;
};

template <int Dim>
std::unique_ptr<Stepper<Dim>> make_stepper(Model<Dim>& model);

}  // namespace cleave
