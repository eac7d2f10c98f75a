#include "libmpm/mpm/mpm_step.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <type_traits>

#include "libmpm/material/linear_elastic.hpp"
#include "libmpm/method/describe.hpp"
#include "libmpm/mpm/crack_fields.hpp"
#include "libmpm/mpm/crack_front_eval.hpp"
#include "libmpm/mpm/particle_strain.hpp"
#include "libmpm/mpm/spin_transfer.hpp"
#include "libmpm/core/parallel.hpp"
#include "libmpm/mpm/strip_order.hpp"
#include "libmpm/mpm/stencil.hpp"
#include "libmpm/mpm/step_timers.hpp"

namespace cleave {
namespace {

template <int Dim, class SF>
class MpmStepper final : public Stepper<Dim> {
  using St = Stencil<Dim, SF>;

 public:
  explicit MpmStepper(Model<Dim>& m) : m_(m), P_(m.particles), G_(m.grid) {
    stride_ = G_.strides();
    inv_h_ = 1.0 / G_.h;
    grid_.resize(G_.node_count());
    kin_.assign(G_.node_count(), NodeKinematics<Dim>{Vec<Dim>::Zero(), Vec<Dim>::Zero()});
    dx_.assign(P_.size(), Vec<Dim>::Zero());
    traits_ = traits(m.scheme);
    all_linear_elastic_ = true;
    for (const auto& mat : m.materials)
      all_linear_elastic_ = all_linear_elastic_ && dynamic_cast<const LinearElastic<Dim>*>(mat.get()) != nullptr;
    if (!m.cracks.empty() || m.body_contact.active()) cf_ = std::make_unique<CrackFields<Dim, SF>>(m, grid_, kin_);
    // Linear elasticity's strain is C^-1 : sigma: the stress update leaves it, and whatever reads it
    // takes it from the stress (StrainOf, particle_strain.hpp; sync_strain before a checkpoint).
    P_.strain_derived = all_linear_elastic_;
    if (m.spin_transfer) spin_ = std::make_unique<SpinTransfer<Dim>>(m);
    track_travel_ = Dim == 3 && cf_ && m.crack_tips.has_value();
  }

  void sync_strain() override {
    if (!P_.strain_derived) return;
    const StrainOf<Dim> strain(m_);
    const std::size_t n = P_.size();
#pragma omp parallel for schedule(static) if (worth_parallel(n))
    for (std::size_t p = 0; p < n; ++p) P_.strain[p] = strain(p);
  }

  std::string take_warning() override {
    if (!cf_) return {};
    const long o = cf_->take_overflow();
    if (o > 0)
      return "step " + std::to_string(step_) + ": " + std::to_string(o) +
             " particle-node pair(s) needed a fifth velocity field at a node (more than two cracks meet there, "
             "one line crosses three cracks, or too many bodies in contact meet there); they used the node's "
             "ordinary field";
    return {};
  }

  std::vector<crack::TipRecord> crack_tip_parameters(const crack::TipSettings& ts) override {
    if (!cf_) return {};
    // A particle's acceleration in the last step: Task 5's nodal accelerations, each node's from
    // the field the particle uses there.
    return cf_->tip_parameters(m_, ts, [&](std::size_t p) { return particle_acceleration(p); });
  }
  // A particle's acceleration in the last step: Task 5's nodal accelerations, each node's from the
  // field the particle uses there.
  Vec<Dim> particle_acceleration(std::size_t p) const {
    St s;
    s.eval(G_, stride_, inv_h_, P_.x[p], P_.half_width[p]);
    Vec<Dim> a = Vec<Dim>::Zero();
    s.for_each_weight([&](int64_t n, double w) { a += w * cf_->kin(n, cf_->field_of(p, n, node_position(n))).a; });
    return a;
  }

