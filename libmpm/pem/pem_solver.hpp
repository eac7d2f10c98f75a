// PEM time stepping (seed 004 §2.6 and §3): central differences (velocity Verlet) with kinetic
// damping; the pair forces of pair_law.hpp; a step that breaks more than break_limit of the pairs is
// redone as two half steps (down to max_halvings), as seed 004's step 4 asks; equilibrium and
// separation checks for the end of the run. Deterministic for any thread count: every particle sums
// only its own pair entries, and the next pair state is written apart and committed after the step.
#pragma once
#include <vector>

#include "libmpm/method/state_io.hpp"
#include "libmpm/pem/pem_model.hpp"

namespace cleave::pem {

template <int Dim>
struct PemGlobal {
  double time = 0.0;
  long step = 0;
  double kinetic = 0.0, strain = 0.0, external_work = 0.0, damping_loss = 0.0;
  std::size_t broken = 0;          // pairs (once each) not intact, pre-cracks included
  double residual = 0.0;           // |F_int + F_ext| over free components (N, 2-norm)
  double relative_residual = 0.0;  // residual / max(|F_ext|, |F_int|)
  double max_speed = 0.0;
  Vec<Dim> momentum = Vec<Dim>::Zero();
  double total() const { return kinetic + strain; }
};

template <int Dim>
class PemSolver {
 public:
  explicit PemSolver(PemSystem<Dim>& m);

  // Advances by m.dt (in halves where too many pairs would break in one step).
  void step();

  double time() const { return time_; }
  long step_count() const { return step_; }
  long halved_steps() const { return halved_; }
  PemGlobal<Dim> global_state() const;
  // What the equilibrium stop needs, without global_state's sums over every pair: the residual force
  // over the free components (N, 2-norm), it relative to max(|F_ext|, |F_int|), the largest speed.
  struct Balance {
    double residual = 0.0, relative_residual = 0.0, max_speed = 0.0;
  };
  Balance balance() const;
  // Broken pairs / all pairs of each particle (pre-cracks count as broken; seed 004 eq. 4).
  std::vector<double> damage() const;
  // Stress from the pair forces: sigma_i = 1/(2 V_i) sum_j F_ij (x) d_ij, symmetrised; zz from the
  // analysis (plane stress 0, plane strain nu (xx + yy) with the network's nu = 1/4).
  std::vector<Sym<Dim>> stress() const;
  // Current positions x0 + u, for the frames (the step works with reference vectors and displacements).
  std::vector<Vec<Dim>> positions() const;

  void save(StateWriter& w) const;
  void load(StateReader& r);

 private:
  void advance(double dt, int depth);
  void set_loads(double t);
  // Accelerations a_next and the next pair state from the current positions and half-step
  // velocities; returns the pairs (each counted once) that broke.
  std::size_t forces(double dt);
  void commit();
  // The current vector along pair entry e from its particle (displacement ui) to its partner j: the
  // stored reference vector plus the difference of displacements. x0[j] - x0[i] of neighbours is
  // exact (Sterbenz) and the displacements are small; y[j] - y[i] of absolute positions lost the
  // pair's force to rounding at about k ulp(|y|) (1e-5 N per pair 8 m from the origin), which held
  // the cantilever's relative residual at 9e-5 at 100 000 particles, short of any equilibrium
  // tolerance below it. The reference vectors stream in entry order; reading x0[j] instead made a
  // pair update twice as slow (a second random read).
  Vec<Dim> separation(int64_t e, const Vec<Dim>& ui, std::size_t j) const {
    return Eigen::Map<const Vec<Dim>>(m_.pairs.xi.data() + Dim * e) + (m_.points.u[j] - ui);
  }
  // A pre-cracked pair's crack normal, oriented from particle i towards its partner, and the change
  // of their separation along it (< 0: pressed together).
  Vec<Dim> cut_direction(std::size_t i, int64_t e) const;
  double cut_gap(std::size_t i, int64_t e) const;  // the next state (accelerations, internal forces, pairs) becomes the current one
  Vec<Dim> kicked(std::size_t p, double h) const;
  double load_power(double h) const;  // power of the loads and reactions at v + h a

  PemSystem<Dim>& m_;
  std::vector<Vec<Dim>> a_next_, fint_, fint_next_, fext_, u_save_, v_save_;
  std::vector<uint8_t> intact_next_;
  std::vector<double> b_next_, alpha_next_;
  std::vector<int64_t> breaks_;  // per particle, this step
  std::vector<int32_t> loaded_, fixed_;
  double time_ = 0.0, work_ = 0.0, damp_ = 0.0;
  long step_ = 0, halved_ = 0;
  bool parallel_ = false, plastic_ = false;
};

}  // namespace cleave::pem
