#include "libmpm/pd/pd_solver.hpp"

#include <cmath>

#include "libmpm/core/parallel.hpp"
#include "libmpm/method/prescribed_motion.hpp"

namespace cleave::pd {

template <int Dim>
PdSolver<Dim>::PdSolver(PdSystem<Dim>& m) : m_(m) {
  const auto& P = m_.points;
  const std::size_t n = P.size();
  parallel_ = worth_parallel(n);
  y_.resize(n);
  fext_.assign(n, Vec<Dim>::Zero());
  fint_.assign(n, Vec<Dim>::Zero());
  std::vector<uint8_t> loaded(n, 0);
  for (const auto& ld : m_.loads)
    for (int32_t p : ld.points) loaded[p] = 1;
  for (std::size_t p = 0; p < n; ++p) {
    if (loaded[p] || m_.gravity.squaredNorm() > 0) loaded_.push_back(static_cast<int32_t>(p));
    if (P.fixed[p]) fixed_.push_back(static_cast<int32_t>(p));
  }
  for (std::size_t p = 0; p < n; ++p) y_[p] = P.x0[p] + P.u[p];
  update_loads(0.0);
  forces();
  flush_denormals_on_all_threads();
}

template <int Dim>
void PdSolver<Dim>::restore(double time, long step, double work, double damping_loss) {
  time_ = time;
  step_ = step;
  work_ = work;
  damp_ = damping_loss;
  auto& P = m_.points;
  for (std::size_t p = 0; p < P.size(); ++p) y_[p] = P.x0[p] + P.u[p];
  update_loads(time_);
  for (int32_t p : fixed_) {
    // The internal force at the checkpoint, for the reaction work of the next step.
    const Vec<Dim> a = P.a[p];
    fint_[p] = P.mass[p] * a - fext_[p];
  }
}

template <int Dim>
void PdSolver<Dim>::update_loads(double t) {
  auto& P = m_.points;
  for (int32_t p : loaded_) P.b[p] = m_.gravity * (P.mass[p] / P.volume[p]);
  for (const auto& ld : m_.loads) {
    const double f = ld.factor(t);
    for (int32_t p : ld.points) P.b[p] += f * ld.force_density;
  }
  for (int32_t p : loaded_) fext_[p] = P.b[p] * P.volume[p];
}

template <int Dim>
void PdSolver<Dim>::forces() {
  auto& P = m_.points;
  auto& N = m_.nb;
  const std::size_t n = P.size();
  const Vec<Dim>* __restrict y = y_.data();
  const int64_t* __restrict off = N.offset.data();
  const int32_t* __restrict partner = N.partner.data();
  const double* __restrict r0 = N.r0.data();
  const double* __restrict stiff = N.stiff.data();
  const double* __restrict s0 = N.s0.data();
  uint8_t* __restrict intact = N.intact.data();
  const double kappa = m_.damping;
#pragma omp parallel for schedule(static) if (parallel_)
  for (std::size_t i = 0; i < n; ++i) {
    const Vec<Dim> yi = y[i];
    Vec<Dim> f = Vec<Dim>::Zero();
    for (int64_t e = off[i]; e < off[i + 1]; ++e) {
      if (!intact[e]) continue;
      const Vec<Dim> d = y[partner[e]] - yi;
      const double r = d.norm();
      const double s = (r - r0[e]) / r0[e];
      if (s > s0[e]) {
        intact[e] = 0;  // the partner's copy sees the same doubles and breaks in this step too
        continue;
      }
      f += (stiff[e] * s / r) * d;
    }
    // f is the force density (N/m^3); acceleration = (f + b) / rho - kappa v.
    const double rho = P.mass[i] / P.volume[i];
    P.a[i] = (f + P.b[i]) / rho - kappa * P.v[i];
    if (P.fixed[i]) fint_[i] = f * P.volume[i];
  }
}

template <int Dim>
void PdSolver<Dim>::step() {
  auto& P = m_.points;
  const std::size_t n = P.size();
  const double dt = m_.dt, h = 0.5 * dt;
  // Work of the external forces and of the reactions at prescribed velocities over the step:
  // trapezoidal in the force, exact in the displacement increment dt * v_half.
  const double work_old = load_power(h);

#pragma omp parallel for schedule(static) if (parallel_)
  for (std::size_t p = 0; p < n; ++p) {
    P.v[p] = kicked(p, h);
    P.u[p] += dt * P.v[p];
    y_[p] = P.x0[p] + P.u[p];
  }
  // Damping acts on the half-step velocity (a = ... - kappa v); its dissipation over the step.
  if (m_.damping > 0)
    damp_ += dt * m_.damping * deterministic_sum(n, [&](std::size_t p) { return P.mass[p] * P.v[p].squaredNorm(); });
  time_ += dt;
  ++step_;
  update_loads(time_);
  forces();
  // Both sums use v_half (v + h a_old = the half-step velocity for free points).
  work_ += 0.5 * dt * (work_old + load_power(0.0));

#pragma omp parallel for schedule(static) if (parallel_)
  for (std::size_t p = 0; p < n; ++p) P.v[p] = kicked(p, h);
}

template <int Dim>
Vec<Dim> PdSolver<Dim>::kicked(std::size_t p, double h) const {
  return kicked_velocity<Dim>(m_.points, p, h);
}

template <int Dim>
double PdSolver<Dim>::load_power(double h) const {
  const auto& P = m_.points;
  double w = 0.0;
  for (int32_t p : loaded_) w += fext_[p].dot(P.v[p] + h * P.a[p]);
  return add_reaction_power<Dim>(w, P, fixed_, fint_, fext_);
}

template <int Dim>
PdGlobal<Dim> PdSolver<Dim>::global_state() const {
  const auto& P = m_.points;
  const auto& N = m_.nb;
  PdGlobal<Dim> g;
  g.time = time_;
  g.step = step_;
  g.external_work = work_;
  g.damping_loss = damp_;
  const std::size_t n = P.size();
  g.kinetic = 0.5 * deterministic_sum(n, [&](std::size_t p) { return P.mass[p] * P.v[p].squaredNorm(); });
  // W = 1/2 sum_i V_i sum_j w(xi, eta) V_j beta, w = c s^2 |xi| / 2 (each bond appears twice).
  g.strain = deterministic_sum(n, [&](std::size_t i) {
    double s = 0.0;
    for (int64_t e = N.offset[i]; e < N.offset[i + 1]; ++e) {
      if (!N.intact[e]) continue;
      const double r = (y_[N.partner[e]] - y_[i]).norm();
      const double st = (r - N.r0[e]) / N.r0[e];
      s += 0.25 * N.stiff[e] * st * st * N.r0[e];
    }
    return s * P.volume[i];
  });
  std::size_t broken = 0;
  for (uint8_t b : N.intact) broken += b ? 0 : 1;
  g.broken = broken / 2;
  for (int d = 0; d < Dim; ++d)
    g.momentum[d] = deterministic_sum(n, [&](std::size_t p) { return P.mass[p] * P.v[p][d]; });
  return g;
}

template <int Dim>
std::vector<double> PdSolver<Dim>::damage() const {
  const auto& N = m_.nb;
  const std::size_t n = m_.points.size();
  std::vector<double> phi(n, 0.0);
#pragma omp parallel for schedule(static) if (parallel_)
  for (std::size_t i = 0; i < n; ++i) {
    double all = 0.0, kept = 0.0;
    for (int64_t e = N.offset[i]; e < N.offset[i + 1]; ++e) {
      all += N.w0[e];
      kept += N.intact[e] ? N.w0[e] : 0.0;
    }
    phi[i] = all > 0.0 ? 1.0 - kept / all : 0.0;
  }
  return phi;
}

template <int Dim>
std::vector<Sym<Dim>> PdSolver<Dim>::stress() const {
  const auto& P = m_.points;
  const auto& N = m_.nb;
  const std::size_t n = P.size();
  std::vector<Sym<Dim>> sig(n);
  const bool plane_strain = m_.analysis == Analysis::PlaneStrain;
#pragma omp parallel for schedule(static) if (parallel_)
  for (std::size_t i = 0; i < n; ++i) {
    Mat<Dim> S = Mat<Dim>::Zero();
    for (int64_t e = N.offset[i]; e < N.offset[i + 1]; ++e) {
      if (!N.intact[e]) continue;
      const std::size_t j = static_cast<std::size_t>(N.partner[e]);
      const Vec<Dim> d = y_[j] - y_[i];
      const double r = d.norm();
      const double s = (r - N.r0[e]) / N.r0[e];
      // stiff = c beta V_j: (stiff s / r) d is f_ij V_j; xi the reference bond vector.
      S += (N.stiff[e] * s / r) * d * (P.x0[j] - P.x0[i]).transpose();
    }
    S *= 0.5;
    Mat<Dim> sym = 0.5 * (S + S.transpose());
    Sym<Dim> out;
    if constexpr (Dim == 2) {
      out << sym(0, 0), sym(1, 1), plane_strain ? 0.25 * (sym(0, 0) + sym(1, 1)) : 0.0, sym(0, 1);
    } else {
      out << sym(0, 0), sym(1, 1), sym(2, 2), sym(0, 1), sym(1, 2), sym(0, 2);
    }
    sig[i] = out;
  }
  return sig;
}

template class PdSolver<2>;
template class PdSolver<3>;

}  // namespace cleave::pd
