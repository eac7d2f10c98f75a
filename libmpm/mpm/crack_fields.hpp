// Multiple velocity fields at nodes near 2D explicit cracks (seed 002, §2.1-2.2 and Appendix A),
// with crack contact and crack translation (Task 7).
//
// Every particle-node pair has a field key: the cracks its connecting line crosses and the side
// the particle is on (at most two crossings, so two cracks may meet at a node). Key 0 (no
// crossing) is the node's ordinary field and lives in the stepper's grid arrays; a node that also
// receives another key gets a block of up to three extra slots, so a node holds up to four fields
// as in NairnMPM. A pair that would need a fifth field is counted and reported, and its particle
// then uses the node's ordinary field.
//
// Cost model: a per-step spatial index maps each cell to the crack segments within kReach cells of
// it. Particles farther than near_reach_ from every segment of their cell's entries ("far"
// particles) can neither cross a crack nor touch a multi-field node with a non-zero weight, so they
// keep the stepper's single-field fast path; only "near" particles take the paths here.
#pragma once
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "libmpm/crack/crack2d.hpp"
#include "libmpm/mpm/model.hpp"
#include "libmpm/core/parallel.hpp"
#include "libmpm/mpm/stencil.hpp"
#include "libmpm/mpm/step_timers.hpp"

namespace cleave {

// Nodal velocity and acceleration side by side: Task 5 gathers both from one cache line.
template <int Dim>
struct NodeKinematics {
  Vec<Dim> v, a;
};

template <class SF>
class CrackFields {
  static constexpr int Dim = 2;
  using St = Stencil<2, SF>;
  using V = Vec<2>;

 public:
  static constexpr int N = St::N;
  static constexpr int kExtra = 3;  // extra fields per node: four in all
  // Cells: a particle reaches nodes up to 1 cell away (linear) or 1.5 cells (uGIMP, half-width
  // <= 0.5 cell), so a particle sharing a node with a pair whose line crosses a segment is within
  // twice that of the segment.
  static constexpr int kReach = SF::K == 2 ? 2 : 3;

  CrackFields(Model<2>& m, GridFields<2>& grid, std::vector<NodeKinematics<2>>& kin)
      : m_(m), P_(m.particles), G_(m.grid), grid_(grid), kin_(kin), cracks_(m.cracks) {
    stride_ = G_.strides();
    inv_h_ = 1.0 / G_.h;
    cells_[0] = G_.nodes[0] - 1;
    cells_[1] = G_.nodes[1] - 1;
    cell_head_.assign(static_cast<std::size_t>(cells_[0]) * cells_[1], -1);
    node_block_.assign(G_.node_count(), -1);
    near_flag_.assign(P_.size(), 0);
    near_index_.assign(P_.size(), -1);
    area0_.resize(P_.size());
    for (const auto& b : m.bodies)
      for (std::size_t p = b.first; p < b.first + b.count; ++p) area0_[p] = P_.volume0[p] / b.thickness;
    // A node has a non-zero weight for a particle within r cells of it on each axis: r = 1 (linear),
    // 1 + half-width (uGIMP). A multi-field node's field comes from a particle-node line that meets a
    // segment, so that segment point lies within r of the node, and a particle weighting the node
    // lies within 2 r of it. (Nodes of zero weight receive nothing and are read with weight 0, so
    // a far particle that has one at a multi-field node is still exact on the fast path; and no line
    // from a far particle to a node of its stencil or of a loaded face, at most 1.5 cells away, can
    // reach a segment, so field_of's -1 for it is the classification's answer.) A little slack
    // covers the rounding of the weights at the edge of the support; at most kReach.
    double r = 1.0;
    if constexpr (SF::K == 3) {
      double lmax = 0.5;
      if (!P_.half_width.empty()) lmax = *std::max_element(P_.half_width.begin(), P_.half_width.end());
      r += std::clamp(lmax, 0.0, 0.5);
    }
    near_reach_ = std::min(static_cast<double>(kReach), 2.0 * r + 1e-6) * G_.h;
    for (const auto& c : cracks_) {
      if (c.contact_law == Law::None) continue;
      (c.detection == crack::Crack2D::Detection::Volume ? need_volume_ : need_disp_) = true;
    }
  }

  bool active() const { return !cracks_.empty(); }
  // One flag per particle: near a crack at the start of the step (set by the stepper's strip-order
  // pass with near_test(), between prepare_index() and prepare_fields()).
  const uint8_t* near_flags() const { return near_flag_.data(); }
  uint8_t* near_flags() { return near_flag_.data(); }
  const std::vector<int32_t>& near_list() const { return near_; }
  // Per particle: its index in near_list(), or -1 when it is not near a crack.
  const int32_t* near_index() const { return near_index_.data(); }
  // The stencil of near particle k (index into near_list()), evaluated once in prepare_fields(): every pass
  // of a step evaluates the shape functions at the start-of-step positions (a pass that moves the
  // particles does so after its last use of them), so one evaluation serves the whole step.
  const St& stencil(std::size_t k) const { return near_st_[k]; }
  std::size_t block_count() const { return block_node_.size(); }

