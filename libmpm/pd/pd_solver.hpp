// Bond-based (PMB) peridynamics time stepping (seed 003): pairwise force f = c s mu with s the bond
// stretch, bonds broken for good when s > s0, velocity-Verlet integration. Deterministic for any
// OpenMP thread count: every point sums only its own neighbour entries, in list order.
#pragma once
#include <vector>

#include "libmpm/pd/pd_model.hpp"

namespace cleave::pd {

template <int Dim>
struct PdGlobal {
  double time = 0.0;
  long step = 0;
  double kinetic = 0.0, strain = 0.0, external_work = 0.0, damping_loss = 0.0;
  std::size_t broken = 0;  // bonds (counted once) broken during the run
  Vec<Dim> momentum = Vec<Dim>::Zero();
  double total() const { return kinetic + strain; }
};

template <int Dim>
class PdSolver {
 public:
  // Computes the initial accelerations (and breaks bonds already over-stretched, none normally).
  explicit PdSolver(PdSystem<Dim>& m);

  // One velocity-Verlet step of m.dt: v += dt/2 a; u += dt v; a = f(u)/rho; v += dt/2 a, with
  // prescribed velocity components held and kinetic damping -kappa v (v at the half step).
  void step();

  double time() const { return time_; }
  long step_count() const { return step_; }
  double external_work() const { return work_; }
  double damping_loss() const { return damp_; }
  // Resuming: time, step counter and the accumulated works (the point state is restored by the caller).
  void restore(double time, long step, double work, double damping_loss);

  PdGlobal<Dim> global_state() const;
  // Damage phi = 1 - sum(intact w0) / sum(w0) over the point's initial bonds (pre-cracks excluded:
  // they are not bonds); points without bonds have phi = 0.
  std::vector<double> damage() const;
  // Stress estimated from the bond forces (docs/peridynamics.md): sigma_i = 1/2 sum_j f_ij (x) xi_ij V_j,
  // symmetrised, zz from the analysis (plane stress 0, plane strain nu (sxx + syy), nu = 1/4).
  std::vector<Sym<Dim>> stress() const;

 private:
  void update_loads(double t);
  void forces();  // m.points.a from the current positions (breaks bonds)
  // Point p's velocity after a kick of h: v + h a, with its prescribed components held.
  Vec<Dim> kicked(std::size_t p, double h) const;
  // Power of the external forces at v + h a and of the reactions at the prescribed velocities.
  double load_power(double h) const;

  PdSystem<Dim>& m_;
  std::vector<Vec<Dim>> y_;          // current positions x0 + u
  std::vector<Vec<Dim>> fext_;       // external force per point (N) at the current time
  std::vector<Vec<Dim>> fint_;       // internal force per point (N) at the current time (fixed points only)
  std::vector<int32_t> loaded_, fixed_;
  double time_ = 0.0, work_ = 0.0, damp_ = 0.0;
  long step_ = 0;
  bool parallel_ = false;
};

}  // namespace cleave::pd
