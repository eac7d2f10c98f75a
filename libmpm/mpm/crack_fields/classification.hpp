// Layer of the crack fields (libmpm/mpm/crack_fields.hpp; layering: grid_cells.hpp): which side of
// which crack each particle-node pair lies on (seed 002 Appendix A, line crossing), for the
// particles near a crack: their list, their stencils, and per pair a field key (the cracks its
// connecting line crosses and the particle's side of each, at most two) with the segment crossed.
// Only the near particles are classified: the spatial index guarantees that every other particle's
// lines cross nothing.
// 2D: the crossing test of polylines (crack/crossing.hpp); 3D: that of triangle meshes
// (crack/crossing3d.hpp, seed 000 Appendix A), on the triangles of the index entries.
#pragma once
#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <vector>

#include "libmpm/core/parallel.hpp"
#include "libmpm/crack/crack2d.hpp"
#include "libmpm/crack/crossing3d.hpp"
#include "libmpm/crack/reference_side.hpp"
#include "libmpm/mpm/crack_fields/body_groups.hpp"
#include "libmpm/mpm/model.hpp"
#include "libmpm/mpm/stencil.hpp"

namespace cleave::crack_fields {

template <int Dim, class SF>
class Classification : public BodyGroups<Dim, SF> {
  using Base = BodyGroups<Dim, SF>;
  using St = Stencil<Dim, SF>;
  using V = Vec<Dim>;

 public:
  static constexpr int N = St::N;

 protected:
  using typename Base::Entry;
  using Base::cell_head_, Base::cell_of, Base::cracks_, Base::entries_, Base::G_, Base::inv_h_;
  using Base::node_position, Base::stride_, Base::tri_hi_, Base::tri_ids_, Base::tri_lo_;
  using Base::bodies_, Base::body_tag;
  using Base::crack_epoch_, Base::index_epoch_, Base::tight_, Base::tight_begin_, Base::tight_head, Base::tight_ids_;
  static constexpr uint32_t kOverflow = crack::kFieldKeyOverflow;  // a line crossing three or more cracks

  explicit Classification(Model<Dim>& m) : Base(m), P_(m.particles) {
    near_flag_.assign(P_.size(), 0);
    near_index_.assign(P_.size(), -1);
  }

