// The PEM force between two particles as a function of their distance (seed 004 §2.5, figures 4
// and 5; docs/pem.md): repulsive below the balance distance, attractive above it, zero once the
// pair has broken. Stretch eps = (r - l0) / l0 on the reference length l0.
//
// Elastic law: slope k (N/m) from eps = -inf to the peak eps_p, then a second slope falling linearly
// to zero force at the cutoff eps_c (eps_c == eps_p: brittle, one slope); beyond eps_c the pair breaks
// for good. Plastic law: the balance length b shifts once |f - back force| exceeds the yield force
// (1D return mapping, linear kinematic hardening H), and the pair breaks when the total stretch
// passes eps_c. A broken pair closer than its balance length repels with slope k and carries
// Coulomb friction across the line of the pair (the caller adds the friction).
#pragma once
#include <cmath>
#include <cstdint>

namespace cleave::pem {

// What a material gives every pair of its elements (per unit stretch, per the pair's l0).
struct PairLaw {
  double eps_peak = INFINITY;  // stretch at the peak attraction
  double eps_cut = INFINITY;   // stretch at the cutoff distance (>= eps_peak)
  double eps_yield = INFINITY; // plastic: yield stretch (force k l0 eps_yield); inf: elastic law
  double hardening = 0.0;      // plastic: H / k (linear kinematic hardening), >= 0
  bool plastic() const { return std::isfinite(eps_yield); }
};

// The axial force (positive: attraction) of an intact elastic pair at elongation dl = r - l0.
inline double elastic_force(double k, double l0, double dl, const PairLaw& law) {
  const double eps = dl / l0;
  if (eps <= law.eps_peak) return k * dl;
  // Softening branch: from k l0 eps_p at eps_p down to 0 at eps_c.
  return k * l0 * law.eps_peak * (law.eps_cut - eps) / (law.eps_cut - law.eps_peak);
}

// Plastic return mapping: given the balance length b and back force alpha of the last converged
// state, the force at distance r and the updated b, alpha (written to b_out, alpha_out).
inline double plastic_force(double k, double l0, double r, const PairLaw& law, double b, double alpha,
                            double& b_out, double& alpha_out) {
  const double fy = k * l0 * law.eps_yield;
  const double H = law.hardening * k;
  const double trial = k * (r - b);
  const double over = std::fabs(trial - alpha) - fy;
  if (over <= 0.0) {
    b_out = b, alpha_out = alpha;
    return trial;
  }
  const double sign = trial - alpha > 0.0 ? 1.0 : -1.0;
  const double dlam = over / (k + H);  // plastic elongation increment
  b_out = b + sign * dlam;
  alpha_out = alpha + sign * H * dlam;
  return trial - sign * k * dlam;
}

}  // namespace cleave::pem

namespace cleave::pem {

// Energy stored in an intact elastic pair at elongation dl (the integral of elastic_force).
inline double elastic_energy(double k, double l0, double dl, const PairLaw& law) {
  const double eps = dl / l0;
  if (eps <= law.eps_peak) return 0.5 * k * dl * dl;
  const double ep = law.eps_peak, ec = law.eps_cut, kl2 = k * l0 * l0;
  const double e = std::min(eps, ec);
  return 0.5 * kl2 * ep * ep + kl2 * ep * ((ec - ep) * (ec - ep) - (ec - e) * (ec - e)) / (2.0 * (ec - ep));
}

}  // namespace cleave::pem