  // --- Task 1 preamble: spatial index, near particles, line crossing (Appendix A), field slots ----
  // In three parts: prepare_index(); then the near flags, set from near_test() in the stepper's
  // strip-order pass, which streams every particle's position anyway (a pass of its own here cost
  // about 2 % of a step at 230 000 particles); then prepare_fields(whether a flag changed).
  void prepare_index() {
    for (auto& c : cracks_) c.update_extent();
    build_index();
  }
  // An entry of the spatial index (build_index).
  struct Entry {
    int32_t crack, seg_lo, seg_hi, next;
    V lo, hi;  // bounding box of the range's vertices seg_lo .. seg_hi + 1
  };
  // Is a particle at x near a crack: in a cell with index entries, within near_reach_ of the box of
  // one of them? in_box(x): is x in the box of the cells with entries (a few comparisons, which
  // the caller's loop vectorises); operator(): the full test, for x in that box.
  // (Everything by value: the caller's flag stores (uint8_t) could otherwise alias these members
  // and force reloads in its loop.)
  struct NearTest {
    double ox, oy, inv_h, lo0, hi0, lo1, hi1, reach;
    int64_t ny;
    const int32_t* head;
    const Entry* entries;
    uint8_t in_box(const V& x) const {
      const double fx = (x.x() - ox) * inv_h, fy = (x.y() - oy) * inv_h;
      return (fx >= lo0) & (fx < hi0) & (fy >= lo1) & (fy < hi1);
    }
    uint8_t operator()(const V& x) const {
      const double fx = (x.x() - ox) * inv_h, fy = (x.y() - oy) * inv_h;  // (= cell_of's cell)
      for (int32_t e = head[static_cast<int64_t>(fx) * ny + static_cast<int64_t>(fy)]; e >= 0; e = entries[e].next) {
        const Entry& en = entries[e];
        if (x.x() >= en.lo.x() - reach && x.x() <= en.hi.x() + reach && x.y() >= en.lo.y() - reach &&
            x.y() <= en.hi.y() + reach)
          return 1;
      }
      return 0;
    }
  };
  NearTest near_test() const {
    return {G_.origin.x(), G_.origin.y(), inv_h_, box_lo_[0], box_hi_[0], box_lo_[1], box_hi_[1], near_reach_,
            static_cast<int64_t>(cells_[1]), cell_head_.data(), entries_.data()};
  }
  void prepare_fields(bool flags_changed) {
    side_fields_.resize(cracks_.size());
    side_valid_.assign(cracks_.size(), 0);
    if (flags_changed) {
      CLEAVE_TIME(NearList);
      collect_near_particles();
    }
    {
      CLEAVE_TIME(Classify);
      classify_pairs();
    }
    CLEAVE_TIME(Allocate);
    allocate_fields();
  }

  // Calls f(node, x, w, g) for every stencil node of near particle k (index into near_list()):
  // x < 0 means the node's ordinary field (the stepper's arrays), else the extra slot index.
  // (Most near particles use only ordinary fields: they take a path with x = -1 known to the compiler.)
  template <class F>
  void for_each_pair(std::size_t k, const St& s, F&& f) const {
    if (!slot_any_[k]) {
      s.for_each([&](int64_t n, double w, const V& g) { f(n, -1, w, g); });
      return;
    }
    const uint8_t* sl = &pair_slot_[k * N];
    int j = 0;
    s.for_each([&](int64_t n, double w, const V& g) {
      const uint8_t q = sl[j++];
      f(n, q ? static_cast<int32_t>(node_block_[n] * kExtra + q - 1) : -1, w, g);
    });
  }
  template <class F>
  void for_each_pair_weight(std::size_t k, const St& s, F&& f) const {
    if (!slot_any_[k]) {
      s.for_each_weight([&](int64_t n, double w) { f(n, -1, w); });
      return;
    }
    const uint8_t* sl = &pair_slot_[k * N];
    int j = 0;
    s.for_each_weight([&](int64_t n, double w) {
      const uint8_t q = sl[j++];
      f(n, q ? static_cast<int32_t>(node_block_[n] * kExtra + q - 1) : -1, w);
    });
  }

  // Task 1 for near particle k: masses and momenta per field (eq. 26), total nodal volume (eq. 27)
  // and, for displacement contact, mass-weighted displacements per field (seed 000 eq. 68).
  // Each detection method's sums only when a crack uses it (volumes: seed 002; displacements: seed 000).
  void extrapolate(std::size_t k, const St& s) {
    if (need_volume_) {
      if (need_disp_) return extrapolate<true, true>(k, s);
      return extrapolate<true, false>(k, s);
    }
    if (need_disp_) return extrapolate<false, true>(k, s);
    extrapolate<false, false>(k, s);
  }
  template <bool volume, bool disp>
  void extrapolate(std::size_t k, const St& s) {
    const std::size_t p = static_cast<std::size_t>(near_[k]);
    const double mp = P_.mass[p];
    const V mv = mp * P_.v[p];
    V mu = V::Zero();
    if constexpr (disp) mu = mp * P_.u[p];
    double area = 0.0;
    if constexpr (volume) {
      const auto& e = P_.strain[p];
      area = area0_[p] * (1.0 + e[0]) * (1.0 + e[1]);  // eq. 25
    }
    for_each_pair_weight(k, s, [&](int64_t n, int32_t x, double w) {
      if (x < 0) {
        grid_.mass[n] += mp * w;
        grid_.momentum[n] += mv * w;
        if constexpr (disp) {
          const int32_t b = node_block_[n];
          if (b >= 0) disp0_[b] += mu * w;
        }
      } else {
        mass_[x] += mp * w;
        momentum_[x] += mv * w;
        if constexpr (disp) disp_[x] += mu * w;
      }
      if constexpr (volume) {
        const int32_t b = node_block_[n];
        if (b >= 0) volume_[b] += area * w;
      }
    });
  }

  double& mass(int64_t n, int32_t x) { return x < 0 ? grid_.mass[n] : mass_[x]; }
  V& momentum(int64_t n, int32_t x) { return x < 0 ? grid_.momentum[n] : momentum_[x]; }
  V& force(int64_t n, int32_t x) { return x < 0 ? grid_.force[n] : force_[x]; }
  const NodeKinematics<2>& kin(int64_t n, int32_t x) const { return x < 0 ? kin_[n] : xkin_[x]; }

  // Field slot (as in for_each_pair) for the pair particle p - node n, classified afresh: for loads
  // whose stencil is not the particle's own (face tractions). Falls back to the ordinary field when
  // the node has no field with this key.
  int32_t field_of(std::size_t p, int64_t n, const V& node_pos) const {
    if (!near_flag_[p]) return -1;
    int32_t seg[2];
    const uint32_t key = classify(P_.x[p], node_pos, seg);
    if (key == 0 || key == kOverflow) return -1;
    return extra_field(n, key);
  }

  // Task 3, grid part, for the extra fields: body force and damping (eq. 28).
  void body_force_and_damping(const V& gravity, double kappa) {
    for (std::size_t x = 0; x < mass_.size(); ++x)
      if (mass_[x] > 0.0) force_[x] += mass_[x] * gravity - kappa * momentum_[x];
  }