  std::vector<crack::FrontRecord> crack_front_parameters(const crack::TipSettings& ts) override {
    if constexpr (Dim == 3) {
      if (!cf_) return {};
      front_particles_.travel = travel_;
      return crack_front_records<SF>(m_, ts, [&](std::size_t p) { return particle_acceleration(p); },
                                     track_travel_ ? &front_particles_ : nullptr);
    } else {
      return {};
    }
  }

  double time() const override { return time_; }
  double external_work() const override { return external_work_; }
  long step_count() const override { return step_; }
  void restore(double t, long s, double w) override {
    time_ = t;
    step_ = s;
    external_work_ = w;
  }

  // The tasks of Appendix A, with passes over the particles fused where the data allow it: a pass
  // that gathers from one node array may scatter into another, so the stress update of Task 2 runs
  // with the force extrapolation of Task 3, and Task 5 with the re-extrapolation of Task 6c.
  StepProblem step() override {
    const double dt = m_.dt;
    if (omp_get_max_threads() != ftz_threads_) {  // new threads start with denormals on
      flush_denormals_on_all_threads();
      ftz_threads_ = omp_get_max_threads();
    }
    skip_ = nullptr;
    near_index_ = nullptr;
    bool ordered = false;
    if (cf_) {  // Task 1, line crossing: fields of the particles near cracks
        {
          CLEAVE_TIME(CrackIndex);
          cf_->prepare_index();
        }
        bool near_changed;
        {
          CLEAVE_TIME(Strips);
          near_changed = order_.build(P_, G_, inv_h_, cf_->near_flags(), cf_->near_test());
        }
        cf_->prepare_fields(near_changed);
        skip_ = cf_->near_flags();
        near_index_ = cf_->near_index();
        ordered = true;
      }
    if (!ordered) {
      CLEAVE_TIME(Strips);
      order_.build(P_, G_, inv_h_);
    }
    const double traction_work_before = traction_dot_u(), gravity_power_before = gravity_power();
    const double dts = dt * traits_.fraction;

    task1_extrapolate();
    apply_momentum_conditions();  // Task 2
    crack_contact(ContactCall::Start);
    if (traits_.update_before_forces) {  // Tasks 2-3: USF and USAVG update stresses first
      nodal_velocities();
      stress_pass<true, true, false>(dts);
    } else {
      stress_pass<false, true, false>(0.0);  // Task 3 only
    }
    finish_forces();  // Task 3, grid part
    task4_update_momenta(dt);
    const bool late_update = traits_.update_after_move || traits_.reextrapolate;
    StepProblem problem = track_travel_ ? task5_update_particles<true>(dt, traits_.reextrapolate, !late_update)
                                        : task5_update_particles<false>(dt, traits_.reextrapolate, !late_update);
    if (traits_.reextrapolate) {  // Task 6c
      apply_momentum_conditions();
      crack_contact(ContactCall::Remapped);
      nodal_velocities();
    }
    if (late_update) stress_pass<true, false, true>(dts);  // Task 6a / 6c
    if (traits_.reextrapolate && !m_.cracks.empty()) {  // crack faces that touch only now (contact.hpp)
      crack_contact(ContactCall::Closing);
      cf_->nodal_velocities();
    }
    if (cf_) {
      CLEAVE_TIME(CrackMotion);
      cf_->move_cracks(dt);  // Task 7
    }

    // (time_ is still the step's start: the tractions of this step, over its displacements.)
    external_work_ += traction_dot_u() - traction_work_before + 0.5 * dt * (gravity_power_before + gravity_power());
    time_ += dt;
    ++step_;
    if (also_left_ >= 0)
      problem.what += "; also particle " + std::to_string(also_left_) + " at " + position_text<Dim>(P_.x[also_left_]) +
                      " left the grid";
    return problem;
  }

