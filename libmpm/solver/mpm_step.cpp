#include "libmpm/solver/mpm_step.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "libmpm/solver/parallel.hpp"
#include "libmpm/solver/stencil.hpp"

namespace cleave {
namespace {

template <int Dim, class SF>
class MpmStepper final : public Stepper<Dim> {
  using St = Stencil<Dim, SF>;
  static constexpr int N = St::N;

 public:
  explicit MpmStepper(Model<Dim>& m) : m_(m), P_(m.particles), G_(m.grid) {
    stride_ = G_.strides();
    inv_h_ = 1.0 / G_.h;
    grid_.resize(G_.node_count());
    gvel_.assign(G_.node_count(), Vec<Dim>::Zero());
    gacc_.assign(G_.node_count(), Vec<Dim>::Zero());
    dx_.assign(P_.size(), Vec<Dim>::Zero());
    traits_ = traits(m.scheme);
  }

  double time() const override { return time_; }
  long step_count() const override { return step_; }
  void restore(double t, long s, double w) override {
    time_ = t;
    step_ = s;
    external_work_ = w;
  }

  StepProblem step() override {
    const double dt = m_.dt;
    flush_denormals_on_all_threads();
    order_.build(P_, G_, inv_h_);
    const double traction_power_before = traction_power();

    task1_extrapolate();
    task2_conditions_and_first_update(dt);
    task3_forces();
    task4_update_momenta(dt);
    StepProblem problem = task5_update_particles(dt);
    task6_late_update(dt);
    move_particles();

    external_work_ += 0.5 * dt * (traction_power_before + traction_power());
    time_ += dt;
    ++step_;
    return problem;
  }

  GlobalState<Dim> global_state() const override {
    GlobalState<Dim> s;
    s.time = time_;
    s.step = step_;
    s.external_work = external_work_;
    const std::size_t n = P_.size();
    s.kinetic = deterministic_sum(n, [&](std::size_t p) { return 0.5 * P_.mass[p] * P_.v[p].squaredNorm(); });
    s.strain = deterministic_sum(n, [&](std::size_t p) {
      return P_.volume0[p] * m_.materials[P_.material[p]]->strain_energy_density(P_.stress[p], P_.strain[p]);
    });
    for (int d = 0; d < Dim; ++d)
      s.momentum[d] = deterministic_sum(n, [&](std::size_t p) { return P_.mass[p] * P_.v[p][d]; });
    return s;
  }

 private:
  // Task 1: nodal masses and momenta from the particles (eq. 26).
  void task1_extrapolate() {
    std::fill(grid_.mass.begin(), grid_.mass.end(), 0.0);
    std::fill(grid_.momentum.begin(), grid_.momentum.end(), Vec<Dim>::Zero());
    order_.scatter([&](std::size_t p) {
      St s;
      s.eval(G_, stride_, inv_h_, P_.x[p], P_.half_width[p]);
      const double mp = P_.mass[p];
      const Vec<Dim> mv = mp * P_.v[p];
      for (int k = 0; k < N; ++k) {
        grid_.mass[s.node[k]] += mp * s.w[k];
        grid_.momentum[s.node[k]] += mv * s.w[k];
      }
    });
  }

  // Task 2: grid velocity conditions on the momenta; USF and USAVG update stresses here.
  void task2_conditions_and_first_update(double dt) {
    apply_momentum_conditions();
    if (traits_.update_before_forces) update_stresses(dt * traits_.fraction);
  }