  // Prescribed velocity components hold for every field at the node (Task 2 / Task 6c).
  void apply_momentum_conditions(const GridConditions<2>& C) {
    for (std::size_t c = 0; c < C.node.size(); ++c) {
      const int32_t b = node_block_[C.node[c]];
      if (b < 0) continue;
      for (int s = 0; s < block_nslots_[b]; ++s)
        for (int d = 0; d < 2; ++d)
          if (C.mask[c] & (1u << d)) momentum_[b * kExtra + s][d] = mass_[b * kExtra + s] * C.velocity[c][d];
    }
  }
  // Zero force on prescribed components for every field (Task 3); returns the reaction power of
  // the extra fields, sum f . v_prescribed, for the external-work account.
  double zero_prescribed_forces(const GridConditions<2>& C) {
    double power = 0.0;
    for (std::size_t c = 0; c < C.node.size(); ++c) {
      const int32_t b = node_block_[C.node[c]];
      if (b < 0) continue;
      for (int s = 0; s < block_nslots_[b]; ++s)
        for (int d = 0; d < 2; ++d)
          if (C.mask[c] & (1u << d)) {
            power += force_[b * kExtra + s][d] * C.velocity[c][d];
            force_[b * kExtra + s][d] = 0.0;
          }
    }
    return power;
  }

  // Task 4 for the extra fields (eq. 29), then contact with force back-calculation, then the
  // velocities and accelerations of every field at multi-field nodes.
  void update_momenta(double dt) {
    for (std::size_t x = 0; x < mass_.size(); ++x)
      if (mass_[x] > 0.0) momentum_[x] += dt * force_[x];
    contact(dt, true);
    for (std::size_t b = 0; b < block_node_.size(); ++b) {
      const int64_t n = block_node_[b];
      if (grid_.mass[n] > 0.0) {
        kin_[n].v = grid_.momentum[n] / grid_.mass[n];
        kin_[n].a = grid_.force[n] / grid_.mass[n];
      }
      for (int s = 0; s < block_nslots_[b]; ++s) {
        const std::size_t x = b * kExtra + s;
        if (mass_[x] > 0.0) {
          xkin_[x].v = momentum_[x] / mass_[x];
          xkin_[x].a = force_[x] / mass_[x];
        }
      }
    }
  }

  // Task 6c starts the extra fields' momenta afresh (the ordinary field's are zeroed by the stepper).
  void clear_momenta() { std::fill(momentum_.begin(), momentum_.end(), V::Zero()); }

  // Nodal velocities of the extra fields from the latest momenta (Subtask 1, eq. 34).
  void nodal_velocities() {
    for (std::size_t x = 0; x < mass_.size(); ++x)
      if (mass_[x] > 0.0) xkin_[x].v = momentum_[x] / mass_[x];
  }

  // Contact (seed 002 §2.2; seed 000 Appendix B) at every multi-field node, between each pair of
  // fields whose keys differ in exactly one crack. With back_compute (Task 4) the momentum changes
  // are also added to the forces as Δp/dt so that Task 5 moves the particles consistently.
  // Every multi-field node on its own (it changes only its own fields' momenta and forces): in
  // parallel from kParallelPoints nodes.
  void contact(double dt, bool back_compute = false) {
    const double cell_volume = G_.h * G_.h;
    flag_closing_surfaces(dt);
    const std::size_t nb = block_node_.size();
#pragma omp parallel for schedule(static) if (parallel_points(nb))
    for (std::size_t b = 0; b < nb; ++b) {
      const int64_t n = block_node_[b];
      const int nf = 1 + block_nslots_[b];
      for (int i = 0; i < nf; ++i)
        for (int j = i + 1; j < nf; ++j) {
          const int32_t xi = i == 0 ? -1 : static_cast<int32_t>(b * kExtra + i - 1);
          const int32_t xj = static_cast<int32_t>(b * kExtra + j - 1);
          const uint32_t ki = i == 0 ? 0u : block_key_[xi], kj = block_key_[xj];
          int crack, rank_i, rank_j;
          if (!differ_in_one_crack(ki, kj, crack, rank_i, rank_j)) continue;
          const int32_t xa = rank_i > rank_j ? xi : xj, xb = rank_i > rank_j ? xj : xi;
          const double ma = mass(n, xa), mb = mass(n, xb);
          if (!(ma > 0.0 && mb > 0.0)) continue;
          V nrm = normal_sum(xi, crack) + normal_sum(xj, crack);
          const double len = nrm.norm();
          if (!(len > 0.0)) continue;
          nrm /= len;  // from above to below
          const crack::Crack2D& c = cracks_[crack];
          const Law law = c.contact_law;
          if (law == Law::None) continue;
          V& pa = momentum(n, xa);
          V& pb = momentum(n, xb);
          const V dv = pa / ma - pb / mb;
          const double approach = dv.dot(nrm);  // > 0: the faces move towards each other
          bool touching;
          if (c.detection == crack::Crack2D::Detection::Volume) {
            // Eq. 10. An opening g takes about g h (1 - d/h) from the volume of a node at distance d
            // from the crack, so approaching faces count as touching while g <= (1 - v_sep) h / (1 - d/h):
            // the gap at which they stop depends on where the crack lies among the nodes (0.1 cell on
            // a node row, 0.2 cell half a cell off; docs/validation.md, 2D cracks item 4).
            const double vrel = volume_[b] / cell_volume;
            touching = vrel > c.v_contact || (vrel >= c.v_sep && approach > 0.0);
          } else {
            // Seed 000 eqs. 69-70, with the displacements predicted to the end of the step
            // (u + dt v): testing the start-of-step overlap alone lets the faces pass each other
            // by up to one step's approach (dt |dv.n|) before contact acts.
            const V ua = (xa < 0 ? disp0_[b] : disp_[xa]) / ma, ub = (xb < 0 ? disp0_[b] : disp_[xb]) / mb;
            touching = approach > 0.0 && (ua - ub + dt * dv).dot(nrm) > 0.0;
          }
          // The node carries a crack point whose faces touch or would cross within the step
          // (flag_closing_surfaces): contact, whatever the node-averaged indicator says.
          if (!touching && approach > 0.0 && closing_[b * cracks_.size() + crack]) touching = true;
          if (!touching) continue;
          // Stick: both fields take the centre-of-mass velocity (eq. 13).
          const V stick = (ma * pb - mb * pa) / (ma + mb);
          V dp;
          if (law == Law::Stick) {
            dp = stick;
          } else {
            const double dpn = stick.dot(nrm);
            dp = dpn * nrm;
            if (law == Law::Friction) {
              // Coulomb: the tangential change needed to stick, capped at mu |normal change|
              // (eqs. 14-18 in momentum form).
              const V dpt = stick - dp;
              const double t = dpt.norm(), cap = c.friction * std::fabs(dpn);
              dp += t <= cap ? dpt : dpt * (cap / t);
            }
          }
          pa += dp;
          pb -= dp;
          if (back_compute) {
            force(n, xa) += dp / dt;
            force(n, xb) -= dp / dt;
          }
        }
    }
  }

