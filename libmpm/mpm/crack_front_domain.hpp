// J at a crack-front node by the equivalent domain integral (Shih, Moran & Nakamura 1986; the dynamic
// form of Nakamura, Shih & Freund 1985): the contour form of eq. 33 turned by the divergence theorem
// into an integral over a tube about the front, with a weight q that is 1 at the front and 0 on the
// tube's surface. For a stationary crack and q_k = q e1_k (e1: ahead of the front, in the crack's plane)
//
//   int_front J(s) psi(s) ds = int_V [ (sigma_ij u_i,k - W delta_kj) q_k,j + rho u''_i u_i,k q_k ] dV,
//
// psi the weight along the front. The kinetic energy's two terms, -T q_k,k - T,k q_k = -(T q_k),k,
// integrate to the tube's surface, where q = 0, and to the crack's faces, where q is tangent: nothing.
// Why a domain: the plane contour of eqs. 32-33 leaves out what the front's curvature and the fields'
// change along the front put into the 3D J (the out-of-plane term, taken only to first order in the
// curvature and for the near-tip fields: docs/validation.md); the domain takes both exactly, for any
// tube radius, and its integrand is read at the particles, where MPM keeps stress and strain.
//
// q = phi(r) psi(s) e1(s), r and s the distance from and the arc length along the front's polyline of
// a point's nearest point on it, is taken with its gradient in closed form at each particle
// (DomainWeight below says why not from the grid's nodes).
#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

#include "libmpm/core/types.hpp"
#include "libmpm/crack/explicit_crack.hpp"
#include "libmpm/crack/front_parameters.hpp"

namespace cleave::detail {

// A front as a polyline with its frames' e1 at the nodes, for the nearest point of x on it. An open
// end within a cell and a half of a symmetry plane that the front runs into is continued by the
// mirror image of the front's first `extent` of length (the model's mirror half): the weight q of a
// node near the plane is then the mirror-symmetric one of the whole body, and the half body's integral
// with the node's weight plus its image's is the whole body's with the node's weight.
struct FrontPolyline {
  std::vector<Vec<3>> x, e1;
  std::vector<double> s;  // arc length at each node
  bool closed = false;
  double length = 0.0;  // the whole polyline's (a closed one's includes the closing segment)
  std::size_t first = 0;       // the index of the front's node 0 (after the mirrored nodes)
  std::vector<double> planes;  // the arc lengths at which the polyline crosses a mirror plane

