// The dynamic J vector and K_I, K_II, K_III at the nodes of the fronts of a 3D model (seed 000 §3),
// the 3D counterpart of crack_tip_eval.hpp, with the same steps at each front node:
// eq. 36: the particles around the node extrapolate W, K, stress, displacement gradient and
// displacement to the nodes, separately for each velocity field (a particle-node pair's field is the
// crack-crossing key of its connecting line); eq. 37: a contour point takes each node's value from
// the field a particle there would use; eqs. 38-39: midpoint rule over the circle in the plane normal
// to the front, with all three traction and displacement-gradient components (dropping the
// out-of-plane one loses K_III^2 / 2 mu: validation.md §4); eq. 33 adds the volume term over the
// particles inside the contour, per unit length of front (a slab of one cell along the front).
//
// Only what the contours need is extrapolated: the nodes of the cells of the contour points, of the
// opening probes and of the front node (and of eq. 33's particles), from the particles whose stencils
// reach them. A first pass over the front nodes lists those grid nodes; their sums are taken once,
// for all front nodes (crack_front_sums.hpp), and each front node takes its own rigid motion out of
// them. Front nodes run in parallel, every sum in a fixed particle order: the result does not depend
// on the thread count.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <span>
#include <stdexcept>
#include <vector>

#include "libmpm/core/parallel.hpp"
#include "libmpm/crack/crossing3d.hpp"
#include "libmpm/crack/front_along_term.hpp"
#include "libmpm/crack/front_parameters.hpp"
#include "libmpm/mpm/crack_front_domain.hpp"
#include "libmpm/mpm/crack_front_fit.hpp"
#include "libmpm/mpm/crack_front_kept.hpp"
#include "libmpm/mpm/crack_front_sums.hpp"
#include "libmpm/mpm/crack_tip_eval.hpp"  // kCodCells
#include "libmpm/mpm/model.hpp"
#include "libmpm/mpm/particle_strain.hpp"
#include "libmpm/mpm/stencil.hpp"

