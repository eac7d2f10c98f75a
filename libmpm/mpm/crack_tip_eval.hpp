// The dynamic J-integral and K_I / K_II at the crack tips of a 2D model (seed 000 §3, in the plane).
//
// Eq. 36: the particles around a tip extrapolate W (stress-work density), K (kinetic-energy
// density), stress, displacement gradient and displacement to the nodes, separately for each
// velocity field (a particle-node pair's field is the crack-crossing key of its connecting line,
// as in the step). Eq. 37: a contour point takes each of its nodes' values from the field that a
// particle at that point would use there. Eq. 38: midpoint rule over the contour. Eq. 33 adds the
// volume term over the particles inside the contour, with their accelerations and velocity
// gradients from the grid.
//
// Only particles within reach of a contour take part, and nothing here runs unless the scene asks
// for crack-tip parameters, so scenes without "crack_tips" pay nothing.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

#include "libmpm/core/parallel.hpp"
#include "libmpm/crack/propagation.hpp"
#include "libmpm/crack/reference_side.hpp"
#include "libmpm/crack/tip_parameters.hpp"
#include "libmpm/mpm/model.hpp"
#include "libmpm/mpm/particle_strain.hpp"
#include "libmpm/mpm/stencil.hpp"

namespace cleave {

// Least distance behind a tip, in cells, at which the opening ratio that splits J into K_I and K_II
// is read.
inline constexpr double kCodCells = 3.0;
// How many points, half a cell apart from there on, the opening ratio is fitted over.
inline constexpr int kCodPoints = 5;

namespace detail {
// The cracks as far as they come within `radius` (max-norm) of x: for each crack with a segment whose
// box meets that square, a copy of its contiguous range of such segments (id and points only). For
// every line inside the square the crossing test gives the same answer as on the whole crack: the
// range holds every segment that can reach the line, and its end vertices lie outside the square
// (or are the crack's own ends), so no line touches them. A tip's evaluation then costs what its
// neighbourhood holds, not the length a growing crack has reached.
inline std::vector<crack::Crack2D> cracks_near(const std::vector<crack::Crack2D>& cracks, const Vec<2>& x, double radius) {
  std::vector<crack::Crack2D> out;
  const Vec<2> lo = x.array() - radius, hi = x.array() + radius;
  for (const auto& c : cracks) {
    std::size_t first = c.points.size(), last = 0;
    for (std::size_t s = 0; s + 1 < c.points.size(); ++s) {
      const Vec<2> a = c.points[s].cwiseMin(c.points[s + 1]), b = c.points[s].cwiseMax(c.points[s + 1]);
      if ((a.array() > hi.array()).any() || (b.array() < lo.array()).any()) continue;
      first = std::min(first, s), last = s;
    }
    if (first > last) continue;
    crack::Crack2D l;
    l.id = c.id;
    l.points.assign(c.points.begin() + static_cast<std::ptrdiff_t>(first), c.points.begin() + static_cast<std::ptrdiff_t>(last + 2));
    if (c.reference.size() == c.points.size())
      l.reference.assign(c.reference.begin() + static_cast<std::ptrdiff_t>(first),
                         c.reference.begin() + static_cast<std::ptrdiff_t>(last + 2));
    l.Surface<2>::update_extent();
    if (c.cuts()) {  // the crack's cut ends as the stepper's crossing sees them (ExplicitCrack::cut_end)
      l.tip_cut = c.tip_cut, l.cut_end = c.cut_end, l.cut_reach = c.cut_reach, l.cut_away = c.cut_away;
      l.node_split = c.node_split;
      l.cut_at[0] = c.cut_at[0], l.cut_at[1] = c.cut_at[1], l.cut_out[0] = c.cut_out[0], l.cut_out[1] = c.cut_out[1];
      l.cross_points.assign(c.cross_points.begin() + static_cast<std::ptrdiff_t>(first),
                            c.cross_points.begin() + static_cast<std::ptrdiff_t>(last + 2));
      if (!c.split_points.empty())
        l.split_points.assign(c.split_points.begin() + static_cast<std::ptrdiff_t>(first),
                              c.split_points.begin() + static_cast<std::ptrdiff_t>(last + 2));
      const auto f = static_cast<int32_t>(first), n = static_cast<int32_t>(l.points.size());
      l.cross_first = std::max(c.cross_first - f, 0), l.cross_last = std::min(c.cross_last - f, n - 1);
    }
    out.push_back(std::move(l));
  }
  return out;
}

// Mass-weighted nodal sums of one velocity field at one node (eq. 36).
struct TipFieldSums {
  double m = 0.0;
  double energy = 0.0;     // m W
  // m rho |v|^2 and m rho v: the kinetic-energy density relative to the tip, K = rho |v - v_tip|^2 / 2,
  // follows from these once the tip's velocity is known.
  double rho = 0.0, rho_vv = 0.0;
  Vec<2> rho_v = Vec<2>::Zero();
  Vec<3> stress = Vec<3>::Zero();  // m (sxx, syy, sxy)
  Mat<2> grad_u = Mat<2>::Zero();  // m du_i/dx_j
  Vec<2> u = Vec<2>::Zero(), v = Vec<2>::Zero();
  Vec<2> X = Vec<2>::Zero();  // m (x - u): the reference position (the openings' rotation, below)
};

// The sums of eq. 36 per (node, field key) over a box of nodes about a tip: a list per node, its
// keys ascending (as a std::map ordered them, which this replaced: the map's lookups were half the
// cost of a growth check).
class TipNodeSums {
 public:
  TipNodeSums(const std::array<int, 2>& nodes, const Vec<2>& lo_x, const Vec<2>& hi_x, const Vec<2>& origin, double h) {
    for (int d = 0; d < 2; ++d) {
      lo_[d] = std::clamp(static_cast<int64_t>(std::floor((lo_x[d] - origin[d]) / h)), int64_t{0}, int64_t{nodes[d] - 1});
      n_[d] = std::clamp(static_cast<int64_t>(std::ceil((hi_x[d] - origin[d]) / h)), int64_t{0}, int64_t{nodes[d] - 1}) -
              lo_[d] + 1;
    }
    stride_ = nodes[1];
    head_.assign(static_cast<std::size_t>(n_[0] * n_[1]), -1);
  }
  // The sums of (node, key), created empty when new; nullptr for a node outside the box.
  TipFieldSums* get(int64_t node, uint32_t key) {
    const int64_t l = local(node);
    if (l < 0) return nullptr;
    // The link to follow: the node's head (prev < 0) or slot prev's next. (Indices, not pointers:
    // push_back below may move the slots.)
    int32_t prev = -1, e = head_[l];
    while (e >= 0 && slots_[e].key < key) prev = e, e = slots_[e].next;
    if (e >= 0 && slots_[e].key == key) return &slots_[e].sums;
    slots_.push_back({key, e, {}});
    const auto added = static_cast<int32_t>(slots_.size() - 1);
    (prev < 0 ? head_[l] : slots_[prev].next) = added;
    return &slots_.back().sums;
  }
  const TipFieldSums* find(int64_t node, uint32_t key) const {
    const int64_t l = local(node);
    if (l < 0) return nullptr;
    for (int32_t e = head_[l]; e >= 0 && slots_[e].key <= key; e = slots_[e].next)
      if (slots_[e].key == key) return &slots_[e].sums;
    return nullptr;
  }
  // f(sums) for every key of the node, ascending.
  template <class F>
  void each(int64_t node, F&& f) const {
    const int64_t l = local(node);
    if (l >= 0)
      for (int32_t e = head_[l]; e >= 0; e = slots_[e].next) f(slots_[e].sums);
  }

