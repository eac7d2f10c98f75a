// The shared pieces of the crack-front evaluation (crack_front_eval.hpp): particles and crack
// triangles binned by grid cell, eq. 36's raw nodal sums per velocity field taken once per evaluation
// for every grid node a front node reads (NodeSums), the particles' full displacement gradient, and
// the curvature of a front (the out-of-plane term's kappa).
#pragma once
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "libmpm/core/parallel.hpp"
#include "libmpm/crack/crack2d.hpp"  // FieldKeyBuilder
#include "libmpm/crack/crossing3d.hpp"
#include "libmpm/crack/front_parameters.hpp"
#include "libmpm/mpm/model.hpp"
#include "libmpm/mpm/particle_strain.hpp"
#include "libmpm/mpm/stencil.hpp"

namespace cleave {

namespace detail {

// A 3D grid's linear node index taken apart: its (i, j, k) and its position.
struct NodeIndexing {
  explicit NodeIndexing(const GridGeometry<3>& G) : origin(G.origin), h(G.h) {
    const auto st = G.strides();
    for (int d = 0; d < 3; ++d) stride[d] = static_cast<int64_t>(st[d]);
  }
  std::array<int64_t, 3> ijk(int64_t n) const {
    std::array<int64_t, 3> c;
    for (int d = 0; d < 3; ++d) c[d] = n / stride[d], n %= stride[d];
    return c;
  }
  // The position of node (i, j, k) (callers have its (i, j, k) already: ijk's divisions once).
  Vec<3> position(const std::array<int64_t, 3>& c) const {
    return Vec<3>(coordinate(0, c[0]), coordinate(1, c[1]), coordinate(2, c[2]));
  }
  // The coordinate along axis d of the nodes with index i along it.
  double coordinate(int d, int64_t i) const { return origin[d] + h * static_cast<double>(i); }
  Vec<3> origin;
  double h;
  std::array<int64_t, 3> stride;
};

// out = the sorted union of the node indices in lists (each a range of int64_t). The front nodes'
// lists of grid nodes overlap: marked in a bitmap over their range of indices when it is not much
// longer than they are (a pass over it gives the union in order, where sorting was a good part of
// listing them), else sorted. bits: the bitmap's buffer.
template <class Lists>
void sorted_union(const Lists& lists, std::vector<int64_t>& out, std::vector<uint64_t>& bits) {
  out.clear();
  int64_t lo = INT64_MAX, hi = INT64_MIN;
  std::size_t total = 0;
  for (const auto& v : lists)
    for (const int64_t n : v) lo = std::min(lo, n), hi = std::max(hi, n), ++total;
  if (total == 0) return;
  const std::size_t words = static_cast<std::size_t>((hi - lo) / 64 + 1);
  if (words > 16 * total) {
    for (const auto& v : lists) out.insert(out.end(), v.begin(), v.end());
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return;
  }
  bits.assign(words, 0);
  for (const auto& v : lists)
    for (const int64_t n : v) bits[static_cast<std::size_t>((n - lo) >> 6)] |= uint64_t{1} << ((n - lo) & 63);
  for (std::size_t w = 0; w < words; ++w)
    for (uint64_t b = bits[w]; b; b &= b - 1) out.push_back(lo + static_cast<int64_t>(64 * w) + std::countr_zero(b));
}

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
    const double inv_h = 1.0 / G.h;  // (as cells_in_box's test)
    for (int d = 0; d < 3; ++d) c[d] = static_cast<int64_t>(std::floor((x[d] - G.origin[d]) * inv_h));
    return c;
  }
  // The box of the grid's cells that meet [box_lo, box_hi] (clamped to the grid).
  void set_box(const GridGeometry<3>& G, const Vec<3>& box_lo, const Vec<3>& box_hi) {
    const auto a = cell_of(G, box_lo), b = cell_of(G, box_hi);
    for (int d = 0; d < 3; ++d) {
      const int64_t cells = std::max(1, G.nodes[d] - 1);
      lo[d] = std::clamp<int64_t>(a[d], 0, cells - 1);
      n[d] = std::clamp<int64_t>(b[d], 0, cells - 1) - lo[d] + 1;
    }
  }
  // The particles of x in the grid's cells that meet [box_lo, box_hi], from one pass over all.
  void build(const GridGeometry<3>& G, const std::vector<Vec<3>>& x, const Vec<3>& box_lo, const Vec<3>& box_hi) {
    set_box(G, box_lo, box_hi);
    std::vector<int64_t> cell(x.size());
    cells_in_box(G, x, lo, n, nullptr, x.size(), cell.data());
    std::vector<int32_t> kept;
    for (std::size_t p = 0; p < x.size(); ++p)
      if (cell[p] >= 0) kept.push_back(static_cast<int32_t>(p));
    std::erase(cell, -1);
    place(kept.data(), cell.data(), kept.size());
  }
  // The bins of particles ids[k] in cells cell[k] of the box (-1: none), k < count, ids in index order.
  void place(const int32_t* ids, const int64_t* cell, std::size_t count) {
    const int64_t total = n[0] * n[1] * n[2];
    begin.assign(total + 1, 0);
    for (std::size_t k = 0; k < count; ++k)
      if (cell[k] >= 0) ++begin[cell[k] + 1];
    for (int64_t c = 0; c < total; ++c) begin[c + 1] += begin[c];
    particle.resize(begin[total]);
    std::vector<int64_t> next(begin.begin(), begin.end() - 1);
    for (std::size_t k = 0; k < count; ++k)
      if (cell[k] >= 0) particle[next[cell[k]]++] = ids[k];
  }

