// The rigid motion of the material about a crack-front node (crack_front_eval.hpp): the mass-weighted
// mean rotation and the least-squares spin of the particles in a cylinder about the node (its axis
// along the front). Neighbouring front nodes, half a cell apart, fit over mostly the same particles,
// a thousand or so each: the particles of the cells the fits read are copied once per evaluation into
// arrays by cell (structure of arrays, each cell's run padded to whole lanes with massless entries),
// so that each fit runs over contiguous lanes that vectorise. Each lane sums its own entries in cell
// order and the lanes are added in order: the result does not depend on the thread count.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "libmpm/mpm/crack_front_sums.hpp"  // CellBins
#include "libmpm/mpm/particles.hpp"

namespace cleave::detail {

class FitCells {
 public:
  static constexpr int kLanes = 8;

  // Copies the particles of the bins' cells `cells` (any order, repeats allowed); fit reads only these.
  // An object kept from one evaluation to the next (FrontParticles::fits) reuses its arrays: each
  // entry that fit reads is written here, so they are grown, never cleared.
  void pack(const Particles<3>& P, const CellBins& bins, const std::vector<int64_t>& listed) {
    mark_.assign(bins.begin.size(), 0);
    for (const int64_t c : listed) mark_[c] = 1;
    cells_.clear();  // in cell order
    for (std::size_t c = 0; c < mark_.size(); ++c)
      if (mark_[c]) cells_.push_back(static_cast<int64_t>(c));
    start_.assign(bins.begin.size(), 0), end_.assign(bins.begin.size(), 0);
    at_.assign(cells_.size() + 1, 0);
    for (std::size_t k = 0; k < cells_.size(); ++k) {
      const int64_t count = bins.begin[cells_[k] + 1] - bins.begin[cells_[k]];
      at_[k + 1] = at_[k] + (count + kLanes - 1) / kLanes * kLanes;
      start_[cells_[k]] = at_[k], end_[cells_[k]] = at_[k + 1];
    }
    const std::size_t total = static_cast<std::size_t>(at_.back());
    for (auto* a : {&x_, &y_, &z_, &m_, &vx_, &vy_, &vz_, &tx_, &ty_, &tz_})
      if (a->size() < total) a->resize(total);
    if (id_.size() < total) id_.resize(total);
    const bool rotations = !P.rotation3.empty();
#pragma omp parallel for schedule(static) if (total > 4096)
    for (std::size_t k = 0; k < cells_.size(); ++k) {
      std::size_t e = static_cast<std::size_t>(at_[k]);
      for (int64_t q = bins.begin[cells_[k]]; q < bins.begin[cells_[k] + 1]; ++q, ++e) {
        const int32_t p = bins.particle[q];
        id_[e] = p;
        x_[e] = P.x[p].x(), y_[e] = P.x[p].y(), z_[e] = P.x[p].z(), m_[e] = P.mass[p];
        vx_[e] = P.v[p].x(), vy_[e] = P.v[p].y(), vz_[e] = P.v[p].z();
        if (rotations) tx_[e] = P.rotation3[p].x(), ty_[e] = P.rotation3[p].y(), tz_[e] = P.rotation3[p].z();
        else tx_[e] = ty_[e] = tz_[e] = 0.0;
      }
      // Padding: m = 0, which the fit may take in but adds nothing (every value finite), and id -1.
      for (; e < static_cast<std::size_t>(at_[k + 1]); ++e) {
        id_[e] = -1;
        x_[e] = y_[e] = z_[e] = m_[e] = vx_[e] = vy_[e] = vz_[e] = tx_[e] = ty_[e] = tz_[e] = 0.0;
      }
    }
  }

