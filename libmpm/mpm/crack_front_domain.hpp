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
// tube radius in the continuum, and its integrand is read at the particles, where MPM keeps stress and
// strain. (On a coarse discrete model the radius still matters: a 2-cell tube's weight falls across the
// tip's own cells; docs/validation.md, "The domain integral".)
//
// q = phi(r) psi(s) e1(s), r and s the distance from and the arc length along the front's polyline of
// a point's nearest point on it, is taken with its gradient in closed form at each particle
// (FrontTube below says why not from the grid's nodes, and how a particle is read once for all the
// front nodes whose weights reach it).
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <utility>
#include <vector>

#include "libmpm/core/types.hpp"
#include "libmpm/crack/explicit_crack.hpp"
#include "libmpm/crack/front_parameters.hpp"
#include "libmpm/mpm/crack_front_sums.hpp"  // CellBins, displacement_gradient

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
  // Segment k joins node k to node k + 1 (a closed polyline's last, to node 0).
  std::size_t segments() const { return closed ? x.size() : (x.empty() ? 0 : x.size() - 1); }
  Near nearest(const Vec<3>& p) const {
    if (x.size() == 1) return {s[0], (p - x[0]).norm(), Vec<3>::Zero(), Vec<3>::Zero(), e1[0], Vec<3>::Zero()};
    Candidate best;
    for (std::size_t k = 0; k < segments(); ++k) consider(p, k, best);
    return finish(p, best);
  }
  // The same among the segments ids (ascending; the first of the nearest, as nearest()): the answer of
  // nearest() wherever that lies on one of them.
  Near nearest_among(const Vec<3>& p, std::span<const uint32_t> ids) const {
    Candidate best;
    for (const uint32_t k : ids) consider(p, k, best);
    return finish(p, best);
  }
  // Where p's nearest point on segment k lies: t along it (0 at node k, 1 at its end), the distance r,
  // and the segment's squared length.
  struct Foot {
    double t, r, len2;
  };
  Foot foot(const Vec<3>& p, std::size_t k) const {
    const Vec<3> d = x[(k + 1) % x.size()] - x[k];
    const double len2 = d.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp((p - x[k]).dot(d) / len2, 0.0, 1.0) : 0.0;
    return {t, (p - x[k] - t * d).norm(), len2};
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

 private:
  struct Candidate {
    double r = INFINITY, s = 0.0, t = 0.0;
    std::size_t k = 0;
  };
  void consider(const Vec<3>& p, std::size_t k, Candidate& best) const {
    const Foot f = foot(p, k);
    if (f.r < best.r) best = {f.r, s[k] + f.t * std::sqrt(f.len2), f.t, k};
  }
  Near finish(const Vec<3>& p, const Candidate& c) const {
    Near best;
    best.r = c.r, best.s = c.s;
    if (!(c.r < INFINITY)) return best;
    const Vec<3> d = x[(c.k + 1) % x.size()] - x[c.k];
    const double len = d.norm();
    const Vec<3> foot = x[c.k] + c.t * d;
    if (best.r > 0.0) best.away = (p - foot) / best.r;
    const Vec<3> e = (1.0 - c.t) * e1[c.k] + c.t * e1[(c.k + 1) % x.size()];
    best.e1 = e.normalized();
    if (c.t > 0.0 && c.t < 1.0 && len > 0.0) {
      best.grad_s = d / len;
      const Vec<3> de = (e1[(c.k + 1) % x.size()] - e1[c.k]) / len;  // d e / ds; of the unit vector: its part normal to it
      best.de1_ds = (de - best.e1 * best.e1.dot(de)) / e.norm();
    }
    return best;
  }
};

// b(u) = 1 - 10 u^3 + 15 u^4 - 6 u^5 on [0, 1] (1 at 0, 0 at 1, with zero slope and curvature at both),
// and its derivative.
inline double smooth_step(double u) {
  return u <= 0.0 ? 1.0 : u >= 1.0 ? 0.0 : 1.0 - u * u * u * (10.0 - u * (15.0 - 6.0 * u));
}
inline double smooth_step_slope(double u) { return u <= 0.0 || u >= 1.0 ? 0.0 : -30.0 * u * u * (1.0 - u) * (1.0 - u); }

