// The shared pieces of the crack-front evaluation (crack_front_eval.hpp): particles and crack
// triangles binned by grid cell, eq. 36's raw nodal sums per velocity field taken once per evaluation
// for every grid node a front node reads (NodeSums), the particles' full displacement gradient, and
// the curvature of a front (the out-of-plane term's kappa).
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "libmpm/core/parallel.hpp"
#include "libmpm/crack/crack2d.hpp"  // FieldKeyBuilder
#include "libmpm/crack/crossing3d.hpp"
#include "libmpm/crack/front_parameters.hpp"
#include "libmpm/mpm/model.hpp"
#include "libmpm/mpm/stencil.hpp"

namespace cleave {

namespace detail {

// Mass-weighted nodal sums of one velocity field at one node (eq. 36), 3D.
struct FrontFieldSums {
  uint32_t key = 0;
  double m = 0.0, energy = 0.0, rho = 0.0, rho_vv = 0.0;
  Vec<3> rho_v = Vec<3>::Zero(), u = Vec<3>::Zero(), v = Vec<3>::Zero();
  Mat<3> stress = Mat<3>::Zero(), grad_u = Mat<3>::Zero();
};

// The particles of a box of grid cells binned by cell (counting sort): the particles of a cell in
// index order. Cells are named by their grid indices (i, j, k); those outside the box hold none.
struct CellBins {
  std::array<int64_t, 3> lo{}, n{};  // the box: cells lo .. lo + n - 1 along each axis
  std::vector<int64_t> begin;        // per cell of the box + 1
  std::vector<int32_t> particle;

  // The box's index of cell (i, j, k), or -1 outside the box.
  int64_t index(int64_t i, int64_t j, int64_t k) const {
    i -= lo[0], j -= lo[1], k -= lo[2];
    if (i < 0 || j < 0 || k < 0 || i >= n[0] || j >= n[1] || k >= n[2]) return -1;
    return (i * n[1] + j) * n[2] + k;
  }
  static std::array<int64_t, 3> cell_of(const GridGeometry<3>& G, const Vec<3>& x) {
    std::array<int64_t, 3> c;
    for (int d = 0; d < 3; ++d) c[d] = static_cast<int64_t>(std::floor((x[d] - G.origin[d]) / G.h));
    return c;
  }
  // f(p) for each particle p of cell (i, j, k), in index order.
  template <class F>
  void for_cell(int64_t i, int64_t j, int64_t k, F&& f) const {
    const int64_t c = index(i, j, k);
    if (c >= 0)
      for (int64_t q = begin[c]; q < begin[c + 1]; ++q) f(particle[q]);
  }
  // The particles of x in the grid's cells that meet [box_lo, box_hi].
  void build(const GridGeometry<3>& G, const std::vector<Vec<3>>& x, const Vec<3>& box_lo, const Vec<3>& box_hi) {
    const auto a = cell_of(G, box_lo), b = cell_of(G, box_hi);
    for (int d = 0; d < 3; ++d) {
      const int64_t cells = std::max(1, G.nodes[d] - 1);
      lo[d] = std::clamp<int64_t>(a[d], 0, cells - 1);
      n[d] = std::clamp<int64_t>(b[d], 0, cells - 1) - lo[d] + 1;
    }
    const int64_t total = n[0] * n[1] * n[2];
    begin.assign(total + 1, 0);
    std::vector<int64_t> cell(x.size());
#pragma omp parallel for schedule(static) if (x.size() > 65536)
    for (std::size_t p = 0; p < x.size(); ++p) {
      const auto c = cell_of(G, x[p]);
      cell[p] = index(c[0], c[1], c[2]);
    }
    for (std::size_t p = 0; p < x.size(); ++p)
      if (cell[p] >= 0) ++begin[cell[p] + 1];
    for (int64_t c = 0; c < total; ++c) begin[c + 1] += begin[c];
    particle.resize(begin[total]);
    std::vector<int64_t> next(begin.begin(), begin.end() - 1);
    for (std::size_t p = 0; p < x.size(); ++p)
      if (cell[p] >= 0) particle[next[cell[p]]++] = static_cast<int32_t>(p);
  }
};

// The triangles of every crack binned by grid cell, each in the cells its box meets (by a hair more,
// so that rounding cannot drop one): a triangle whose box meets a line's box is in one of the cells
// the line's box meets, so the field key of a line from these is exact, as the stepper's.
class TriangleBins {
 public:
  explicit TriangleBins(const Model<3>& m) : m_(m) {
    const auto& G = m.grid;
    for (int d = 0; d < 3; ++d) cells_[d] = std::max(1, G.nodes[d] - 1);
    lo_.resize(m.cracks.size()), hi_.resize(m.cracks.size());
    std::vector<std::array<int64_t, 6>> spans;
    begin_.assign(cells_[0] * cells_[1] * cells_[2] + 1, 0);
    for (const auto& c : m.cracks)
      for (std::size_t t = 0; t < c.simplices.size(); ++t) {
        const auto& T = c.simplices[t];
        const Vec<3> lo = c.points[T[0]].cwiseMin(c.points[T[1]]).cwiseMin(c.points[T[2]]);
        const Vec<3> hi = c.points[T[0]].cwiseMax(c.points[T[1]]).cwiseMax(c.points[T[2]]);
        lo_[c.id].push_back(lo), hi_[c.id].push_back(hi);
        std::array<int64_t, 6> sp;
        for (int d = 0; d < 3; ++d) sp[d] = index(lo, d, -1e-9), sp[3 + d] = index(hi, d, 1e-9);
        spans.push_back(sp);
        for_span(sp, [&](int64_t cell) { ++begin_[cell + 1]; });
      }
    for (std::size_t i = 1; i < begin_.size(); ++i) begin_[i] += begin_[i - 1];
    entry_.resize(static_cast<std::size_t>(begin_.back()));
    std::vector<int64_t> next(begin_.begin(), begin_.end() - 1);
    std::size_t k = 0;
    for (const auto& c : m.cracks)
      for (std::size_t t = 0; t < c.simplices.size(); ++t)
        for_span(spans[k++], [&](int64_t cell) { entry_[next[cell]++] = {c.id, static_cast<int32_t>(t)}; });
  }