 private:
  struct Slot {
    uint32_t key;
    int32_t next;
    TipFieldSums sums;
  };
  int64_t local(int64_t node) const {
    const int64_t i = node / stride_ - lo_[0], j = node % stride_ - lo_[1];
    return i < 0 || j < 0 || i >= n_[0] || j >= n_[1] ? -1 : i * n_[1] + j;
  }
  int64_t lo_[2], n_[2], stride_;
  std::vector<int32_t> head_;
  std::vector<Slot> slots_;
};
}  // namespace detail

// accel(p): the acceleration of particle p in the last step (from the grid, with its own fields).
template <class SF, class Accel>
std::vector<crack::TipRecord> evaluate_crack_tips(const Model<2>& m, const crack::TipSettings& ts, Accel&& accel) {
  using V = Vec<2>;
  using St = Stencil<2, SF>;
  const auto& P = m.particles;
  const auto& G = m.grid;
  const double h = G.h, inv_h = 1.0 / h;
  const auto stride = G.strides();
  const auto node_pos = [&](int64_t n) { return V(G.origin.x() + h * (n / stride[0]), G.origin.y() + h * (n % stride[0])); };
  // Particles whose stencils reach a node that a contour point interpolates from, plus the
  // particles feeding those nodes: (contour extent + 1 cell) + 2 x 1.5 cells, and a margin.
  const double contour_extent = ts.radius * h * (ts.contour == crack::TipSettings::Contour::Circle ? 1.0 : std::sqrt(2.0));
  const double reach = contour_extent + 4.5 * h;

  // f(node, bilinear weight) for the four nodes of x's cell, in the order (0, 0), (0, 1), (1, 0),
  // (1, 1), the weights taken at `at` clamped to that cell; false (no call) when the cell is not
  // inside the grid. for_cell_nodes: the weights at x itself.
  const auto for_cell_nodes_at = [&](const V& x, const V& at, auto&& f) {
    const double fx = (x.x() - G.origin.x()) * inv_h, fy = (x.y() - G.origin.y()) * inv_h;
    const int i = static_cast<int>(std::floor(fx)), j = static_cast<int>(std::floor(fy));
    if (i < 0 || j < 0 || i + 1 >= G.nodes[0] || j + 1 >= G.nodes[1]) return false;
    const double rx = std::clamp((at.x() - G.origin.x()) * inv_h - i, 0.0, 1.0);
    const double ry = std::clamp((at.y() - G.origin.y()) * inv_h - j, 0.0, 1.0);
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b)
        f(static_cast<int64_t>(i + a) * stride[0] + (j + b), (a ? rx : 1.0 - rx) * (b ? ry : 1.0 - ry));
    return true;
  };
  const auto for_cell_nodes = [&](const V& x, auto&& f) { return for_cell_nodes_at(x, x, f); };
  // Small-strain displacement gradient of particle p relative to the rigid rotation theta of the
  // contour's material (below): its strain plus its integrated rotation less theta.
  double theta = 0.0;
  const StrainOf<2> strain(m);
  const auto grad_u_of = [&](std::size_t p, const Sym<2>& e) {
    const double r = P.rotation[p] - theta;
    Mat<2> g;
    g << e[0], e[3] - r, e[3] + r, e[1];
    return g;
  };
  const auto grad_u = [&](std::size_t p) { return grad_u_of(p, strain(p)); };
  std::vector<double> thickness(P.size(), 1.0);  // 2D masses are per body thickness
  for (const auto& b : m.bodies)
    for (std::size_t p = b.first; p < b.first + b.count; ++p) thickness[p] = b.thickness;