  GlobalState<Dim> global_state() const override {
    GlobalState<Dim> s;
    s.time = time_;
    s.step = step_;
    s.external_work = external_work_;
    const std::size_t n = P_.size();
    s.kinetic = deterministic_sum(n, [&](std::size_t p) { return 0.5 * P_.mass[p] * P_.v[p].squaredNorm(); });
    const StrainOf<Dim> strain(m_);
    s.strain = deterministic_sum(n, [&](std::size_t p) {
      return P_.volume0[p] * m_.materials[P_.material[p]]->strain_energy_density(P_.stress[p], strain(p));
    });
    for (int d = 0; d < Dim; ++d)
      s.momentum[d] = deterministic_sum(n, [&](std::size_t p) { return P_.mass[p] * P_.v[p][d]; });
    return s;
  }

 private:
  // Task 1: nodal masses and momenta from the particles (eq. 26).
  void task1_extrapolate() {
    CLEAVE_TIME(Task1);
    std::fill(grid_.mass.begin(), grid_.mass.end(), 0.0);
    std::fill(grid_.momentum.begin(), grid_.momentum.end(), Vec<Dim>::Zero());
    // With spin_transfer the same pass sums the nodes' mass-weighted positions (spin_transfer.hpp).
    auto pass = [&](auto with_moments) {
      constexpr bool moments = decltype(with_moments)::value;
      auto far = [&](std::size_t p) CLEAVE_INLINE {
        St s;
        s.eval(G_, stride_, inv_h_, P_.x[p], P_.half_width[p]);
        const double mp = P_.mass[p];
        const Vec<Dim> mv = mp * P_.v[p];
        Vec<Dim> r = Vec<Dim>::Zero();
        if constexpr (moments) r = spin_->offset(P_.x[p]);
        s.for_each_weight([&](int64_t n, double w) {
          grid_.mass[n] += mp * w;
          grid_.momentum[n] += mv * w;
          if constexpr (moments) spin_->add(n, mp * w, r);
        });
      };
      if (!cf_) return order_.scatter(far);
      const int32_t* nk = near_index_;
      order_.scatter(far, [&](std::size_t p) CLEAVE_INLINE {
        if (cf_->plain_extrapolation(nk[p])) return far(p);
        cf_->extrapolate(nk[p], cf_->stencil(nk[p]));
        if constexpr (moments) {
          St s;
          s.eval(G_, stride_, inv_h_, P_.x[p], P_.half_width[p]);
          const Vec<Dim> r = spin_->offset(P_.x[p]);
          s.for_each_weight([&](int64_t n, double w) { spin_->add(n, P_.mass[p] * w, r); });
        }
      });
    };
    if (!spin_) return pass(std::false_type{});
    spin_->fit(P_);
    if (cf_) cf_->follow_scene_spin(spin_->spin());
    spin_->clear();
    pass(std::true_type{});
  }

  // Passes over the particles. The particles near cracks (with cracks present) take a path of
  // their own, near(k) for near particle k of the crack module's list, which uses each pair's
  // velocity field; far(p) serves all others.
  // Scatter passes (far and near add into nodes): in strip order, each strip's near particles after
  // its far ones (StripOrder::scatter), so the near particles run in parallel too and every node
  // sums in the same order for any thread count. (Before: the near particles' scatters ran after
  // all others, serially in list order: 0.5-0.9 ms of a 21 ms step with two threads in the 0.25 mm
  // DCB benchmark. A test per particle in one loop for both kinds slowed the far path by ~5 %.)
  template <class Far, class Near>
  void scatter_pass(Far&& far, Near&& near) {
    const int32_t* nk = near_index_;
    order_.scatter(far, [&](std::size_t p) { near(static_cast<std::size_t>(nk[p])); });
  }
  // Gather passes (each body writes only its own particle): the far particles, then the near ones,
  // in one parallel region (a thread that finishes its share of the far ones starts on the near).
  template <class Far, class Near>
  void gather_pass(Far&& far, Near&& near) {
    const std::size_t np = P_.size(), nn = near_index_ ? cf_->near_list().size() : 0;
    const uint8_t* skip = skip_;
#pragma omp parallel if (worth_parallel(np))
    {
#pragma omp for schedule(static) nowait
      for (std::size_t p = 0; p < np; ++p)
        if (!skip || !skip[p]) far(p);
#pragma omp for schedule(dynamic, 256)
      for (std::size_t k = 0; k < nn; ++k) near(k);
    }
  }

