// Top layer of the crack fields (libmpm/mpm/crack_fields.hpp; layering: grid_cells.hpp): crack
// contact (seed 002 §2.2; seed 000 Appendix B) at every multi-field node, between each pair of
// fields whose keys differ in exactly one crack: detection (the crack's nodal-volume or
// nodal-displacement indicator, overridden where the tracked surfaces close), then the crack's law
// (stick, frictionless or Coulomb friction) as a momentum exchange between the two fields.
// The nodal volume is compared with a cell's area (2D) or volume (3D). 3D particles carry no
// rotation, so 3D displacement detection compares the fields' displacements without the rotation
// correction of 2D. The same loop couples the fields of two bodies in declared contact
// (body_groups.hpp): their pair's law, a normal from the fields' mass gradients, detection by
// position or volume; bodies press but never pull in the exchange of momentum (Task 4).
#pragma once
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <vector>

#include "libmpm/core/part_costs.hpp"
#include "libmpm/crack/crack2d.hpp"
#include "libmpm/mpm/crack_fields/crack_motion.hpp"
#include "libmpm/mpm/crack_fields/line_weight.hpp"
#include "libmpm/mpm/model.hpp"

namespace cleave::crack_fields {

template <int Dim, class SF>
class CrackContact : public CrackMotion<Dim, SF> {
  using Base = CrackMotion<Dim, SF>;
  using V = Vec<Dim>;

