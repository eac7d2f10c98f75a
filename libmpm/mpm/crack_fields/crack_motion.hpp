// Layer of the crack fields (libmpm/mpm/crack_fields.hpp; layering: grid_cells.hpp): Task 7
// (eq. 32). Crack particles move with the centre-of-mass nodal velocity; the surfaces above and
// below move with the velocity field of their side. Which field a surface follows at each node of
// its cell (its side fields) depends on the crack geometry and the fields' keys, not on the
// momenta, so it is found once per step and again only after a crack moved; contact (the layer
// above) reads the same side fields to predict the opening each crack point is about to have.
// A crack point's normal is its polyline's left normal (2D) or the area-weighted normal of its
// triangles (3D, crack::point_normals); a crack's spin is a rate (2D) or a vector (3D).
#pragma once
#include <algorithm>
#include <cstdint>
#include <optional>
#include <type_traits>
#include <vector>

#include <Eigen/Cholesky>

#include "libmpm/crack/crack2d.hpp"
#include "libmpm/crack/fronts.hpp"
#include "libmpm/mpm/crack_fields/field_slots.hpp"
#include "libmpm/mpm/model.hpp"

namespace cleave::crack_fields {

template <int Dim, class SF>
class CrackMotion : public FieldSlots<Dim, SF> {
  using Base = FieldSlots<Dim, SF>;
  using V = Vec<Dim>;

 protected:
  using Spin = std::conditional_t<Dim == 2, double, Vec<3>>;  // a crack's rigid rotation rate

