#include "libmpm/pem/calibration.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace cleave::pem {

std::vector<double> nnls_normal(const std::vector<double>& Gv, const std::vector<double>& bv, int n) {
  using Eigen::MatrixXd;
  using Eigen::VectorXd;
  const Eigen::Map<const MatrixXd> G(Gv.data(), n, n);
  const Eigen::Map<const VectorXd> b(bv.data(), n);
  VectorXd a = VectorXd::Zero(n);
  std::vector<bool> passive(n, false);
  const double tol = 1e-12 * (b.cwiseAbs().maxCoeff() + 1e-300);
  auto solve_passive = [&](VectorXd& s) {
    std::vector<int> idx;
    for (int i = 0; i < n; ++i)
      if (passive[i]) idx.push_back(i);
    const int m = static_cast<int>(idx.size());
    MatrixXd Gp(m, m);
    VectorXd bp(m);
    for (int i = 0; i < m; ++i) {
      bp[i] = b[idx[i]];
      for (int j = 0; j < m; ++j) Gp(i, j) = G(idx[i], idx[j]);
    }
    // Degenerate directions (nearly parallel pairs not merged by the caller) make Gp singular: the
    // minimum-norm solution shares their part.
    const VectorXd sp = Gp.completeOrthogonalDecomposition().solve(bp);
    s.setZero();
    for (int i = 0; i < m; ++i) s[idx[i]] = sp[i];
  };
  for (int outer = 0; outer < 3 * n + 10; ++outer) {
    const VectorXd w = b - G * a;
    int j = -1;
    double best = tol;
    for (int i = 0; i < n; ++i)
      if (!passive[i] && w[i] > best) best = w[i], j = i;
    if (j < 0) break;
    passive[j] = true;
    VectorXd s(n);
    for (int inner = 0; inner < 3 * n + 10; ++inner) {
      solve_passive(s);
      bool feasible = true;
      for (int i = 0; i < n; ++i)
        if (passive[i] && s[i] <= 0.0) feasible = false;
      if (feasible) break;
      double step = 1.0;
      for (int i = 0; i < n; ++i)
        if (passive[i] && s[i] <= 0.0) step = std::min(step, a[i] / (a[i] - s[i]));
      a += step * (s - a);
      for (int i = 0; i < n; ++i)
        if (passive[i] && a[i] <= 1e-14 * (a.cwiseAbs().maxCoeff() + 1e-300)) passive[i] = false, a[i] = 0.0;
    }
    a = s;
  }
  for (int i = 0; i < n; ++i) a[i] = std::max(0.0, a[i]);
  return std::vector<double>(a.data(), a.data() + n);
}

template <int Dim>
std::vector<double> fit_element_pairs(const std::vector<Vec<Dim>>& t, double volume, double mu) {
  // Pairs along one line (a quadrangle's opposite sides) are one unknown, shared equally afterwards:
  // the active set method would otherwise give it all to one of them and leave the other slack (a
  // corner particle held by one pair is a mechanism).
  const int n = static_cast<int>(t.size());
  std::vector<int> group(n, -1);
  std::vector<int> members;
  std::vector<Vec<Dim>> dirs;
  for (int p = 0; p < n; ++p) {
    for (int g = 0; g < static_cast<int>(dirs.size()) && group[p] < 0; ++g)
      if (std::fabs(std::fabs(t[p].dot(dirs[g])) - 1.0) < 1e-9) group[p] = g;
    if (group[p] < 0) group[p] = static_cast<int>(dirs.size()), dirs.push_back(t[p]), members.push_back(0);
    ++members[group[p]];
  }
  const int m = static_cast<int>(dirs.size());
  std::vector<double> G(m * m), b(m, 3.0 * mu * volume);  // <T_p, mu I_s> = mu (1 + 1 + 1)
  for (int p = 0; p < m; ++p)
    for (int q = 0; q < m; ++q) {
      const double c = dirs[p].dot(dirs[q]);
      G[p + m * q] = c * c * c * c;
    }
  const auto ag = nnls_normal(G, b, m);
  std::vector<double> a(n);
  for (int p = 0; p < n; ++p) a[p] = ag[group[p]] / members[group[p]];
  return a;
}

template <int Dim>
void NetworkTensor<Dim>::add(const Vec<Dim>& t, double a) {
  int idx = 0;
  for (int i = 0; i < Dim; ++i)
    for (int j = 0; j < Dim; ++j)
      for (int k = 0; k < Dim; ++k)
        for (int l = 0; l < Dim; ++l) c[idx++] += a * t[i] * t[j] * t[k] * t[l];
}

template <int Dim>
void NetworkTensor<Dim>::isotropic(double& lambda, double& mu, double& anisotropy) const {
  // Basis A = delta_ij delta_kl, B = delta_ik delta_jl + delta_il delta_jk; 2x2 normal equations.
  const int N = Dim * Dim * Dim * Dim;
  std::vector<double> A(N), B(N);
  int idx = 0;
  for (int i = 0; i < Dim; ++i)
    for (int j = 0; j < Dim; ++j)
      for (int k = 0; k < Dim; ++k)
        for (int l = 0; l < Dim; ++l, ++idx) {
          A[idx] = (i == j && k == l) ? 1.0 : 0.0;
          B[idx] = (i == k && j == l ? 1.0 : 0.0) + (i == l && j == k ? 1.0 : 0.0);
        }
  double AA = 0, AB = 0, BB = 0, Ac = 0, Bc = 0, cc = 0;
  for (int q = 0; q < N; ++q) {
    const double cq = volume > 0 ? c[q] / volume : 0.0;
    AA += A[q] * A[q], AB += A[q] * B[q], BB += B[q] * B[q], Ac += A[q] * cq, Bc += B[q] * cq, cc += cq * cq;
  }
  const double det = AA * BB - AB * AB;
  lambda = (Ac * BB - Bc * AB) / det;
  mu = (AA * Bc - AB * Ac) / det;
  double rest = 0, iso = 0;
  for (int q = 0; q < N; ++q) {
    const double cq = volume > 0 ? c[q] / volume : 0.0;
    const double fit = lambda * A[q] + mu * B[q];
    rest += (cq - fit) * (cq - fit), iso += fit * fit;
  }
  anisotropy = iso > 0 ? std::sqrt(rest / iso) : 0.0;
}

void young_poisson(double lambda, double mu, bool plane_stress_2d, double& E, double& nu) {
  if (plane_stress_2d) {
    E = 4.0 * mu * (lambda + mu) / (lambda + 2.0 * mu);
    nu = lambda / (lambda + 2.0 * mu);
  } else {
    E = mu * (3.0 * lambda + 2.0 * mu) / (lambda + mu);
    nu = lambda / (2.0 * (lambda + mu));
  }
}

template std::vector<double> fit_element_pairs<2>(const std::vector<Vec<2>>&, double, double);
template std::vector<double> fit_element_pairs<3>(const std::vector<Vec<3>>&, double, double);
template struct NetworkTensor<2>;
template struct NetworkTensor<3>;

}  // namespace cleave::pem