  // For each particle ids[q] (or q, ids null), q < count: its cell's index in the box of cells c0 ..
  // c0 + span - 1, or -1 outside it, into cell[q]. A branch-free test per particle that vectorises
  // (most particles lie outside the box).
  // Returns the least distance of these particles to a face of their cells, in cells: none of them
  // changes cell before it has moved that far.
  static double cells_in_box(const GridGeometry<3>& G, const std::vector<Vec<3>>& x, const std::array<int64_t, 3>& c0,
                             const std::array<int64_t, 3>& span, const int32_t* ids, std::size_t count, int64_t* cell) {
    // In the box: c0 <= (x - origin) / h < c0 + span along each axis (cell_of's arithmetic).
    double blo[3], bhi[3];
    for (int d = 0; d < 3; ++d) blo[d] = static_cast<double>(c0[d]), bhi[d] = static_cast<double>(c0[d] + span[d]);
    const double ox = G.origin.x(), oy = G.origin.y(), oz = G.origin.z(), inv_h = 1.0 / G.h;
    double slack = 1.0;
#pragma omp parallel for schedule(static) if (count > 65536) reduction(min : slack)
    for (std::size_t q = 0; q < count; ++q) {
      const Vec<3>& y = x[ids ? static_cast<std::size_t>(ids[q]) : q];
      const double u = (y.x() - ox) * inv_h, v = (y.y() - oy) * inv_h, w = (y.z() - oz) * inv_h;
      const bool in = (u >= blo[0]) & (u < bhi[0]) & (v >= blo[1]) & (v < bhi[1]) & (w >= blo[2]) & (w < bhi[2]);
      const double fu = std::floor(u), fv = std::floor(v), fw = std::floor(w);
      const int64_t i = static_cast<int64_t>(fu) - c0[0], j = static_cast<int64_t>(fv) - c0[1],
                    k = static_cast<int64_t>(fw) - c0[2];
      cell[q] = in ? (i * span[1] + j) * span[2] + k : -1;
      const double a = std::min(u - fu, fu + 1.0 - u), b = std::min(v - fv, fv + 1.0 - v), c = std::min(w - fw, fw + 1.0 - w);
      slack = std::min(slack, std::min(a, std::min(b, c)));
    }
    return slack;
  }
};