 public:
  // The four calls of a step (mpm_step.cpp), in order: what each may add and what it applies.
  enum class Call {
    Start,     // Task 2, on the momenta mapped from the particles
    Forces,    // Task 4, after the forces: the exchanges are also added to the forces (back-computed)
    Remapped,  // Task 6c, on the re-extrapolated momenta the second stress update reads
    Closing,   // after that stress update, for the crack motion (Task 7): crack pairs that touch only now
  };
  // Contact at every multi-field node, between each pair of fields whose keys differ in exactly one
  // crack. In Task 4 the momentum changes are also added to the forces as Δp/dt so that Task 5 moves
  // the particles consistently.
  // A pair that touches at one call of a step keeps touching for the rest of the step (Tasks 2, 4
  // and 6c apply the law to it), and Task 4 adds no pair in which a field holds less than
  // kMinForcedShare of the pair's mass. Such a field is material whose support just reaches a node
  // beyond the crack: after the forces its velocity is dominated by dt f / m, f its particles' stress
  // through a full cell's gradient, and m a sliver of their mass. Task 4 read that as an approach and
  // moved the impulse to the field across the crack, while Tasks 2 and 6c, on the same pair's unforced
  // velocities, let it go: a one-way spring across the crack that fed energy into a spinning cracked
  // disk until it blew up (displacement detection, every law; stick with volume detection). Coupled
  // in every task of the step or in none, the disk at 1 rad/ms keeps its energy to 3e-4 over a radian
  // with every law and detection, and colliding faces still stop within 1 % of a cell (docs/validation.md,
  // cracks under rigid rotation).
  // A crack pair decided in Task 2 does no work: the particles keep their mapped relative velocity u0
  // (FLIP), Task 4's exchange cancels the forces' change δ of it, and the two stress halves each
  // see the faces held together, so the exchanges' work sums to zero at first order. A pair added
  // later does not. Added in Task 4 while its faces moved apart at the step's start (u0 < 0 along
  // the normal) and together after the forces (u0 + δ > 0), it makes μ |u0| (u0 + δ) / 2 (μ the
  // reduced mass), so Task 4 adds only pairs that approached before the forces too. Added in
  // Task 6c, it holds the faces in the second stress half while the particles never received the
  // exchange, so Task 6c adds none; the pairs that touch only then are applied after that stress
  // update (Call::Closing), where they keep the crack's tracked faces from crossing as they move
  // (Task 7) and strain nothing. A crack kinked on a node gained 1.41 % in 40 us without both rules
  // and loses 0.50 % with them (docs/validation.md, "Stability at the extremes"). Bodies in contact
  // keep the rules they had (their pairs press only in Task 4; body_groups.hpp).
  // Every multi-field node on its own (it changes only its own fields' momenta and forces): in
  // parallel from kParallelPoints nodes.
  void contact(double dt, Call call) {
    const bool back_compute = call == Call::Forces;
    const int was = costs::enter(costs::Contact);  // the run's costs (crack_fields.hpp says why calls)
    double cell_volume = G_.h * G_.h;
    if constexpr (Dim == 3) cell_volume *= G_.h;
    update_spins();
    flag_closing_surfaces(dt);
    line_points_.assign(cracks_.size(), nullptr);  // (volume detection's crack lines, found before the loop)
    for (std::size_t ci = 0; ci < cracks_.size(); ++ci)
      if (cracks_[ci].contact_law != Law::None && cracks_[ci].detection == crack::Detection::Volume)
        line_points_[ci] = &read_points(ci);
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
          // Fields of two bodies (body_groups.hpp), or of one body on two sides of one crack.
          const int gi = bodies_ ? field_group(n, ki) : 0, gj = bodies_ ? field_group(n, kj) : 0;
          const bool two_bodies = gi != gj;
          int crack = 0, rank_i = 0, rank_j = 0;
          if (!two_bodies && !differ_in_one_crack(ki, kj, crack, rank_i, rank_j)) continue;
          const int32_t xa = rank_i >= rank_j ? xi : xj, xb = rank_i >= rank_j ? xj : xi;
          const double ma = mass(n, xa), mb = mass(n, xb);
          if (!(ma > 0.0 && mb > 0.0)) continue;
          // The normal from a to b: the crack's (from above to below), or between bodies the
          // difference of the two fields' sums m_p grad S (each points out of its own body), or the
          // sum of the body the scene names as the pair's flat face (its "normal" key).
          V nrm;
          if (!two_bodies) nrm = normal_sum(xi, crack) + normal_sum(xj, crack);
          else {
            const int from = contact_.normal_group(gi, gj);
            nrm = from == gi ? mass_gradient(b, xa) : from == gj ? V(-mass_gradient(b, xb))
                                                                : V(mass_gradient(b, xa) - mass_gradient(b, xb));
          }
          const double len = nrm.norm();
          if (!(len > 0.0)) continue;
          nrm /= len;
          // A pair of bodies the scene did not declare sticks, as on one field (no law).
          const crack::ContactSettings* c = two_bodies ? contact_.law(gi, gj) : &cracks_[crack];
          const Law law = c ? c->contact_law : Law::Stick;
          if (law == Law::None) continue;
          V& pa = momentum(n, xa);
          V& pb = momentum(n, xb);
          // The fields' velocities are those of their mass centres, which lie on either side of the
          // crack: in a body spinning at omega they differ by omega x (ca - cb) while the faces stay
          // together. The faces' relative velocity is what remains after the crack's own spin
          // (crack_spin). Two bodies share no spin.
          const Spin w = two_bodies ? no_spin() : spin_[crack];
          const V ca = field_centre(n, xa), cb = field_centre(n, xb);
          const V rigid = cross(w, ca - cb);
          const V dv = pa / ma - pb / mb - rigid;
          const double approach = dv.dot(nrm);  // > 0: the faces move towards each other
          uint8_t& touched = touching_[b * kPairSlots + i * kFieldSlots + j];  // earlier in this step
          if (call == Call::Closing && (two_bodies || touched)) continue;  // (applied already)
          bool touching = touched || !c;
          // A sliver's share: of the pair's mass across a crack (one material), of its volume between two
          // bodies (whose densities may differ 100-fold: by mass, a heavy impactor's pair with a light
          // beam was always a sliver, never added in Task 4, and the beam impact gained 1-12 % energy).
          const double sa = two_bodies ? field_volume(b, xa) : ma, sb = two_bodies ? field_volume(b, xb) : mb;
          bool may_add = !touching && !(back_compute && std::min(sa, sb) < kMinForcedShare * (sa + sb));
          if (may_add && !two_bodies) {  // a crack pair added after Task 2 (the rules above)
            if (call == Call::Remapped) may_add = false;
            else if (back_compute) {
              const V before = (pa - dt * force(n, xa)) / ma - (pb - dt * force(n, xb)) / mb - rigid;
              may_add = before.dot(nrm) > 0.0;
            }
          }
          if (!may_add) {
            // (kept from earlier in the step, or not Task 4's to add)
          } else if (c->detection == crack::Detection::Volume) {
            // Eq. 10, with the volume's deficit measured against the crack's weight in the node. An
            // opening g takes g L from the volume of a node, L the integral of its shape function
            // along the crack (L = h (1 - d/h) at a distance d from a straight crack along the grid),
            // so seed 002's V_rel >= v_sep let approaching faces touch at g <= (1 - v_sep) h / (1 -
            // d/h): 0.1 cell on a node row, 0.2 half a cell off, and a crack moving across the rows
            // closed unlike one at rest (17.8 % at 0.5 mm cells against a bound of 10.2 %:
            // docs/validation.md, 2D cracks item 4). With 1 - V_rel <= (1 - v_sep) L / h they touch
            // at g <= (1 - v_sep) h wherever the crack lies (the seed's criterion on a node row).
            // 2D, along the crack where its faces part (read_points); 3D and two bodies: L = h.
            const double vrel = volume_[b] / cell_volume;
            if (two_bodies || Dim == 3) touching = vrel > c->v_contact || (vrel >= c->v_sep && approach > 0.0);
            else
              touching = vrel > c->v_contact ||
                         (approach > 0.0 && 1.0 - vrel <= (1.0 - c->v_sep) * crack_line_weight(n, crack));
          } else if (c->detection == crack::Detection::Position) {
            // Two bodies: their fields' mass centres, each within its own body, come closer along the
            // normal than d_contact cells by the end of the step (the centres of two bodies pressed
            // together at a node lie about 2/3 of a cell apart).
            touching = approach > 0.0 && (cb - ca).dot(nrm) - dt * approach < c->d_contact * G_.h;
          } else {
            // Seed 000 eqs. 69-70, with the displacements predicted to the end of the step
            // (u + dt v): testing the start-of-step overlap alone lets the faces pass each other
            // by up to one step's approach (dt |dv.n|) before contact acts.
            // The gap between the faces, not between the fields' displacements: the mass centres of
            // the two fields started at Xa and Xb, and a rotation R of the material about them turns
            // Xa - Xb into R (Xa - Xb) without moving the faces apart, so the overlap is
            // (ca - cb) - R (Xa - Xb) = ua - ub + (I - R)(Xa - Xb), R from the node's mean rotation.
            // (Without it a body turned by theta read an overlap (1 - cos theta) |Xa - Xb| and
            // contact acted on faces that had not moved apart: docs/validation.md.)
            const V ua = (xa < 0 ? disp0_[b] : disp_[xa]) / ma, ub = (xb < 0 ? disp0_[b] : disp_[xb]) / mb;
            V gap = ua - ub;
            double mn = grid_.mass[n];
            for (int s = 0; s < block_nslots_[b]; ++s) mn += mass_[b * kExtra + s];
            const double th = mn > 0.0 ? rot_[b] / mn : 0.0;
            if constexpr (Dim == 2) {  // (3D particles carry no rotation: the gap as it is)
              if (th != 0.0) {
                const V d0 = (ca - ua) - (cb - ub);  // Xa - Xb
                const double cs = std::cos(th), sn = std::sin(th);
                gap += d0 - V(cs * d0.x() - sn * d0.y(), sn * d0.x() + cs * d0.y());
              }
            }
            touching = approach > 0.0 && (gap + dt * dv).dot(nrm) > 0.0;
          }
          // The node carries a crack point whose faces touch or would cross within the step
          // (flag_closing_surfaces): contact, whatever the node-averaged indicator says.
          if (may_add && !touching && approach > 0.0 && !two_bodies && closing_[b * cracks_.size() + crack])
            touching = true;
          if (!touching) continue;
          touched = 1;
          // Bodies press but do not pull: the exchange of momentum (Task 4) between the fields of two
          // bodies acts only while they approach. (Tasks 2 and 6c, which correct the velocities that
          // strain the particles, keep a touching pair together both ways. Pushing only there too
          // gained energy as colliding disks came apart, +0.5 % at 1 mm cells, +1 % at 0.5 mm; pulling
          // in Task 4 too glued a block resting under gravity to its slope.)
          if (two_bodies && back_compute && law != Law::Stick && !(approach > 0.0)) continue;
          // Stick: both fields take the centre-of-mass velocity (eq. 13), up to the rigid spin's
          // difference between their mass centres (the change that makes dv zero).
          const V stick = (ma * pb - mb * pa) / (ma + mb) + (ma * mb / (ma + mb)) * rigid;
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
              const double t = dpt.norm(), cap = c->friction * std::fabs(dpn);
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
    costs::leave(was);
  }
  // A new step: its pairs start apart (called once the step's fields are allocated).
  void begin_step_contact() { touching_.assign(block_node_.size() * kPairSlots, 0); }
  // The mass gradient of field x of block b (x < 0: the ordinary field).
  V mass_gradient(std::size_t b, int32_t x) const { return x < 0 ? grad0_[b] : grad_[x]; }
  double field_volume(std::size_t b, int32_t x) const { return x < 0 ? fvol0_[b] : fvol_[x]; }

