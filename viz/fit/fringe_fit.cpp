#include "viz/fit/fringe_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>

namespace cleave::viz {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;
const double kRoot2Pi = std::sqrt(2 * std::numbers::pi);

// The unknowns, scaled so that each is of order one: a coefficient of term n is stored in fringe
// orders at the points' largest radius R (A_n = q S R^(1 - n/2), S = f_sigma / t), the tip offset
// in units of R, the direction change in radians.
struct Layout {
  int terms = 0;
  bool tip = false, angle = false;
  double S = 0, R = 0, X0 = 0, Y0 = 0, A0 = 0;
  int size() const { return terms + (terms - 1) + (tip ? 2 : 0) + (angle ? 1 : 0); }
  // Index of B_n in q (n = 1 or n >= 3).
  int b_index(int n) const { return terms + (n == 1 ? 0 : n - 2); }
  double coefficient_scale(int n) const { return S * std::pow(R, 1.0 - 0.5 * n); }
  TipField field(const VectorXd& q) const {
    TipField f;
    f.a.assign(terms, 0.0), f.b.assign(terms, 0.0);
    for (int n = 1; n <= terms; ++n) {
      f.a[n - 1] = q[n - 1] * coefficient_scale(n);
      if (n != 2) f.b[n - 1] = q[b_index(n)] * coefficient_scale(n);
    }
    int k = 2 * terms - 1;
    f.x0 = X0, f.y0 = Y0, f.alpha = A0;
    if (tip) f.x0 += q[k] * R, f.y0 += q[k + 1] * R, k += 2;
    if (angle) f.alpha += q[k];
    return f;
  }
};

double residuals(const Layout& L, const VectorXd& q, const std::vector<FringePoint>& pts, VectorXd& e) {
  const TipField f = L.field(q);
  for (std::size_t k = 0; k < pts.size(); ++k) e[k] = f.stress_difference(pts[k].x, pts[k].y) / L.S - pts[k].N;
  return e.squaredNorm();
}

void jacobian(const Layout& L, const VectorXd& q, const std::vector<FringePoint>& pts, MatrixXd& J) {
  VectorXd ep(pts.size()), em(pts.size());
  for (int j = 0; j < q.size(); ++j) {
    const double h = 1e-6 * std::max(1.0, std::abs(q[j]));
    VectorXd qp = q, qm = q;
    qp[j] += h, qm[j] -= h;
    residuals(L, qp, pts, ep);
    residuals(L, qm, pts, em);
    J.col(j) = (ep - em) / (2 * h);
  }
}

struct Solution {
  VectorXd q;
  double rss = std::numeric_limits<double>::infinity();
  int iterations = 0;
  bool converged = false;
};

Solution levenberg_marquardt(const Layout& L, VectorXd q, const std::vector<FringePoint>& pts, int max_it) {
  const std::size_t m = pts.size();
  VectorXd e(m), e_try(m);
  MatrixXd J(m, q.size());
  Solution s;
  double rss = residuals(L, q, pts, e), lambda = 1e-3;
  for (int it = 1; it <= max_it; ++it) {
    s.iterations = it;
    if (!std::isfinite(rss)) break;
    if (rss <= 1e-26 * double(m)) { s.converged = true; break; }  // exact data, fitted exactly
    jacobian(L, q, pts, J);
    const MatrixXd A = J.transpose() * J;
    const VectorXd g = J.transpose() * e;
    bool accepted = false;
    double drop = 0, step = 0;
    while (lambda < 1e16) {
      MatrixXd M = A;
      for (int j = 0; j < q.size(); ++j) M(j, j) += lambda * std::max(A(j, j), 1e-12);
      const VectorXd d = M.ldlt().solve(-g);
      const VectorXd qt = q + d;
      const double rt = residuals(L, qt, pts, e_try);
      if (std::isfinite(rt) && rt < rss) {
        drop = rss - rt, step = d.norm();
        q = qt, e = e_try, rss = rt, accepted = true;
        lambda = std::max(lambda / 3, 1e-12);
        break;
      }
      lambda *= 4;
    }
    // No downhill step at any damping: a stationary point (to round-off) when the gradient is small.
    if (!accepted) { s.converged = g.norm() <= 1e-8 * std::max(1.0, std::sqrt(rss)) * std::sqrt(double(m)); break; }
    // Converged when an iteration no longer changes the sum (1e-10 of it: the numerical Jacobian's
    // differences are good to about 1e-10) or the unknowns (1e-9 of their size).
    if (drop <= 1e-10 * rss || step <= 1e-9 * (1 + q.norm())) { s.converged = true; break; }
  }
  s.q = q, s.rss = rss;
  return s;
}

std::string unit_of_term(int n) {
  const int twice = 2 - n;  // m^(twice / 2)
  if (twice == 0) return "Pa";
  if (twice % 2 == 0) return "Pa m^" + std::to_string(twice / 2);
  return "Pa m^" + std::string(twice < 0 ? "-" : "") + std::to_string(std::abs(twice) / 2) + ".5";
}

}  // namespace

