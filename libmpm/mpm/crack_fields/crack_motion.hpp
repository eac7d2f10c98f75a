// Layer of the crack fields (libmpm/mpm/crack_fields.hpp; layering: grid_cells.hpp): Task 7
// (eq. 32). Crack particles move with the centre-of-mass nodal velocity; the surfaces above and
// below move with the velocity field of their side. Which field a surface follows at each node of
// its cell (its side fields) depends on the crack geometry and the fields' keys, not on the
// momenta, so it is found once per step and again only after a crack moved; contact (the layer
// above) reads the same side fields to predict the opening each crack point is about to have.
// 2D only: crack::Crack2D polylines, their left normals and bilinear cell nodes.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "libmpm/crack/crack2d.hpp"
#include "libmpm/mpm/crack_fields/field_slots.hpp"
#include "libmpm/mpm/model.hpp"

namespace cleave::crack_fields {

template <int Dim, class SF>
class CrackMotion : public FieldSlots<Dim, SF> {
  static_assert(Dim == 2, "crack fields: 2D only (crack::Crack2D surfaces)");
  using Base = FieldSlots<Dim, SF>;
  using V = Vec<Dim>;

 public:
  // Moves every crack with the end-of-step momenta.
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

 protected:
  using Base::block_nslots_, Base::classify, Base::cracks_, Base::extra_field, Base::G_, Base::grid_;
  using Base::kExtra, Base::kOverflow, Base::linear_nodes, Base::mass_, Base::momentum_, Base::node_block_;
  using Base::node_position, Base::parallel_points;
  static constexpr double kProbe = 1e-3;  // cells: how far above/below a surface its probe sits

  CrackMotion(Model<Dim>& m, GridFields<Dim>& grid, std::vector<NodeKinematics<Dim>>& kin) : Base(m, grid, kin) {}

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

  std::vector<std::vector<SideFields>> side_fields_;  // per crack, two per point (side_fields())
  std::vector<uint8_t> side_valid_;                   // per crack: side_fields_ are up to date
};

}  // namespace cleave::crack_fields