  struct Motion {
    Vec<3> theta = Vec<3>::Zero(), omega = Vec<3>::Zero();
    int32_t nearest = -1;  // the particle of `cells` nearest to x (-1: none)
  };
  // The fit over the particles of `cells` (packed) within half_height of the plane through x normal to
  // e3 and within radius of the axis: theta the mean rotation, omega the spin that best explains
  // their velocities about their mass centre (zero when they do not determine it). Of particles
  // equally near x, `nearest` is the one packed first.
  Motion fit(const std::vector<int64_t>& cells, const Vec<3>& x, const Vec<3>& e3, double half_height,
             double radius) const {
    // Per lane: m, m r (3), m v (3), m r x v (3), m r r^T (6: xx yy zz xy yz zx), m theta (3), r = x_p - x.
    constexpr int kSums = 19;
    alignas(64) double acc[kSums][kLanes] = {};
    alignas(64) double best[kLanes];
    alignas(64) int64_t best_at[kLanes];
    std::fill(best, best + kLanes, INFINITY), std::fill(best_at, best_at + kLanes, int64_t(-1));
    const double ex = e3.x(), ey = e3.y(), ez = e3.z(), ox = x.x(), oy = x.y(), oz = x.z(), radius2 = radius * radius;
    const double *X = x_.data(), *Y = y_.data(), *Z = z_.data(), *M = m_.data();
    const double *VX = vx_.data(), *VY = vy_.data(), *VZ = vz_.data(), *TX = tx_.data(), *TY = ty_.data(), *TZ = tz_.data();
    const int32_t* id = id_.data();
    for (const int64_t cell : cells) {
      for (int64_t b = start_[cell]; b < end_[cell]; b += kLanes) {
#pragma omp simd
        for (int l = 0; l < kLanes; ++l) {
          const int64_t e = b + l;
          const double rx = X[e] - ox, ry = Y[e] - oy, rz = Z[e] - oz;
          const double a = rx * ex + ry * ey + rz * ez;
          const double px = rx - a * ex, py = ry - a * ey, pz = rz - a * ez;
          const bool in = (std::fabs(a) <= half_height) & (px * px + py * py + pz * pz <= radius2);
          const double d2 = id[e] >= 0 ? rx * rx + ry * ry + rz * rz : INFINITY;
          best_at[l] = d2 < best[l] ? e : best_at[l];
          best[l] = std::min(best[l], d2);
          const double m = in ? M[e] : 0.0;
          const double vx = VX[e], vy = VY[e], vz = VZ[e];
          acc[0][l] += m;
          acc[1][l] += m * rx, acc[2][l] += m * ry, acc[3][l] += m * rz;
          acc[4][l] += m * vx, acc[5][l] += m * vy, acc[6][l] += m * vz;
          acc[7][l] += m * (ry * vz - rz * vy), acc[8][l] += m * (rz * vx - rx * vz), acc[9][l] += m * (rx * vy - ry * vx);
          acc[10][l] += m * rx * rx, acc[11][l] += m * ry * ry, acc[12][l] += m * rz * rz;
          acc[13][l] += m * rx * ry, acc[14][l] += m * ry * rz, acc[15][l] += m * rz * rx;
          acc[16][l] += m * TX[e], acc[17][l] += m * TY[e], acc[18][l] += m * TZ[e];
        }
      }
    }
    double sum[kSums];
    for (int k = 0; k < kSums; ++k) {
      sum[k] = 0.0;
      for (int l = 0; l < kLanes; ++l) sum[k] += acc[k][l];
    }
    Motion out;
    int lane = -1;
    for (int l = 0; l < kLanes; ++l)
      if (best_at[l] >= 0 && (lane < 0 || best[l] < best[lane] || (best[l] == best[lane] && best_at[l] < best_at[lane])))
        lane = l;
    if (lane >= 0) out.nearest = id_[static_cast<std::size_t>(best_at[lane])];
    const double msum = sum[0];
    if (!(msum > 0.0)) return out;
    out.theta = Vec<3>(sum[16], sum[17], sum[18]) / msum;
    // About the mass centre c (from x): sum m (r - c)(r - c)^T = sum m r r^T - M c c^T, and
    // sum m (r - c) x (v - v_mean) = sum m r x v - c x sum m v (the fit's particles lie within a few
    // cells of x, so little is lost to cancellation).
    const Vec<3> c = Vec<3>(sum[1], sum[2], sum[3]) / msum, mv(sum[4], sum[5], sum[6]);
    Mat<3> rr;
    rr << sum[10], sum[13], sum[15], sum[13], sum[11], sum[14], sum[15], sum[14], sum[12];
    rr -= msum * c * c.transpose();
    const Mat<3> inertia = rr.trace() * Mat<3>::Identity() - rr;
    const Vec<3> moment = Vec<3>(sum[7], sum[8], sum[9]) - c.cross(mv);
    if (inertia.determinant() > 0.0) out.omega = inertia.ldlt().solve(moment);
    return out;
  }

 private:
  std::vector<int64_t> start_, end_;  // per bins cell: its run of entries (empty when not packed)
  std::vector<uint8_t> mark_;          // (pack's buffers: the cells listed, in cell order, and their runs)
  std::vector<int64_t> cells_, at_;
  std::vector<double> x_, y_, z_, m_, vx_, vy_, vz_, tx_, ty_, tz_;
  std::vector<int32_t> id_;  // the particle (-1: padding)
};

}  // namespace cleave::detail