  // Subtask 3: the constitutive update, without a virtual call when every material is linear elastic
  // (and then of the stress alone: the strain is taken from it, P_.strain_derived).
  CLEAVE_INLINE void update_stress(std::size_t p, const Mat<Dim>& L, double dts) {
    const Material<Dim>* mat = m_.materials[P_.material[p]].get();
    if (all_linear_elastic_)  // devirtualised: inlined into the calling loop
      static_cast<const LinearElastic<Dim>*>(mat)->update_stress_inline(P_.stress[p], L, dts);
    else
      mat->update(P_.stress[p], P_.strain[p], L, dts);
  }

  // Contact at multi-field nodes whenever momenta were (re)computed (Tasks 2 and 6c), and for the
  // crack motion after the last stress update.
  using ContactCall = typename CrackFields<Dim, SF>::ContactCall;
  void crack_contact(ContactCall call) {
    if (cf_) {
      CLEAVE_TIME(Contact);
      cf_->contact(m_.dt, call);
    }
  }

  // Updating stresses and strains (Subtasks 2-3: velocity gradient eq. 36 from the nodal velocities
  // in kin_, then the constitutive law) when `update`; then, optionally, the internal force of
  // Task 3 (eq. 28) with the updated stress, and the deferred position update.
  // (Compiled once per combination, so the hot loop carries no flag tests.)
  template <bool update, bool scatter_force, bool move>
  void stress_pass(double dts) {
    auto body = [&](std::size_t p) CLEAVE_INLINE {
      St s;
      s.eval(G_, stride_, inv_h_, P_.x[p], P_.half_width[p]);
      if constexpr (update) {
        const Mat<Dim> L = s.gradient([&](int64_t n) -> const Vec<Dim>& { return kin_[n].v; });
        integrate_spin(P_, p, L, dts);
        update_stress(p, L, dts);
      }
      if constexpr (scatter_force) {
        const Sym<Dim> vs = P_.volume0[p] * P_.stress[p];
        s.for_each_divergence(vs, [&](int64_t n, const Vec<Dim>& f) { grid_.force[n] -= f; });
      }
      if constexpr (move) {
        P_.x[p] += dx_[p];
        P_.u[p] += dx_[p];
      }
    };
    CLEAVE_TIME(Stress);
    if constexpr (scatter_force) std::fill(grid_.force.begin(), grid_.force.end(), Vec<Dim>::Zero());
    if (cf_) {  // particles near cracks: the same with each pair's velocity field
      const auto& near = cf_->near_list();
      auto near_body = [&](std::size_t k) CLEAVE_INLINE {  // (stencils: the start-of-step ones, cached)
        const std::size_t p = static_cast<std::size_t>(near[k]);
        if (cf_->plain(k)) return body(p);
        if constexpr (update) {
          Mat<Dim> L = Mat<Dim>::Zero();
          cf_->for_each_pair(k, cf_->stencil(k), [&](int64_t n, int32_t x, double, const Vec<Dim>& g) {
            L.noalias() += cf_->kin(n, x).v * g.transpose();
          });
          integrate_spin(P_, p, L, dts);
          update_stress(p, L, dts);
        }
        if constexpr (scatter_force) {
          const Sym<Dim> vs = P_.volume0[p] * P_.stress[p];
          cf_->for_each_pair(k, cf_->stencil(k), [&](int64_t n, int32_t x, double, const Vec<Dim>& g) {
            cf_->force(n, x) -= sym_dot<Dim>(vs, g);
          });
        }
        if constexpr (move) {
          P_.x[p] += dx_[p];
          P_.u[p] += dx_[p];
        }
      };
      if constexpr (scatter_force) return scatter_pass(body, near_body);
      else return gather_pass(body, near_body);
    }
    if constexpr (scatter_force) order_.scatter(body);
    else gather_pass(body, [](std::size_t) {});
  }