// The particles of the tube of radius R about a front's polyline, each with the part of its share of
// the domain integral that does not depend on the front node. About node j the weight is
// q = phi(r) psi_j(s) e1(s): phi falls from 1 within R_in of the front to 0 at R, psi_j from 1 at the
// node to 0 at L along the front from it (and from its mirror images), both smooth steps b, so that
// q's gradient is continuous: the particles' midpoint rule then sums it without the error of where a
// lattice cuts a jump (linear ramps: Williams' field along a grid axis +1.8 % in J). q and its gradient
// are taken at the particles in closed form: the gradient of an interpolation of q from the grid's
// nodes mixes the slope along a front that runs at an angle to the grid into the direction ahead,
// where the near-tip integrand is singular (the same field along a front turned 30 degrees: J within
// 4 % node to node).
//
// The gradient is grad q = psi_j A + psi_j' B, with A = phi' e1 (x) away + phi de1/ds (x) grad s and
// B = phi e1 (x) grad s, and the displacement gradient is the particle's G less the node's rigid
// rotation theta_j, G - S(theta_j) (S linear: S(w) x = w x x). So the integrand
// (sigma_ij u_i,k - W delta_kj) q_k,j + rho u''_i u_i,k q_k is, per particle,
// psi_j (a - theta_j . a_theta) + psi_j' (b - theta_j . b_theta): a particle's nearest point, stress,
// energy and acceleration are read once per evaluation, not once for each node whose weight reaches it
// (a node's weight reaches the particles within L along the front, a score of nodes' at the rod's
// spacing).
struct TubeParticle {
  double s = 0.0;  // the arc length of its nearest point on the front
  double a = 0.0, b = 0.0;
  Vec<3> a_theta = Vec<3>::Zero(), b_theta = Vec<3>::Zero();
  double material = 0.0;  // V phi: with psi_j, its share of the tube's volume
};
// What the tube reads of a particle: volume, mass, strain energy density W, stress, displacement
// gradient (with the particle's own rotation, not the node's), acceleration (zero without inertia).
struct TubeInput {
  double volume = 0.0, mass = 0.0, W = 0.0;
  Mat<3> stress = Mat<3>::Zero(), grad_u = Mat<3>::Zero();
  Vec<3> accel = Vec<3>::Zero();
};

class FrontTube {
 public:
  FrontTube(const FrontPolyline& line, double R, double R_in) : line_(&line), R_(R), R_in_(R_in) {}

  // The particles of bins (positions x) within R of the polyline, in cell and particle order; read(p)
  // gives particle p's TubeInput. A segment within R of a particle lies within R and the half-diagonal of its
  // cell's centre, so each cell searches only those segments: the nearest of them is the whole
  // polyline's wherever that one lies within R.
  template <class Read>
  void build(const GridGeometry<3>& G, const CellBins& bins, const std::vector<Vec<3>>& x, Read&& read) {
    const FrontPolyline& line = *line_;
    const double h = G.h, reach = R_ + 0.5 * std::sqrt(3.0) * h;
    std::vector<std::pair<int64_t, uint32_t>> pairs;  // (cell of the bins, segment)
    for (std::size_t k = 0; k < line.segments(); ++k) {
      const Vec<3> &a = line.x[k], &b = line.x[(k + 1) % line.x.size()];
      const auto c0 = CellBins::cell_of(G, a.cwiseMin(b) - Vec<3>::Constant(reach)),
                 c1 = CellBins::cell_of(G, a.cwiseMax(b) + Vec<3>::Constant(reach));
      for (int64_t i = c0[0]; i <= c1[0]; ++i)
        for (int64_t j = c0[1]; j <= c1[1]; ++j)
          for (int64_t l = c0[2]; l <= c1[2]; ++l) {
            const int64_t cell = bins.index(i, j, l);
            if (cell < 0 || bins.begin[cell] == bins.begin[cell + 1]) continue;
            if (line.foot(G.origin + h * Vec<3>(i + 0.5, j + 0.5, l + 0.5), k).r <= reach)
              pairs.push_back({cell, static_cast<uint32_t>(k)});
          }
    }
    std::sort(pairs.begin(), pairs.end());
    std::vector<std::size_t> cell_begin;  // cell c's pairs: pairs[cell_begin[c] .. cell_begin[c + 1])
    for (std::size_t q = 0; q < pairs.size(); ++q)
      if (q == 0 || pairs[q].first != pairs[q - 1].first) cell_begin.push_back(q);
    cell_begin.push_back(pairs.size());
    std::vector<uint32_t> segs(pairs.size());
    for (std::size_t q = 0; q < pairs.size(); ++q) segs[q] = pairs[q].second;
    const std::size_t cells = cell_begin.size() - 1;
    std::vector<std::vector<TubeParticle>> of_cell(cells);
#pragma omp parallel for schedule(dynamic, 4) if (cells > 8)
    for (std::size_t c = 0; c < cells; ++c) {
      const int64_t cell = pairs[cell_begin[c]].first;
      const std::span<const uint32_t> ids(segs.data() + cell_begin[c], segs.data() + cell_begin[c + 1]);
      for (int64_t q = bins.begin[cell]; q < bins.begin[cell + 1]; ++q) {
        const int32_t p = bins.particle[q];
        const auto near = line.nearest_among(x[p], ids);
        if (!(near.r < R_)) continue;
        of_cell[c].push_back(share(near, read(p)));
      }
    }
    particles_.clear();
    for (const auto& v : of_cell) particles_.insert(particles_.end(), v.begin(), v.end());
  }