// The triangles of every crack binned by grid cell over a box of cells (cells lo .. lo + n - 1), each
// in the cells its box meets (by a hair more, so that rounding cannot drop one): a triangle whose box
// meets a line's box is in one of the cells the line's box meets, so the field key of a line inside
// the box from these is exact, as the stepper's. (Positions outside the box are taken to its edge
// cells: keys there are not exact.)
class TriangleBins {
 public:
  TriangleBins(const Model<3>& m, const std::array<int64_t, 3>& lo, const std::array<int64_t, 3>& n)
      : m_(m), first_(lo), cells_(n) {
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
        bool meets = true;  // the triangle's box meets the box of cells
        for (int d = 0; d < 3; ++d) {
          const int64_t a = unclamped(lo, d, -1e-9), b = unclamped(hi, d, 1e-9);
          meets = meets && b >= 0 && a < cells_[d];
          sp[d] = std::clamp<int64_t>(a, 0, cells_[d] - 1), sp[3 + d] = std::clamp<int64_t>(b, 0, cells_[d] - 1);
        }
        if (!meets) sp = {0, 0, 0, -1, -1, -1};  // (no cell)
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

  // The triangles of every crack entered in the cells that the box [lo, hi] meets, per crack sorted
  // and unique: among them every triangle whose box meets a segment inside [lo, hi]. Gathered once
  // for all the lines from one point (a particle to its stencil's nodes), with that point's side of
  // each triangle kept as it is first needed.
  struct Candidates {
    std::vector<int32_t> begin;  // per crack + 1: the crack's range in ids
    std::vector<int32_t> ids;    // triangle ids
    std::vector<int8_t> side;    // the point's volume_sign per candidate (kUnknown: not computed yet)
    std::vector<int32_t> line_ids, line_at;  // scratch: one line's triangles and their candidate index
    // mask_lines's: bit k of axis[d][a] set when candidate k's box meets, along axis d, the span of
    // the point and the a-th node coordinate of its block (valid while `masked`).
    uint64_t axis[3][3] = {};
    bool masked = false;
  };
  static constexpr int8_t kUnknown = 2;
  void gather(const Vec<3>& lo, const Vec<3>& hi, Candidates& c) const {
    std::array<int64_t, 6> sp;
    for (int d = 0; d < 3; ++d) sp[d] = index(lo, d, 0.0), sp[3 + d] = index(hi, d, 0.0);
    c.ids.clear(), c.begin.assign(1, 0);
    for (const auto& o : m_.cracks) {
      const std::size_t first = c.ids.size();
      for_span(sp, [&](int64_t cell) {
        for (int64_t e = begin_[cell]; e < begin_[cell + 1]; ++e)
          if (entry_[e].first == o.id) c.ids.push_back(entry_[e].second);
      });
      // (One cell's entries are already in triangle order.)
      if (sp[0] != sp[3] || sp[1] != sp[4] || sp[2] != sp[5]) {
        std::sort(c.ids.begin() + first, c.ids.end());
        c.ids.erase(std::unique(c.ids.begin() + first, c.ids.end()), c.ids.end());
      }
      c.begin.push_back(static_cast<int32_t>(c.ids.size()));
    }
    c.side.assign(c.ids.size(), kUnknown);
    c.masked = false;
  }
  // Whether the cells that the box [lo, hi] meets lie in the binned box (gather is exact for it).
  bool covers(const Vec<3>& lo, const Vec<3>& hi) const {
    for (int d = 0; d < 3; ++d)
      if (unclamped(lo, d, 0.0) < 0 || unclamped(hi, d, 0.0) >= cells_[d]) return false;
    return true;
  }
  // The candidates of a point in the closed cell (i, j, k) for its lines to the cell's corners: the
  // cell's own entries (a triangle whose box meets the closed cell is entered in it: the slack).
  void gather_cell(const std::array<int64_t, 3>& ijk, Candidates& c) const {
    c.ids.clear(), c.begin.assign(1, 0);
    std::array<int64_t, 3> b;
    for (int d = 0; d < 3; ++d) {
      b[d] = ijk[d] - first_[d];
      if (b[d] < 0 || b[d] >= cells_[d]) {  // (outside the box: its edge cells)
        const auto& G = m_.grid;
        const Vec<3> lo = G.origin + G.h * Vec<3>(double(ijk[0]), double(ijk[1]), double(ijk[2]));
        return gather(lo, lo + Vec<3>::Constant(G.h), c);
      }
    }
    const int64_t cell = (b[0] * cells_[1] + b[1]) * cells_[2] + b[2];
    for (const auto& o : m_.cracks) {
      for (int64_t e = begin_[cell]; e < begin_[cell + 1]; ++e)
        if (entry_[e].first == o.id) c.ids.push_back(entry_[e].second);
      c.begin.push_back(static_cast<int32_t>(c.ids.size()));
    }
    c.side.assign(c.ids.size(), kUnknown);
    c.masked = false;
  }
  // The candidates of a particle at x for its lines to the nodes of its stencil of K x K x K nodes,
  // base its first node and first that node's position: every such line lies in the box of the first
  // and last nodes and x (for linear shapes the particle's closed cell).
  template <int K>
  void gather_stencil(const std::array<int64_t, 3>& base, const Vec<3>& first, const Vec<3>& x, Candidates& c) const {
    if constexpr (K == 2) {
      gather_cell(base, c);
    } else {
      const Vec<3> last = first + Vec<3>::Constant((K - 1) * m_.grid.h);
      gather(first.cwiseMin(x), last.cwiseMax(x), c);
    }
  }
  // For the lines from x to the nodes of the block of K x K x K grid nodes from node `first` (i, j, k),
  // node (a, b, e) of it at (i + a, j + b, k + e): each candidate's box tested once per axis and node
  // coordinate (as the stepper's classify_block3), so that key(x, xn, c, a, b, e) finds a line's
  // triangles by one AND. Most lines near a front meet none of their cell's candidates: their box
  // tests, line by line, were most of the keys' cost.
  template <int K>
  void mask_lines(const Vec<3>& x, const std::array<int64_t, 3>& first, Candidates& c) const {
    static_assert(K <= 3);
    std::fill(c.side.begin(), c.side.end(), kUnknown);  // (the candidates may be another point's)
    c.masked = c.ids.size() <= 64;
    if (!c.masked) return;
    const NodeIndexing ix(m_.grid);
    double nc[3][K];  // (NodeIndexing::position's coordinates: the nodes of the callers' lines)
    for (int d = 0; d < 3; ++d)
      for (int a = 0; a < K; ++a) nc[d][a] = ix.coordinate(d, first[d] + a);
    for (auto& row : c.axis)
      for (uint64_t& w : row) w = 0;
    for (const auto& o : m_.cracks)
      for (int32_t k = c.begin[o.id]; k < c.begin[o.id + 1]; ++k) {
        const Vec<3>&tlo = lo_[o.id][c.ids[k]], &thi = hi_[o.id][c.ids[k]];
        for (int d = 0; d < 3; ++d)
          for (int a = 0; a < K; ++a)
            c.axis[d][a] |= static_cast<uint64_t>(thi[d] >= std::min(x[d], nc[d][a]) && tlo[d] <= std::max(x[d], nc[d][a]))
                            << k;
      }
  }
  // The field key of the line x -> xn (crack_fields' key: one code per crossed crack, in crack order)
  // from the candidates gathered over a box that holds the line, x the point they were gathered for:
  // the triangles whose boxes meet the line's box, in triangle order, as the stepper tests them.
  // (a, b, e): xn's place in the block of mask_lines, when the candidates are masked.
  // (The masks' answer inline: most masked lines meet no candidate, and the call to the crossing
  // tests was a good part of their cost.)
  uint32_t key(const Vec<3>& x, const Vec<3>& xn, Candidates& c, int a = -1, int b = -1, int e = -1) const {
    return a >= 0 && masked_out(c, a, b, e) ? 0 : key_tested(x, xn, c, a, b, e);
  }
  // Whether key(x, xn, c, a, b, e) is 0 by the masks alone (xn not needed).
  static bool masked_out(const Candidates& c, int a, int b, int e) {
    return c.masked && (c.axis[0][a] & c.axis[1][b] & c.axis[2][e]) == 0;
  }
  // key() by the crossing tests.
  uint32_t key_tested(const Vec<3>& x, const Vec<3>& xn, Candidates& c, int a, int b, int e) const {
    const Vec<3> lo = x.cwiseMin(xn), hi = x.cwiseMax(xn);
    const bool masked = c.masked && a >= 0;
    const uint64_t line = masked ? c.axis[0][a] & c.axis[1][b] & c.axis[2][e] : 0;
    // Of the triangles whose boxes meet the line's box, those whose boxes the line itself meets: a
    // line across a cell has its box meet a dozen triangles' boxes, of which it passes through two or
    // three; each one skipped saves four or five exact volume signs.
    const Vec<3> inv = (xn - x).cwiseInverse();
    const double slack = crack::segment_box_slack(m_.grid.h, std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff()));
    crack::FieldKeyBuilder key;
    for (const auto& o : m_.cracks) {
      c.line_ids.clear(), c.line_at.clear();
      const auto &tlo = lo_[o.id], &thi = hi_[o.id];
      for (int32_t k = c.begin[o.id]; k < c.begin[o.id + 1]; ++k) {
        const int32_t t = c.ids[k];
        const bool box = masked ? (line >> k & 1) != 0
                                : (thi[t].array() >= lo.array()).all() && (tlo[t].array() <= hi.array()).all();
        if (box && crack::segment_meets_box(x, inv, tlo[t], thi[t], slack)) c.line_ids.push_back(t), c.line_at.push_back(k);
      }
      if (c.line_ids.empty()) continue;
      const auto point_side = [&](std::size_t k) {
        int8_t& s = c.side[c.line_at[k]];
        if (s == kUnknown) {
          const auto& T = o.simplices[c.line_ids[k]];
          s = static_cast<int8_t>(crack::volume_sign(o.points[T[0]], o.points[T[1]], o.points[T[2]], x));
        }
        return static_cast<int>(s);
      };
      const crack::Side side =
          crack::triangle_list_crossing_with(o.points.data(), o.simplices.data(), c.line_ids.data(), c.line_ids.size(),
                                             x, xn, point_side, nullptr,
                                             o.front_cut.dropper(o.points.data(), o.simplices.data()));
      if (side != crack::Side::None && !key.add(o.id, side)) return crack::kFieldKeyOverflow;
    }
    return key.key();
  }
  // The bounding boxes of crack c's triangles.
  const std::vector<Vec<3>>& box_lo(int c) const { return lo_[c]; }
  const std::vector<Vec<3>>& box_hi(int c) const { return hi_[c]; }