  // Task 3, grid part: tractions, body force, damping; zero force on prescribed components.
  void finish_forces() {
    CLEAVE_TIME(Forces);
    for (const auto& t : m_.tractions) {
      const Vec<Dim> tr = t.traction * t.time_function(time_);
      for (std::size_t j = 0; j < t.particles.size(); ++j) {
        const int32_t p = t.particles[j];
        St s;
        s.eval(G_, stride_, inv_h_, face_centre(t, p), face_half_widths(t, p).data());
        const Vec<Dim> F = tr * t.face_area[j];
        // The face point moves with the body: once a face on a node line has moved outwards, part of
        // its weight falls on nodes without mass, whose forces are dropped (linear shape functions
        // lost 4.6 % of a plate's load at a displacement of 0.046 cell). The force is shared among
        // the nodes that carry mass, in proportion to their weights.
        // The field that receives the face's share at each node (near a crack, each node's field as
        // seen from the particle; elsewhere the ordinary field), looked up once: its force, if it
        // has mass, and the weight.
        Vec<Dim>* target[St::N];
        double wt[St::N];
        int count = 0;
        double wsum = 0.0;
        s.for_each_weight([&](int64_t n, double w) {
          double mass = grid_.mass[n];
          Vec<Dim>* f = &grid_.force[n];
          if (cf_ && skip_[p]) {
            const int32_t x = cf_->field_of(p, n, node_position(n));
            mass = cf_->mass(n, x), f = &cf_->force(n, x);
          }
          if (!(mass > 0.0)) return;
          target[count] = f, wt[count] = w, ++count;
          wsum += w;
        });
        if (!(wsum > 0.0)) continue;
        for (int e = 0; e < count; ++e) *target[e] += F * (wt[e] / wsum);
      }
    }
    const bool gravity = m_.gravity.squaredNorm() > 0.0;
    const double kappa = m_.damping;
    if (gravity || kappa > 0.0) {
      const std::size_t nn = grid_.mass.size();
#pragma omp parallel for schedule(static) if (worth_parallel(nn))
      for (std::size_t n = 0; n < nn; ++n) {
        if (grid_.mass[n] <= 0.0) continue;
        grid_.force[n] += grid_.mass[n] * m_.gravity - kappa * grid_.momentum[n];
      }
      if (cf_) cf_->body_force_and_damping(m_.gravity, kappa);
    }
    const auto& C = m_.conditions;
    for (std::size_t c = 0; c < C.node.size(); ++c)
      for (int d = 0; d < Dim; ++d)
        if (C.mask[c] & (1u << d)) {
          // The reaction that holds a non-zero prescribed velocity does work.
          external_work_ -= grid_.force[C.node[c]][d] * C.velocity[c][d] * m_.dt;
          grid_.force[C.node[c]][d] = 0.0;
        }
    if (cf_) external_work_ -= cf_->zero_prescribed_forces(C) * m_.dt;
  }

  // Task 4: p' = p + dt f (eq. 29), and the nodal velocity and acceleration Task 5 gathers.
  void task4_update_momenta(double dt) {
    CLEAVE_TIME(Task4);
    const std::size_t nn = grid_.mass.size();
#pragma omp parallel for schedule(static) if (worth_parallel(nn))
    for (std::size_t n = 0; n < nn; ++n) {
      if (grid_.mass[n] <= 0.0) continue;
      grid_.momentum[n] += dt * grid_.force[n];
      const double inv_m = 1.0 / grid_.mass[n];
      kin_[n].v = grid_.momentum[n] * inv_m;
      kin_[n].a = grid_.force[n] * inv_m;
    }
    if (spin_) spin_->carry(grid_.mass, kin_, [&](int64_t n) { return node_position(n); });
    if (cf_) cf_->update_momenta(dt);  // with contact and back-computed forces
  }