  // Task 7 (eq. 32): crack particles move with the centre-of-mass nodal velocity; the surfaces
  // above and below move with the velocity field of their side. Uses the end-of-step momenta.
  // At an interior crack tip (crack.tip[end], material ahead of it) the two faces meet: its surfaces
  // stay at the crack point itself, so the tracked opening there is zero. Followed with the side
  // fields instead, a tip's surfaces interpolate nodes whose fields belong to the crack flanks behind
  // the tip (the tip's cell is cut only partly), and the tip "opened" by about 70 % of the interior
  // opening in a plate at rest (docs/validation.md, 2D cracks item 4). A free end (an edge crack's
  // mouth, no material ahead) keeps following its sides.
  void move_cracks(double dt) {
    for (std::size_t ci = 0; ci < cracks_.size(); ++ci) {
      crack::Crack2D& c = cracks_[ci];
      const std::size_t np = c.points.size();
      std::vector<V> vm(np), va(np), vb(np);
      const std::vector<SideFields>& sides = side_fields(ci);
#pragma omp parallel for schedule(static) if (parallel_points(np))
      for (std::size_t i = 0; i < np; ++i) {
        const V vcm = cm_velocity(c.points[i]);
        vm[i] = vcm;
        if (is_tip(c, i)) {
          va[i] = vb[i] = vcm;
          continue;
        }
        va[i] = side_velocity(sides[2 * i], vcm);
        vb[i] = side_velocity(sides[2 * i + 1], vcm);
      }
      for (std::size_t i = 0; i < np; ++i) {
        c.points[i] += dt * vm[i];
        c.above[i] += dt * va[i];
        c.below[i] += dt * vb[i];
        if (is_tip(c, i)) c.above[i] = c.below[i] = c.points[i];
      }
      c.update_extent();
      // Every crack's lines may cross this one, which has moved: the next crack classifies afresh.
      std::fill(side_valid_.begin(), side_valid_.end(), 0);
    }
  }

  // Contact detection from the tracked crack surfaces. Both node-based indicators (seed 002's
  // relative nodal volume, seed 000's mass-weighted nodal displacements) average the opening over a
  // node's support, 2-3 cells of crack: where the opening varies on the cell scale (near a tip,
  // closing after a wide opening) a node reads "apart" (V_rel < v_sep, or a positive mean
  // displacement gap) while the faces beside it already touch, and they cross there (-12 % to -16 %
  // of a cell in the colliding-disk scene, docs/validation.md). The tracked surfaces give the local
  // opening: a crack point whose normal opening, predicted to the end of the step with the side
  // velocities it moves with (move_cracks), is <= 0 flags the nodes that move its two surfaces, and
  // contact() treats approaching fields at those nodes as touching.
  void flag_closing_surfaces(double dt) {
    const std::size_t nc = cracks_.size();
    closing_.assign(block_node_.size() * nc, 0);
    for (std::size_t ci = 0; ci < nc; ++ci) {
      const crack::Crack2D& c = cracks_[ci];
      if (c.contact_law == Law::None) continue;
      const std::vector<SideFields>& sides = side_fields(ci);
      const std::size_t np = c.points.size();
#pragma omp parallel for schedule(static) if (parallel_points(np))
      for (std::size_t i = 0; i < np; ++i) {
        if (is_tip(c, i)) continue;  // its faces meet by definition (move_cracks): no gap to close
        const V nl = left_normal(c, i);
        const V vcm = cm_velocity(c.points[i]);
        const V va = side_velocity(sides[2 * i], vcm);
        const V vb = side_velocity(sides[2 * i + 1], vcm);
        if ((c.above[i] - c.below[i] + dt * (va - vb)).dot(nl) > 0.0) continue;
        auto flag = [&](int64_t n, double) {  // (relaxed: only ever set to 1 here, by any point)
          const int32_t b = node_block_[n];
          if (b >= 0) std::atomic_ref<uint8_t>(closing_[b * nc + ci]).store(1, std::memory_order_relaxed);
        };
        linear_nodes(c.above[i], flag);
        linear_nodes(c.below[i], flag);
      }
    }
  }

  // Pairs that needed a fifth field since the last call (reported by the stepper).
  long take_overflow() {
    const long o = overflow_;
    overflow_ = 0;
    return o;
  }

 private:
  static constexpr double kProbe = 1e-3;  // cells: how far above/below a surface its probe sits
  static constexpr uint32_t kOverflow = crack::kFieldKeyOverflow;  // a line crossing three or more cracks
  using Law = crack::Crack2D::ContactLaw;

  static V segment_normal(const crack::Crack2D& c, std::size_t s) {
    const V t = c.points[s + 1] - c.points[s];
    return V(t.y(), -t.x()) / t.norm();  // right of the crack direction: from above to below
  }
  // Is crack point i an interior crack tip (an end point with material ahead, crack.tip[end])?
  static bool is_tip(const crack::Crack2D& c, std::size_t i) {
    return (i == 0 && c.tip[0]) || (i + 1 == c.points.size() && c.tip[1]);
  }
  static V left_normal(const crack::Crack2D& c, std::size_t i) {
    V t = V::Zero();
    if (i > 0) t += (c.points[i] - c.points[i - 1]).normalized();
    if (i + 1 < c.points.size()) t += (c.points[i + 1] - c.points[i]).normalized();
    const double l = t.norm();
    return l > 0.0 ? V(-t.y() / l, t.x() / l) : V::Zero();
  }