  // Task 3: internal, external and damping forces (eq. 28); zero force on prescribed components.
  void task3_forces() {
    std::fill(grid_.force.begin(), grid_.force.end(), Vec<Dim>::Zero());
    order_.scatter([&](std::size_t p) {
      St s;
      s.eval(G_, stride_, inv_h_, P_.x[p], P_.half_width[p]);
      const Sym<Dim> vs = P_.volume0[p] * P_.stress[p];
      for (int k = 0; k < N; ++k) grid_.force[s.node[k]] -= sym_dot<Dim>(vs, s.g[k]);
    });
    for (const auto& t : m_.tractions) {
      const Vec<Dim> tr = t.traction * t.time_function(time_);
      for (std::size_t j = 0; j < t.particles.size(); ++j) {
        const int32_t p = t.particles[j];
        St s;
        s.eval(G_, stride_, inv_h_, face_centre(t, p), face_half_widths(t, p).data());
        const Vec<Dim> F = tr * t.face_area[j];
        for (int k = 0; k < N; ++k) grid_.force[s.node[k]] += F * s.w[k];
      }
    }
    const bool gravity = m_.gravity.squaredNorm() > 0.0;
    const double kappa = m_.damping;
    if (gravity || kappa > 0.0) {
      const std::size_t nn = grid_.mass.size();
#pragma omp parallel for schedule(static)
      for (std::size_t n = 0; n < nn; ++n) {
        if (grid_.mass[n] <= 0.0) continue;
        grid_.force[n] += grid_.mass[n] * m_.gravity - kappa * grid_.momentum[n];
      }
    }
    const auto& C = m_.conditions;
    for (std::size_t c = 0; c < C.node.size(); ++c)
      for (int d = 0; d < Dim; ++d)
        if (C.mask[c] & (1u << d)) {
          // The reaction needed to hold the prescribed velocity does work when that velocity is not zero.
          external_work_ -= grid_.force[C.node[c]][d] * C.velocity[c][d] * m_.dt;
          grid_.force[C.node[c]][d] = 0.0;
        }
  }

  // Task 4: p' = p + dt f (eq. 29).
  void task4_update_momenta(double dt) {
    const std::size_t nn = grid_.mass.size();
#pragma omp parallel for schedule(static)
    for (std::size_t n = 0; n < nn; ++n) {
      if (grid_.mass[n] <= 0.0) continue;
      grid_.momentum[n] += dt * grid_.force[n];
      const double inv_m = 1.0 / grid_.mass[n];
      gvel_[n] = grid_.momentum[n] * inv_m;
      gacc_[n] = grid_.force[n] * inv_m;
    }
  }

  // Task 5: particle velocity and position increments (eq. 30). Positions move after Task 6,
  // which still needs the shape functions of the start of the step.
  StepProblem task5_update_particles(double dt) {
    const std::size_t np = P_.size();
    long bad = std::numeric_limits<long>::max();
#pragma omp parallel for schedule(static) reduction(min : bad)
    for (std::size_t p = 0; p < np; ++p) {
      St s;
      s.eval(G_, stride_, inv_h_, P_.x[p], P_.half_width[p]);
      Vec<Dim> a = Vec<Dim>::Zero(), v = Vec<Dim>::Zero();
      for (int k = 0; k < N; ++k) {
        a += gacc_[s.node[k]] * s.w[k];
        v += gvel_[s.node[k]] * s.w[k];
      }
      P_.v[p] += dt * a;
      dx_[p] = dt * v;
      const Vec<Dim> xn = P_.x[p] + dx_[p];
      if (!P_.v[p].allFinite() || !stencil_inside<Dim, SF>(G_, inv_h_, xn, P_.half_width[p]))
        bad = std::min(bad, static_cast<long>(p));
    }
    if (bad == std::numeric_limits<long>::max()) return {};
    const bool finite = P_.v[bad].allFinite() && dx_[bad].allFinite();
    return {bad, finite ? "left the grid" : "velocity or position is not finite (NaN/Inf)"};
  }