 public:
  // Moves every crack with the end-of-step momenta.
  // A field's nodal velocity is the velocity of its mass centre, which sits off the node (and off the
  // crack) by up to half a cell on its side: in a body that spins at omega, the above and below fields
  // of a node differ by omega x (their centres' separation) although the faces do not move apart. So a
  // surface takes each field's velocity carried from the field's mass centre to the surface with the
  // crack's own spin (crack_spin: the rigid rotation rate of its points): without that the surfaces of
  // a spinning crack slid past each other at omega times the centres' separation, and the rotating
  // tangential offset opened or closed the tracked crack (docs/validation.md, cracks under rigid rotation).
  // At an interior crack tip (crack.tip[end], material ahead of it) the two faces meet: its surfaces
  // stay at the crack point itself, so the tracked opening there is zero. Followed with the side
  // fields instead, a tip's surfaces interpolate nodes whose fields belong to the crack flanks behind
  // the tip (the tip's cell is cut only partly), and the tip "opened" by about 70 % of the interior
  // opening in a plate at rest (docs/validation.md, 2D cracks item 4). A free end (an edge crack's
  // mouth, no material ahead) keeps following its sides.
  void move_cracks(double dt) {
    spin_.resize(cracks_.size());
    vm_.resize(cracks_.size());
    for (std::size_t ci = 0; ci < cracks_.size(); ++ci) {
      crack::ExplicitCrack<Dim>& c = cracks_[ci];
      const std::size_t np = c.points.size();
      std::vector<V> va(np), vb(np);
      const std::vector<SideFields>& sides = side_fields(ci);
      std::vector<V>& vm = vm_[ci];
      const Spin spin = spin_[ci] = crack_spin(c, read_points(ci), vm);
#pragma omp parallel for schedule(static) if (parallel_points(np))
      for (std::size_t i = 0; i < np; ++i) {
        const V vcm = vm[i];
        if (is_tip(c, i)) {
          va[i] = vb[i] = vcm;
          continue;
        }
        va[i] = side_velocity(sides[2 * i], vcm, spin, c.above[i]);
        vb[i] = side_velocity(sides[2 * i + 1], vcm, spin, c.below[i]);
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
      if constexpr (Dim == 3) note_crack_state();  // (and the side keys kept are those of before)
    }
  }

 protected:
  using Base::block_nslots_, Base::classify, Base::cracks_, Base::extra_field, Base::G_, Base::grid_;
  using Base::kExtra, Base::kOverflow, Base::linear_nodes, Base::mass_, Base::momentum_, Base::node_block_;
  using Base::cell_of, Base::node_position, Base::parallel_points, Base::pos0_, Base::pos_;
  using Base::block_key_, Base::block_node_, Base::kin_, Base::xkin_;
  using Base::crack_epoch_, Base::index_epoch_, Base::note_crack_state;
  using Base::bodies_, Base::crack_group_, Base::group_tag;
  static constexpr double kProbe = 1e-3;  // cells: how far above/below a surface its probe sits

  CrackMotion(Model<Dim>& m, GridFields<Dim>& grid, std::vector<NodeKinematics<Dim>>& kin) : Base(m, grid, kin) {
    if constexpr (Dim == 3) {
      tip_point_.resize(cracks_.size());
      point_normal_.resize(cracks_.size());
      for (std::size_t ci = 0; ci < cracks_.size(); ++ci) {
        const auto& c = cracks_[ci];
        tip_point_[ci].assign(c.points.size(), 0);
        for (std::size_t f = 0; f < c.fronts.size(); ++f)
          if (f < c.tip.size() && c.tip[f])
            for (int32_t n : c.fronts[f].nodes) tip_point_[ci][n] = 1;
      }
    }
  }

  // Is crack point i an interior crack tip (2D: an end point with material ahead, crack.tip[end];
  // 3D: a node of a front that is a tip)?
  bool is_tip(const crack::ExplicitCrack<Dim>& c, std::size_t i) const {
    if constexpr (Dim == 3) return tip_point_[c.id][i] != 0;
    else return (i == 0 && c.tip[0]) || (i + 1 == c.points.size() && c.tip[1]);
  }
  // The unit normal at crack point i, towards "above" (3D: from the last refresh of the crack's
  // side fields, which every loop over crack points runs first).
  V left_normal(const crack::ExplicitCrack<Dim>& c, std::size_t i) const {
    if constexpr (Dim == 3) return point_normal_[c.id][i];
    else return left_normal2(c, i);
  }
  static V left_normal2(const crack::ExplicitCrack<Dim>& c, std::size_t i) {
    V t = V::Zero();
    if (i > 0) t += (c.points[i] - c.points[i - 1]).normalized();
    if (i + 1 < c.points.size()) t += (c.points[i + 1] - c.points[i]).normalized();
    const double l = t.norm();
    return l > 0.0 ? V(-t.y() / l, t.x() / l) : V::Zero();
  }

  // The crack's spin: the rigid rotation rate of its points moving with the centre-of-mass
  // velocities, fitted by least squares with each point weighted by the mass about it (zero for a crack
  // that only translates or opens symmetrically), each point's velocity read at `at` (read_points).
  // vm receives the points' centre-of-mass velocities.
  // Points outside the material (the band of a cell a crack keeps beyond a body's face) weigh little
  // or nothing: unweighted, with each node's p / m interpolated, one such point of the uGIMP rod (beyond
  // its corner at the two symmetry planes) read 1.9e7 m/s, the spin 2.2e7 rad/s, and the nodal
  // velocities carried with it moved particles 20 mm in a step (docs/validation.md, 3D cracks item 8).
  Spin crack_spin(const crack::ExplicitCrack<Dim>& c, const std::vector<V>& at, std::vector<V>& vm) const {
    const std::size_t np = c.points.size();
    vm.resize(np);
    std::vector<double> mass(np);
#pragma omp parallel for schedule(static) if (parallel_points(np))
    for (std::size_t i = 0; i < np; ++i) vm[i] = cm_velocity(at[i], mass[i]);
    if (scene_spin_) return *scene_spin_;
    V xm = V::Zero(), vbar = V::Zero();
    double msum = 0.0;
    for (std::size_t i = 0; i < np; ++i) xm += mass[i] * c.points[i], vbar += mass[i] * vm[i], msum += mass[i];
    if (!(msum > 0.0)) return no_spin();
    xm /= msum, vbar /= msum;
    if constexpr (Dim == 3) {
      // omega minimising sum |dv - omega x r|^2: (sum |r|^2 I - r r^T) omega = sum r x dv.
      Mat<3> A = Mat<3>::Zero();
      V b = V::Zero();
      for (std::size_t i = 0; i < np; ++i) {
        const V r = c.points[i] - xm, dv = vm[i] - vbar;
        A += mass[i] * (r.squaredNorm() * Mat<3>::Identity() - r * r.transpose());
        b += mass[i] * r.cross(dv);
      }
      const Eigen::LDLT<Mat<3>> ldlt(A);
      if (!(A.trace() > 0.0) || ldlt.info() != Eigen::Success) return V::Zero();
      const V w = ldlt.solve(b);
      return w.allFinite() ? w : V::Zero();
    } else {
      double num = 0.0, den = 0.0;
      for (std::size_t i = 0; i < np; ++i) {
        const V r = c.points[i] - xm, dv = vm[i] - vbar;
        num += mass[i] * (r.x() * dv.y() - r.y() * dv.x());
        den += mass[i] * r.squaredNorm();
      }
      return den > 0.0 ? num / den : 0.0;
    }
  }
  // With mpm.spin_transfer the cracks follow the scene's spin (the rigid fit of every particle,
  // spin_transfer.hpp), which the nodes off the cracks carry their velocities with: one spin on both
  // sides of a block's edge. A crack's own fit, from its points' centre-of-mass velocities, reads the
  // mouth of an edge crack (points at the body's edge, whose nodes move with their mass centres half a
  // cell inside) and the faces' opening.
 public:
  void follow_scene_spin(const Spin& w) { scene_spin_ = w; }

 protected:
  static V cross(double omega, const V& r) { return V(-omega * r.y(), omega * r.x()); }
  static V cross(const Vec<3>& omega, const V& r) { return omega.cross(r); }
  static Spin no_spin() {
    if constexpr (Dim == 3) return Vec<3>::Zero();
    else return 0.0;
  }
  static bool spinning(double omega) { return omega != 0.0; }
  static bool spinning(const Vec<3>& omega) { return (omega.array() != 0.0).any(); }
  // Every crack's spin and its points' centre-of-mass velocities (vm_) from the current momenta.
  void update_spins() {
    spin_.resize(cracks_.size());
    vm_.resize(cracks_.size());
    for (std::size_t ci = 0; ci < cracks_.size(); ++ci) spin_[ci] = crack_spin(cracks_[ci], read_points(ci), vm_[ci]);
  }
  // The spin a field of block b follows (slot s, or -1 for the ordinary field): that of the crack its
  // key names (the ordinary field: the crack of the block's first extra field).
  Spin field_spin(int32_t b, int s) const {
    const uint32_t key = block_key_[b * kExtra + (s < 0 ? 0 : s)];
    const uint32_t code = crack::key_code(key, 0) ? crack::key_code(key, 0) : crack::key_code(key, 1);
    return code ? spin_[crack::code_crack(code)] : no_spin();
  }
  // The fields' nodal velocities at multi-field nodes, carried from each field's mass centre to the
  // node with its crack's spin: v = p / m + omega x (x_node - centre). A field's momentum over its mass
  // is the velocity of its mass centre, which sits up to half a cell off the node on its side of the
  // crack; taken as the node's velocity, a body spinning at omega got a velocity gradient about 5/8 of
  // the true one across the first cell row beside the crack, hence a spurious shear strain rate of about
  // omega / 5 and stresses that grew to the MPa range in a few steps (aluminium at 1 rad/ms), which J
  // and contact then read (docs/validation.md, cracks under rigid rotation). Exact for any rigid motion
  // of the crack's neighbourhood; momenta and accelerations are unchanged (momentum is conserved).
  void carry_nodal_velocities_to_nodes() {
    for (std::size_t b = 0; b < block_node_.size(); ++b) {
      const int64_t n = block_node_[b];
      const V xn = node_position(n);
      const int32_t bb = static_cast<int32_t>(b);
      if (grid_.mass[n] > 0.0) {
        const Spin w = field_spin(bb, -1);
        if (spinning(w)) kin_[n].v += cross(w, xn - field_centre(n, -1));
      }
      for (int s = 0; s < block_nslots_[b]; ++s) {
        const int32_t x = static_cast<int32_t>(b * kExtra + s);
        if (!(mass_[x] > 0.0)) continue;
        const Spin w = field_spin(bb, s);
        if (spinning(w)) xkin_[x].v += cross(w, xn - field_centre(n, x));
      }
    }
  }
  // The mass centre of field xs at node n (the node itself where it has no mass sums: an ordinary
  // field away from the crack, whose particles surround it).
  V field_centre(int64_t n, int32_t xs) const {
    if (xs >= 0) return mass_[xs] > 0.0 ? V(pos_[xs] / mass_[xs]) : node_position(n);
    const int32_t b = node_block_[n];
    return b >= 0 && grid_.mass[n] > 0.0 ? V(pos0_[b] / grid_.mass[n]) : node_position(n);
  }

  // Where a 2D crack point's velocity is read: moved along the crack's normal onto the discrete
  // crack, which the particles' sorting puts between the particle rows about the line, not on the
  // line. The nodes of the point's cell that carry this crack's fields show where: split nodes on
  // both sides of the line put it half-way between them (a crack 0.3 cell above a node line, with
  // particle rows at 0.25 and 0.75, lies at 0.5), split nodes on one side only, on their line (0.1
  // above: at 0). Read on the line instead, the point moved with the material 0.2 cell below the
  // discrete crack, which under opening moves down: a growing crack 0.26 cell above a node line drifted
  // onto the particle row at 0.25 within 14 mm, and there its discrete crack stepped half a cell and
  // kinked it (docs/validation.md, growing cracks 2). Only the normal component moves, so a rigid
  // rotation still carries the point with the body. A point whose cell holds another crack's fields
  // (a junction, whose cracks share a point that must stay shared) and 3D points are read where they
  // are (3D cracks do not grow; their figures were measured so).
  V on_discrete_crack(const crack::ExplicitCrack<Dim>& c, std::size_t i) const {
    const V& x = c.points[i];
    if constexpr (Dim == 3) {
      return x;
    } else {
      const V n = left_normal2(c, i);
      double w_side[3] = {0.0, 0.0, 0.0};  // below the line, on it, above
      V x_side[3] = {V::Zero(), V::Zero(), V::Zero()};
      bool shared = false;
      linear_nodes(x, [&](int64_t node, double w) {
        if (w == 0.0) return;
        const int on = carries(node, c.id);
        shared |= (on & 2) != 0;
        if (!(on & 1)) return;
        const V xn = node_position(node);
        const double s = (xn - x).dot(n);
        const int k = (s > 0.0) - (s < 0.0) + 1;
        w_side[k] += w, x_side[k] += w * xn;
      });
      const double split = w_side[0] + w_side[1] + w_side[2];
      if (!(split > 0.0) || shared) return x;
      V at = x_side[1];
      if (w_side[0] > 0.0 && w_side[2] > 0.0) {
        const double half = 0.5 * (w_side[0] + w_side[2]);
        at += half * (x_side[0] / w_side[0] + x_side[2] / w_side[2]);
      } else {
        at += x_side[0] + x_side[2];
      }
      return x + ((at / split - x).dot(n)) * n;
    }
  }
  // Where the points of crack ci read their velocity (on_discrete_crack). A function of the crack's
  // geometry and the fields' keys, as the side fields are: found with them, once per step and after
  // a crack moved (a step reads them up to five times: four contact calls and the crack motion).
  const std::vector<V>& read_points(std::size_t ci) {
    if constexpr (Dim == 3) {
      return cracks_[ci].points;
    } else {
      side_fields(ci);
      return read_at_[ci];
    }
  }
  // Which cracks' fields node n carries: 1 crack ci's, 2 another's (or a key that overflowed).
  int carries(int64_t n, int ci) const {
    const int32_t b = node_block_[n];
    if (b < 0) return 0;
    int on = 0;
    for (int s = 0; s < block_nslots_[b]; ++s) {
      const uint32_t key = block_key_[b * kExtra + s];
      if (key == crack::kFieldKeyOverflow) {
        on |= 2;
        continue;
      }
      for (int k = 0; k < 2; ++k) {
        const uint32_t code = crack::key_code(key, k);
        if (code) on |= crack::code_crack(code) == ci ? 1 : 2;
      }
    }
    return on;
  }

  // The centre-of-mass velocity at x (and the mass about it, m_sum): the nodes' momenta interpolated
  // over their masses interpolated. Not the nodes' velocities p / m interpolated: a node that a
  // particle's support only grazes (uGIMP: a particle's domain edge moved a hair d past the node's
  // reach, weight ~ d^2; linear: a particle just entered its cell) holds a mass that vanishes faster
  // than the force it takes, so its velocity after a step grows as 1 / d, and a crack point beside it
  // would take that with its full weight. Where the mass is spread evenly the two are the same.
  V cm_velocity(const V& x, double& m_sum) const {
    V p_sum = V::Zero();
    m_sum = 0.0;
    linear_nodes(x, [&](int64_t n, double w) {
      double m = grid_.mass[n];
      V p = grid_.momentum[n];
      const int32_t b = node_block_[n];
      if (b >= 0)
        for (int s = 0; s < block_nslots_[b]; ++s) m += mass_[b * kExtra + s], p += momentum_[b * kExtra + s];
      if (m > 0.0) p_sum += w * p, m_sum += w * m;
    });
    return m_sum > 0.0 ? V(p_sum / m_sum) : V::Zero();
  }

  // The nodes of a surface's cell, with bilinear weights, and the field at each that its probe
  // selects (nodes without a field for that side left out). They depend on the crack geometry and
  // the fields' keys, not on the momenta, so they are found once per step (up to three contact
  // passes and the crack motion read them), and again only after a crack moved.
  struct SideFields {
    int count = 0;
    int64_t node[1 << Dim];
    double w[1 << Dim];
    int32_t field[1 << Dim];
  };
  // The side fields of crack ci, two per point (2 i: above, 2 i + 1: below), found afresh when a
  // crack has moved since. Called before the loops over crack points, which run in parallel.
  const std::vector<SideFields>& side_fields(std::size_t ci) {
    if (!side_valid_[ci]) find_side_fields(ci);
    return side_fields_[ci];
  }
  // The velocity a surface at x follows: that of the field a virtual particle at its point's probe
  // would use, carried from each field's mass centre to x with the crack's spin, interpolated at the
  // surface (fallback where no such field has mass). A field holding less than a hundredth of the mass
  // of the surface's heaviest side field counts in proportion to its mass: one that a particle's support
  // only grazes has a velocity ~ 1 / d (cm_velocity says why). Counted in full, such a field of the
  // uGIMP rod moved its surfaces until they read closed where the faces stood 0.1 mm apart, and contact
  // held them there: K_I at the deepest point fell to 0 by 80 us (docs/validation.md, crack fronts).
  // (Every field in proportion to its mass let the colliding disks' faces cross by 0.06 cell, those
  // under a tenth by 0.014; the criterion is 0.01. Under a hundredth: 0.0045, 0.0037 before.)
  V side_velocity(const SideFields& sf, const V& fallback, const Spin& spin, const V& x) const {
    double heaviest = 0.0;
    for (int e = 0; e < sf.count; ++e) heaviest = std::max(heaviest, side_mass(sf, e));
    V sum = V::Zero();
    double wsum = 0.0;
    for (int e = 0; e < sf.count; ++e) {
      const int64_t n = sf.node[e];
      const int32_t xs = sf.field[e];
      const double m = side_mass(sf, e);
      if (!(m > 0.0)) continue;
      const double w = sf.w[e] * std::min(1.0, m / (kLightField * heaviest));
      sum += w * (xs < 0 ? grid_.momentum[n] : momentum_[xs]) / m, wsum += w;
      if (spinning(spin)) sum += w * cross(spin, x - field_centre(n, xs));
    }
    return wsum > 0.0 ? V(sum / wsum) : fallback;
  }
  static constexpr double kLightField = 0.01;
  double side_mass(const SideFields& sf, int e) const { return sf.field[e] < 0 ? grid_.mass[sf.node[e]] : mass_[sf.field[e]]; }
  // 3D: a surface's nodes, weights and keys are functions of the crack geometry alone, so they are
  // kept while crack_epoch_ stays (SpatialIndex::note_crack_state); only the fields that the keys
  // select are found afresh (the fields' slots are numbered anew every step).
  struct SideKeys {
    int count = 0;
    int64_t node[1 << Dim];
    double w[1 << Dim];
    uint32_t key[1 << Dim];
  };
  void find_side_fields(std::size_t ci) {
    const crack::ExplicitCrack<Dim>& c = cracks_[ci];
    bool keys_kept = false;
    if constexpr (Dim == 3) {
      side_keys_.resize(cracks_.size());
      side_key_epoch_.resize(cracks_.size(), ~uint64_t{0});
      keys_kept = side_key_epoch_[ci] == crack_epoch_ && side_keys_[ci].size() == 2 * c.points.size();
      // Keys found with an index of an earlier geometry (a crack moved by move_cracks before this
      // one's turn) are not those of a fresh index: not kept.
      side_key_epoch_[ci] = index_epoch_ == crack_epoch_ ? crack_epoch_ : ~uint64_t{0};
      if (!keys_kept) {
        point_normal_[ci] = crack::point_normals(c);
        side_keys_[ci].resize(2 * c.points.size());
      }
    }
    auto& out = side_fields_[ci];
    out.assign(2 * c.points.size(), SideFields{});
    const std::size_t np = c.points.size();
    if constexpr (Dim == 2) {
      read_at_.resize(cracks_.size());
      read_at_[ci].resize(np);
    }
    // (dynamic: a point's cost varies tenfold, with the triangles about it and whether its keys are kept)
#pragma omp parallel for schedule(dynamic, 16) if (parallel_points(np))
    for (std::size_t i = 0; i < np; ++i) {
      if constexpr (Dim == 2) read_at_[ci][i] = on_discrete_crack(c, i);
      if (is_tip(c, i)) continue;  // a tip's surfaces follow the point itself
      for (int side = 0; side < 2; ++side) {
        SideKeys local;
        SideKeys& sk = Dim == 3 ? side_keys_[ci][2 * i + side] : local;
        if (!keys_kept) surface_keys(c, i, side, sk);
        SideFields& sf = out[2 * i + side];
        for (int e = 0; e < sk.count; ++e) {
          if (sk.key[e] == kOverflow) continue;
          const uint32_t key = bodies_ ? sk.key[e] | group_tag(crack_group_[ci], sk.node[e]) : sk.key[e];
          const int32_t xs = key == 0 ? -1 : extra_field(sk.node[e], key);
          if (key != 0 && xs < 0) continue;  // the node has no field for that side
          sf.node[sf.count] = sk.node[e], sf.w[sf.count] = sk.w[e], sf.field[sf.count] = xs;
          ++sf.count;
        }
      }
    }
    side_valid_[ci] = 1;
  }
  // The nodes of point i's surface on `side` (0 above, 1 below), their weights and the keys of the
  // lines from the surface's probe to them.
  void surface_keys(const crack::ExplicitCrack<Dim>& c, std::size_t i, int side, SideKeys& sk) const {
    const V nl = left_normal(c, i);
    // The probes sit just off the crack line itself, not off the surfaces: a surface that has
    // moved across the line (faces pressed together) must keep following its own side's field.
    const V probe = side == 0 ? V(c.points[i] + kProbe * G_.h * nl) : V(c.points[i] - kProbe * G_.h * nl);
    constexpr int kN = 1 << Dim;
    int nn = 0;
    linear_nodes(side == 0 ? c.above[i] : c.below[i], [&](int64_t n, double w) { sk.node[nn] = n, sk.w[nn++] = w; });
    sk.count = nn;
    for (int e = 0; e < kN; ++e) sk.key[e] = 0;
    if constexpr (Dim == 3) {  // the eight lines at once (classify_block3: same keys)
      const int64_t cell = nn == kN ? cell_of(probe) : -1;
      if (cell >= 0) {
        double nc[3][2];
        for (int a = 0; a < 2; ++a)
          nc[0][a] = node_position(sk.node[4 * a]).x(), nc[1][a] = node_position(sk.node[2 * a]).y(),
          nc[2][a] = node_position(sk.node[a]).z();
        int32_t seg[2];
        this->template classify_block3<2>(
            cell, probe, nc, [](int) { return true; }, [&](int) { return seg; },
            [&](int j, uint32_t k) { sk.key[j] = k; });
      }
    } else {
      for (int e = 0; e < nn; ++e) {
        int32_t seg[2];
        sk.key[e] = classify(probe, node_position(sk.node[e]), seg);
      }
    }
  }

  std::vector<std::vector<SideFields>> side_fields_;  // per crack, two per point (side_fields())
  std::vector<Spin> spin_;                            // per crack: its spin (crack_spin, update_spins)
  std::optional<Spin> scene_spin_;                    // follow_scene_spin: every crack's spin, when set
  std::vector<std::vector<uint8_t>> tip_point_;       // 3D, per crack and point: on a front that is a tip
  std::vector<std::vector<V>> point_normal_;          // 3D, per crack and point: normal (find_side_fields)
  std::vector<std::vector<V>> vm_;                    // per crack: its points' centre-of-mass velocities
  std::vector<uint8_t> side_valid_;                   // per crack: side_fields_ (and read_at_) are up to date
  std::vector<std::vector<V>> read_at_;               // 2D, per crack and point: read_points()
  std::vector<std::vector<SideKeys>> side_keys_;      // 3D, per crack, two per point (find_side_fields)
  std::vector<uint64_t> side_key_epoch_;              // 3D, per crack: the crack_epoch_ of side_keys_
};

}  // namespace cleave::crack_fields