 protected:
  using typename Base::SideFields, typename Base::Spin;
  using Base::block_key_, Base::block_node_, Base::block_nslots_, Base::cm_velocity, Base::crack_spin, Base::cracks_;
  using Base::cross, Base::field_centre, Base::grid_, Base::mass_, Base::rot_, Base::spin_, Base::update_spins;
  using Base::vm_;
  using Base::bodies_, Base::contact_, Base::field_group, Base::fvol_, Base::fvol0_, Base::grad_, Base::grad0_;
  using Base::no_spin;
  using Base::disp0_, Base::disp_, Base::force, Base::G_, Base::is_tip, Base::kExtra, Base::left_normal;
  using Base::linear_nodes, Base::mass, Base::momentum, Base::node_block_, Base::normal_sum;
  using Base::cell_head_, Base::cell_of, Base::entries_, Base::node_position, Base::read_points;
  using Base::parallel_points, Base::side_fields, Base::side_mass, Base::side_velocity, Base::volume_;
  using Law = crack::ContactLaw;

  CrackContact(Model<Dim>& m, GridFields<Dim>& grid, std::vector<NodeKinematics<Dim>>& kin) : Base(m, grid, kin) {}

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
      const crack::ExplicitCrack<Dim>& c = cracks_[ci];
      if (c.contact_law == Law::None) continue;
      const std::vector<SideFields>& sides = side_fields(ci);
      const std::size_t np = c.points.size();
      const Spin spin = spin_[ci];
      const std::vector<V>& vm = vm_[ci];
#pragma omp parallel for schedule(static) if (parallel_points(np))
      for (std::size_t i = 0; i < np; ++i) {
        if (is_tip(c, i)) continue;  // its faces meet by definition (move_cracks): no gap to close
        if (off_material(sides[2 * i]) || off_material(sides[2 * i + 1])) continue;
        const V nl = left_normal(c, i);
        const V vcm = vm[i];
        const V va = side_velocity(sides[2 * i], vcm, spin, c.above[i]);
        const V vb = side_velocity(sides[2 * i + 1], vcm, spin, c.below[i]);
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

  // Does a surface lie about half a cell or more outside its side's material? Then the mass its side
  // fields hold at the surface (their nodes' masses at its weights) is under a quarter of the
  // heaviest of them (inside the material it is about half or more: a surface on a node line takes
  // the nodes that hold half their material on its side). Such a point (a mouth beyond a body's
  // edge: drawn there, or carried there by cut_through_near_edges) has no faces that could touch, and
  // its surfaces follow fields that a few particles graze: in a DCB spinning at 0.1 rad/ms, its
  // crack drawn 2 mm past the loaded edge, they drifted shut at 5 cm/s, the mouth's nodes were held
  // in contact from 0.52 ms and the arms stopped vibrating (docs/validation.md, "Spinning bodies").
  bool off_material(const SideFields& sf) const {
    double heaviest = 0.0, held = 0.0;
    for (int e = 0; e < sf.count; ++e) {
      const double m = side_mass(sf, e);
      heaviest = std::max(heaviest, m), held += sf.w[e] * m;
    }
    return held < 0.25 * heaviest;
  }

  // Do keys a and b differ in exactly one crack? Then crack is that crack, and rank (+1 above,
  // 0 not crossed, -1 below) says which field holds the material above it.
  static bool differ_in_one_crack(uint32_t a, uint32_t b, int& crack, int& rank_a, int& rank_b) {
    int cr[4], ra[4], rb[4], n = 0;
    auto add = [&](uint32_t key, int* r) {
      for (int c = 0; c < 2; ++c) {
        const uint32_t code = crack::key_code(key, c);
        if (!code) continue;
        const int k = crack::code_crack(code), rank = (code - 1) % 2 ? -1 : 1;
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

  // 2D: the crack's weight in node n's volume, L / h (volume detection above): the integral of the
  // node's shape function along the polyline of the crack's read points (on its discrete crack, where
  // the particles' domains part), over the segments the spatial index lists for a cell beside the node
  // (they reach kReach >= 2 cells, the support one). 1 where the node has no cell (the seed's rule).
  double crack_line_weight(int64_t n, int crack) const {
    if constexpr (Dim == 3) {
      return 1.0;
    } else {
      const V xn = node_position(n);
      int64_t cell = cell_of(xn + V::Constant(0.5 * G_.h));
      if (cell < 0) cell = cell_of(xn - V::Constant(0.5 * G_.h));
      const std::vector<V>* pts = line_points_[static_cast<std::size_t>(crack)];
      if (cell < 0 || !pts) return 1.0;
      double sum = 0.0;
      for (int32_t e = cell_head_[cell]; e >= 0; e = entries_[e].next) {
        const auto& en = entries_[e];
        if (en.crack != crack) continue;
        for (int32_t s = en.seg_lo; s <= en.seg_hi; ++s)
          sum += hat_integral_along((*pts)[static_cast<std::size_t>(s)], (*pts)[static_cast<std::size_t>(s) + 1], xn, G_.h);
      }
      return sum / G_.h;
    }
  }
  std::vector<const std::vector<V>*> line_points_;  // per crack: its read points, for volume detection

  static constexpr int kFieldSlots = 1 + kExtra, kPairSlots = kFieldSlots * kFieldSlots;
  // (1 - 1/2)^2 / 2: with linear shape functions, material more than half a cell beyond the crack.
  static constexpr double kMinForcedShare = 0.125;
  std::vector<uint8_t> touching_;  // per block and field pair (i, j): touched earlier in this step
  std::vector<uint8_t> closing_;  // per block and crack: a crack point's faces close (contact())
};

}  // namespace cleave::crack_fields
