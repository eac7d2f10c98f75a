#include "libmpm/pem/pem_solver.hpp"

#include <algorithm>
#include <cmath>

#include "libmpm/core/parallel.hpp"
#include "libmpm/method/prescribed_motion.hpp"

namespace cleave::pem {

template <int Dim>
PemSolver<Dim>::PemSolver(PemSystem<Dim>& m) : m_(m) {
  auto& P = m_.points;
  const std::size_t n = P.x0.size();
  parallel_ = worth_parallel(n);
  plastic_ = !m_.pairs.b.empty();
  a_next_.resize(n), fint_.assign(n, Vec<Dim>::Zero()), fint_next_.assign(n, Vec<Dim>::Zero()), fext_.assign(n, Vec<Dim>::Zero());
  breaks_.assign(n, 0);
  intact_next_ = m_.pairs.intact;
  if (plastic_) b_next_ = m_.pairs.b, alpha_next_ = m_.pairs.alpha;
  std::vector<uint8_t> loaded(n, m_.gravity.squaredNorm() > 0 ? 1 : 0);
  for (const auto& ld : m_.loads)
    for (int32_t p : ld.nodes) loaded[p] = 1;
  for (std::size_t p = 0; p < n; ++p) {
    if (loaded[p]) loaded_.push_back(static_cast<int32_t>(p));
    if (P.fixed[p]) fixed_.push_back(static_cast<int32_t>(p));
  }
  set_loads(0.0);
  forces(m_.dt);
  commit();
  flush_denormals_on_all_threads();
}

template <int Dim>
void PemSolver<Dim>::set_loads(double t) {
  const auto& P = m_.points;
  for (int32_t p : loaded_) fext_[p] = m_.gravity * P.mass[p];
  for (const auto& ld : m_.loads) {
    const double f = ld.factor(t);
    for (std::size_t q = 0; q < ld.nodes.size(); ++q) fext_[ld.nodes[q]] += f * ld.force[q];
  }
}

template <int Dim>
std::size_t PemSolver<Dim>::forces(double dt) {
  auto& P = m_.points;
  auto& N = m_.pairs;
  const std::size_t n = P.x0.size();
  const double kappa = m_.damping, mu = m_.friction;
  const auto& mats = m_.materials;
#pragma omp parallel for schedule(static) if (parallel_)
  for (std::size_t i = 0; i < n; ++i) {
    const Vec<Dim> ui = P.u[i];
    Vec<Dim> F = Vec<Dim>::Zero();
    int64_t broke = 0;
    for (int64_t e = N.offset[i]; e < N.offset[i + 1]; ++e) {
      const auto j = static_cast<std::size_t>(N.partner[e]);
      const Vec<Dim> d = separation(e, ui, j);
      const double r = d.norm();
      if (!(r > 0.0)) {
        intact_next_[e] = N.intact[e];
        continue;
      }
      // |xi| is the stored l0 bit for bit (the same difference of the same nodes); taking it from the
      // reference vector already read saves a stream of 8 bytes per entry.
      const double l0 = Eigen::Map<const Vec<Dim>>(N.xi.data() + Dim * e).norm(), k = N.k[e];
      const PairLaw& law = mats[N.law[e]].law;
      double f = 0.0;  // along d: > 0 attraction
      bool intact = N.intact[e] != 0;
      if (intact && (r - l0) > law.eps_cut * l0) intact = false, ++broke;
      if (intact) {
        if (plastic_ && law.plastic()) f = plastic_force(k, l0, r, law, N.b[e], N.alpha[e], b_next_[e], alpha_next_[e]);
        else f = elastic_force(k, l0, r - l0, law);
      } else if (N.cut[e] >= 0) {
        // A pair cut by a pre-crack: the crack's faces touch across the crack normal n. They repel
        // with the pair's stiffness when pressed together (gap change g < 0 along n) and carry
        // Coulomb friction along the crack; sliding alone stretches or shortens the pair freely.
        const Vec<Dim> nrm = cut_direction(i, e);
        const double g = cut_gap(i, e);
        if (g < 0.0) {
          F += (k * g) * nrm;
          const Vec<Dim> vrel = P.v[j] - P.v[i];
          const Vec<Dim> vt = vrel - vrel.dot(nrm) * nrm;
          const double s = vt.norm();
          if (s > 0.0 && mu > 0.0) {
            const double mred = P.mass[i] * P.mass[j] / (P.mass[i] + P.mass[j]);
            F += (std::min(mu * k * -g, mred * s / dt) / s) * vt;
          }
        }
      } else if (r < l0) {
        // A broken pair closer than its balance distance repels, and carries Coulomb friction across
        // the line of the pair (seed 004 §2.4), capped so that it cannot reverse the relative sliding
        // within the step.
        f = k * (r - l0);
        const Vec<Dim> dir = d / r;
        const Vec<Dim> vrel = P.v[j] - P.v[i];
        const Vec<Dim> vt = vrel - vrel.dot(dir) * dir;
        const double s = vt.norm();
        if (s > 0.0 && mu > 0.0) {
          const double mred = P.mass[i] * P.mass[j] / (P.mass[i] + P.mass[j]);
          const double ft = std::min(mu * std::fabs(f), mred * s / dt);
          F += (ft / s) * vt;
        }
      }
      intact_next_[e] = intact ? 1 : 0;
      if (plastic_ && !(intact && law.plastic())) b_next_[e] = N.b[e], alpha_next_[e] = N.alpha[e];
      F += (f / r) * d;
    }
    breaks_[i] = broke;
    fint_next_[i] = F;
    a_next_[i] = (F + fext_[i]) / P.mass[i] - kappa * P.v[i];
  }
  int64_t total = 0;
  for (std::size_t i = 0; i < n; ++i) total += breaks_[i];
  return static_cast<std::size_t>(total / 2);
}


template <int Dim>
Vec<Dim> PemSolver<Dim>::cut_direction(std::size_t i, int64_t e) const {
  const auto& N = m_.pairs;
  Vec<Dim> nrm;
  for (int c = 0; c < Dim; ++c) nrm[c] = N.cut_normal[Dim * N.cut[e] + c];
  const Vec<Dim> d0 = m_.points.x0[N.partner[e]] - m_.points.x0[i];
  return nrm.dot(d0) < 0 ? Vec<Dim>(-nrm) : nrm;
}

template <int Dim>
double PemSolver<Dim>::cut_gap(std::size_t i, int64_t e) const {
  const std::size_t j = m_.pairs.partner[e];
  const Vec<Dim> d = separation(e, m_.points.u[i], j), d0 = m_.points.x0[j] - m_.points.x0[i];
  return (d - d0).dot(cut_direction(i, e));
}

template <int Dim>
void PemSolver<Dim>::commit() {
  std::swap(m_.points.a, a_next_);
  std::swap(fint_, fint_next_);
  std::swap(m_.pairs.intact, intact_next_);
  if (plastic_) std::swap(m_.pairs.b, b_next_), std::swap(m_.pairs.alpha, alpha_next_);
}

template <int Dim>
Vec<Dim> PemSolver<Dim>::kicked(std::size_t p, double h) const {
  return kicked_velocity<Dim>(m_.points, p, h);
}

template <int Dim>
double PemSolver<Dim>::load_power(double h) const {
  double w = 0.0;
  for (int32_t p : loaded_) w += fext_[p].dot(kicked(p, h));
  return add_reaction_power<Dim>(w, m_.points, fixed_, fint_, fext_);
}

template <int Dim>
void PemSolver<Dim>::step() {
  advance(m_.dt, 0);
  ++step_;
}

template <int Dim>
void PemSolver<Dim>::advance(double dt, int depth) {
  auto& P = m_.points;
  const std::size_t n = P.x0.size();
  const double h = 0.5 * dt;
  const bool may_halve = depth < m_.max_halvings;
  if (may_halve) u_save_ = P.u, v_save_ = P.v;
  const double power_old = load_power(h);
#pragma omp parallel for schedule(static) if (parallel_)
  for (std::size_t p = 0; p < n; ++p) {
    P.v[p] = kicked(p, h);
    P.u[p] += dt * P.v[p];
  }
  set_loads(time_ + dt);
  const std::size_t broke = forces(dt);
  const double limit = std::max(1.0, m_.break_limit * double(m_.pair_count));
  if (may_halve && double(broke) > limit) {
    // Too many pairs break in one step (seed 004, step 4): the step is redone in two halves.
    P.u = u_save_, P.v = v_save_;
    set_loads(time_);
    ++halved_;
    advance(h, depth + 1);
    advance(h, depth + 1);
    return;
  }
  commit();
  if (m_.damping > 0)
    damp_ += dt * m_.damping * deterministic_sum(n, [&](std::size_t p) { return P.mass[p] * P.v[p].squaredNorm(); });
  time_ += dt;
  // The reactions' power uses v_half (prescribed) and the loads' the half-step velocity: trapezoidal.
  work_ += 0.5 * dt * (power_old + load_power(0.0));
#pragma omp parallel for schedule(static) if (parallel_)
  for (std::size_t p = 0; p < n; ++p) P.v[p] = kicked(p, h);
}

template <int Dim>
std::vector<Vec<Dim>> PemSolver<Dim>::positions() const {
  const auto& P = m_.points;
  std::vector<Vec<Dim>> y(P.x0.size());
  for (std::size_t p = 0; p < y.size(); ++p) y[p] = P.x0[p] + P.u[p];
  return y;
}

template <int Dim>
typename PemSolver<Dim>::Balance PemSolver<Dim>::balance() const {
  const auto& P = m_.points;
  double r2 = 0, e2 = 0, i2 = 0, vmax = 0;
  for (std::size_t p = 0; p < P.x0.size(); ++p) {
    for (int d = 0; d < Dim; ++d) {
      if (P.fixed[p] & (1u << d)) continue;
      const double res = fint_[p][d] + fext_[p][d];
      r2 += res * res, e2 += fext_[p][d] * fext_[p][d], i2 += fint_[p][d] * fint_[p][d];
    }
    vmax = std::max(vmax, P.v[p].norm());
  }
  Balance b;
  b.residual = std::sqrt(r2);
  const double ref = std::sqrt(std::max(e2, i2));
  b.relative_residual = ref > 0 ? b.residual / ref : 0.0;
  b.max_speed = vmax;
  return b;
}

template <int Dim>
PemGlobal<Dim> PemSolver<Dim>::global_state() const {
  const auto& P = m_.points;
  const auto& N = m_.pairs;
  const std::size_t n = P.x0.size();
  PemGlobal<Dim> g;
  g.time = time_, g.step = step_, g.external_work = work_, g.damping_loss = damp_;
  g.kinetic = 0.5 * deterministic_sum(n, [&](std::size_t p) { return P.mass[p] * P.v[p].squaredNorm(); });
  g.strain = 0.5 * deterministic_sum(n, [&](std::size_t i) {
    double s = 0.0;
    for (int64_t e = N.offset[i]; e < N.offset[i + 1]; ++e) {
      const double r = separation(e, P.u[i], N.partner[e]).norm(), l0 = N.l0[e], k = N.k[e];
      const PairLaw& law = m_.materials[N.law[e]].law;
      if (N.intact[e]) {
        if (plastic_ && law.plastic()) s += 0.5 * k * (r - N.b[e]) * (r - N.b[e]);
        else s += elastic_energy(k, l0, r - l0, law);
      } else if (N.cut[e] >= 0) {
        const double g = cut_gap(i, e);
        if (g < 0.0) s += 0.5 * k * g * g;
      } else if (r < l0) {
        s += 0.5 * k * (r - l0) * (r - l0);
      }
    }
    return s;
  });
  std::size_t broken = 0;
  for (uint8_t b : N.intact) broken += b ? 0 : 1;
  g.broken = broken / 2;
  const Balance b = balance();
  g.residual = b.residual, g.relative_residual = b.relative_residual, g.max_speed = b.max_speed;
  for (int d = 0; d < Dim; ++d) g.momentum[d] = deterministic_sum(n, [&](std::size_t p) { return P.mass[p] * P.v[p][d]; });
  return g;
}

template <int Dim>
std::vector<double> PemSolver<Dim>::damage() const {
  const auto& N = m_.pairs;
  const std::size_t n = m_.points.x0.size();
  std::vector<double> phi(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const int64_t all = N.offset[i + 1] - N.offset[i];
    int64_t broken = 0;
    for (int64_t e = N.offset[i]; e < N.offset[i + 1]; ++e) broken += N.intact[e] ? 0 : 1;
    phi[i] = all > 0 ? double(broken) / double(all) : 0.0;
  }
  return phi;
}

template <int Dim>
std::vector<Sym<Dim>> PemSolver<Dim>::stress() const {
  const auto& P = m_.points;
  const auto& N = m_.pairs;
  const std::size_t n = P.x0.size();
  std::vector<Sym<Dim>> sig(n);
  const bool plane_strain = m_.analysis == Analysis::PlaneStrain;
#pragma omp parallel for schedule(static) if (parallel_)
  for (std::size_t i = 0; i < n; ++i) {
    Mat<Dim> S = Mat<Dim>::Zero();
    for (int64_t e = N.offset[i]; e < N.offset[i + 1]; ++e) {
      const Vec<Dim> d = separation(e, P.u[i], N.partner[e]);
      const double r = d.norm(), l0 = N.l0[e], k = N.k[e];
      if (!(r > 0.0)) continue;
      const PairLaw& law = m_.materials[N.law[e]].law;
      double f = 0.0;
      if (N.cut[e] >= 0 && !N.intact[e]) {
        // Contact across a pre-crack: the force k g n, along the crack normal.
        const double g = cut_gap(i, e);
        if (g < 0.0) S += (k * g) * cut_direction(i, e) * d.transpose();
        continue;
      }
      if (N.intact[e]) f = plastic_ && law.plastic() ? k * (r - N.b[e]) : elastic_force(k, l0, r - l0, law);
      else if (r < l0) f = k * (r - l0);
      S += (f / r) * d * d.transpose();
    }
    S *= 0.5 / P.volume[i];
    Sym<Dim> out;
    if constexpr (Dim == 2) {
      out << S(0, 0), S(1, 1), plane_strain ? 0.25 * (S(0, 0) + S(1, 1)) : 0.0, S(0, 1);
    } else {
      out << S(0, 0), S(1, 1), S(2, 2), S(0, 1), S(1, 2), S(0, 2);
    }
    sig[i] = out;
  }
  return sig;
}

template <int Dim>
void PemSolver<Dim>::save(StateWriter& w) const {
  const auto& P = m_.points;
  w.value(time_), w.value(step_), w.value(halved_), w.value(work_), w.value(damp_);
  w.array(P.u), w.array(P.v), w.array(P.a), w.array(fint_), w.array(m_.pairs.intact);
  if (plastic_) w.array(m_.pairs.b), w.array(m_.pairs.alpha);
}

template <int Dim>
void PemSolver<Dim>::load(StateReader& r) {
  auto& P = m_.points;
  r.value(time_), r.value(step_), r.value(halved_), r.value(work_), r.value(damp_);
  r.array(P.u, "particles"), r.array(P.v, "particles"), r.array(P.a, "particles"), r.array(fint_, "particles");
  r.array(m_.pairs.intact, "pairs");
  if (plastic_) r.array(m_.pairs.b, "pairs"), r.array(m_.pairs.alpha, "pairs");
  set_loads(time_);
}

template class PemSolver<2>;
template class PemSolver<3>;

}  // namespace cleave::pem