  // J1 at front node j (its weight along the front reaching L from it and from its mirror images) with
  // the node's rigid rotation theta taken out, and the tube's material as a share of full material
  // (1 in a tube of particles of full volume).
  struct Reading {
    double J1 = 0.0, material = 0.0;
  };
  Reading read(std::size_t j, double L, const Vec<3>& theta) const {
    const FrontPolyline& line = *line_;
    const double sj = line.node_s(j);
    double centres[3] = {sj, 0.0, 0.0};
    int count = 1;
    for (const double plane : line.planes)  // (an image farther than 2 L weighs nothing on this side)
      if (std::fabs(plane - sj) < L && count < 3) centres[count++] = 2.0 * plane - sj;
    const double lo = *std::min_element(centres, centres + count) - L, hi = *std::max_element(centres, centres + count) + L;
    double sum = 0.0, material = 0.0;
    Vec<3> sum_theta = Vec<3>::Zero();
    for (const TubeParticle& t : particles_) {
      if (!line.closed && (t.s <= lo || t.s >= hi)) continue;
      double psi = 0.0, dpsi = 0.0;
      for (int c = 0; c < count; ++c) {
        const double ds = line.along(centres[c], t.s), u = std::fabs(ds) / L;
        psi += smooth_step(u), dpsi += smooth_step_slope(u) * (ds > 0.0 ? 1.0 : -1.0) / L;
      }
      if (psi == 0.0 && dpsi == 0.0) continue;
      sum += psi * t.a + dpsi * t.b, sum_theta += psi * t.a_theta + dpsi * t.b_theta;
      material += psi * t.material;
    }
    // The tube's volume weighted by phi psi in full material: (int phi dA) (int psi ds),
    // int phi dA = pi R_in^2 + pi w R_in + (2/7) pi w^2 (w = R - R_in).
    const double w = R_ - R_in_, psi_ds = line.psi_integral(sj, L);
    if (!(psi_ds > 0.0)) return {};  // (a front of one node: no length to weigh; flagged as empty)
    const double full = M_PI * (R_in_ * R_in_ + w * R_in_ + 2.0 / 7.0 * w * w) * psi_ds;
    return {(sum - theta.dot(sum_theta)) / psi_ds, full > 0.0 ? material / full : 0.0};
  }
  const std::vector<TubeParticle>& particles() const { return particles_; }

 private:
  TubeParticle share(const FrontPolyline::Near& near, const TubeInput& in) const {
    const double w = R_ - R_in_, u = (near.r - R_in_) / w;
    const double phi = smooth_step(u), dphi = smooth_step_slope(u) / w;
    const Mat<3> A = dphi * near.e1 * near.away.transpose() + phi * near.de1_ds * near.grad_s.transpose();
    const Mat<3> B = phi * near.e1 * near.grad_s.transpose();
    const Mat<3> M = in.grad_u.transpose() * in.stress;
    TubeParticle t;
    t.s = near.s;
    t.a = in.volume * (M.cwiseProduct(A).sum() - in.W * A.trace()) + in.mass * phi * (in.grad_u.transpose() * in.accel).dot(near.e1);
    t.b = in.volume * (M.cwiseProduct(B).sum() - in.W * B.trace());
    // S(e_c), the rotations about the axes (the same for every particle).
    static const std::array<Mat<3>, 3> kS = {displacement_gradient(Sym<3>::Zero(), Vec<3>::UnitX()),
                                             displacement_gradient(Sym<3>::Zero(), Vec<3>::UnitY()),
                                             displacement_gradient(Sym<3>::Zero(), Vec<3>::UnitZ())};
    for (int c = 0; c < 3; ++c) {
      const Mat<3>& S = kS[c];
      const Mat<3> Sm = S.transpose() * in.stress;
      t.a_theta[c] = in.volume * Sm.cwiseProduct(A).sum() + in.mass * phi * (S.transpose() * in.accel).dot(near.e1);
      t.b_theta[c] = in.volume * Sm.cwiseProduct(B).sum();
    }
    t.material = in.volume * phi;
    return t;
  }

  const FrontPolyline* line_;
  double R_, R_in_;
  std::vector<TubeParticle> particles_;
};

}  // namespace cleave::detail
