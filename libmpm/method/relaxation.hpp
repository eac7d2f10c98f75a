// Dynamic relaxation to a static state, for any method with kinetic damping (scene key "static"):
// the damping is kept critical for the body's lowest mode, and the run ends once the state stops
// changing.
//
// The lowest mode's frequency comes from the Rayleigh quotient of the current displacement,
// omega^2 = 2 U / sum_p m_p |u_p|^2 (U the strain energy): under a static load the displacement
// converges to the static deflection, whose quotient is close to (and not below) the lowest
// stretching or bending mode's omega^2 that it is made of; kappa = 2 omega would damp that mode
// critically (a = -kappa v; kDampingRatio below). The quotient needs the body held against rigid motion (supports, or loads in
// balance): a rigid drift carries no strain energy and would read omega low.
//
// Static when, at a check, the mean strain energy U of the last half period (pi / omega of the lowest
// mode) differs from that of the half period before by less than tol U, and the kinetic energy is
// below tol U. The lowest mode, about critically damped, creeps to the static state: a remaining
// fraction e of its amplitude moves U by about 2 e, and the two means by about that, so e < tol / 2;
// a swing of that mode moves the halves' means apart by 4/pi of its amplitude in U (two checks a whole
// period apart could meet at the same U). Means, not extremes: MPM's cell-crossing noise and crack
// contact keep U fluctuating by about 1e-4 of itself (the DCB) with no trend. The kinetic guard is
// loose on purpose: higher modes are under-damped and that noise keeps a kinetic energy of 1e-6 to
// 1e-4 U that carries almost no displacement.
// J, and so K^2, are quadratic in the displacement like U: K then has about tol / 2 relative error.
#pragma once
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <algorithm>
#include <deque>
#include <sstream>
#include <string>
#include <utility>

#include "libmpm/core/parallel.hpp"
#include "libmpm/method/state_io.hpp"

namespace cleave {

class Relaxation {
 public:
  static constexpr long kCheckEvery = 10;  // steps between checks (three global sums each)
  // The Rayleigh quotient bounds the lowest frequency from above (37 against 34 /ms in the cracked
  // strip), and an over-damped mode creeps: kappa = 2 x 0.9 omega_R keeps the lowest mode near
  // critical (a damping ratio of 0.9 when omega_R is exact: 0.15 % overshoot).
  static constexpr double kDampingRatio = 0.9;

  explicit Relaxation(double tolerance) : tol_(tolerance) {}
  bool due(long step) const { return step % kCheckEvery == 0; }

  // A check at time t with the strain energy U, kinetic energy K and sum m |u|^2; returns the
  // damping coefficient to use from now on.
  double check(double t, double U, double K, double mu2) {
    if (U > 0 && mu2 > 0) omega_ = std::sqrt(2 * U / mu2);
    kappa_ = 2 * kDampingRatio * omega_;
    history_.push_back({t, U});
    // One period of history, compared as two halves.
    const double period = omega_ > 0 ? 2 * 3.14159265358979323846 / omega_ : INFINITY;
    while (history_.size() > 2 && t - history_[1].first >= period) history_.pop_front();
    const bool spanned = omega_ > 0 && t - history_.front().first >= period;
    double sum[2] = {0, 0};
    int count[2] = {0, 0};
    for (const auto& [th, Uh] : history_) {
      const int half = th >= t - 0.5 * period;
      sum[half] += Uh, ++count[half];
    }
    change_ = (U > 0 && count[0] && count[1]) ? std::fabs(sum[1] / count[1] - sum[0] / count[0]) / U : INFINITY;
    kinetic_ratio_ = U > 0 ? K / U : INFINITY;
    reached_ = spanned && kinetic_ratio_ <= tol_ && change_ <= tol_;
    if (reached_ && reached_at_ < 0) reached_at_ = t;
    return kappa_;
  }
  // The same with sum m |u|^2 taken over a method's points (arrays `mass` and `u`), in a fixed order.
  template <class Points>
  double check(double t, double U, double K, const Points& P) {
    return check(t, U, K, deterministic_sum(P.mass.size(), [&](std::size_t q) { return P.mass[q] * P.u[q].squaredNorm(); }));
  }
  bool reached() const { return reached_; }
  double kappa() const { return kappa_; }
  double omega() const { return omega_; }
  double tolerance() const { return tol_; }
  // Where the relaxation stands, for messages: "U changed 3.1e-03 over a period, K/U 2.0e-05".
  std::string state() const {
    std::ostringstream s;
    s.precision(2);
    s << std::scientific << "mean strain energy of the last half period differs from the one before by " << change_ << " of itself, kinetic/strain "
      << kinetic_ratio_ << " (tolerance " << tol_ << " for both); lowest mode "
      << omega_ << " rad/s, damping " << kappa_ << " 1/s";
    return s.str();
  }

  void save(StateWriter& w) const {
    w.value(omega_), w.value(kappa_), w.value(change_), w.value(kinetic_ratio_), w.value(reached_at_);
    w.value(static_cast<int>(reached_));
    w.value(static_cast<uint64_t>(history_.size()));
    for (const auto& [t, U] : history_) w.value(t), w.value(U);
  }
  void load(StateReader& r) {
    int reached = 0;
    r.value(omega_), r.value(kappa_), r.value(change_), r.value(kinetic_ratio_), r.value(reached_at_), r.value(reached);
    reached_ = reached != 0;
    uint64_t n = 0;
    r.value(n);
    if (n > 1000000) throw std::runtime_error(r.file() + ": checkpoint's relaxation history is corrupt");
    history_.resize(n);
    for (auto& [t, U] : history_) r.value(t), r.value(U);
  }

 private:
  double tol_;
  double omega_ = 0, kappa_ = 0, change_ = INFINITY, kinetic_ratio_ = INFINITY, reached_at_ = -1;
  bool reached_ = false;
  std::deque<std::pair<double, double>> history_;  // (t, U) at the checks of the last period
};

}  // namespace cleave