  // Task 5 (eq. 30): particle velocities, and position increments that are applied now or, when a
  // later stress update still needs the start-of-step shape functions, after it. With
  // reextrapolate, the new particle momenta go straight back to the grid (Task 6c, eq. 31).
  // kTravel: travel_ follows the step's longest move (only runs that evaluate 3D crack fronts use it).
  template <bool kTravel>
  StepProblem task5_update_particles(double dt, bool reextrapolate, bool move) {
    constexpr long none = std::numeric_limits<long>::max();
    // Two checks: a velocity that is not finite, and (else) a particle that left the grid. Of each,
    // the lowest-numbered particle is reported, whatever the thread count.
    std::atomic<long> bad{none}, left{none};
    auto lowest = [](std::atomic<long>& a, long p) CLEAVE_INLINE {
      long cur = a.load();
      while (p < cur && !a.compare_exchange_weak(cur, p)) {
      }
    };
    // The longest move of the step (its square), for travel_: raised rarely, read without a fence.
    std::atomic<double> longest{0.0};
    auto highest = [](std::atomic<double>& a, double v) CLEAVE_INLINE {
      double cur = a.load(std::memory_order_relaxed);
      while (v > cur && !a.compare_exchange_weak(cur, v, std::memory_order_relaxed)) {
      }
    };
    auto finish = [&](std::size_t p, const Vec<Dim>& dx) CLEAVE_INLINE {
      if constexpr (kTravel) highest(longest, dx.squaredNorm());
      if (!P_.v[p].allFinite()) lowest(bad, static_cast<long>(p));
      else if (!stencil_inside<Dim, SF>(G_, inv_h_, P_.x[p] + dx)) lowest(left, static_cast<long>(p));
      if (move) {
        P_.x[p] += dx;
        P_.u[p] += dx;
      } else {
        dx_[p] = dx;
      }
    };
    // Damping (Task 3) acts on the nodes' momenta, so it never reaches the part of a particle's
    // velocity that the grid does not represent (v_p less the nodes' velocity at the particle, which
    // the FLIP update carries unchanged from step to step). That part is damped here at the same rate.
    // Without it a uGIMP DCB at 2 mm cells never became static: particles at its loaded corners kept
    // +-2e-3 m/s alternating cell by cell, a thousand times the body's motion (docs/speed-accuracy.md).
    // The nodes' momenta are the particles' (before any condition), so momentum is unchanged.
    const double damp = std::min(m_.damping * dt, 1.0);
    auto update_velocity = [&](std::size_t p, const Vec<Dim>& a, const Vec<Dim>& v) CLEAVE_INLINE {
      P_.v[p] += dt * a;
      if (damp > 0.0) P_.v[p] -= damp * (P_.v[p] - v);
    };
    auto body = [&](std::size_t p) CLEAVE_INLINE {
      St s;
      s.eval(G_, stride_, inv_h_, P_.x[p], P_.half_width[p]);
      Vec<Dim> a = Vec<Dim>::Zero(), v = Vec<Dim>::Zero();
      s.for_each_weight([&](int64_t n, double w) {
        a += kin_[n].a * w;
        v += kin_[n].v * w;
      });
      update_velocity(p, a, v);
      const Vec<Dim> dx = dt * v;
      if (reextrapolate) {
        const Vec<Dim> mv = P_.mass[p] * P_.v[p];
        s.for_each_weight([&](int64_t n, double w) { grid_.momentum[n] += mv * w; });
      }
      finish(p, dx);
    };
    {
      CLEAVE_TIME(Task5);
      if (reextrapolate) std::fill(grid_.momentum.begin(), grid_.momentum.end(), Vec<Dim>::Zero());
      bool done = false;
      if (cf_) {
        if (reextrapolate) cf_->clear_momenta();
        const auto& near = cf_->near_list();
        auto near_body = [&](std::size_t k) CLEAVE_INLINE {
          const std::size_t p = static_cast<std::size_t>(near[k]);
          if (cf_->plain(k)) return body(p);
          Vec<Dim> a = Vec<Dim>::Zero(), v = Vec<Dim>::Zero();
          cf_->for_each_pair_weight(k, cf_->stencil(k), [&](int64_t n, int32_t x, double w) {
            const auto& kn = cf_->kin(n, x);
            a += kn.a * w;
            v += kn.v * w;
          });
          update_velocity(p, a, v);
          if (reextrapolate) {  // Task 6c
            const Vec<Dim> mv = P_.mass[p] * P_.v[p];
            cf_->for_each_pair_weight(k, cf_->stencil(k),
                                      [&](int64_t n, int32_t x, double w) { cf_->momentum(n, x) += mv * w; });
          }
          finish(p, dt * v);
        };
        if (reextrapolate) scatter_pass(body, near_body);
        else gather_pass(body, near_body);
        done = true;
      }
      if (!done) {
        if (reextrapolate) order_.scatter(body);
        else gather_pass(body, [](std::size_t) {});
      }
    }
    if constexpr (kTravel) travel_ += std::sqrt(longest.load());  // (a non-finite move stops the run below)
    // Both checks tripped: the second particle is named once the step has moved it (step()).
    const long b = bad.load(), l = left.load();
    also_left_ = b != none && l != none ? l : -1;
    if (b != none) return {b, "velocity is not finite (NaN/Inf)"};
    if (l != none) return {l, "left the grid"};
    return {};
  }

