#include "libmpm/crack/front_along_term.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

namespace cleave::crack {

double along_front_length(const TipSettings& s, double cell) {
  const double r = s.radius * cell;
  // Over the near-tip fields q = g(theta) / (distance from the front), so int_A q dA = int g(theta) R(theta)
  // dtheta, R the distance to the contour: r on the circle, r / max(|cos theta|, |sin theta|) on the
  // square, where the cos theta and cos 2 theta parts of g cancel over the four quarters and the
  // constant part gives 8 ln(1 + sqrt 2) r against the circle's 2 pi r.
  if (s.contour == TipSettings::Contour::Rectangle) return 4.0 / M_PI * std::log(1.0 + std::sqrt(2.0)) * r;
  return r;
}

std::vector<AlongFrontResult> subtract_along_front_term(const std::vector<AlongFrontNode>& nodes, bool closed,
                                                        double length, double L, double reach) {
  const std::size_t n = nodes.size();
  std::vector<AlongFrontResult> out(n);
  for (std::size_t k = 0; k < n; ++k) {
    const auto& a = nodes[k];
    const auto K = stress_intensity3(a.J1, a.cod_I, a.cod_II, a.cod_III, a.mu, a.nu);
    out[k] = {a.J1, K.KI, K.KII, K.KIII, false};
  }
  if (n < 3) return out;
  // Per node: the window's nodes and their offsets along the front, and the sign of x3 against s.
  std::vector<std::vector<std::pair<std::size_t, double>>> window(n);
  std::vector<double> sign(n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    for (std::size_t j = 0; j < n; ++j) {
      if (!nodes[j].fit) continue;
      double d = nodes[j].s - nodes[k].s;
      if (closed && length > 0.0) d -= length * std::round(d / length);
      if (std::fabs(d) <= reach) window[k].push_back({j, d});
    }
    const std::size_t prev = k > 0 ? k - 1 : (closed ? n - 1 : 0), next = k + 1 < n ? k + 1 : (closed ? 0 : n - 1);
    const double t = (nodes[next].x - nodes[prev].x).dot(nodes[k].e3);
    sign[k] = t > 0.0 ? 1.0 : (t < 0.0 ? -1.0 : 0.0);
  }
  // K_II K_III = rho J with rho fixed by the openings (K ~ sqrt J), so the corrected J solve a linear
  // system: J_k + c_k sum_j w_kj rho_j J_j = J1_k, w_kj the least-squares slope's weights over node k's
  // window (times the sign of x3 against s), c_k = L (1/8 + nu) / mu. (A fixed-point iteration of the
  // same equations diverges where the window is short against the front's radius: the slope's
  // weights grow as 1 / window.)
  std::vector<double> rho(n);
  for (std::size_t k = 0; k < n; ++k) {
    const auto& a = nodes[k];
    const auto K = stress_intensity3(1.0, a.cod_I, a.cod_II, a.cod_III, a.mu, a.nu);
    rho[k] = K.KII * K.KIII;
  }
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::VectorXd rhs(static_cast<Eigen::Index>(n));
  for (std::size_t k = 0; k < n; ++k) {
    const auto& a = nodes[k];
    rhs[Eigen::Index(k)] = a.J1;
    entries.emplace_back(Eigen::Index(k), Eigen::Index(k), 1.0);
    const auto& w = window[k];
    if (w.size() < 3 || sign[k] == 0.0) continue;
    double ms = 0.0;
    for (const auto& [j, d] : w) ms += d;
    ms /= double(w.size());
    double sxx = 0.0;
    for (const auto& [j, d] : w) sxx += (d - ms) * (d - ms);
    if (!(sxx > 0.0)) continue;
    const double c = L * (0.125 + a.nu) / a.mu * sign[k] / sxx;
    for (const auto& [j, d] : w) entries.emplace_back(Eigen::Index(k), Eigen::Index(j), c * (d - ms) * rho[j]);
    out[k].applied = true;
  }
  const auto size = static_cast<Eigen::Index>(n);
  Eigen::SparseMatrix<double> A(size, size);
  A.setFromTriplets(entries.begin(), entries.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(A);
  if (lu.info() != Eigen::Success) {  // (singular: leave J as it is)
    for (auto& o : out) o.applied = false;
    return out;
  }
  const Eigen::VectorXd J = lu.solve(rhs);
  for (std::size_t k = 0; k < n; ++k) {
    if (!out[k].applied) continue;
    const auto& a = nodes[k];
    const auto K = stress_intensity3(J[Eigen::Index(k)], a.cod_I, a.cod_II, a.cod_III, a.mu, a.nu);
    out[k] = {J[Eigen::Index(k)], K.KI, K.KII, K.KIII, true};
  }
  return out;
}

}  // namespace cleave::crack