namespace cleave {

// accel(p): the acceleration of particle p in the last step (from the grid, with its own fields).
// near (optional): the particles near the fronts kept by the caller between evaluations, with its
// bound on how far particles have moved, and the buffers the evaluation reuses (FrontParticles);
// without it every particle is tested and the buffers are made afresh.
template <class SF, class Accel>
std::vector<crack::FrontRecord> evaluate_crack_fronts(const Model<3>& m, const crack::TipSettings& ts, Accel&& accel,
                                                      detail::FrontParticles* near = nullptr) {
  using V = Vec<3>;
  using St = Stencil<3, SF>;
  using Sums = detail::FrontFieldSums;
  const auto& P = m.particles;
  const StrainOf<3> strain(m);
  const auto& G = m.grid;
  const double h = G.h, inv_h = 1.0 / h;
  const auto stride = G.strides();
  const detail::NodeIndexing node_indexing(G);
  const auto node_ijk = [&](int64_t n) { return node_indexing.ijk(n); };
  const auto node_pos = [&](const std::array<int64_t, 3>& ijk) { return node_indexing.position(ijk); };
  const bool circle = ts.contour == crack::TipSettings::Contour::Circle;
  const double contour_extent = ts.radius * h * (circle ? 1.0 : std::sqrt(2.0));
  const double cod_distance = std::max(ts.radius, kCodCells) * h;
  const bool domain = ts.integral == crack::TipSettings::Integral::Domain;
  // Everything a front node's evaluation touches lies within this distance of it: the contour, its
  // cells' nodes and the particles reaching them (1 + 1.5 cells), and the domain integral's particles
  // (within radius + along), with a margin.
  const double reach = std::max({contour_extent, cod_distance, domain ? (ts.radius + ts.along) * h : 0.0}) + 4.5 * h;
  const bool rotations = !P.rotation3.empty();


  struct Job {
    int crack, front, node;
  };
  std::vector<Job> jobs;
  for (const auto& c : m.cracks)
    for (std::size_t f = 0; f < c.fronts.size(); ++f)
      if (c.tip[f])
        for (std::size_t k = 0; k < c.fronts[f].nodes.size(); ++k)
          jobs.push_back({c.id, static_cast<int>(f), static_cast<int>(k)});
  // The domain integral's fronts as polylines (one per front with jobs), and each job's.
  std::vector<detail::FrontPolyline> lines;
  std::vector<int> line_of(jobs.size(), -1);
  if (domain)
    for (std::size_t j = 0; j < jobs.size(); ++j) {
      if (j == 0 || jobs[j].crack != jobs[j - 1].crack || jobs[j].front != jobs[j - 1].front)
        lines.emplace_back(m.cracks[jobs[j].crack], static_cast<std::size_t>(jobs[j].front), m.symmetry_planes, h,
                           (ts.radius + ts.along + 2.0) * h);
      line_of[j] = static_cast<int>(lines.size()) - 1;
    }
  // The particles binned in the box of everything the front nodes' evaluations touch.
  detail::CellBins local_bins;
  const detail::CellBins& bins = [&]() -> const detail::CellBins& {
    V lo = V::Constant(INFINITY), hi = -lo;
    for (const Job& jb : jobs) {
      const V& x = m.cracks[jb.crack].points[m.cracks[jb.crack].fronts[jb.front].nodes[jb.node]];
      lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
    }
    const V margin = V::Constant(reach + 2.0 * h);
    if (jobs.empty()) return local_bins;
    if (near) return near->bins_for(G, P.x, lo - margin, hi + margin);
    local_bins.build(G, P.x, lo - margin, hi + margin);
    return local_bins;
  }();
  // Every particle-node line's field key, here and in the shared sums, from one binning of the triangles.
  std::array<int64_t, 3> tri_lo = bins.lo, tri_n = bins.n;  // the particles' box and two cells about it
  for (int d = 0; d < 3; ++d) {
    const int64_t cells = std::max(1, G.nodes[d] - 1);
    const int64_t a = std::max<int64_t>(0, bins.lo[d] - 2), b = std::min<int64_t>(cells - 1, bins.lo[d] + bins.n[d] + 1);
    tri_lo[d] = a, tri_n[d] = std::max<int64_t>(1, b - a + 1);
  }
  const detail::TriangleBins tris(m, tri_lo, tri_n);
  // The domain integral's tubes, one per polyline: each particle of a tube read once (FrontTube), with
  // its own rotation in its displacement gradient (each front node takes out its rigid rotation).
  std::vector<detail::FrontTube> tubes;
  tubes.reserve(lines.size());
  for (const auto& line : lines) {
    tubes.emplace_back(line, ts.radius * h, ts.inner * ts.radius * h);
    tubes.back().build(G, bins, P.x, [&](int32_t p) {
      detail::TubeInput in;
      const Sym<3> e = strain(p);
      in.volume = strained_volume<3>(P.volume0[p], e), in.mass = P.mass[p];
      in.W = m.materials[P.material[p]]->strain_energy_density(P.stress[p], e);
      in.stress = detail::full_tensor(P.stress[p]);
      in.grad_u = detail::displacement_gradient(e, rotations ? P.rotation3[p] : V::Zero());
      if (ts.volume_term) in.accel = accel(p);  // (eq. 33's inertia)
      return in;
    });
  }
  std::vector<crack::FrontRecord> out(jobs.size());
  std::vector<uint8_t> done(jobs.size(), 0);
  std::vector<std::string> failure(jobs.size());
  std::vector<V> e3_of(jobs.size(), V::Zero());  // each node's e3, and its material's mu and nu
  std::vector<double> mu_of(jobs.size(), 0.0), nu_of(jobs.size(), 0.0);

  // Two passes over the front nodes: the first only lists the grid nodes each one reads (need);
  // then eq. 36's sums at all of them, once (a front node's neighbours, half a cell away, read
  // mostly the same nodes); the second pass evaluates each front node from those sums.
  std::vector<std::vector<int64_t>> need_of(jobs.size());
  // What the first pass finds for each front node and the second uses.
  struct State {
    std::vector<crack::FrontContourPoint> contour;
    V up, down;            // the opening probes
    bool have_cod = false;  // (a crack point behind the node was found for them)
    std::vector<std::pair<int32_t, double>> inside;  // eq. 33's particles and their slab weights
    double slab_material = 0.0;  // the slab's share held by particles and their images
    std::vector<int64_t> fit_cells;  // the cells that can hold the rigid-motion fit's particles
  };
  std::vector<State> state(jobs.size());
  detail::NodeSums local_sums;
  detail::FitCells local_fits;
  detail::NodeSums& shared = near ? near->sums : local_sums;
  detail::FitCells& fits = near ? near->fits : local_fits;
  // The rigid motion's fit (as in 2D): the particles within a cell and a half of the contour's plane
  // and within `fit` of the front, in the cells within fit_reach of the node whose centres lie within
  // a cell and a half of the plane plus the cell's half-diagonal.
  const double fit = contour_extent + 1.5 * h;
  const double fit_reach = std::sqrt(fit * fit + 2.25 * h * h) * (1.0 + 1e-12);
  for (int pass = 0; pass < 2; ++pass) {
  if (pass == 1) {
    shared.build<SF>(m, bins, tris, need_of);
    std::vector<int64_t> cells;
    for (const State& S : state) cells.insert(cells.end(), S.fit_cells.begin(), S.fit_cells.end());
    fits.pack(P, bins, cells);
  }
#pragma omp parallel for schedule(dynamic, 1) if (jobs.size() > 1)
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    try {
    const Job job = jobs[j];
    detail::TriangleBins::Candidates cand;  // the crack triangles near a point, for its lines' keys
    const auto& c = m.cracks[job.crack];
    const crack::FrontFrame f = crack::front_frame(c, job.front, job.node);
    crack::FrontRecord& rec = out[j];
    rec.crack = job.crack, rec.front = job.front, rec.node = job.node;
    rec.x = f.x;
    rec.s = crack::front_arc_lengths(c, job.front)[job.node];
    if (!c.fronts[job.front].flags.empty()) rec.flag = c.fronts[job.front].flags[job.node];
    // g(cell, plane, distance) for each non-empty cell of the bins within distance d of the node and
    // with plane <= plane_max, in cell order: plane, the distance of its centre from the contour's
    // plane; distance, the node's from the cell.
    const auto for_cells_near = [&](double d, double plane_max, auto&& g) {
      const int r = static_cast<int>(std::ceil(d * inv_h));
      const auto [ci, cj, ck] = detail::CellBins::cell_of(G, f.x);
      // Per axis and cell offset: its part of the centre's distance from the plane and of the node's
      // squared distance from the cell. Their sums screen the cells (most of the cube lies off the
      // plane or out of reach) with a margin far above their rounding, so that only cells the exact
      // tests below reject are skipped.
      constexpr int kMaxR = 16;
      double along[3][2 * kMaxR + 1], off[3][2 * kMaxR + 1];
      const bool screen = r <= kMaxR;
      for (int k = 0; screen && k < 3; ++k)
        for (int o = -r; o <= r; ++o) {
          const double lo = G.origin[k] + h * static_cast<double>((k == 0 ? ci : k == 1 ? cj : ck) + o);
          along[k][o + r] = (lo + 0.5 * h - f.x[k]) * f.e3[k];
          const double gap = f.x[k] - std::clamp(f.x[k], lo, lo + h);
          off[k][o + r] = gap * gap;
        }
      const double plane_screen = plane_max * (1.0 + 1e-9) + 1e-9 * h, d2_screen = d * d * (1.0 + 1e-9) + 1e-18 * h * h;
      for (int64_t a = ci - r; a <= ci + r; ++a)
        for (int64_t b = cj - r; b <= cj + r; ++b)
          for (int64_t e = ck - r; e <= ck + r; ++e) {
            if (screen) {
              const int ia = static_cast<int>(a - ci + r), ib = static_cast<int>(b - cj + r), ie = static_cast<int>(e - ck + r);
              if (std::fabs(along[0][ia] + along[1][ib] + along[2][ie]) > plane_screen ||
                  off[0][ia] + off[1][ib] + off[2][ie] > d2_screen)
                continue;
            }
            const int64_t cell = bins.index(a, b, e);
            if (cell < 0 || bins.begin[cell] == bins.begin[cell + 1]) continue;
            const V corner = G.origin + h * V(a, b, e);
            const double plane = std::fabs((corner + V::Constant(0.5 * h) - f.x).dot(f.e3));
            if (plane > plane_max) continue;
            const double distance = (f.x - f.x.cwiseMax(corner).cwiseMin(corner + V::Constant(h))).norm();
            if (distance > d) continue;
            g(cell, plane, distance);
          }
    };

    if (pass == 0) {
    State& S = state[j];
    // Among the node's own crack's triangles ids: the squared distance of the one nearest to x (the
    // first in the list of those as near), its point nearest to x into q and its normal (if any).
    const auto &tlo = tris.box_lo(c.id), &thi = tris.box_hi(c.id);
    const auto nearest_among = [&](const auto& ids, const V& x, V& q, V& normal) {
      double best = INFINITY;
      for (const int32_t id : ids) {
        // No point of a triangle whose box is farther than the best so far can be nearer.
        if ((x - x.cwiseMax(tlo[id]).cwiseMin(thi[id])).squaredNorm() >= best) continue;
        const auto& T = c.simplices[id];
        const V a = c.points[T[0]], b = c.points[T[1]], cc = c.points[T[2]];
        V nrm = (b - a).cross(cc - a);
        if (!(nrm.squaredNorm() > 0.0)) continue;
        nrm.normalize();
        // Closest point of the triangle: the projection if it falls inside, else the nearest edge point.
        V p = x - (x - a).dot(nrm) * nrm;
        const auto inside_edge = [&](const V& e0, const V& e1) { return (e1 - e0).cross(p - e0).dot(nrm) >= 0.0; };
        if (!(inside_edge(a, b) && inside_edge(b, cc) && inside_edge(cc, a))) {
          V bestp = a;
          double bd = INFINITY;
          for (const auto& [e0, e1] : {std::pair<V, V>{a, b}, {b, cc}, {cc, a}}) {
            const double s = std::clamp((x - e0).dot(e1 - e0) / (e1 - e0).squaredNorm(), 0.0, 1.0);
            const V y = e0 + s * (e1 - e0);
            if ((y - x).squaredNorm() < bd) bd = (y - x).squaredNorm(), bestp = y;
          }
          p = bestp;
        }
        const double d = (p - x).squaredNorm();
        if (d < best) best = d, q = p, normal = nrm;
      }
      return best;
    };
    // The crack's surface point nearest to x among its triangles within reach of the node (their
    // boxes meet the box about it), and the normal of its triangle. x is a copy: a caller passes q as
    // x (as a reference, q's first update moved x, and the search went on about the first triangle's
    // point). The nearest of the triangles binned in x's cell bounds the distance d; every triangle
    // as near has its box within d of x, so those binned about x within d give the same answer as all
    // those within reach (the first of the nearest in triangle order), while d leaves them in reach.
    const auto own = [&](const detail::TriangleBins::Candidates& k) {
      return std::span<const int32_t>(k.ids.data() + k.begin[c.id], k.ids.data() + k.begin[c.id + 1]);
    };
    const auto nearest_on_crack = [&](const V x, V& q, V& normal) {
      tris.gather_cell(detail::CellBins::cell_of(G, x), cand);
      V q0, n0;
      const double bound = std::sqrt(nearest_among(own(cand), x, q0, n0)) * (1.0 + 1e-9) + 1e-12 * h;
      const V lo = x - V::Constant(bound), hi = x + V::Constant(bound);
      if (bound <= reach - cod_distance - h && tris.covers(lo, hi)) {
        tris.gather(lo, hi, cand);
        return nearest_among(own(cand), x, q, normal) < INFINITY;
      }
      std::vector<int32_t> local;
      for (std::size_t t = 0; t < c.simplices.size(); ++t)
        if (((thi[t] - f.x).array() >= -reach).all() && ((tlo[t] - f.x).array() <= reach).all())
          local.push_back(static_cast<int32_t>(t));
      return nearest_among(local, x, q, normal) < INFINITY;
    };

    // The contour starts where the circle meets the crack (seed 000 step 1).
    double theta0 = -M_PI;
    {
      V q, nrm;
      if (nearest_on_crack(f.x - ts.radius * h * f.e1, q, nrm)) {
        const V d = q - f.x;
        if (d.norm() > 0.1 * h) theta0 = std::atan2(d.dot(f.e2), d.dot(f.e1));
      }
    }
    S.contour = crack::front_contour_points(f, ts, h, theta0);
    // Opening probes: each face's field just off the crack, cod_distance behind the node.
    V cod_point = f.x - cod_distance * f.e1, cod_normal = f.e2;
    S.have_cod = nearest_on_crack(cod_point, cod_point, cod_normal);
    const double probe = 1e-3 * h;
    S.up = cod_point + probe * cod_normal, S.down = cod_point - probe * cod_normal;

    // The nodes whose sums the contour needs: those of the cells of its points, of the probes and
    // of the front node (sorted, unique).
    std::vector<int64_t> need;
    const auto add_cell_nodes = [&](const V& x) {
      std::array<int64_t, 3> i;
      for (int d = 0; d < 3; ++d) {
        i[d] = static_cast<int64_t>(std::floor((x[d] - G.origin[d]) * inv_h));
        if (i[d] < 0 || i[d] + 1 >= G.nodes[d]) return;
      }
      for (int k = 0; k < 8; ++k)
        need.push_back((i[0] + (k & 1)) * int64_t(stride[0]) + (i[1] + ((k >> 1) & 1)) * int64_t(stride[1]) +
                       (i[2] + ((k >> 2) & 1)));
    };
    for (const auto& cp : S.contour) add_cell_nodes(cp.x);
    add_cell_nodes(S.up), add_cell_nodes(S.down), add_cell_nodes(f.x);

    // The particles inside the contour, projected on its plane, within a slab of one cell along the
    // front (each weighted by the part of its extent in the slab, per unit length): eq. 33's volume
    // and the out-of-plane term's area. Symmetry planes normal to the front within the slab (a node
    // on one, or a slab one cell thick between two) mirror the material: its images count too (the
    // integrands are even in the distance to the plane).
    std::vector<double> mirrors;  // the planes' positions along e3 from the node
    for (const auto& [axis, position] : m.symmetry_planes) {
      const double z0 = (position - f.x[axis]) / f.e3[axis];
      if (std::fabs(f.e3[axis]) > 0.999 && std::fabs(z0) <= h) mirrors.push_back(z0);
    }
    // One walk over the cells about the node for eq. 33's particles and the fit's cells.
    // A particle of the slab lies within `bound` of the node: inside the contour's extent in the
    // plane, and within a cell of it along the front (three with a mirror plane).
    const bool slab_particles = ts.volume_term || ts.out_of_plane_term;
    const double s3max = mirrors.empty() ? h : 3.0 * h;
    const double bound = std::sqrt(contour_extent * contour_extent + s3max * s3max) + 1e-9 * h;
    // A particle of the slab lies within a cell of the contour's plane (half the slab, plus half a
    // particle), and its cell's centre within half the cell's extent along e3 of it: a cell whose
    // centre lies farther holds none, unless a mirror plane is near. (That half extent is
    // h/2 (|e3x| + |e3y| + |e3z|): the cell's half-diagonal only for e3 along a diagonal.)
    const double slab_cells = mirrors.empty() ? h * (1.0 + 0.5 * f.e3.lpNorm<1>()) + 1e-9 * h : INFINITY;
    double last_volume = -1.0, l = 0.0;  // (cbrt of the last particle's volume: most particles share it)
    const double fit_plane = 2.37 * h;
    const double plane_max = slab_particles ? std::max(fit_plane, slab_cells) : fit_plane;
    for_cells_near(std::max(slab_particles ? bound : 0.0, fit_reach), plane_max, [&](int64_t cell, double plane, double distance) {
      if (distance <= fit_reach && plane <= fit_plane) S.fit_cells.push_back(cell);
      if (!slab_particles || distance > bound || plane > slab_cells) return;
      for (int64_t q = bins.begin[cell]; q < bins.begin[cell + 1]; ++q) {
        const int32_t p = bins.particle[q];
        const double s3 = (P.x[p] - f.x).dot(f.e3);
        if (mirrors.empty() && std::fabs(s3) >= h) continue;  // (particles are at most a cell wide)
        if (!crack::inside_front_contour(f, ts, h, P.x[p])) continue;
        if (P.volume0[p] != last_volume) last_volume = P.volume0[p], l = std::cbrt(last_volume);
        const auto in_slab = [&](double c) {
          return std::max(0.0, std::min(c + 0.5 * l, 0.5 * h) - std::max(c - 0.5 * l, -0.5 * h));
        };
        double in = in_slab(s3);
        for (const double z0 : mirrors) in += in_slab(2.0 * z0 - s3);
        if (in <= 0.0) continue;
        S.inside.push_back({p, in / (l * h)});
        S.slab_material += P.volume0[p] * in / l;
        if (!ts.volume_term) continue;
        St st;
        st.eval(G, stride, inv_h, P.x[p], P.half_width[p]);
        st.for_each_weight([&](int64_t n, double) { need.push_back(n); });
      }
    });
    const std::span<const int64_t> lists[] = {need};
    std::vector<uint64_t> bits;
    detail::sorted_union(lists, need_of[j], bits);
    continue;
    }
    const State& S = state[j];
    const std::vector<int64_t>& need = need_of[j];
    const auto& contour = S.contour;
    const auto& inside = S.inside;
    const V &up = S.up, &down = S.down;
    // need_index(n): n's position in `need` (sorted), or -1. (A few hundred lookups per front node:
    // a dense table over the box of nodes about it cost more to clear than they do.)
    const auto need_index = [&](int64_t n) {
      const auto it = std::lower_bound(need.begin(), need.end(), n);
      return it != need.end() && *it == n ? static_cast<int>(it - need.begin()) : -1;
    };

    // The rigid motion of the material about the node (FitCells), and the particle nearest the node
    // (its material gives mu, nu).
    const detail::FitCells::Motion motion = fits.fit(S.fit_cells, f.x, f.e3, 1.5 * h, fit);
    const V theta = motion.theta, omega = motion.omega;
    int32_t nearest = motion.nearest;
    if (nearest < 0) {  // (no particle in those cells: the nearest within reach)
      double nearest_d = INFINITY;
      for_cells_near(reach, INFINITY, [&](int64_t cell, double, double) {
        for (int64_t q = bins.begin[cell]; q < bins.begin[cell + 1]; ++q) {
          const int32_t p = bins.particle[q];
          if (const double d = (P.x[p] - f.x).norm(); d < nearest_d) nearest_d = d, nearest = p;
        }
      });
    }
    const auto v_rel = [&](int32_t p) { V v = P.v[p] - omega.cross(P.x[p] - f.x); return v; };
    const auto grad_u = [&](int32_t p) {
      return detail::displacement_gradient(strain(p), rotations ? V(P.rotation3[p] - theta) : V(-theta));
    };

    // Eq. 36 at the needed nodes: per node, its fields' sums (at most a few), from the shared raw
    // sums with this node's rigid motion taken out: grad u - [theta]x, v - omega x (x - x_f).
    // (Node i's fields: sums[first[i]] .. sums[first[i + 1] - 1].)
    std::vector<Sums> sums;
    sums.reserve(need.size() + 16);
    std::vector<int32_t> first(need.size() + 1, 0);
    const Mat<3> W_theta = detail::displacement_gradient(Sym<3>::Zero(), theta);
    for (std::size_t i = 0; i < need.size(); ++i) {
      first[i] = static_cast<int32_t>(sums.size());
      for (const detail::RawSums& r : shared.at(need[i])) {
        Sums t;
        t.key = r.key, t.m = r.m, t.energy = r.energy, t.stress = r.stress, t.u = r.u;
        t.grad_u = r.grad_u - r.m * W_theta;
        t.v = r.mv - omega.cross(r.mx - r.m * f.x);
        t.rho = r.rho;
        t.rho_v = r.rho_v - omega.cross(r.rho_x - r.rho * f.x);
        // sum rho |v - omega x (x - x_f)|^2 from the moments of x about the origin.
        const V rxv = r.rho_xv - f.x.cross(r.rho_v);
        const Mat<3> rr = r.rho_xx - r.rho_x * f.x.transpose() - f.x * r.rho_x.transpose() + r.rho * f.x * f.x.transpose();
        t.rho_vv = r.rho_vv - 2.0 * omega.dot(rxv) + omega.squaredNorm() * rr.trace() - omega.dot(rr * omega);
        sums.push_back(t);
      }
    }
    first[need.size()] = static_cast<int32_t>(sums.size());
    const auto fields_at = [&](int i) { return std::span<const Sums>(sums.data() + first[i], sums.data() + first[i + 1]); };
    if (nearest < 0) continue;  // no material at this front node (done stays 0: no row)
    const auto field = [&](int64_t n, uint32_t key) -> const Sums* {
      const int i = need_index(n);
      if (i < 0) return nullptr;
      for (const Sums& s : fields_at(i))
        if (s.key == key && s.m > 0.0) return &s;
      return nullptr;
    };
    const auto for_cell_nodes = [&](const V& x, auto&& g) {
      std::array<int64_t, 3> i;
      double r[3];
      for (int d = 0; d < 3; ++d) {
        const double fx = (x[d] - G.origin[d]) * inv_h;
        i[d] = static_cast<int64_t>(std::floor(fx));
        if (i[d] < 0 || i[d] + 1 >= G.nodes[d]) return false;
        r[d] = fx - i[d];
      }
      for (int k = 0; k < 8; ++k) {
        const int a = k & 1, b = (k >> 1) & 1, e = (k >> 2) & 1;
        const double w = (a ? r[0] : 1 - r[0]) * (b ? r[1] : 1 - r[1]) * (e ? r[2] : 1 - r[2]);
        g((i[0] + a) * int64_t(stride[0]) + (i[1] + b) * int64_t(stride[1]) + (i[2] + e), w);
      }
      return true;
    };

    // The front node's velocity: the centre-of-mass velocity of all fields at its cell's nodes.
    V v_tip = V::Zero();
    {
      double wsum = 0.0;
      for_cell_nodes(f.x, [&](int64_t n, double w) {
        const int i = need_index(n);
        if (i < 0 || w == 0.0) return;
        double mn = 0.0;
        V pn = V::Zero();
        for (const Sums& s : fields_at(i)) mn += s.m, pn += s.v;
        if (!(mn > 0.0)) return;
        v_tip += w * pn / mn, wsum += w;
      });
      if (wsum > 0.0) v_tip /= wsum;
    }

    // Eq. 37 at x: energy (W + K relative to the front node), stress, gradient, displacement.
    struct Point {
      double energy = 0.0;
      Mat<3> stress = Mat<3>::Zero(), grad_u = Mat<3>::Zero();
      V u = V::Zero();
    };
    const auto interpolate = [&](const V& x, Point& q) {
      q = Point{};
      double wsum = 0.0;
      std::array<int64_t, 3> cell;
      for (int d = 0; d < 3; ++d) cell[d] = static_cast<int64_t>(std::floor((x[d] - G.origin[d]) * inv_h));
      tris.gather_cell(cell, cand);  // (x's lines to its cell's corners)
      tris.mask_lines<2>(x, cell, cand);
      const bool in_grid = for_cell_nodes(x, [&](int64_t n, double w) {
        if (w == 0.0) return;
        const auto ijk = node_ijk(n);
        const Sums* s = field(n, tris.key(x, node_pos(ijk), cand, ijk[0] - cell[0], ijk[1] - cell[1], ijk[2] - cell[2]));
        if (!s) return;
        const double k = w / s->m;
        const double kinetic = 0.5 * (s->rho_vv - 2.0 * v_tip.dot(s->rho_v) + s->rho * v_tip.squaredNorm());
        q.energy += k * (s->energy + kinetic), q.stress += k * s->stress, q.grad_u += k * s->grad_u, q.u += k * s->u;
        wsum += w;
      });
      if (!in_grid || !(wsum > 0.0)) return false;
      q.energy /= wsum, q.stress /= wsum, q.grad_u /= wsum, q.u /= wsum;
      return true;
    };

    // Eqs. 38-39 in global axes: J = sum [(W + K) n - (grad u)^T (sigma n)] dGamma.
    V J = V::Zero();
    for (const auto& cp : contour) {
      Point q;
      if (!interpolate(cp.x, q)) {
        if (!domain) rec.flag |= crack::kFlagContourOutside;  // (the domain integral checks its own tube)
        continue;
      }
      J += cp.length * (q.energy * cp.n - q.grad_u.transpose() * (q.stress * cp.n));
    }
    // Eq. 33's volume term: sum over the slab's particles of (m_p / slab) [(grad u)^T a - (grad v)^T v].
    for (const auto& [p, weight] : inside) {
      if (!ts.volume_term) break;  // (the list serves the out-of-plane term too)
      St st;
      st.eval(G, stride, inv_h, P.x[p], P.half_width[p]);
      const auto base = node_ijk(st.base);
      tris.gather_stencil<St::K>(base, node_pos(base), P.x[p], cand);
      tris.mask_lines<St::K>(P.x[p], base, cand);
      Mat<3> gv = Mat<3>::Zero();
      st.for_each([&](int64_t n, double, const V& g) {
        const auto ijk = node_ijk(n);
        const Sums* s = field(n, tris.key(P.x[p], node_pos(ijk), cand, ijk[0] - base[0], ijk[1] - base[1], ijk[2] - base[2]));
        if (s) gv += (s->v / s->m) * g.transpose();
      });
      J += P.mass[p] * weight * (grad_u(p).transpose() * accel(p) - gv.transpose() * (v_rel(p) - v_tip));
    }
    rec.J1 = J.dot(f.e1);
    rec.J2 = J.dot(f.e2);
    // The out-of-plane term of the 3D J: J at the front = J on the contour - int_A d(sigma_i3 u_i,k)
    // /dx3 dA (x3 along the front; what the plane contour's divergence leaves of the 3D field). To
    // first order in the front's curvature kappa (e1 turning towards e3 at the rate kappa), in the
    // frame that turns with the front, sigma_i3 u_i,k = q^_k + kappa x3 sigma_i1 u_i,k. The second
    // part gives kappa int_A sigma_i1 u_i,k dA, an area integral in the contour's plane. The first,
    // the change of q^_k along the front, is taken for k = 1 after every node is done, from the
    // near-tip fields' int_A q^_1 dA ~ K_II K_III at the nodes (front_along_term.hpp), not from the
    // particles: a derivative along the front across one slab's particles, or between the nodes'
    // int_A q^_k, reads the particle lattice rather than the field (docs/validation.md). For J2
    // (k = 2) it is left out.
    if (ts.out_of_plane_term && !domain) {
      const double kappa = front_curvature(c.fronts[job.front], c.points, job.node);
      double q1 = 0.0, q2 = 0.0;
      for (const auto& [p, weight] : inside) {
        // t1 . (grad u e_k) = (grad u^T t1) . e_k, on scalars (as Eigen products GCC left these out of
        // line here, a call per particle and node: 4 % of an evaluation).
        const V t1 = sym_dot<3>(P.stress[p], f.e1);
        const Mat<3> gu = grad_u(p);
        double g1 = 0.0, g2 = 0.0;
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) g1 += t1[i] * gu(i, j) * f.e1[j], g2 += t1[i] * gu(i, j) * f.e2[j];
        q1 += P.volume0[p] * weight * g1, q2 += P.volume0[p] * weight * g2;
      }
      // The slab should be full of material (the contour's area times one cell): a free surface
      // across it leaves part of the area out.
      const double area = circle ? M_PI * ts.radius * ts.radius * h * h : 4.0 * ts.radius * ts.radius * h * h;
      if (S.slab_material < 0.9 * area * h) rec.flag |= crack::kFlagContourOutside;
      rec.J1 -= kappa * q1, rec.J2 -= kappa * q2;
    }
    // J1 by the domain integral (crack_front_domain.hpp) from the particles of the front's tube.
    if (domain) {
      const auto r = tubes[line_of[j]].read(static_cast<std::size_t>(job.node), ts.along * h, theta);
      rec.J1 = r.J1;
      if (r.material < 0.9) rec.flag |= crack::kFlagContourOutside;  // (a free surface across the tube)
    }

    Point a, b;
    if (S.have_cod && interpolate(up, a) && interpolate(down, b)) {
      const V d = a.u - b.u;
      rec.cod_I = d.dot(f.e2), rec.cod_II = d.dot(f.e1), rec.cod_III = d.dot(f.e3);
    } else {
      rec.flag |= crack::kFlagNoOpening;
    }
    double mu = 0.0, nu = 0.0;
    if (!m.materials[P.material[nearest]]->isotropic_elastic(mu, nu))
      throw std::runtime_error("crack '" + c.name + "': K from J needs an isotropic elastic material at its fronts");
    const auto k = crack::stress_intensity3(rec.J1, rec.cod_I, rec.cod_II, rec.cod_III, mu, nu);
    rec.KI = k.KI, rec.KII = k.KII, rec.KIII = k.KIII;
    e3_of[j] = f.e3, mu_of[j] = mu, nu_of[j] = nu;
    done[j] = 1;
    } catch (const std::exception& e) {
      failure[j] = e.what();
    }
  }
  }
  for (const auto& e : failure)
    if (!e.empty()) throw std::runtime_error(e);
  // The out-of-plane term's along-front part, from the K of each front's nodes (front_along_term.hpp).
  if (ts.out_of_plane_term && !domain) {
    const double L = crack::along_front_length(ts, h);
    for (std::size_t a = 0; a < jobs.size();) {
      std::size_t b = a;  // jobs a .. b - 1: one front's nodes, in node order
      while (b < jobs.size() && jobs[b].crack == jobs[a].crack && jobs[b].front == jobs[a].front) ++b;
      std::vector<crack::AlongFrontNode> nodes;
      std::vector<std::size_t> at;
      for (std::size_t j = a; j < b; ++j) {
        if (!done[j]) continue;
        const crack::FrontRecord& r = out[j];
        nodes.push_back({r.x, e3_of[j], r.s, r.J1, r.cod_I, r.cod_II, r.cod_III, mu_of[j], nu_of[j], r.flag == 0});
        at.push_back(j);
      }
      const auto& c = m.cracks[jobs[a].crack];
      const auto& front = c.fronts[jobs[a].front];
      const auto s = crack::front_arc_lengths(c, jobs[a].front);
      const double length =
          s.empty() ? 0.0 : s.back() + (c.points[front.nodes.back()] - c.points[front.nodes.front()]).norm();
      const auto res = crack::subtract_along_front_term(nodes, front.closed, length, L, ts.radius * h);
      for (std::size_t i = 0; i < at.size(); ++i) {
        if (!res[i].applied) continue;
        crack::FrontRecord& r = out[at[i]];
        r.J1 = res[i].J1, r.KI = res[i].KI, r.KII = res[i].KII, r.KIII = res[i].KIII;
      }
      a = b;
    }
  }
  std::vector<crack::FrontRecord> kept;
  for (std::size_t j = 0; j < jobs.size(); ++j)
    if (done[j]) kept.push_back(out[j]);
  return kept;
}

// The evaluation compiled once per shape-function style in crack_front_eval.cpp (the stepper's
// translation unit stays the hot loops' alone); accel as above.
using FrontAcceleration = std::function<Vec<3>(std::size_t)>;
template <class SF>
std::vector<crack::FrontRecord> crack_front_records(const Model<3>& m, const crack::TipSettings& ts,
                                                    const FrontAcceleration& accel,
                                                    detail::FrontParticles* near = nullptr);
extern template std::vector<crack::FrontRecord> crack_front_records<LinearShape>(const Model<3>&, const crack::TipSettings&,
                                                                                 const FrontAcceleration&,
                                                                                 detail::FrontParticles*);
extern template std::vector<crack::FrontRecord> crack_front_records<UGimpShape>(const Model<3>&, const crack::TipSettings&,
                                                                                const FrontAcceleration&,
                                                                                detail::FrontParticles*);

}  // namespace cleave