 private:
  // The cell index along d of x, shifted by `slack` cells before rounding down.
  int64_t unclamped(const Vec<3>& x, int d, double slack) const {
    const auto& G = m_.grid;
    return static_cast<int64_t>(std::floor((x[d] - G.origin[d]) / G.h + slack)) - first_[d];
  }
  int64_t index(const Vec<3>& x, int d, double slack) const {
    return std::clamp<int64_t>(unclamped(x, d, slack), 0, cells_[d] - 1);
  }
  template <class F>
  void for_span(const std::array<int64_t, 6>& sp, F&& f) const {
    for (int64_t i = std::max<int64_t>(sp[0], 0); i <= std::min(sp[3], cells_[0] - 1); ++i)
      for (int64_t j = std::max<int64_t>(sp[1], 0); j <= std::min(sp[4], cells_[1] - 1); ++j)
        for (int64_t k = std::max<int64_t>(sp[2], 0); k <= std::min(sp[5], cells_[2] - 1); ++k)
          f((i * cells_[1] + j) * cells_[2] + k);
  }
  const Model<3>& m_;
  std::array<int64_t, 3> first_{}, cells_{};  // the box of cells
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

// A particle's share of RawSums per unit of its shape-function weight N, laid out flat so that a
// node's sums take it as one run of fused multiply-adds (acc += N c): mass-weighted entries (m_p
// times 1, energy density, stress, displacement gradient, u, v, x), then density-weighted ones
// (m_p^2 / V_p0 times 1, v, |v|^2, x, x cross v, x x^T). Computed once per particle, where each of
// the up to 27 nodes it reaches would otherwise rebuild the tensors from the particle arrays.
struct ParticleShare {
  enum : int {
    kM = 0, kEnergy = 1, kStress = 2, kGradU = 8, kU = 17, kV = 20, kX = 23,  // (stress, x x^T: Sym order)
    kRho = 26, kRhoV = 27, kRhoVV = 30, kRhoX = 31, kRhoXV = 34, kRhoXX = 37, kUsed = 43, kSize = 48
  };
  alignas(64) double c[kSize];