  // The list of near particles, in particle order, from the flags (only when a flag changed): in
  // parallel over fixed chunks, each filled at the offset of a prefix sum of the chunk counts.
  void collect_near_particles() {
    kept_epoch_ = ~uint64_t{0};  // a new list: no particle keeps its keys (classify_pairs3)
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
    if constexpr (Dim == 3) {
      return add_crossing3(b, crack, tri_ids_.data() + lo, hi - lo + 1, xp, xn);
    } else {
      const crack::ExplicitCrack<Dim>& c = cracks_[crack];
      if (!crack::extent_overlaps(c, xp, xn)) return true;  // Subtask 1
      // Cut tips: the polyline and segments ExplicitCrack::crossing_polyline gives for this node.
      const Vec<Dim>* pts = c.crossing_polyline(xn, lo, hi);
      if (!pts) return true;
      std::size_t s = 0;
      const crack::Side side = crack::polyline_crossing(pts + lo, static_cast<std::size_t>(hi - lo + 2), xp, xn, &s);
      return side == crack::Side::None || b.add(crack, side, lo + static_cast<int32_t>(s));
    }
  }
  // 3D: the same with the n triangles ids[0 .. n-1] of the crack; the segment slot gets the triangle.
  // Only the triangles whose boxes meet the line's box are tested (exact: the others cannot meet it).
  bool add_crossing3(crack::FieldKeyBuilder& b, int32_t crack, const int32_t* ids, int n, const V& xp,
                     const V& xn) const {
    const crack::ExplicitCrack<Dim>& c = cracks_[crack];
    if (n <= 0 || !crack::extent_overlaps(c, xp, xn)) return true;
    const V lo = xp.cwiseMin(xn), hi = xp.cwiseMax(xn);
    const std::vector<V>&tlo = tri_lo_[crack], &thi = tri_hi_[crack];
    int32_t near[64];
    int m = 0;
    for (int k = 0; k < n && m <= 64; ++k) {
      const int32_t t = ids[k];
      if ((thi[t].array() >= lo.array()).all() && (tlo[t].array() <= hi.array()).all()) {
        if (m < 64) near[m] = t;
        ++m;
      }
    }
    if (m == 0) return true;
    const bool narrowed = m <= 64;
    std::size_t t = 0;
    const crack::Side side =
        narrowed ? crack::triangle_list_crossing(c.points.data(), c.simplices.data(), near, static_cast<std::size_t>(m),
                                                 xp, xn, &t, c.front_cut.dropper(c.points.data(), c.simplices.data()))
                 : crack::triangle_list_crossing(c.points.data(), c.simplices.data(), ids, static_cast<std::size_t>(n),
                                                 xp, xn, &t, c.front_cut.dropper(c.points.data(), c.simplices.data()));
    return side == crack::Side::None || b.add(crack, side, static_cast<int32_t>(t));
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
  // With contact between bodies, each key gets its body tag (body_groups.hpp, from the node marks of
  // prepare_index); 3D keeps no keys from the last step (their tags change).
  void classify_pairs() {
    const std::size_t nn = near_.size();
    pair_key_.resize(nn * N);
    pair_seg_.resize(nn * N * 2);
    near_st_.resize(nn);
    key_any_.resize(nn);
    if (bodies_) kept_epoch_ = ~uint64_t{0};
    if constexpr (Dim == 3) classify_pairs3(nn);
    else classify_pairs2(nn);
    if (bodies_) tag_body_fields(nn);
  }
  void tag_body_fields(const std::size_t nn) {
#pragma omp parallel for schedule(static) if (nn >= 512)
    for (std::size_t k = 0; k < nn; ++k) {
      const std::size_t p = static_cast<std::size_t>(near_[k]);
      int j = 0;
      uint8_t any = key_any_[k];
      near_st_[k].for_each_weight([&](int64_t n, double w) {
        uint32_t& key = pair_key_[k * N + j++];
        if (w == 0.0 || key == kOverflow) return;
        key |= body_tag(p, n);
        any |= key != 0;
      });
      key_any_[k] = any;
    }
  }
  void classify_pairs2(const std::size_t nn) {
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
      // A particle a hair from a crack's line is sorted by its side in the reference configuration
      // (crack/reference_side.hpp): the crossing test takes it at xc, the nearest such crack deciding.
      crack::SortingPosition sorted(xp, xp - P_.u[p], crack::kSortingHair * G_.h);
      if (nsub >= 0)
        for (int e = 0; e < nsub; ++e) sorted.consider(cracks_[sub[e].crack], sub[e].lo, sub[e].hi);
      else
        for (int32_t e = cell_head_[cell]; e >= 0; e = entries_[e].next)
          sorted.consider(cracks_[entries_[e].crack], entries_[e].seg_lo, entries_[e].seg_hi);
      const V xc = sorted.at;
      int j = 0;
      s.for_each_weight([&](int64_t, double w) {
        const std::size_t q = k * N + j;
        const V xn(nx[j / St::K], ny[j % St::K]);
        ++j;
        pair_key_[q] = 0;
        if (w == 0.0) return;  // no contribution: no field needed
        pair_key_[q] = nsub >= 0 ? classify_sub(sub, nsub, xc, xn, &pair_seg_[2 * q])
                                 : classify_in_cell(cell, xc, xn, &pair_seg_[2 * q]);
      });
    }
  }