  int64_t cell_of(const V& x) const {
    const double fx = (x.x() - G_.origin.x()) * inv_h_, fy = (x.y() - G_.origin.y()) * inv_h_;
    if (!(fx >= 0.0 && fy >= 0.0 && fx < cells_[0] && fy < cells_[1])) return -1;
    return static_cast<int64_t>(fx) * cells_[1] + static_cast<int64_t>(fy);
  }

  // The spatial index: for each cell, per crack, the range of segments whose bounding box grown by
  // kReach cells overlaps the cell. A contiguous range is exact for the crossing test: a segment
  // outside it cannot reach the particle-node box, and the range's end vertices are either the
  // crack's tips or vertices no particle-node line of this cell can touch.
  void build_index() {
    for (int64_t c : touched_) cell_head_[c] = -1;
    touched_.clear();
    entries_.clear();
    box_lo_[0] = box_lo_[1] = 0.0;  // empty until a cell gets an entry
    box_hi_[0] = box_hi_[1] = 0.0;
    int bi0 = cells_[0], bi1 = -1, bj0 = cells_[1], bj1 = -1;
    const double grow = kReach * G_.h;
    for (std::size_t ci = 0; ci < cracks_.size(); ++ci) {
      const auto& pts = cracks_[ci].points;
      for (std::size_t s = 0; s + 1 < pts.size(); ++s) {
        const V lo = pts[s].cwiseMin(pts[s + 1]).array() - grow, hi = pts[s].cwiseMax(pts[s + 1]).array() + grow;
        const int i0 = std::max(0, static_cast<int>(std::floor((lo.x() - G_.origin.x()) * inv_h_)));
        const int i1 = std::min(cells_[0] - 1, static_cast<int>(std::floor((hi.x() - G_.origin.x()) * inv_h_)));
        const int j0 = std::max(0, static_cast<int>(std::floor((lo.y() - G_.origin.y()) * inv_h_)));
        const int j1 = std::min(cells_[1] - 1, static_cast<int>(std::floor((hi.y() - G_.origin.y()) * inv_h_)));
        if (i0 <= i1 && j0 <= j1) {
          bi0 = std::min(bi0, i0), bi1 = std::max(bi1, i1);
          bj0 = std::min(bj0, j0), bj1 = std::max(bj1, j1);
        }
        for (int i = i0; i <= i1; ++i)
          for (int j = j0; j <= j1; ++j) {
            const int64_t cell = static_cast<int64_t>(i) * cells_[1] + j;
            int32_t e = cell_head_[cell];
            while (e >= 0 && entries_[e].crack != static_cast<int32_t>(ci)) e = entries_[e].next;
            if (e >= 0) {
              Entry& en = entries_[e];
              // The box takes every vertex of the range, also those of segments that skip this cell.
              for (std::size_t v = static_cast<std::size_t>(en.seg_hi) + 2; v <= s + 1; ++v)
                en.lo = en.lo.cwiseMin(pts[v]), en.hi = en.hi.cwiseMax(pts[v]);
              en.seg_hi = static_cast<int32_t>(s);  // segments arrive in order
            } else {
              if (cell_head_[cell] < 0) touched_.push_back(cell);
              entries_.push_back({static_cast<int32_t>(ci), static_cast<int32_t>(s), static_cast<int32_t>(s),
                                  cell_head_[cell], pts[s].cwiseMin(pts[s + 1]), pts[s].cwiseMax(pts[s + 1])});
              cell_head_[cell] = static_cast<int32_t>(entries_.size() - 1);
            }
          }
      }
    }
    if (bi0 <= bi1) {
      box_lo_[0] = bi0, box_hi_[0] = bi1 + 1.0;
      box_lo_[1] = bj0, box_hi_[1] = bj1 + 1.0;
    }
  }

  // The list of near particles, in particle order, from the flags (only when a flag changed): in
  // parallel over fixed chunks, each filled at the offset of a prefix sum of the chunk counts.
  void collect_near_particles() {
    for (int32_t p : near_) near_index_[p] = -1;
    const std::size_t np = P_.size();
    constexpr std::size_t kChunk = 8192;
    const std::size_t chunks = (np + kChunk - 1) / kChunk;
    chunk_begin_.assign(chunks + 1, 0);
    const bool par = worth_parallel(np);
#pragma omp parallel for schedule(static) if (par)
    for (std::size_t c = 0; c < chunks; ++c) {
      std::size_t count = 0;
      const std::size_t end = std::min(np, (c + 1) * kChunk);
      for (std::size_t p = c * kChunk; p < end; ++p) count += near_flag_[p];
      chunk_begin_[c + 1] = count;
    }
    for (std::size_t c = 0; c < chunks; ++c) chunk_begin_[c + 1] += chunk_begin_[c];
    near_.resize(chunk_begin_[chunks]);
#pragma omp parallel for schedule(static) if (par)
    for (std::size_t c = 0; c < chunks; ++c) {
      if (chunk_begin_[c + 1] == chunk_begin_[c]) continue;
      std::size_t k = chunk_begin_[c];
      const std::size_t end = std::min(np, (c + 1) * kChunk);
      for (std::size_t p = c * kChunk; p < end; ++p)
        if (near_flag_[p]) {
          near_index_[p] = static_cast<int32_t>(k);
          near_[k++] = static_cast<int32_t>(p);
        }
    }
  }

  // Field key of the line particle xp -> node xn: one code per crossed crack,
  // code = 2 crack + (below ? 1 : 0) + 1, two codes packed in ascending order (low 16 bits first).
  // seg receives the crossed segment of each code (same order). Key 0: no crossing.
  uint32_t classify(const V& xp, const V& xn, int32_t seg[2]) const {
    const int64_t cell = cell_of(xp);
    if (cell < 0) return 0;
    return classify_in_cell(cell, xp, xn, seg);
  }
  // The same for a particle known to lie in `cell` (>= 0).
  uint32_t classify_in_cell(int64_t cell, const V& xp, const V& xn, int32_t seg[2]) const {
    crack::FieldKeyBuilder b;
    for (int32_t e = cell_head_[cell]; e >= 0; e = entries_[e].next) {
      const Entry& en = entries_[e];
      if (!add_crossing(b, en.crack, en.seg_lo, en.seg_hi, xp, xn)) return kOverflow;
    }
    return b.key(seg);
  }