  // With contact between bodies, only the cracked body's particles: another body's share nodes with it
  // near the contour but move on fields of their own (the step's keys carry body tags; these do not).
  const std::vector<uint8_t> groups = particle_groups(m);
  std::vector<crack::TipRecord> out;
  for (const auto& c : m.cracks) {
    if (!c.tip[0] && !c.tip[1]) continue;  // (no tip: nothing to evaluate, no pass over the particles)
    const uint8_t own = groups.empty() ? 0 : crack_group(m, groups, static_cast<std::size_t>(c.id));
    const auto other = [&](std::size_t p) { return !groups.empty() && groups[p] != own; };
    // The cracked body's mass-weighted mean rotation: its rigid turn, for the openings below.
    const auto turn = deterministic_sums<2>(P.size(), [&](std::size_t p, double* acc) {
      if (other(p)) return;
      acc[0] += P.mass[p], acc[1] += P.mass[p] * P.rotation[p];
    });
    const double body_theta = turn[0] > 0.0 ? turn[1] / turn[0] : 0.0;
    for (int end = 0; end < 2; ++end) {
      if (!c.tip[end]) continue;
      const crack::TipFrame f = crack::tip_frame(c, end);
      crack::TipRecord rec;
      rec.crack = c.id;
      rec.end = end;
      rec.x = f.tip;

      // The rigid motion of the material round the tip (the particles within a cell and a half of the
      // contour): its mean rotation theta (of the particles' integrated rotations) and its spin omega
      // (the least-squares rigid fit of their velocities). J is evaluated relative to it: displacement
      // gradients less theta, velocities less omega x (x - tip) (and, below, less the tip's velocity),
      // so that a body that turns or spins rigidly contributes nothing. With the absolute quantities a
      // spinning unloaded disk read J up to 1e4 J/m^2 after one radian (its rotation times the stresses,
      // and the kinetic energy of the spin): docs/validation.md, cracks under rigid rotation. A rigid
      // rotation adds theta times the net force on the contour's material to J, which vanishes at rest
      // and is the centripetal term in a spinning body. The accelerations of eq. 33 stay absolute:
      // with the relative gradients they carry the centrifugal body force, the physical part.
      // The particles within the square of side 2 reach about the tip (reach exceeds the rigid fit's
      // radius): the passes below test only these, in particle order.
      std::vector<std::size_t> around;
      for (std::size_t p = 0; p < P.size(); ++p)
        if (std::abs(P.x[p].x() - f.tip.x()) <= reach && std::abs(P.x[p].y() - f.tip.y()) <= reach) around.push_back(p);
      double omega = 0.0;
      {
        const double fit = contour_extent + 1.5 * h;
        double msum = 0.0, mth = 0.0;
        V mx = V::Zero(), mv = V::Zero();
        for (std::size_t p : around) {
          if ((P.x[p] - f.tip).norm() > fit || other(p)) continue;
          const double mp = P.mass[p];
          msum += mp, mth += mp * P.rotation[p], mx += mp * P.x[p], mv += mp * P.v[p];
        }
        theta = 0.0;
        if (msum > 0.0) {
          theta = mth / msum;
          mx /= msum, mv /= msum;
          double num = 0.0, den = 0.0;
          for (std::size_t p : around) {
            if ((P.x[p] - f.tip).norm() > fit || other(p)) continue;
            const V r = P.x[p] - mx, dv = P.v[p] - mv;
            num += P.mass[p] * (r.x() * dv.y() - r.y() * dv.x());
            den += P.mass[p] * r.squaredNorm();
          }
          if (den > 0.0) omega = num / den;
        }
      }
      // Particle p's velocity less the spin about the tip.
      const auto v_rel = [&](std::size_t p) {
        const V r = P.x[p] - f.tip;
        return V(P.v[p].x() + omega * r.y(), P.v[p].y() - omega * r.x());
      };

      // Lines from the particles within reach to their nodes stay within reach + 2 cells of the tip.
      const std::vector<crack::Crack2D> local = detail::cracks_near(m.cracks, f.tip, reach + 3.0 * h);
      // Eq. 36: nodal sums per (node, field key).
      // (Nodes of the particles within reach: up to 2 cells beyond them with uGIMP.)
      detail::TipNodeSums sums(G.nodes, f.tip.array() - (reach + 3.0 * h), f.tip.array() + (reach + 3.0 * h), G.origin, h);
      // Where the crossing test takes each particle: a hair from a crack's line, on its reference side
      // (crack/reference_side.hpp), as the stepper sorts it.
      std::vector<V> sort_x(around.size());
      for (std::size_t k = 0; k < around.size(); ++k)
        sort_x[k] = crack::sorting_position(local, P.x[around[k]], P.x[around[k]] - P.u[around[k]], crack::kSortingHair * h);
      std::vector<std::size_t> inside;
      std::vector<V> inside_x;
      std::size_t nearest = P.size();
      double nearest_d = INFINITY;
      for (std::size_t k = 0; k < around.size(); ++k) {
        const std::size_t p = around[k];
        const double d = (P.x[p] - f.tip).norm();
        if (d > reach || other(p)) continue;
        if (d < nearest_d) nearest_d = d, nearest = p;
        if (ts.volume_term && crack::inside_contour(f, ts, h, P.x[p])) inside.push_back(p), inside_x.push_back(sort_x[k]);
        const auto& s = P.stress[p];
        const Sym<2> e = strain(p);
        const Material<2>& mat = *m.materials[P.material[p]];
        const double mp = P.mass[p];
        const double energy = mat.strain_energy_density(s, e);
        const Mat<2> gu = grad_u_of(p, e);
        const V vp = v_rel(p);
        St st;
        st.eval(G, stride, inv_h, P.x[p], P.half_width[p]);
        st.for_each_weight([&](int64_t n, double w) {
          if (w == 0.0) return;
          const uint32_t key = crack::field_key(local, sort_x[k], node_pos(n));
          if (key == crack::kFieldKeyOverflow) return;
          detail::TipFieldSums* ap = sums.get(n, key);
          if (!ap) return;  // (never: the box holds every node of these particles)
          auto& a = *ap;
          const double mw = mp * w;
          a.m += mw;
          a.energy += mw * energy;
          a.stress += mw * Vec<3>(s[0], s[1], s[3]);
          a.grad_u += mw * gu;
          a.u += mw * P.u[p];
          a.X += mw * (P.x[p] - P.u[p]);
          a.v += mw * vp;
          const double rho = mp / P.volume0[p];
          a.rho += mw * rho;
          a.rho_vv += mw * rho * vp.squaredNorm();
          a.rho_v += mw * rho * vp;
        });
      }
      if (nearest == P.size()) continue;  // no material at this tip

      // The tip's velocity: the centre-of-mass velocity of all fields at the tip, which the crack
      // points move with (Task 7). Kinetic energies and velocities enter J relative to it, so that a
      // crack carried by a translating body gives the J of the body at rest (Galilean invariance;
      // with absolute velocities a translating body's K term is large and its discretisation error
      // does not cancel). For a crack at rest this changes nothing.
      V v_tip = V::Zero();
      {
        double wsum = 0.0;
        for_cell_nodes(f.tip, [&](int64_t n, double w) {
          double mn = 0.0;
          V pn = V::Zero();
          sums.each(n, [&](const detail::TipFieldSums& q) { mn += q.m, pn += q.v; });
          if (!(mn > 0.0) || w == 0.0) return;
          v_tip += w * pn / mn;
          wsum += w;
        });
        if (wsum > 0.0) v_tip /= wsum;
      }

      // Eq. 37: the field values a particle at x would see (bilinear weights of x's cell); energy is
      // W + K with K relative to the tip.
      auto interpolate = [&](const V& x, detail::TipFieldSums& q) {
        q = detail::TipFieldSums{};
        double wsum = 0.0;
        const bool in_grid = for_cell_nodes(x, [&](int64_t n, double w) {
          const detail::TipFieldSums* it = sums.find(n, crack::field_key(local, x, node_pos(n)));
          if (w == 0.0 || !it || !(it->m > 0.0)) return;
          const auto& s = *it;
          const double k = w / s.m;
          const double kinetic = 0.5 * (s.rho_vv - 2.0 * v_tip.dot(s.rho_v) + s.rho * v_tip.squaredNorm());
          q.energy += k * (s.energy + kinetic), q.stress += k * s.stress, q.grad_u += k * s.grad_u, q.u += k * s.u;
          q.X += k * s.X;
          wsum += w;
        });
        if (!in_grid || !(wsum > 0.0)) return false;  // outside the grid or the material
        q.energy /= wsum, q.stress /= wsum, q.grad_u /= wsum, q.u /= wsum, q.X /= wsum;
        q.m = 1.0;
        return true;
      };

      // Eqs. 38-39: J = sum [(W + K) n - (grad u)^T (sigma n)] dGamma, in global axes.
      V J = V::Zero();
      for (const auto& cp : crack::contour_points(c, end, ts, h)) {
        detail::TipFieldSums q;
        if (!interpolate(cp.x, q)) continue;
        const V tn(q.stress[0] * cp.n.x() + q.stress[2] * cp.n.y(), q.stress[2] * cp.n.x() + q.stress[1] * cp.n.y());
        J += cp.length * (q.energy * cp.n - q.grad_u.transpose() * tn);
      }
      // Eq. 33's volume term, sum m_p / b [(grad u)^T a - (grad v)^T v] over the particles inside
      // (b the thickness: J is per unit length of crack front).
      for (std::size_t i = 0; i < inside.size(); ++i) {
        const std::size_t p = inside[i];
        St st;
        st.eval(G, stride, inv_h, P.x[p], P.half_width[p]);
        Mat<2> gv = Mat<2>::Zero();
        st.for_each([&](int64_t n, double, const V& g) {
          const detail::TipFieldSums* it = sums.find(n, crack::field_key(local, inside_x[i], node_pos(n)));
          if (it && it->m > 0.0) gv += (it->v / it->m) * g.transpose();
        });
        J += P.mass[p] / thickness[p] * (grad_u(p).transpose() * accel(p) - gv.transpose() * (v_rel(p) - v_tip));
      }
      // A kinked crack (one that grew off its line) has faces inside the contour that are not along
      // e1, and traction-free faces carry the energy term there: J1 at the tip = the contour's J1 +
      // sum over those faces of (W- - W+) (n . e1) ds (n the face's normal towards "+"; the
      // divergence theorem over the contour's region, whose boundary they are). Without it J1 of a
      // tip that had just kinked by 70 degrees read -1e4 J/m^2 where the plate's loading gave +2e4.
      // Faces along e1 (every straight crack) add nothing and are skipped.
      double faces = 0.0;
      {
        const std::size_t n = c.points.size();
        const double probe = 1e-3 * h, piece = 0.25 * h;
        double along = 0.0;
        for (std::size_t k = 0; k + 1 < n && along <= 2.0 * contour_extent + h; ++k) {
          const V a = crack::vertex_from_tip(c, end, k), b = crack::vertex_from_tip(c, end, k + 1);
          const double len = (a - b).norm();
          along += len;
          const V ahead = (a - b) / len, nrm(-ahead.y(), ahead.x());
          const double ne1 = nrm.dot(f.e1);
          if (std::abs(ne1) < 1e-9) continue;
          const int pieces = std::max(1, static_cast<int>(std::ceil(len / piece)));
          for (int i = 0; i < pieces; ++i) {
            const V x = b + ((i + 0.5) / pieces) * (a - b);
            detail::TipFieldSums up, down;
            if (!crack::inside_contour(f, ts, h, x)) continue;
            if (interpolate(x + probe * nrm, up) && interpolate(x - probe * nrm, down))
              faces += (len / pieces) * (down.energy - up.energy) * ne1;
          }
        }
      }
      rec.J1 = J.dot(f.e1) + faces;
      rec.J2 = J.dot(f.e2);

      // Each face's field holds the displacement of its mass centre, which started at X (sum m (x -
      // u) / m), about 3/8 of a cell off the crack on its side: a rigid rotation R of the body turns
      // their separation Xa - Xb without opening the faces, so the opening is ua - ub + (I - R)(Xa - Xb)
      // (as contact's gap). Without it a loaded DCB spinning at 0.1 rad/ms read a tangential opening
      // of about the angle turned times 3/4 of a cell, ten times its normal one by 0.09 rad (K_II / K_I
      // = -11, K_I < 0 at times; now 1.05 % at most). R turns by the cracked body's mean rotation, not
      // by the contour's (theta above): near a mixed-mode tip the material's rotation is the
      // deformation's, which the fields' offset carries in together with its strain, and taking out
      // the rotation alone moved the exact K field's K_II / K_I = 0.5 to 0.486 (from 0.504).
      const double cs = std::cos(body_theta), sn = std::sin(body_theta);
      const auto unturned = [&](const V& dX) {
        return V(dX.x() - (cs * dX.x() - sn * dX.y()), dX.y() - (sn * dX.x() + cs * dX.y()));
      };
      // The two faces' displacements (and reference positions) at crack point x, each face's field
      // probed at x +- off: read at the nodes of x's cell that carry both faces' fields (the nodes the
      // crack splits there), with bilinear weights renormalised over them, so that the faces are
      // sampled by the same nodes, as mirror images about the discrete crack (the weights: below);
      // only where no node of the cell carries both, each face over the nodes that carry it. (Each
      // face over its own nodes read a growing crack 0.15 cell above a node line unevenly: the upper
      // face from the split nodes below it and, at weight 0.15, the whole nodes above, the lower face
      // from the split nodes alone. A mode I field's tangential displacement varies with the distance
      // from the crack, so this read K_II / K_I = +0.1 % where the discrete crack has none (1e-5 now),
      // and the crack turned off its line: 0.08 cell within 20 cells, now 0.00; docs/validation.md,
      // growing cracks 2.)
      auto read_faces = [&](const V& x, const V& off, detail::TipFieldSums& up, detail::TipFieldSums& down) {
        up = detail::TipFieldSums{}, down = detail::TipFieldSums{};
        const detail::TipFieldSums* a[4] = {};
        const detail::TipFieldSums* b[4] = {};
        int k = 0, both = 0;
        for_cell_nodes(x, [&](int64_t n, double w) {
          const int e = k++;
          a[e] = sums.find(n, crack::field_key(local, x + off, node_pos(n)));
          b[e] = sums.find(n, crack::field_key(local, x - off, node_pos(n)));
          if (w == 0.0 || !a[e] || !b[e] || a[e] == b[e] || !(a[e]->m > 0.0) || !(b[e]->m > 0.0)) a[e] = b[e] = nullptr;
          else ++both;
        });
        if (both == 0) return interpolate(x + off, up) && interpolate(x - off, down);
        // The weights are those of the discrete crack beside x: half-way between the nearest particles
        // on either side of the crack's line (the particles' sorting puts it there), where the faces'
        // fields are mirror images. With x's own weights a crack 0.26 cell above a node line (particle
        // rows at 0.25 and 0.75, the discrete crack at 0.5) took 0.74 of its tangential opening from
        // the lower node line, where a mode I crack's is the opposite of the upper one's: K_II / K_I
        // -0.3 % where the discrete crack has none, and a growing crack turned 0.12 cell off its line
        // within 20 cells (docs/validation.md, growing cracks 2).
        const V nrm = off.normalized(), along(nrm.y(), -nrm.x());
        double gap_above = INFINITY, gap_below = -INFINITY;
        for (std::size_t k = 0; k < around.size(); ++k) {
          if (other(around[k])) continue;
          const V r = sort_x[k] - x;
          const double d = r.dot(nrm);
          if (std::abs(r.dot(along)) > 0.5 * h || std::abs(d) > 1.5 * h) continue;
          if (d > 0.0) gap_above = std::min(gap_above, d);
          if (d < 0.0) gap_below = std::max(gap_below, d);
        }
        const V xd = std::isfinite(gap_above) && std::isfinite(gap_below) ? V(x + 0.5 * (gap_above + gap_below) * nrm) : x;
        double wsum = 0.0;
        k = 0;
        for_cell_nodes_at(x, xd, [&](int64_t, double w) {
          const int e = k++;
          if (!a[e]) return;
          up.u += w * a[e]->u / a[e]->m, up.X += w * a[e]->X / a[e]->m;
          down.u += w * b[e]->u / b[e]->m, down.X += w * b[e]->X / b[e]->m;
          wsum += w;
        });
        if (!(wsum > 0.0)) return interpolate(x + off, up) && interpolate(x - off, down);
        up.u /= wsum, up.X /= wsum, down.u /= wsum, down.X /= wsum;
        return true;
      };
      // Near-tip openings behind the tip from the contour radius, but at least 3 cells, over the
      // next kCodPoints half cells: each face's field, probed just off the crack line on its side.
      // Closer in, the tip's own cells distort the opening ratio (inclined centre crack, tan 30 =
      // 0.577: 0.642, 0.609, 0.581, 0.573, 0.571 at 1-5 cells behind the tip; docs/validation.md).
      // The ratio K_II / K_I is the least-squares slope of the tangential against the normal
      // openings over those points (issue 14 item 4: one point's tangential opening carries the
      // discrete faces' noise, which turned a growing crack off its plane).
      // A point on a segment off e1 (the crack kinked since, less than the reading distance behind
      // the tip) holds the openings of the crack's earlier direction: a small kink's first-order
      // intensities (Cotterell & Rice) carry them to the tip's direction. Without this a tip that
      // kinked by 70 degrees under mode II read the old mode II ratio and kinked by 70 degrees again.
      {
        double s11 = 0.0, s12 = 0.0, sum1 = 0.0;
        int read = 0;
        const double probe = 1e-3 * h;
        for (int k = 0; k < kCodPoints; ++k) {
          const crack::CrackPoint cp = crack::point_behind_tip(c, end, (std::max(ts.radius, kCodCells) + 0.5 * k) * h);
          detail::TipFieldSums up, down;
          if (!read_faces(cp.x, probe * cp.normal, up, down)) continue;
          const V d = up.u - down.u + unturned(up.X - down.X);
          double o1 = d.dot(f.e2), o2 = d.dot(f.e1);
          const V ahead(cp.normal.y(), -cp.normal.x());
          const double phi = std::atan2(ahead.x() * f.e1.y() - ahead.y() * f.e1.x(), ahead.dot(f.e1));
          if (std::abs(phi) > 1e-6) std::tie(o1, o2) = crack::kink_intensities(d.dot(cp.normal), d.dot(ahead), phi);
          s11 += o1 * o1, s12 += o1 * o2, sum1 += o1;
          ++read;
        }
        if (read > 0) {
          rec.cod_I = sum1 / read;
          rec.cod_II = s11 > 0.0 ? rec.cod_I * s12 / s11 : 0.0;
        }
      }
      double mu = 0.0, nu = 0.0;
      if (!m.materials[P.material[nearest]]->isotropic_elastic(mu, nu))
        throw std::runtime_error("crack '" + c.name + "': K from J needs an isotropic elastic material at the tip");
      const auto k = crack::stress_intensity(rec.J1, rec.cod_I, rec.cod_II, mu, crack::kolosov_kappa(m.analysis, nu));
      rec.KI = k.KI;
      rec.KII = k.KII;
      rec.material = P.material[nearest];
      out.push_back(rec);
    }
  }
  return out;
}

}  // namespace cleave