  // 3D: the keys of the lines from xp (in `cell`, >= 0) to the nodes of a K x K x K block, node (a, b, c)
  // at (nc[0][a], nc[1][b], nc[2][c]), for each pair j = (a K + b) K + c that want(j) asks for:
  // emit(j, key) with the crossed segments written to seg_of(j) (as classify's); false, and nothing
  // emitted, when no triangle is near (every key 0). Each index entry of the cell is first narrowed
  // to the triangles whose bounding boxes meet the closed box B of xp and the nodes (exact, as in 2D:
  // a triangle apart from B cannot meet a line, and the crossing rules are per triangle); each line
  // is then tested on the triangles of that short list whose boxes meet its own box. A line's box
  // spans xp and one node, so it is found axis by axis: bit i of bits[d][a] says whether triangle
  // i's box meets, along axis d, the span of xp and the block's a-th node coordinate (the triangle
  // meets line (a, b, c) when its three bits are set: one AND per 64 triangles). xp's side of each triangle's plane is
  // computed once for all its lines. Same keys and segments as classify() line by line.
  template <int K, class Want, class Seg, class Emit>
  bool classify_block3(int64_t cell, const V& xp, const double (&nc)[3][K], Want&& want, Seg&& seg_of,
                       Emit&& emit) const {
    static_assert(K <= 8);
    constexpr int kMaxTri = 512;  // triangles kept; more: the full entries, line by line
    V lo = xp, hi = xp;
    for (int d = 0; d < 3; ++d)
      for (int a = 0; a < K; ++a) lo[d] = std::min(lo[d], nc[d][a]), hi[d] = std::max(hi[d], nc[d][a]);
    int32_t ids[kMaxTri];
    SubRange sub[kMaxSub];  // per entry: its triangles in ids[lo .. hi]
    int nsub = 0, nid = 0;
    // The triangles meeting B from the cell's full lists, or from the fewer of a nearby cell's tight
    // lists (tight_head: the same triangles in the same order); each way with at most kMaxSub entries.
    auto entries_from = [&](int32_t e) {
      int n = 0;
      for (; e >= 0 && n <= kMaxSub; e = entries_[e].next) ++n;
      return n;
    };
    int32_t th = entries_from(cell_head_[cell]) <= kMaxSub ? tight_head(cell, lo, hi) : -1;
    if (th >= 0 && entries_from(th) > kMaxSub) th = -1;
    for (int32_t e = th >= 0 ? th : cell_head_[cell]; e >= 0; e = entries_[e].next) {
      const Entry& en = entries_[e];
      if (nsub == kMaxSub) {
        nsub = -1;
        break;
      }
      const int32_t first = nid;
      if ((en.hi.array() >= lo.array()).all() && (en.lo.array() <= hi.array()).all()) {
        const int32_t* list = th >= 0 ? tight_ids_.data() + tight_begin_[e] : tri_ids_.data() + en.seg_lo;
        const int32_t n = th >= 0 ? tight_[e].count : en.seg_hi - en.seg_lo + 1;
        const std::vector<V>&tlo = tri_lo_[en.crack], &thi = tri_hi_[en.crack];
        for (int32_t a = 0; a < n; ++a) {
          const int32_t t = list[a];
          if (!((thi[t].array() >= lo.array()).all() && (tlo[t].array() <= hi.array()).all())) continue;
          if (nid == kMaxTri) {
            nsub = -1;
            break;
          }
          ids[nid++] = t;
        }
        if (nsub < 0) break;
      }
      sub[nsub++] = {en.crack, first, nid - 1};
    }
    constexpr int kLines = K * K * K;
    if (nsub >= 0 && nid == 0) return false;
    if (nsub < 0) {  // too many triangles near: every line on the cell's whole entries
      for (int j = 0; j < kLines; ++j)
        if (want(j)) {
          const V xn(nc[0][j / (K * K)], nc[1][(j / K) % K], nc[2][j % K]);
          emit(j, classify_in_cell(cell, xp, xn, seg_of(j)));
        }
      return true;
    }
    // bits[d][a]: bit i set when triangle ids[i]'s box meets, along axis d, the span of xp and the
    // block's a-th node coordinate; a line's triangles are the AND of its three axes' words.
    constexpr int kWords = kMaxTri / 64;
    const int nw = (nid + 63) / 64;
    uint64_t bits[3][K][kWords];
    for (int d = 0; d < 3; ++d)
      for (int a = 0; a < K; ++a) std::fill_n(bits[d][a], nw, uint64_t{0});
    int8_t side_of[kMaxTri];  // xp's side of triangle ids[i]'s plane; 2: not yet computed
    for (int e = 0; e < nsub; ++e)
      for (int i = sub[e].lo; i <= sub[e].hi; ++i) {
        const V& tlo = tri_lo_[sub[e].crack][ids[i]];
        const V& thi = tri_hi_[sub[e].crack][ids[i]];
        for (int d = 0; d < 3; ++d)
          for (int a = 0; a < K; ++a)
            bits[d][a][i >> 6] |=
                static_cast<uint64_t>(thi[d] >= std::min(xp[d], nc[d][a]) && tlo[d] <= std::max(xp[d], nc[d][a]))
                << (i & 63);
        side_of[i] = 2;
      }
    struct At {  // the triangle ids of the positions hit[]
      const int32_t* ids;
      const int32_t* hit;
      int32_t operator[](std::size_t i) const { return ids[hit[i]]; }
    };
    for (int j = 0; j < kLines; ++j) {
      if (!want(j)) continue;
      const int ax = j / (K * K), ay = (j / K) % K, az = j % K;
      const V xn(nc[0][ax], nc[1][ay], nc[2][az]);
      crack::FieldKeyBuilder b;
      bool overflow = false;
      for (int e = 0; e < nsub && !overflow; ++e) {
        int32_t hit[kMaxTri];  // positions in ids of the triangles meeting the line's box, in order
        int m = 0;
        const int lo = sub[e].lo, hi = sub[e].hi;
        for (int w = lo >> 6; lo <= hi && w <= hi >> 6; ++w) {
          uint64_t word = bits[0][ax][w] & bits[1][ay][w] & bits[2][az][w];
          if (w == lo >> 6) word &= ~uint64_t{0} << (lo & 63);            // from lo
          if (w == hi >> 6) word &= ~uint64_t{0} >> (63 - (hi & 63));     // to hi
          for (; word; word &= word - 1) hit[m++] = 64 * w + std::countr_zero(word);
        }
        if (m == 0) continue;
        const crack::ExplicitCrack<Dim>& c = cracks_[sub[e].crack];
        auto particle_side = [&](std::size_t i) {
          int8_t& sd = side_of[hit[i]];
          if (sd == 2) {
            const auto& T = c.simplices[static_cast<std::size_t>(ids[hit[i]])];
            sd = static_cast<int8_t>(crack::volume_sign(c.points[T[0]], c.points[T[1]], c.points[T[2]], xp));
          }
          return static_cast<int>(sd);
        };
        std::size_t t = 0;
        const crack::Side side = crack::triangle_list_crossing_with(
            c.points.data(), c.simplices.data(), At{ids, hit}, static_cast<std::size_t>(m), xp, xn, particle_side, &t,
            c.front_cut.dropper(c.points.data(), c.simplices.data()));
        overflow = side != crack::Side::None && !b.add(sub[e].crack, side, static_cast<int32_t>(t));
      }
      emit(j, overflow ? kOverflow : b.key(seg_of(j)));
    }
    return true;
  }