  // Adds to b the crossing of the line xp -> xn with segments lo..hi of crack `crack`, if any;
  // false when that is a third crossed crack (the key overflows).
  bool add_crossing(crack::FieldKeyBuilder& b, int32_t crack, int32_t lo, int32_t hi, const V& xp, const V& xn) const {
    const crack::Crack2D& c = cracks_[crack];
    if (!crack::extent_overlaps(c, xp, xn)) return true;  // Subtask 1
    std::size_t s = 0;
    const crack::Side side =
        crack::polyline_crossing(c.points.data() + lo, static_cast<std::size_t>(hi - lo + 2), xp, xn, &s);
    return side == crack::Side::None || b.add(crack, side, lo + static_cast<int32_t>(s));
  }

  // An index entry narrowed for one particle: segments lo..hi of the crack (none when lo > hi).
  struct SubRange {
    int32_t crack, lo, hi;
  };
  static constexpr int kMaxSub = 8;  // entries per cell narrowed; a cell with more uses its full ranges

  // classify_in_cell on narrowed ranges (same answers, see classify_pairs).
  uint32_t classify_sub(const SubRange* sub, int nsub, const V& xp, const V& xn, int32_t seg[2]) const {
    crack::FieldKeyBuilder b;
    for (int e = 0; e < nsub; ++e) {
      const SubRange& sr = sub[e];
      if (sr.lo <= sr.hi && !add_crossing(b, sr.crack, sr.lo, sr.hi, xp, xn)) return kOverflow;
    }
    return b.key(seg);
  }

  // Keys of every pair of every near particle. Per particle, each index entry of its cell is first
  // narrowed to the segments whose bounding box touches the closed box B spanned by the particle and
  // its stencil nodes (an entry covers every segment within kReach cells of the cell, ~2 kReach + 2
  // segments; B meets ~3). Exact: a segment apart from B cannot touch any particle-node line of the
  // particle, nor can the end vertices that the narrowed range shares with such segments, so
  // polyline_crossing's rules (crossing.hpp: a contact only at a vertex on the line, a range end
  // treated as a tip) give the same side and segment on the narrowed range as on the entry's.
  void classify_pairs() {
    const std::size_t nn = near_.size();
    pair_key_.resize(nn * N);
    pair_seg_.resize(nn * N * 2);
    near_st_.resize(nn);
    key_any_.resize(nn);
#pragma omp parallel for schedule(static) if (nn >= 512)
    for (std::size_t k = 0; k < nn; ++k) {
      const std::size_t p = static_cast<std::size_t>(near_[k]);
      const V xp = P_.x[p];
      St& s = near_st_[k];
      s.eval(G_, stride_, inv_h_, xp, P_.half_width[p]);
      // The particle's cell and its first node's grid indices once (node_position's division per
      // node was a large share of this loop); node j of the stencil is (i0 + j / K, j0 + j % K).
      const int64_t cell = cell_of(xp);  // >= 0: a near particle's cell has index entries
      const int64_t i0 = s.base / static_cast<int64_t>(stride_[0]), j0 = s.base % static_cast<int64_t>(stride_[0]);
      // Node coordinates computed once: the box B must hold exactly the values classified.
      double nx[St::K], ny[St::K];
      for (int a = 0; a < St::K; ++a) {
        const V xa = node_position(i0 + a, j0 + a);
        nx[a] = xa.x(), ny[a] = xa.y();
      }
      double lo[2] = {xp.x(), xp.y()}, hi[2] = {xp.x(), xp.y()};
      for (int a = 0; a < St::K; ++a) {
        lo[0] = std::min(lo[0], nx[a]), hi[0] = std::max(hi[0], nx[a]);
        lo[1] = std::min(lo[1], ny[a]), hi[1] = std::max(hi[1], ny[a]);
      }
      auto meets = [&](const V& a, const V& b) {  // the closed box [min(a, b), max(a, b)] meets B
        return std::max(a.x(), b.x()) >= lo[0] && std::min(a.x(), b.x()) <= hi[0] &&
               std::max(a.y(), b.y()) >= lo[1] && std::min(a.y(), b.y()) <= hi[1];
      };
      SubRange sub[kMaxSub];
      int nsub = 0;
      bool any = false;
      for (int32_t e = cell_head_[cell]; e >= 0; e = entries_[e].next) {
        if (nsub == kMaxSub) {
          nsub = -1;
          any = true;
          break;
        }
        const Entry& en = entries_[e];
        int32_t a = en.seg_lo, b = en.seg_hi;
        if (!meets(en.lo, en.hi)) {
          a = b + 1;  // no segment of the entry comes near B
        } else {
          const auto& pts = cracks_[en.crack].points;
          while (a <= b && !meets(pts[a], pts[a + 1])) ++a;
          while (b >= a && !meets(pts[b], pts[b + 1])) --b;
        }
        any = any || a <= b;
        sub[nsub++] = {en.crack, a, b};
      }
      key_any_[k] = any;
      if (!any) {  // every key 0
        std::fill_n(&pair_key_[k * N], N, 0u);
        continue;
      }
      int j = 0;
      s.for_each_weight([&](int64_t, double w) {
        const std::size_t q = k * N + j;
        const V xn(nx[j / St::K], ny[j % St::K]);
        ++j;
        pair_key_[q] = 0;
        if (w == 0.0) return;  // no contribution: no field needed
        pair_key_[q] = nsub >= 0 ? classify_sub(sub, nsub, xp, xn, &pair_seg_[2 * q])
                                 : classify_in_cell(cell, xp, xn, &pair_seg_[2 * q]);
      });
    }
  }