  // The field key of the line x -> xn (crack_fields' key: one code per crossed crack, in crack order);
  // ids: the caller's scratch.
  uint32_t key(const Vec<3>& x, const Vec<3>& xn, std::vector<int32_t>& ids) const {
    const Vec<3> lo = x.cwiseMin(xn), hi = x.cwiseMax(xn);
    std::array<int64_t, 6> sp;
    for (int d = 0; d < 3; ++d) sp[d] = index(lo, d, 0.0), sp[3 + d] = index(hi, d, 0.0);
    crack::FieldKeyBuilder b;
    for (const auto& o : m_.cracks) {
      ids.clear();
      for_span(sp, [&](int64_t cell) {
        for (int64_t e = begin_[cell]; e < begin_[cell + 1]; ++e) {
          const auto [ci, t] = entry_[e];
          if (ci == o.id && (hi_[ci][t].array() >= lo.array()).all() && (lo_[ci][t].array() <= hi.array()).all())
            ids.push_back(t);
        }
      });
      if (ids.empty()) continue;
      std::sort(ids.begin(), ids.end());
      ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
      const crack::Side side = crack::triangle_list_crossing(o.points.data(), o.simplices.data(), ids.data(), ids.size(), x, xn);
      if (side != crack::Side::None && !b.add(o.id, side)) return crack::kFieldKeyOverflow;
    }
    return b.key();
  }