  // 3D: every pair of every near particle by classify_block3 on its stencil's nodes.
  // A particle keeps its stencil and keys from the last step while they are functions of the same
  // inputs: the same near list (collect_near_particles), crack geometry (crack_epoch_), position and
  // half-width, bit for bit (a crack at rest among particles at rest, before the load reaches it).
  void classify_pairs3(const std::size_t nn) {
    const bool keep = kept_epoch_ == crack_epoch_;
    kept_epoch_ = index_epoch_ == crack_epoch_ ? crack_epoch_ : ~uint64_t{0};  // (keys of a fresh index only)
    kept_x_.resize(nn);
    kept_hw_.resize(nn);
#pragma omp parallel for schedule(static) if (nn >= 512)
    for (std::size_t k = 0; k < nn; ++k) {
      const std::size_t p = static_cast<std::size_t>(near_[k]);
      const V xp = P_.x[p];
      const double hw = P_.half_width[p];
      if (keep && std::memcmp(&kept_x_[k], &xp, sizeof(V)) == 0 && std::memcmp(&kept_hw_[k], &hw, sizeof hw) == 0)
        continue;
      kept_x_[k] = xp, kept_hw_[k] = hw;
      St& s = near_st_[k];
      s.eval(G_, stride_, inv_h_, xp, hw);
      int64_t i0[3];
      int64_t r = s.base;
      for (int d = 0; d < 3; ++d) i0[d] = r / static_cast<int64_t>(stride_[d]), r %= static_cast<int64_t>(stride_[d]);
      double nc[3][St::K];
      for (int a = 0; a < St::K; ++a) {
        const V xa = node_position(i0[0] + a, i0[1] + a, i0[2] + a);
        for (int d = 0; d < 3; ++d) nc[d][a] = xa[d];
      }
      bool weighted[N];
      int j = 0;
      s.for_each_weight([&](int64_t, double w) { weighted[j++] = w != 0.0; });
      std::fill_n(&pair_key_[k * N], N, 0u);
      key_any_[k] = classify_block3<St::K>(
          cell_of(xp), xp, nc, [&](int q) { return weighted[q]; }, [&](int q) { return &pair_seg_[2 * (k * N + q)]; },
          [&](int q, uint32_t key) { pair_key_[k * N + q] = key; });
    }
  }

  Particles<Dim>& P_;
  std::vector<uint8_t> near_flag_;  // per particle: near a crack at the start of the step
  std::vector<int32_t> near_;       // the near particles, in particle order
  std::vector<int32_t> near_index_;  // per particle: index in near_, or -1
  std::vector<std::size_t> chunk_begin_;
  std::vector<St> near_st_;       // per near particle: its stencil at the start-of-step position
  std::vector<uint8_t> key_any_;  // per near particle: does a key differ from 0 (set by classify_pairs)
  std::vector<uint32_t> pair_key_;  // per pair (near particle k, stencil node j: k N + j): field key
  std::vector<int32_t> pair_seg_;   // per pair, two: the segment crossed for each code of the key
  // 3D, per near particle: position and half-width of its last classification, valid at kept_epoch_.
  std::vector<V> kept_x_;
  std::vector<double> kept_hw_;
  uint64_t kept_epoch_ = ~uint64_t{0};
};

}  // namespace cleave::crack_fields