  V node_position(int64_t n) const {
    const int64_t i = n / stride_[0], j = n % stride_[0];
    return node_position(i, j);
  }
  V node_position(int64_t i, int64_t j) const { return V(G_.origin.x() + G_.h * i, G_.origin.y() + G_.h * j); }

  // Serial, in particle order: deterministic slot numbering for any thread count.
  void allocate_fields() {
    for (int64_t n : block_node_) node_block_[n] = -1;
    block_node_.clear();
    block_nslots_.clear();
    block_key_.clear();
    std::vector<V>& normals = normals_next_;  // per slot, two (one per code of the key)
    normals.clear();
    seg_normal_.resize(cracks_.size());
    for (std::size_t ci = 0; ci < cracks_.size(); ++ci) {
      const auto& c = cracks_[ci];
      seg_normal_[ci].resize(c.points.size() - 1);
      for (std::size_t sgi = 0; sgi + 1 < c.points.size(); ++sgi) seg_normal_[ci][sgi] = segment_normal(c, sgi);
    }
    const std::size_t nn = near_.size();
    pair_slot_.assign(nn * N, 0);
    slot_any_.assign(nn, 0);
    for (std::size_t k = 0; k < nn; ++k) {
      if (!key_any_[k]) continue;  // every key 0: every pair uses the ordinary field
      int j = 0;
      near_st_[k].for_each_weight([&](int64_t n, double) {
        const std::size_t q = k * N + j++;
        const uint32_t key = pair_key_[q];
        if (key == 0) return;
        if (key == kOverflow) {
          ++overflow_;  // more crossings than a key holds: the pair uses the ordinary field
          return;
        }
        int32_t b = node_block_[n];
        if (b < 0) {
          b = static_cast<int32_t>(block_node_.size());
          node_block_[n] = b;
          block_node_.push_back(n);
          block_nslots_.push_back(0);
          block_key_.insert(block_key_.end(), kExtra, 0u);
          normals.insert(normals.end(), 2 * kExtra, V::Zero());
        }
        const int32_t x = extra_field(n, key);
        int slot = x < 0 ? -1 : x - b * kExtra;
        if (slot < 0) {
          if (block_nslots_[b] == kExtra) {
            ++overflow_;  // a fifth field: this pair falls back to the ordinary field
            return;
          }
          slot = block_nslots_[b]++;
          block_key_[b * kExtra + slot] = key;
        }
        pair_slot_[q] = static_cast<uint8_t>(slot + 1);
        slot_any_[k] = 1;
        for (int c = 0; c < 2; ++c) {
          const uint32_t code = (key >> (16 * c)) & 0xffffu;
          if (!code) continue;
          const int crack = static_cast<int>((code - 1) / 2);
          normals[2 * (b * kExtra + slot) + c] += seg_normal_[crack][pair_seg_[2 * q + c]];
        }
      });
    }
    const std::size_t ns = block_node_.size() * kExtra;
    mass_.assign(ns, 0.0);
    momentum_.assign(ns, V::Zero());
    force_.assign(ns, V::Zero());
    disp_.assign(ns, V::Zero());
    xkin_.assign(ns, NodeKinematics<2>{V::Zero(), V::Zero()});
    normal_.swap(normals);
    volume_.assign(block_node_.size(), 0.0);
    disp0_.assign(block_node_.size(), V::Zero());
  }

  // The extra-field slot of node n holding `key`, or -1 when the node has none.
  int32_t extra_field(int64_t n, uint32_t key) const {
    const int32_t b = node_block_[n];
    if (b < 0) return -1;
    for (int s = 0; s < block_nslots_[b]; ++s)
      if (block_key_[b * kExtra + s] == key) return b * kExtra + s;
    return -1;
  }

  // Sum of the crack normals stored for `crack` in field x (none for the ordinary field).
  V normal_sum(int32_t x, int crack) const {
    if (x < 0) return V::Zero();
    const uint32_t key = block_key_[x];
    V s = V::Zero();
    for (int c = 0; c < 2; ++c) {
      const uint32_t code = (key >> (16 * c)) & 0xffffu;
      if (code && static_cast<int>((code - 1) / 2) == crack) s += normal_[2 * x + c];
    }
    return s;
  }

  // Do keys a and b differ in exactly one crack? Then crack is that crack, and rank (+1 above,
  // 0 not crossed, -1 below) says which field holds the material above it.
  static bool differ_in_one_crack(uint32_t a, uint32_t b, int& crack, int& rank_a, int& rank_b) {
    int cr[4], ra[4], rb[4], n = 0;
    auto add = [&](uint32_t key, int* r) {
      for (int c = 0; c < 2; ++c) {
        const uint32_t code = (key >> (16 * c)) & 0xffffu;
        if (!code) continue;
        const int k = static_cast<int>((code - 1) / 2), rank = (code - 1) % 2 ? -1 : 1;
        int i = 0;
        while (i < n && cr[i] != k) ++i;
        if (i == n) {
          cr[n] = k, ra[n] = 0, rb[n] = 0;
          ++n;
        }
        r[i] = rank;
      }
    };
    add(a, ra);
    add(b, rb);
    int diff = 0;
    for (int i = 0; i < n; ++i)
      if (ra[i] != rb[i]) {
        ++diff;
        crack = cr[i], rank_a = ra[i], rank_b = rb[i];
      }
    return diff == 1;
  }

  V cm_velocity(const V& x) const {
    V sum = V::Zero();
    double wsum = 0.0;
    linear_nodes(x, [&](int64_t n, double w) {
      double m = grid_.mass[n];
      V p = grid_.momentum[n];
      const int32_t b = node_block_[n];
      if (b >= 0)
        for (int s = 0; s < block_nslots_[b]; ++s) m += mass_[b * kExtra + s], p += momentum_[b * kExtra + s];
      if (m > 0.0) sum += w * p / m, wsum += w;
    });
    return wsum > 0.0 ? V(sum / wsum) : V::Zero();
  }