  void set(double m, double energy, const Sym<3>& stress, const Mat<3>& grad_u, const Vec<3>& u, const Vec<3>& v,
           const Vec<3>& x, double rho) {
    c[kM] = m, c[kEnergy] = m * energy;
    for (int i = 0; i < 6; ++i) c[kStress + i] = m * stress[i];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) c[kGradU + 3 * i + j] = m * grad_u(i, j);
    const Vec<3> xv = x.cross(v);
    const double xx[6] = {x[0] * x[0], x[1] * x[1], x[2] * x[2], x[0] * x[1], x[1] * x[2], x[0] * x[2]};
    for (int d = 0; d < 3; ++d) {
      c[kU + d] = m * u[d], c[kV + d] = m * v[d], c[kX + d] = m * x[d];
      c[kRhoV + d] = rho * v[d], c[kRhoX + d] = rho * x[d], c[kRhoXV + d] = rho * xv[d];
    }
    c[kRho] = rho, c[kRhoVV] = rho * v.squaredNorm();
    for (int i = 0; i < 6; ++i) c[kRhoXX + i] = rho * xx[i];
    for (int i = kUsed; i < kSize; ++i) c[i] = 0.0;
  }
};

// One field's running sum of ParticleShare at a node, and the RawSums it stands for.
struct ShareSum {
  uint32_t key = 0;
  alignas(64) double c[ParticleShare::kSize] = {};