  FrontPolyline(const crack::ExplicitCrack<3>& c, std::size_t front,
                const std::vector<std::pair<int, double>>& symmetry_planes = {}, double cell = 0.0,
                double extent = 0.0)
      : closed(c.fronts[front].closed) {
    const auto& nodes = c.fronts[front].nodes;
    for (std::size_t k = 0; k < nodes.size(); ++k) {
      const auto f = crack::front_frame(c, front, k);
      x.push_back(f.x), e1.push_back(f.e1);
    }
    const std::size_t n = x.size();
    // Mirror nodes beyond each open end that runs into a symmetry plane near it.
    std::vector<Vec<3>> before_x, before_e1, after_x, after_e1;
    bool mirror[2] = {false, false}, on[2] = {false, false};
    if (!closed && n >= 2)
      for (int end = 0; end < 2; ++end) {
        const std::size_t e = end == 0 ? 0 : n - 1, in = end == 0 ? 1 : n - 2;
        const Vec<3> t = (x[e] - x[in]).normalized();
        const std::pair<int, double>* nearest_plane = nullptr;  // (the nearest of those within reach)
        for (const auto& plane : symmetry_planes) {
          const double d = std::fabs(x[e][plane.first] - plane.second);
          if (d <= 1.5 * cell && std::fabs(t[plane.first]) >= 0.5 &&
              (!nearest_plane || d < std::fabs(x[e][nearest_plane->first] - nearest_plane->second)))
            nearest_plane = &plane;
        }
        if (nearest_plane) {
          const auto [axis, position] = *nearest_plane;
          mirror[end] = true, on[end] = std::fabs(x[e][axis] - position) <= 1e-6 * cell;
          auto& mx = end == 0 ? before_x : after_x;
          auto& me = end == 0 ? before_e1 : after_e1;
          double run = 0.0;
          for (std::size_t i = 0; i < n && run <= extent; ++i) {
            const std::size_t k = end == 0 ? i : n - 1 - i;
            if (i > 0) run += (x[k] - x[end == 0 ? k - 1 : k + 1]).norm();
            if (i == 0 && on[end]) continue;
            Vec<3> px = x[k], pe = e1[k];
            px[axis] = 2.0 * position - px[axis], pe[axis] = -pe[axis];
            mx.push_back(px), me.push_back(pe);
          }
        }
      }
    std::reverse(before_x.begin(), before_x.end()), std::reverse(before_e1.begin(), before_e1.end());
    first = before_x.size();
    x.insert(x.begin(), before_x.begin(), before_x.end()), e1.insert(e1.begin(), before_e1.begin(), before_e1.end());
    x.insert(x.end(), after_x.begin(), after_x.end()), e1.insert(e1.end(), after_e1.begin(), after_e1.end());
    s.assign(x.size(), 0.0);
    for (std::size_t k = 1; k < x.size(); ++k) s[k] = s[k - 1] + (x[k] - x[k - 1]).norm();
    length = s.empty() ? 0.0 : s.back() + (closed && x.size() > 1 ? (x.front() - x.back()).norm() : 0.0);
    // Where each mirror plane crosses: at the end node on it, or half-way to its image.
    if (mirror[0]) planes.push_back(on[0] ? s[first] : 0.5 * (s[first - 1] + s[first]));
    const std::size_t last = first + n - 1;
    if (mirror[1]) planes.push_back(on[1] ? s[last] : 0.5 * (s[last] + s[last + 1]));
  }
  // The arc length of the front's node k.
  double node_s(std::size_t k) const { return s[first + k]; }
  // The nearest point of the polyline to p: arc length s, distance r, the direction from it to p
  // (unit; zero at r = 0), the gradient of s (the segment's direction inside it, zero about a
  // vertex), e1 interpolated there and its rate along the front.
  struct Near {
    double s = 0.0, r = INFINITY;
    Vec<3> away = Vec<3>::Zero(), grad_s = Vec<3>::Zero(), e1 = Vec<3>::Zero(), de1_ds = Vec<3>::Zero();
  };
  // Among the segments that meet the arc lengths [lo, hi] only (an open polyline's; a closed one's
  // are all searched).
  Near nearest(const Vec<3>& p, double lo = -INFINITY, double hi = INFINITY) const {
    Near best;
    const std::size_t n = x.size(), segments = closed ? n : (n > 0 ? n - 1 : 0);
    if (n == 1) best = {s[0], (p - x[0]).norm(), Vec<3>::Zero(), Vec<3>::Zero(), e1[0], Vec<3>::Zero()};
    std::size_t at = 0, k0 = 0, k1 = segments;
    if (!closed && segments > 0) {  // segment k spans [s[k], s[k + 1]]
      k0 = std::min(segments - 1, static_cast<std::size_t>(std::max<std::ptrdiff_t>(
                                      0, std::upper_bound(s.begin(), s.end(), lo) - s.begin() - 1)));
      k1 = std::min<std::size_t>(segments, static_cast<std::size_t>(std::lower_bound(s.begin(), s.end(), hi) - s.begin()));
      k1 = std::max(k1, k0 + 1);
    }
    double at_t = 0.0;
    for (std::size_t k = k0; k < k1; ++k) {
      const std::size_t l = (k + 1) % n;
      const Vec<3> d = x[l] - x[k];
      const double len2 = d.squaredNorm();
      const double t = len2 > 0.0 ? std::clamp((p - x[k]).dot(d) / len2, 0.0, 1.0) : 0.0;
      const double r = (p - x[k] - t * d).norm();
      if (r < best.r) best.r = r, best.s = s[k] + t * std::sqrt(len2), at = k, at_t = t;
    }
    if (segments == 0) return best;
    const std::size_t l = (at + 1) % n;
    const Vec<3> d = x[l] - x[at];
    const double len = d.norm();
    const Vec<3> foot = x[at] + at_t * d;
    if (best.r > 0.0) best.away = (p - foot) / best.r;
    const Vec<3> e = (1.0 - at_t) * e1[at] + at_t * e1[l];
    best.e1 = e.normalized();
    if (at_t > 0.0 && at_t < 1.0 && len > 0.0) {
      best.grad_s = d / len;
      const Vec<3> de = (e1[l] - e1[at]) / len;  // d e / ds; of the unit vector: its part normal to it
      best.de1_ds = (de - best.e1 * best.e1.dot(de)) / e.norm();
    }
    return best;
  }
  // Arc length from s0 to s1 (signed; the shorter way round a closed front).
  double along(double s0, double s1) const {
    double d = s1 - s0;
    if (closed && length > 0.0) d -= length * std::round(d / length);
    return d;
  }
  // int psi ds over the polyline for the weight psi = b(|s - s_j| / L) about the arc length s_j.
  double psi_integral(double sj, double L) const {
    if (closed) return std::min(L, 0.5 * length);  // (a weight longer than the loop: not a use case)
    const double before = std::min(L, sj), after = std::min(L, s.back() - sj);
    const auto part = [&](double a) {  // int_0^a b(t / L) dt
      const double u = a / L;
      return L * (u - u * u * u * u * (2.5 - u * (3.0 - u)));
    };
    return part(before) + part(after);
  }
};

// b(u) = 1 - 10 u^3 + 15 u^4 - 6 u^5 on [0, 1] (1 at 0, 0 at 1, with zero slope and curvature at both),
// and its derivative.
inline double smooth_step(double u) {
  return u <= 0.0 ? 1.0 : u >= 1.0 ? 0.0 : 1.0 - u * u * u * (10.0 - u * (15.0 - 6.0 * u));
}
inline double smooth_step_slope(double u) { return u <= 0.0 || u >= 1.0 ? 0.0 : -30.0 * u * u * (1.0 - u) * (1.0 - u); }

// The weights of the domain about front node j: the tube of radius R (q = 1 within R_in of the front,
// falling to 0 at R) and psi along the front (1 at the node, 0 at L from it), both smooth steps b, so
// that q's gradient is continuous: the particles' midpoint rule then sums it without the error of
// where a lattice cuts a jump (linear ramps: Williams' field along a grid axis +1.8 % in J, against
// 0.2 % with nodal q). q and its gradient are taken at the particles in closed form: the gradient of
// an interpolation of q from the grid's nodes mixes the slope along a front that runs at an angle to
// the grid into the direction ahead, where the near-tip integrand is singular (the same field along a
// front turned 30 degrees: J within 4 % node to node).
struct DomainWeight {
  const FrontPolyline* line = nullptr;
  std::size_t j = 0;
  double R = 0.0, R_in = 0.0, L = 0.0;
  // q at p (returns false where it and its gradient are zero) and its gradient Q_kj = dq_k / dx_j:
  // the node's weight along the front plus its mirror images'. Most particles a node's walk meets lie outside its weight: they are told by the nearest point
  // among the segments within L of the node and of its images along the front. Where that point is
  // R or more away, or L or more along the front from them all, so is the nearest point of the
  // whole front, or it lies beyond L of them all: the weight is zero either way. Otherwise the whole
  // front's nearest point decides.
  bool q(const Vec<3>& p, Vec<3>& q, Mat<3>& Q) const {
    const double sj = line->node_s(j);
    double centres[3] = {sj, 0.0, 0.0};
    int count = 1;
    for (const double plane : line->planes)  // (an image farther than 2 L weighs nothing on this side)
      if (std::fabs(plane - sj) < L && count < 3) centres[count++] = 2.0 * plane - sj;
    const auto weight = [&](double at, double& psi, double& dpsi) {
      psi = 0.0, dpsi = 0.0;
      for (int c = 0; c < count; ++c) {
        const double ds = line->along(centres[c], at), u = std::fabs(ds) / L;
        psi += smooth_step(u), dpsi += smooth_step_slope(u) * (ds > 0.0 ? 1.0 : -1.0) / L;
      }
      return psi != 0.0 || dpsi != 0.0;
    };
    const double lo = *std::min_element(centres, centres + count) - L, hi = *std::max_element(centres, centres + count) + L;
    double psi, dpsi;
    if (const auto w = line->nearest(p, lo, hi); w.r >= R || !weight(w.s, psi, dpsi)) return false;
    const auto near = line->nearest(p);
    if (near.r >= R || !weight(near.s, psi, dpsi)) return false;
    const double w = R - R_in, u = (near.r - R_in) / w;
    const double phi = smooth_step(u), dphi = smooth_step_slope(u) / w;
    q = phi * psi * near.e1;
    Q = near.e1 * (dphi * psi * near.away + phi * dpsi * near.grad_s).transpose() +
        phi * psi * near.de1_ds * near.grad_s.transpose();
    return true;
  }
  // The tube's volume weighted by phi psi, what the particles' sum of phi psi V_p reads in full
  // material: (int phi dA) (int psi ds), int phi dA = pi R_in^2 + pi w R_in + (2/7) pi w^2 (w = R - R_in).
  double full_volume() const {
    const double w = R - R_in;
    return M_PI * (R_in * R_in + w * R_in + 2.0 / 7.0 * w * w) * line->psi_integral(line->node_s(j), L);
  }
};

}  // namespace cleave::detail