  // The nodes of a surface's cell, with bilinear weights, and the field at each that its probe
  // selects (nodes without a field for that side left out). They depend on the crack geometry and
  // the fields' keys, not on the momenta, so they are found once per step (up to three contact
  // passes and the crack motion read them), and again only after a crack moved.
  struct SideFields {
    int count = 0;
    int64_t node[4];
    double w[4];
    int32_t field[4];
  };
  // The side fields of crack ci, two per point (2 i: above, 2 i + 1: below), found afresh when a
  // crack has moved since. Called before the loops over crack points, which run in parallel.
  const std::vector<SideFields>& side_fields(std::size_t ci) {
    if (!side_valid_[ci]) find_side_fields(ci);
    return side_fields_[ci];
  }
  // The velocity a surface follows: that of the field a virtual particle at its point's probe would
  // use, interpolated at the surface (fallback where no such field has mass).
  V side_velocity(const SideFields& sf, const V& fallback) const {
    V sum = V::Zero();
    double wsum = 0.0;
    for (int e = 0; e < sf.count; ++e) {
      const int64_t n = sf.node[e];
      const int32_t xs = sf.field[e];
      const double w = sf.w[e];
      const double m = xs < 0 ? grid_.mass[n] : mass_[xs];
      if (m > 0.0) sum += w * (xs < 0 ? grid_.momentum[n] : momentum_[xs]) / m, wsum += w;
    }
    return wsum > 0.0 ? V(sum / wsum) : fallback;
  }
  void find_side_fields(std::size_t ci) {
    const crack::Crack2D& c = cracks_[ci];
    auto& out = side_fields_[ci];
    out.assign(2 * c.points.size(), SideFields{});
    const std::size_t np = c.points.size();
#pragma omp parallel for schedule(static) if (parallel_points(np))
    for (std::size_t i = 0; i < np; ++i) {
      if (is_tip(c, i)) continue;  // a tip's surfaces follow the point itself
      const V nl = left_normal(c, i);
      // The probes sit just off the crack line itself, not off the surfaces: a surface that has
      // moved across the line (faces pressed together) must keep following its own side's field.
      for (int side = 0; side < 2; ++side) {
        const V probe = side == 0 ? V(c.points[i] + kProbe * G_.h * nl) : V(c.points[i] - kProbe * G_.h * nl);
        SideFields& sf = out[2 * i + side];
        linear_nodes(side == 0 ? c.above[i] : c.below[i], [&](int64_t n, double w) {
          int32_t seg[2];
          const uint32_t key = classify(probe, node_position(n), seg);
          if (key == kOverflow) return;
          const int32_t xs = key == 0 ? -1 : extra_field(n, key);
          if (key != 0 && xs < 0) return;  // the node has no field for that side
          sf.node[sf.count] = n, sf.w[sf.count] = w, sf.field[sf.count] = xs;
          ++sf.count;
        });
      }
    }
    side_valid_[ci] = 1;
  }

  // Loops over crack points or multi-field nodes (a few hundred, each ~0.1-0.3 us of work) pay for
  // a fork/join from about this many.
  static constexpr std::size_t kParallelPoints = 128;
  static bool parallel_points(std::size_t n) { return n >= kParallelPoints && omp_get_max_threads() > 1; }

  // The four nodes of x's cell with bilinear weights (massless crack particles have no size).
  template <class F>
  void linear_nodes(const V& x, F&& f) const {
    const double fx = (x.x() - G_.origin.x()) * inv_h_, fy = (x.y() - G_.origin.y()) * inv_h_;
    if (!(fx >= 0.0 && fy >= 0.0 && fx <= cells_[0] && fy <= cells_[1])) return;
    const int i = std::min(static_cast<int>(fx), cells_[0] - 1), j = std::min(static_cast<int>(fy), cells_[1] - 1);
    const double rx = fx - i, ry = fy - j;
    const int64_t n00 = static_cast<int64_t>(i) * stride_[0] + j;
    f(n00, (1 - rx) * (1 - ry));
    f(n00 + 1, (1 - rx) * ry);
    f(n00 + stride_[0], rx * (1 - ry));
    f(n00 + stride_[0] + 1, rx * ry);
  }

  Model<2>& m_;
  Particles<2>& P_;
  const GridGeometry<2>& G_;
  GridFields<2>& grid_;
  std::vector<NodeKinematics<2>>& kin_;
  std::vector<crack::Crack2D>& cracks_;
  std::array<std::size_t, 2> stride_;
  double inv_h_;
  int cells_[2];
  double near_reach_;  // a particle is near when within this distance of an index entry's box
  std::vector<double> area0_;

  std::vector<int32_t> cell_head_;
  double box_lo_[2] = {0.0, 0.0}, box_hi_[2] = {0.0, 0.0};  // cells [lo, hi) holding all index entries
  std::vector<int64_t> touched_;
  std::vector<Entry> entries_;

  std::vector<uint8_t> near_flag_;
  std::vector<int32_t> near_;
  std::vector<int32_t> near_index_;  // per particle: index in near_, or -1
  std::vector<std::size_t> chunk_begin_;
  std::vector<St> near_st_;
  std::vector<uint8_t> key_any_;   // per near particle: does a key differ from 0 (set by classify_pairs)
  std::vector<uint8_t> slot_any_;  // per near particle: does a pair use an extra field (allocate_fields)

  std::vector<uint32_t> pair_key_;
  std::vector<int32_t> pair_seg_;
  std::vector<uint8_t> pair_slot_;

  std::vector<int32_t> node_block_;
  std::vector<int64_t> block_node_;
  std::vector<uint8_t> block_nslots_;
  std::vector<uint32_t> block_key_;
  std::vector<double> mass_, volume_;
  std::vector<V> momentum_, force_, disp_, normal_, disp0_, normals_next_;
  std::vector<NodeKinematics<2>> xkin_;
  std::vector<uint8_t> closing_;  // per block and crack: a crack point's faces close (contact())
  std::vector<std::vector<SideFields>> side_fields_;  // per crack, two per point (side_fields())
  std::vector<uint8_t> side_valid_;                   // per crack: side_fields_ are up to date
  long overflow_ = 0;
  bool need_volume_ = false, need_disp_ = false;  // some crack detects contact by volume / displacement
  std::vector<std::vector<V>> seg_normal_;  // per crack and segment: segment_normal, for allocate_fields
};

}  // namespace cleave