const FitParameter& FringeFitResult::parameter(const std::string& name) const {
  for (const auto& p : parameters)
    if (p.name == name) return p;
  throw std::out_of_range("no fitted parameter '" + name + "'");
}

FringeFitResult fit_fringe_orders(const std::vector<FringePoint>& pts, const FringeFitOptions& o) {
  if (o.terms < 1 || o.terms > 8) throw std::invalid_argument("the number of Williams terms must be 1 to 8");
  if (!(o.fringe_constant > 0)) throw std::invalid_argument("the fringe constant must be positive");
  if (!(o.thickness > 0)) throw std::invalid_argument("the thickness must be positive");
  Layout L;
  L.terms = o.terms, L.tip = o.fit_tip, L.angle = o.fit_angle;
  L.S = o.fringe_constant / o.thickness, L.X0 = o.x0, L.Y0 = o.y0, L.A0 = o.alpha;
  const int p = L.size();
  if (int(pts.size()) <= p)
    throw std::invalid_argument("the fit has " + std::to_string(p) + " unknowns and needs more points than that (got " +
                                std::to_string(pts.size()) + ")");
  const double c = std::cos(o.alpha), s = std::sin(o.alpha);
  std::vector<double> K_guess, N_abs;
  for (std::size_t k = 0; k < pts.size(); ++k) {
    const auto& q = pts[k];
    if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.N))
      throw std::invalid_argument("point " + std::to_string(k + 1) + " is not finite");
    const double u = c * (q.x - o.x0) + s * (q.y - o.y0), v = -s * (q.x - o.x0) + c * (q.y - o.y0);
    const double r = std::hypot(u, v);
    L.R = std::max(L.R, r);
    if (r <= 0) throw std::invalid_argument("point " + std::to_string(k + 1) + " lies on the crack tip");
    const double sn = std::abs(std::sin(std::atan2(v, u)));
    if (sn > 0.3) K_guess.push_back(std::abs(q.N) * L.S * std::sqrt(2 * std::numbers::pi * r) / sn);
    N_abs.push_back(std::abs(q.N));
  }
  auto median = [](std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  double K0 = median(K_guess);
  if (!(K0 > 0)) K0 = median(N_abs) * L.S * std::sqrt(2 * std::numbers::pi * L.R);
  if (!(K0 > 0)) throw std::invalid_argument("every point has fringe order 0: nothing to fit");
  const double q1 = K0 / kRoot2Pi / L.coefficient_scale(1), qT = median(N_abs) / 4;

  // Several starts: the fringe field's minima are not unique in the split and in T.
  Solution best;
  for (double kii : {0.0, 0.5, -0.5})
    for (double t : {0.0, 1.0, -1.0}) {
      if (o.terms < 2 && t != 0) continue;
      VectorXd q0 = VectorXd::Zero(p);
      q0[0] = q1;
      q0[L.b_index(1)] = -kii * q1;
      if (o.terms >= 2) q0[1] = t * qT;
      Solution sol = levenberg_marquardt(L, q0, pts, o.max_iterations);
      if (std::isfinite(sol.rss) && (sol.rss < best.rss * (1 - 1e-12) || (!best.converged && sol.converged && sol.rss <= best.rss)))
        best = sol;
    }
  if (!best.converged || !std::isfinite(best.rss))
    throw FitNotConverged("the fringe-order fit did not converge in " + std::to_string(o.max_iterations) +
                          " iterations (RMS residual " + std::to_string(std::sqrt(best.rss / double(pts.size()))) +
                          " fringe orders): check the tip position and the points' orders");

  VectorXd q = best.q;
  if (L.field(q).a[0] < 0)  // the same fringes: report K_I >= 0
    for (int j = 0; j < 2 * o.terms - 1; ++j) q[j] = -q[j];

  FringeFitResult res;
  res.field = L.field(q);
  res.iterations = best.iterations;
  const std::size_t m = pts.size();
  VectorXd e(m);
  const double rss = residuals(L, q, pts, e);
  MatrixXd J(m, p);
  jacobian(L, q, pts, J);
  const MatrixXd A = J.transpose() * J;
  Eigen::SelfAdjointEigenSolver<MatrixXd> eig(A);
  const auto& ev = eig.eigenvalues();
  res.degrees_of_freedom = int(m) - p;
  std::vector<std::string> names;
  for (int n = 1; n <= o.terms; ++n) names.push_back(n == 1 ? "K_I" : n == 2 ? "T" : "A_" + std::to_string(n));
  for (int n = 1; n <= o.terms; ++n)
    if (n != 2) names.push_back(n == 1 ? "K_II" : "B_" + std::to_string(n));
  if (o.fit_tip) names.push_back("x0"), names.push_back("y0");
  if (o.fit_angle) names.push_back("alpha");
  if (!(ev[0] > 1e-13 * ev[p - 1])) {
    // The unknown with the largest share of the null direction is the one the points leave open.
    Eigen::Index worst = 0;
    eig.eigenvectors().col(0).cwiseAbs().maxCoeff(&worst);
    throw std::invalid_argument("the points do not determine " + names[std::size_t(worst)] +
                                ": spread them round the tip (both sides of the crack line, several radii)");
  }
  const double s2 = res.degrees_of_freedom > 0 ? rss / res.degrees_of_freedom : 0.0;
  const MatrixXd cov = s2 * A.inverse();
  auto se = [&](int j) { return std::sqrt(std::max(0.0, cov(j, j))); };
  for (int n = 1; n <= o.terms; ++n) {
    const double k = L.coefficient_scale(n), f = n == 1 ? kRoot2Pi : n == 2 ? 4.0 : 1.0;
    res.parameters.push_back({names[std::size_t(n - 1)], unit_of_term(n), f * q[n - 1] * k, f * se(n - 1) * k});
  }
  for (int n = 1; n <= o.terms; ++n) {
    if (n == 2) continue;
    const int j = L.b_index(n);
    const double k = L.coefficient_scale(n), f = n == 1 ? -kRoot2Pi : 1.0;
    res.parameters.push_back({n == 1 ? "K_II" : "B_" + std::to_string(n), unit_of_term(n), f * q[j] * k, std::abs(f) * se(j) * k});
  }
  // K_I, K_II, T first: the order users read them in.
  std::stable_sort(res.parameters.begin(), res.parameters.end(), [](const FitParameter& a, const FitParameter& b) {
    auto rank = [](const std::string& n) { return n == "K_I" ? 0 : n == "K_II" ? 1 : n == "T" ? 2 : 3; };
    return rank(a.name) < rank(b.name);
  });
  int k = 2 * o.terms - 1;
  if (o.fit_tip) {
    res.parameters.push_back({"x0", "m", res.field.x0, se(k) * L.R});
    res.parameters.push_back({"y0", "m", res.field.y0, se(k + 1) * L.R});
    k += 2;
  }
  if (o.fit_angle) res.parameters.push_back({"alpha", "rad", res.field.alpha, se(k)});

  res.model_N.resize(m), res.residual.resize(m);
  std::map<double, std::pair<std::size_t, double>> by_order;
  for (std::size_t i = 0; i < m; ++i) {
    res.residual[i] = e[Eigen::Index(i)];
    res.model_N[i] = pts[i].N + res.residual[i];
    auto& b = by_order[pts[i].N];
    ++b.first, b.second += res.residual[i] * res.residual[i];
  }
  for (const auto& [N, b] : by_order) res.orders.push_back({N, b.first, std::sqrt(b.second / double(b.first))});
  res.rms = std::sqrt(rss / double(m));
  return res;
}