  void apply_momentum_conditions() {
    CLEAVE_TIME(Conditions);
    const auto& C = m_.conditions;
    for (std::size_t c = 0; c < C.node.size(); ++c)
      for (int d = 0; d < Dim; ++d)
        if (C.mask[c] & (1u << d)) grid_.momentum[C.node[c]][d] = grid_.mass[C.node[c]] * C.velocity[c][d];
    if (cf_) cf_->apply_momentum_conditions(C);
  }

  // Subtask 1: nodal velocities from the latest momenta (eq. 34).
  void nodal_velocities() {
    CLEAVE_TIME(Conditions);
    const std::size_t nn = grid_.mass.size();
#pragma omp parallel for schedule(static) if (worth_parallel(nn))
    for (std::size_t n = 0; n < nn; ++n)
      if (grid_.mass[n] > 0.0) kin_[n].v = grid_.momentum[n] / grid_.mass[n];
    if (spin_) spin_->carry(grid_.mass, kin_, [&](int64_t n) { return node_position(n); });
    if (cf_) cf_->nodal_velocities();
  }

  Vec<Dim> node_position(int64_t n) const {
    std::array<int, Dim> ijk;
    for (int d = 0; d < Dim; ++d) ijk[d] = static_cast<int>((n / int64_t(stride_[d])) % G_.nodes[d]);
    return G_.position(ijk);
  }