 private:
  // The cell index along d of x, shifted by `slack` cells before rounding down.
  int64_t index(const Vec<3>& x, int d, double slack) const {
    const auto& G = m_.grid;
    return std::clamp<int64_t>(static_cast<int64_t>(std::floor((x[d] - G.origin[d]) / G.h + slack)), 0, cells_[d] - 1);
  }
  template <class F>
  void for_span(const std::array<int64_t, 6>& sp, F&& f) const {
    for (int64_t i = std::max<int64_t>(sp[0], 0); i <= std::min(sp[3], cells_[0] - 1); ++i)
      for (int64_t j = std::max<int64_t>(sp[1], 0); j <= std::min(sp[4], cells_[1] - 1); ++j)
        for (int64_t k = std::max<int64_t>(sp[2], 0); k <= std::min(sp[5], cells_[2] - 1); ++k)
          f((i * cells_[1] + j) * cells_[2] + k);
  }
  const Model<3>& m_;
  std::array<int64_t, 3> cells_{};
  std::vector<int64_t> begin_;
  std::vector<std::pair<int32_t, int32_t>> entry_;  // (crack, triangle), per cell in crack and triangle order
  std::vector<std::vector<Vec<3>>> lo_, hi_;        // per crack and triangle: its box
};

// Eq. 36's sums of one velocity field at one node before a front node's rigid motion is taken out,
// with the moments of position that taking out the spin needs (weights m_p N, and m_p N rho for rho_*).
struct RawSums {
  uint32_t key = 0;
  double m = 0.0, energy = 0.0, rho = 0.0, rho_vv = 0.0;
  Vec<3> mv = Vec<3>::Zero(), mx = Vec<3>::Zero(), u = Vec<3>::Zero();
  Vec<3> rho_v = Vec<3>::Zero(), rho_x = Vec<3>::Zero(), rho_xv = Vec<3>::Zero();
  Mat<3> stress = Mat<3>::Zero(), grad_u = Mat<3>::Zero(), rho_xx = Mat<3>::Zero();
};

// A particle's displacement gradient: its small strain plus its integrated rotation w (the skew
// part W_ij = (u_i,j - u_j,i) / 2 as the vector (W_21, W_02, W_10)).
inline Mat<3> displacement_gradient(const Sym<3>& e, const Vec<3>& w) {
  Mat<3> g;
  g << e[0], e[3] - w.z(), e[5] + w.y(),  //
      e[3] + w.z(), e[1], e[4] - w.x(),   //
      e[5] - w.y(), e[4] + w.x(), e[2];
  return g;
}
inline Mat<3> full_tensor(const Sym<3>& s) {
  Mat<3> t;
  t << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
  return t;
}

// RawSums at a set of grid nodes, per field: each node gathers from the particles of the cells
// around it, in cell and particle order (the same sums for any thread count).
class NodeSums {
 public:
  template <class SF>
  void build(const Model<3>& m, const CellBins& bins, const TriangleBins& tris,
             const std::vector<std::vector<int64_t>>& need_of) {
    using St = Stencil<3, SF>;
    nodes_.clear();
    for (const auto& v : need_of) nodes_.insert(nodes_.end(), v.begin(), v.end());
    std::sort(nodes_.begin(), nodes_.end());
    nodes_.erase(std::unique(nodes_.begin(), nodes_.end()), nodes_.end());
    sums_.assign(nodes_.size(), {});
    const auto& P = m.particles;
    const auto& G = m.grid;
    const double h = G.h, inv_h = 1.0 / h;
    const auto stride = G.strides();
    const bool rotations = !P.rotation3.empty();
    constexpr int kLo = St::K == 2 ? -1 : -2, kHi = St::K == 2 ? 0 : 1;  // cells whose particles reach a node
#pragma omp parallel for schedule(dynamic, 16) if (nodes_.size() > 64)
    for (std::size_t u = 0; u < nodes_.size(); ++u) {
      std::vector<int32_t> ids;
      const int64_t n = nodes_[u];
      std::array<int64_t, 3> ijk;
      int64_t rest = n;
      for (int d = 0; d < 3; ++d) ijk[d] = rest / static_cast<int64_t>(stride[d]), rest %= static_cast<int64_t>(stride[d]);
      const Vec<3> xn(G.origin.x() + h * ijk[0], G.origin.y() + h * ijk[1], G.origin.z() + h * ijk[2]);
      auto& list = sums_[u];
      for (int a = kLo; a <= kHi; ++a)
        for (int b = kLo; b <= kHi; ++b)
          for (int e = kLo; e <= kHi; ++e) {
            bins.for_cell(ijk[0] + a, ijk[1] + b, ijk[2] + e, [&](int32_t p) {
              St st;
              st.eval(G, stride, inv_h, P.x[p], P.half_width[p]);
              double w = 0.0;
              st.for_each_weight([&](int64_t nn, double ww) {
                if (nn == n) w = ww;
              });
              if (w == 0.0) return;
              const uint32_t key = tris.key(P.x[p], xn, ids);
              if (key == crack::kFieldKeyOverflow) return;
              auto it = std::find_if(list.begin(), list.end(), [&](const RawSums& r) { return r.key == key; });
              if (it == list.end()) it = list.insert(list.end(), RawSums{}), it->key = key;
              const double mw = P.mass[p] * w, rw = mw * P.mass[p] / P.volume0[p];
              const Vec<3>&x = P.x[p], &v = P.v[p];
              it->m += mw;
              it->energy += mw * m.materials[P.material[p]]->strain_energy_density(P.stress[p], P.strain[p]);
              it->stress += mw * full_tensor(P.stress[p]);
              it->grad_u += mw * displacement_gradient(P.strain[p], rotations ? P.rotation3[p] : Vec<3>::Zero());
              it->u += mw * P.u[p], it->mv += mw * v, it->mx += mw * x;
              it->rho += rw, it->rho_v += rw * v, it->rho_vv += rw * v.squaredNorm();
              it->rho_x += rw * x, it->rho_xv += rw * x.cross(v), it->rho_xx += rw * x * x.transpose();
            });
          }
    }
  }
  const std::vector<RawSums>& at(int64_t n) const {
    const auto it = std::lower_bound(nodes_.begin(), nodes_.end(), n);
    return it != nodes_.end() && *it == n ? sums_[static_cast<std::size_t>(it - nodes_.begin())] : empty_;
  }

 private:
  std::vector<int64_t> nodes_;
  std::vector<std::vector<RawSums>> sums_;
  std::vector<RawSums> empty_;
};

}  // namespace detail

// The curvature of a front at node k in its plane: the rate at which its ahead direction e1 turns
// towards the direction of travel, (delta e1 . delta x) / |delta x|^2 between the neighbouring nodes
// (one-sided at the ends of an open front); > 0 where the front is convex (a penny crack: 1 / radius).
inline double front_curvature(const crack::CrackFront& f, const std::vector<Vec<3>>& points, std::size_t k) {
  const std::size_t n = f.nodes.size();
  if (n < 2) return 0.0;
  const std::size_t a = k == 0 ? (f.closed ? n - 1 : 0) : k - 1;
  const std::size_t b = k + 1 == n ? (f.closed ? 0 : n - 1) : k + 1;
  const Vec<3> dx = points[f.nodes[b]] - points[f.nodes[a]], de = f.ahead[b] - f.ahead[a];
  const double d2 = dx.squaredNorm();
  return d2 > 0.0 ? de.dot(dx) / d2 : 0.0;
}

}  // namespace cleave