  void add(double w, const ParticleShare& s) {
#pragma omp simd
    for (int i = 0; i < ParticleShare::kSize; ++i) c[i] += w * s.c[i];
  }
  RawSums raw() const {
    using S = ParticleShare;
    const auto vec = [&](int k) { return Vec<3>(c[k], c[k + 1], c[k + 2]); };
    const auto sym = [&](int k) {
      Sym<3> t;
      for (int i = 0; i < 6; ++i) t[i] = c[k + i];
      return full_tensor(t);
    };
    RawSums r;
    r.key = key, r.m = c[S::kM], r.energy = c[S::kEnergy], r.rho = c[S::kRho], r.rho_vv = c[S::kRhoVV];
    r.mv = vec(S::kV), r.mx = vec(S::kX), r.u = vec(S::kU);
    r.rho_v = vec(S::kRhoV), r.rho_x = vec(S::kRhoX), r.rho_xv = vec(S::kRhoXV);
    r.stress = sym(S::kStress), r.rho_xx = sym(S::kRhoXX);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) r.grad_u(i, j) = c[S::kGradU + 3 * i + j];
    return r;
  }
};

// RawSums at a set of grid nodes, per field. Each particle that reaches a needed node has its stencil,
// energy density, field keys (of its lines to the needed nodes) and share of the sums found once, and
// adds its share to those nodes at once (a scatter: the nodes' running sums, a few hundred kilobytes,
// stay in cache, where a gather re-read each particle's share, megabytes, from each node). The cells
// are taken in slabs across one axis, each slab whole by one thread and in cell and particle order;
// slabs of one colour touch disjoint nodes and run in parallel, the two colours one after the other:
// the same sums for any thread count. An object kept from one build to the next
// (FrontParticles::sums) reuses its buffers.
class NodeSums {
 public:
  template <class SF>
  void build(const Model<3>& m, const CellBins& bins, const TriangleBins& tris,
             const std::vector<std::vector<int64_t>>& need_of) {
    using St = Stencil<3, SF>;
    constexpr int K = St::K;
    sorted_union(need_of, nodes_, marks_);
    if (sums_.size() < nodes_.size()) sums_.resize(nodes_.size());  // (entries past nodes_.size() unused)
    if (acc_.size() < nodes_.size()) acc_.resize(nodes_.size());
    if (nodes_.empty()) return;
    const auto& P = m.particles;
    const StrainOf<3> strain(m);
    const auto& G = m.grid;
    const double h = G.h, inv_h = 1.0 / h;
    const auto stride = G.strides();
    const bool rotations = !P.rotation3.empty();
    constexpr int kLo = K == 2 ? -1 : -2, kHi = K == 2 ? 0 : 1;  // cells whose particles reach a node
    const NodeIndexing indexing(G);
    const auto ijk_of = [&](int64_t n) { return indexing.ijk(n); };
    const auto node_x = [&](const std::array<int64_t, 3>& ijk) { return indexing.position(ijk); };

    // slot_of(ijk, n): node n's place in nodes_, or -1 (not needed), from a table over the bins' box
    // (+1 node per axis; a binary search for a node outside it).
    std::array<int64_t, 3> mn;
    for (int d = 0; d < 3; ++d) mn[d] = bins.n[d] + 1;
    const auto box_of = [&](const std::array<int64_t, 3>& ijk) -> int64_t {
      int64_t b = 0;
      for (int d = 0; d < 3; ++d) {
        const int64_t i = ijk[d] - bins.lo[d];
        if (i < 0 || i >= mn[d]) return -1;
        b = b * mn[d] + i;
      }
      return b;
    };
    slot_.assign(static_cast<std::size_t>(mn[0] * mn[1] * mn[2]), -1);
    bool all_in_box = true;
    for (std::size_t u = 0; u < nodes_.size(); ++u) {
      const int64_t b = box_of(ijk_of(nodes_[u]));
      if (b < 0) all_in_box = false;
      else slot_[b] = static_cast<int32_t>(u);
    }
    const auto slot_of = [&](const std::array<int64_t, 3>& ijk, int64_t n) -> int64_t {
      const int64_t b = box_of(ijk);
      if (b >= 0) return slot_[b];
      if (all_in_box) return -1;
      const auto it = std::lower_bound(nodes_.begin(), nodes_.end(), n);
      return it != nodes_.end() && *it == n ? it - nodes_.begin() : -1;
    };

    // The cells whose particles reach a needed node (in cell order), in slabs one cell wide (linear:
    // a cell's particles reach its own two node layers) or three wide (uGIMP: from the layer before
    // to the second after) across axis 0: slabs two apart touch no node in common.
    constexpr int64_t kSlab = K == 2 ? 1 : 3;
    std::vector<int64_t>& cells = cells_;
    cells.clear();
    {
      std::vector<uint8_t>& listed = listed_;
      listed.assign(bins.begin.size(), 0);
      for (const int64_t n : nodes_) {
        const auto ijk = ijk_of(n);
        for (int a = kLo; a <= kHi; ++a)
          for (int b = kLo; b <= kHi; ++b)
            for (int e = kLo; e <= kHi; ++e)
              if (const int64_t c = bins.index(ijk[0] + a, ijk[1] + b, ijk[2] + e); c >= 0) listed[c] = 1;
      }
      for (std::size_t c = 0; c < listed.size(); ++c)
        if (listed[c]) cells.push_back(static_cast<int64_t>(c));
    }
    // Slab k holds cells[slab_begin_[k] .. slab_begin_[k + 1]) (cells are ordered by their axis-0 index first).
    const int64_t per_layer = bins.n[1] * bins.n[2];
    slab_begin_.clear();
    int64_t last = -1;
    for (std::size_t q = 0; q < cells.size(); ++q)
      if (const int64_t slab = cells[q] / per_layer / kSlab; slab != last)
        slab_begin_.push_back(static_cast<int64_t>(q)), last = slab;
    slab_begin_.push_back(static_cast<int64_t>(cells.size()));
    const int64_t slabs = static_cast<int64_t>(slab_begin_.size()) - 1;
    for (std::size_t u = 0; u < nodes_.size(); ++u) acc_[u].clear();

#pragma omp parallel
    {
      TriangleBins::Candidates cand;
      std::array<int64_t, 3> cand_base{-1, -1, -1};  // (K = 2: the cell whose candidates cand holds)
      ParticleShare share;
      for (int colour = 0; colour < 2; ++colour) {
#pragma omp for schedule(dynamic, 1)
        for (int64_t k = 0; k < slabs; ++k) {
          // (Slabs of the other colour: the slab's axis-0 index parity, not k's: slabs may be skipped.)
          if (cells[slab_begin_[k]] / per_layer / kSlab % 2 != colour) continue;
          for (int64_t q0 = slab_begin_[k]; q0 < slab_begin_[k + 1]; ++q0) {
            const int64_t c = cells[q0];
            for (int64_t q = bins.begin[c]; q < bins.begin[c + 1]; ++q) {
              const int32_t p = bins.particle[q];
              St st;
              st.eval(G, stride, inv_h, P.x[p], P.half_width[p]);
              const std::array<int64_t, 3> b0 = ijk_of(st.base);
              bool gathered = false, shared = false;
              int j = 0;
              st.for_each_weight([&](int64_t n, double w) {
                const std::array<int64_t, 3> ijk{b0[0] + j / (K * K), b0[1] + j / K % K, b0[2] + j % K};
                const int64_t u = w != 0.0 ? slot_of(ijk, n) : -1;
                if (u >= 0) {
                  if (!gathered) {
                    // (Linear shapes: the particles of a cell share its candidates.)
                    if (K != 2 || cand_base != b0) tris.gather_stencil<K>(b0, node_x(b0), P.x[p], cand);
                    if (K == 2) cand_base = b0;
                    tris.mask_lines<K>(P.x[p], b0, cand);
                    gathered = true;
                  }
                  const int a = j / (K * K), b = j / K % K, e = j % K;
                  const uint32_t key =
                      TriangleBins::masked_out(cand, a, b, e) ? 0 : tris.key_tested(P.x[p], node_x(ijk), cand, a, b, e);
                  if (key != crack::kFieldKeyOverflow) {
                    if (!shared) {
                      const double mass = P.mass[p];
                      const Sym<3> e = strain(p);
                      share.set(mass, m.materials[P.material[p]]->strain_energy_density(P.stress[p], e), P.stress[p],
                                displacement_gradient(e, rotations ? P.rotation3[p] : Vec<3>::Zero()),
                                P.u[p], P.v[p], P.x[p], mass * mass / P.volume0[p]);
                      shared = true;
                    }
                    std::vector<ShareSum>& list = acc_[static_cast<std::size_t>(u)];
                    auto it = std::find_if(list.begin(), list.end(), [&](const ShareSum& s) { return s.key == key; });
                    if (it == list.end()) it = list.insert(list.end(), ShareSum{}), it->key = key;
                    it->add(w, share);
                  }
                }
                ++j;
              });
            }
          }
        }
      }
#pragma omp for schedule(static)
      for (std::size_t u = 0; u < nodes_.size(); ++u) {
        auto& out = sums_[u];
        out.clear();
        for (const ShareSum& s : acc_[u]) out.push_back(s.raw());
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
  // build's buffers (kept for the next build): per node its fields' running sums; the cells read, in
  // cell order, and where each slab of them begins; which cells are listed; each node's slot in the box.
  std::vector<std::vector<ShareSum>> acc_;
  std::vector<int64_t> cells_, slab_begin_;
  std::vector<uint8_t> listed_;
  std::vector<int32_t> slot_;
  std::vector<uint64_t> marks_;  // (sorted_union's bitmap)
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