  // Task 6: USL updates with p'; MUSL/USAVG re-extrapolate the new velocities (eq. 31) with the
  // start-of-step shape functions and update; USF has nothing left to do.
  void task6_late_update(double dt) {
    if (traits_.update_after_move) {
      update_stresses_from_gvel(dt * traits_.fraction);
    } else if (traits_.reextrapolate) {
      std::fill(grid_.momentum.begin(), grid_.momentum.end(), Vec<Dim>::Zero());
      order_.scatter([&](std::size_t p) {
        St s;
        s.eval(G_, stride_, inv_h_, P_.x[p], P_.half_width[p]);
        const Vec<Dim> mv = P_.mass[p] * P_.v[p];
        for (int k = 0; k < N; ++k) grid_.momentum[s.node[k]] += mv * s.w[k];
      });
      apply_momentum_conditions();
      update_stresses(dt * traits_.fraction);
    }
  }

  void move_particles() {
    const std::size_t np = P_.size();
#pragma omp parallel for schedule(static)
    for (std::size_t p = 0; p < np; ++p) {
      P_.x[p] += dx_[p];
      P_.u[p] += dx_[p];
    }
  }

  void apply_momentum_conditions() {
    const auto& C = m_.conditions;
    for (std::size_t c = 0; c < C.node.size(); ++c)
      for (int d = 0; d < Dim; ++d)
        if (C.mask[c] & (1u << d)) grid_.momentum[C.node[c]][d] = grid_.mass[C.node[c]] * C.velocity[c][d];
  }

  // Updating stresses and strains, Subtasks 1-3: nodal velocities from the latest momenta, the
  // particle velocity gradient (eq. 36) and the constitutive law.
  void update_stresses(double dts) {
    const std::size_t nn = grid_.mass.size();
#pragma omp parallel for schedule(static)
    for (std::size_t n = 0; n < nn; ++n)
      if (grid_.mass[n] > 0.0) gvel_[n] = grid_.momentum[n] / grid_.mass[n];
    update_stresses_from_gvel(dts);
  }

  void update_stresses_from_gvel(double dts) {
    const std::size_t np = P_.size();
#pragma omp parallel for schedule(static)
    for (std::size_t p = 0; p < np; ++p) {
      St s;
      s.eval(G_, stride_, inv_h_, P_.x[p], P_.half_width[p]);
      Mat<Dim> L = Mat<Dim>::Zero();
      for (int k = 0; k < N; ++k) L.noalias() += gvel_[s.node[k]] * s.g[k].transpose();
      m_.materials[P_.material[p]]->update(P_.stress[p], P_.strain[p], L, dts);
    }
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
  double traction_power() const {
    double w = 0.0;
    for (const auto& t : m_.tractions) {
      const Vec<Dim> tr = t.traction * t.time_function(time_);
      for (std::size_t j = 0; j < t.particles.size(); ++j) w += t.face_area[j] * tr.dot(P_.v[t.particles[j]]);
    }
    if (m_.gravity.squaredNorm() > 0.0)
      w += deterministic_sum(P_.size(), [&](std::size_t p) { return P_.mass[p] * m_.gravity.dot(P_.v[p]); });
    return w;
  }

  Model<Dim>& m_;
  Particles<Dim>& P_;
  const GridGeometry<Dim>& G_;
  std::array<std::size_t, Dim> stride_;
  double inv_h_;
  GridFields<Dim> grid_;
  std::vector<Vec<Dim>> gvel_, gacc_, dx_;
  StripOrder<Dim> order_;
  SchemeTraits traits_;
  double time_ = 0.0, external_work_ = 0.0;
  long step_ = 0;
};

}  // namespace

template <int Dim>
std::unique_ptr<Stepper<Dim>> make_stepper(Model<Dim>& model) {
  switch (model.shape_function) {
    case ShapeFunctionKind::Linear: return std::make_unique<MpmStepper<Dim, LinearShape>>(model);
    case ShapeFunctionKind::UGimp: return std::make_unique<MpmStepper<Dim, UGimpShape>>(model);
  }
  return nullptr;
}

template std::unique_ptr<Stepper<2>> make_stepper<2>(Model<2>&);
template std::unique_ptr<Stepper<3>> make_stepper<3>(Model<3>&);

}  // namespace cleave