IrwinEstimate irwin_from_apogee(double N, double r_m, double th, double f, double t) {
  // dG/dtheta = 0 at the apogee gives sigma_ox = -q s; the loop equation then gives s.
  const double sn = std::sin(th), cs = std::cos(th), s3 = std::sin(1.5 * th), c3 = std::cos(1.5 * th);
  const double q = sn * cs / (cs * s3 + 1.5 * sn * c3);
  const double c = N * f / t;
  const double s = c / std::sqrt(sn * sn - 2 * q * sn * s3 + q * q);
  return {N, r_m, th, s * std::sqrt(2 * std::numbers::pi * r_m), -q * s};
}

std::vector<IrwinEstimate> irwin_two_point(const std::vector<FringePoint>& pts, double x0, double y0, double alpha,
                                           double f, double t) {
  const double c = std::cos(alpha), s = std::sin(alpha), lo = 20 * std::numbers::pi / 180, hi = 160 * std::numbers::pi / 180;
  std::map<double, std::array<std::vector<std::pair<double, double>>, 2>> loops;  // order -> side -> (theta, r)
  for (const auto& p : pts) {
    const double u = c * (p.x - x0) + s * (p.y - y0), v = -s * (p.x - x0) + c * (p.y - y0);
    const double th = std::atan2(v, u), a = std::abs(th);
    if (a < lo || a > hi || p.N <= 0) continue;
    loops[p.N][th > 0 ? 0 : 1].push_back({a, std::hypot(u, v)});
  }
  // The points' outer radius: a loop whose farthest point reaches it is cut off, not closed.
  double r_out = 0;
  for (const auto& p : pts) r_out = std::max(r_out, std::hypot(p.x - x0, p.y - y0));
  std::vector<IrwinEstimate> out;
  for (auto& [N, sides] : loops) {
    auto& raw = sides[0].size() >= sides[1].size() ? sides[0] : sides[1];
    // The loop's outer edge per 2 degrees of angle: a fringe read from a photo is a band of pixels.
    std::map<int, std::pair<double, double>> bins;
    for (const auto& [th, r] : raw) {
      auto& b = bins[int(std::floor(th * 90 / std::numbers::pi))];
      if (r > b.second) b = {th, r};
    }
    std::vector<std::pair<double, double>> side;
    for (const auto& [k, b] : bins) side.push_back(b);
    if (side.size() < 3) continue;
    std::sort(side.begin(), side.end());
    std::size_t i = 0;
    for (std::size_t j = 1; j < side.size(); ++j)
      if (side[j].second > side[i].second) i = j;
    if (i == 0 || i + 1 == side.size()) continue;  // the apogee is not bracketed by the points
    if (side[i].second >= 0.97 * r_out) continue;  // the loop leaves the points' range
    // Vertex of the parabola through the three points round the farthest.
    const double x1 = side[i - 1].first, x2 = side[i].first, x3 = side[i + 1].first;
    const double y1 = side[i - 1].second, y2 = side[i].second, y3 = side[i + 1].second;
    const double d = (x1 - x2) * (x1 - x3) * (x2 - x3);
    const double A = (x3 * (y2 - y1) + x2 * (y1 - y3) + x1 * (y3 - y2)) / d;
    const double B = (x3 * x3 * (y1 - y2) + x2 * x2 * (y3 - y1) + x1 * x1 * (y2 - y3)) / d;
    double th = x2, r = y2;
    if (A < 0) {
      th = std::clamp(-B / (2 * A), x1, x3);
      r = y1 + A * (th * th - x1 * x1) + B * (th - x1);
    }
    // A vertex well beyond the farthest point: the loop runs out of the points' range (cut off, not closed).
    if (r > 1.05 * y2) continue;
    out.push_back(irwin_from_apogee(N, r, th, f, t));
  }
  return out;
}

}  // namespace cleave::viz