  Vec<Dim> face_centre(const TractionLoad<Dim>& t, int32_t p) const {
    Vec<Dim> x = P_.x[p];
    x[t.axis] += t.side * P_.half_width[p] * G_.h;
    return x;
  }
  std::array<double, Dim> face_half_widths(const TractionLoad<Dim>& t, int32_t p) const {
    std::array<double, Dim> l;
    l.fill(P_.half_width[p]);
    l[t.axis] = 0.0;  // the face is a surface: no averaging across it
    return l;
  }
  // The tractions' work: each face force (at the step's start time) times the displacement of the
  // point it acts on, the face centre, which moves with its particle (face_centre): sum F . u_p,
  // differenced over the step. (Before 2026-11-27 it was integrated with the loaded particle's own
  // velocity, trapezoidal; under FLIP that velocity departs from the one the particle moves with,
  // and the work of a 50 MPa pull on a ringing 40 x 20 mm plate, 1 mm cells, drifted from the energy
  // by +4.6 % of it in 100 us, +7.8 % at 0.5 mm, growing without bound; docs/validation.md,
  // "Stability at the extremes".)
  double traction_dot_u() const {
    double w = 0.0;
    for (const auto& t : m_.tractions) {
      const Vec<Dim> tr = t.traction * t.time_function(time_);
      for (std::size_t j = 0; j < t.particles.size(); ++j) w += t.face_area[j] * tr.dot(P_.u[t.particles[j]]);
    }
    return w;
  }
  // Gravity's power from the particles' velocities (trapezoidal): sum_p m_p g . v_p equals
  // g . sum_n p_n, the nodal power, since the transfers conserve momentum.
  double gravity_power() const {
    if (m_.gravity.squaredNorm() == 0.0) return 0.0;
    return deterministic_sum(P_.size(), [&](std::size_t p) { return P_.mass[p] * m_.gravity.dot(P_.v[p]); });
  }

  Model<Dim>& m_;
  Particles<Dim>& P_;
  const GridGeometry<Dim>& G_;
  std::array<std::size_t, Dim> stride_;
  double inv_h_;
  GridFields<Dim> grid_;
  std::vector<NodeKinematics<Dim>> kin_;
  // Explicit cracks: extra velocity fields, contact, crack motion (null without cracks).
  std::unique_ptr<CrackFields<Dim, SF>> cf_;
  std::unique_ptr<SpinTransfer<Dim>> spin_;  // mpm.spin_transfer (null without it)
  const uint8_t* skip_ = nullptr;         // near-crack flags: those particles take the crack paths
  const int32_t* near_index_ = nullptr;  // per particle: index in the crack module's near list, or -1
  std::vector<Vec<Dim>> dx_;
  StripOrder<Dim> order_;
  SchemeTraits traits_;
  double time_ = 0.0, external_work_ = 0.0;
  // A bound on how far any particle has moved since the stepper was made: the sum of each step's
  // longest move, followed where the scene evaluates 3D crack fronts. The front evaluation keeps its
  // particles near the fronts while this stays small. (Particles move only in Task 5 and its
  // deferred move: code that moved them otherwise would have to add that move here.)
  bool track_travel_ = false;
  double travel_ = 0.0;
  detail::FrontParticles front_particles_;
  long step_ = 0;
  long also_left_ = -1;  // a particle that left the grid in a step that also found a non-finite velocity
  int ftz_threads_ = 0;
  bool all_linear_elastic_ = false;
};

}  // namespace

namespace {

// The stepper compiled for one shape-function style; each style registers it below.
template <int Dim, class SF>
std::unique_ptr<Stepper<Dim>> stepper_for(Model<Dim>& model) {
  return std::make_unique<MpmStepper<Dim, SF>>(model);
}

}  // namespace

CLEAVE_REGISTER_SHAPE_FUNCTION(LinearShape, stepper_for)
CLEAVE_REGISTER_SHAPE_FUNCTION(UGimpShape, stepper_for)

// The style is picked here, once per run; the hot loops are compiled for it.
template <int Dim>
std::unique_ptr<Stepper<Dim>> make_stepper(Model<Dim>& model) {
  const ShapeFunctionStyle& style = shape_function_style(model.shape_function);
  if constexpr (Dim == 2) return style.stepper2(model);
  else return style.stepper3(model);
}

template std::unique_ptr<Stepper<2>> make_stepper<2>(Model<2>&);
template std::unique_ptr<Stepper<3>> make_stepper<3>(Model<3>&);

}  // namespace cleave
