#include "libmpm/pd/bonds.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "libmpm/core/parallel.hpp"

namespace cleave::pd {

namespace {

// Uniform cell grid over the bounding box of the points; cell edge h >= the search radius.
template <int Dim> struct CellGrid {
  Vec<Dim> lo;
  double inv_h = 0.0;
  std::array<int64_t, Dim> n{};
  std::vector<int64_t> start;  // points of cell c are idx[start[c] .. start[c+1]), increasing index
  std::vector<int32_t> idx;

  std::array<int64_t, Dim> cell_of(const Vec<Dim>& p) const {
    std::array<int64_t, Dim> c{};
    for (int d = 0; d < Dim; ++d)
      c[d] = std::clamp<int64_t>(static_cast<int64_t>(std::floor((p[d] - lo[d]) * inv_h)), 0, n[d] - 1);
    return c;
  }
  int64_t flat(const std::array<int64_t, Dim>& c) const {
    int64_t f = 0;
    for (int d = Dim - 1; d >= 0; --d) f = f * n[d] + c[d];
    return f;
  }
};

template <int Dim> CellGrid<Dim> make_grid(const std::vector<Vec<Dim>>& x, double h) {
  CellGrid<Dim> g;
  Vec<Dim> lo = x.front(), hi = x.front();
  for (const auto& p : x) {
    if (!p.allFinite()) throw std::invalid_argument("build_bonds: non-finite point coordinate");
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  g.lo = lo;
  g.inv_h = 1.0 / h;
  const double max_cells = std::max(8.0 * static_cast<double>(x.size()), double(1 << 20));
  double total = 1.0;
  for (int d = 0; d < Dim; ++d) {
    const double nd = std::floor((hi[d] - lo[d]) / h) + 1.0;
    total *= nd;
    if (total > max_cells)
      throw std::invalid_argument("build_bonds: points too sparse for the horizon (too many cells)");
    g.n[d] = static_cast<int64_t>(nd);
  }
  const auto ncell = static_cast<std::size_t>(total);
  std::vector<int64_t> cell(x.size());
  g.start.assign(ncell + 1, 0);
  for (std::size_t p = 0; p < x.size(); ++p) {
    cell[p] = g.flat(g.cell_of(x[p]));
    ++g.start[static_cast<std::size_t>(cell[p]) + 1];
  }
  for (std::size_t c = 0; c < ncell; ++c) g.start[c + 1] += g.start[c];
  g.idx.resize(x.size());
  std::vector<int64_t> fill(g.start.begin(), g.start.end() - 1);
  for (std::size_t p = 0; p < x.size(); ++p)
    g.idx[static_cast<std::size_t>(fill[static_cast<std::size_t>(cell[p])]++)] = static_cast<int32_t>(p);
  return g;
}

// Calls f(j, |x_j - x_i|) for every j > i with |x_j - x_i| < cutoff (any order). Does not throw:
// it runs inside OpenMP regions.
template <int Dim, class F>
void for_each_neighbour(const CellGrid<Dim>& g, const std::vector<Vec<Dim>>& x, std::size_t i,
                        double cutoff, F&& f) {
  const auto c = g.cell_of(x[i]);
  std::array<int64_t, Dim> o{};
  o.fill(-1);
  while (true) {
    std::array<int64_t, Dim> nc{};
    bool inside = true;
    for (int d = 0; d < Dim; ++d) {
      nc[d] = c[d] + o[d];
      inside = inside && nc[d] >= 0 && nc[d] < g.n[d];
    }
    if (inside) {
      const auto fc = static_cast<std::size_t>(g.flat(nc));
      for (int64_t k = g.start[fc]; k < g.start[fc + 1]; ++k) {
        const auto j = static_cast<std::size_t>(g.idx[static_cast<std::size_t>(k)]);
        if (j <= i) continue;
        const double len = (x[j] - x[i]).norm();
        if (len < cutoff) f(static_cast<int32_t>(j), len);  // len == 0 (coincident) is reported too
      }
    }
    int d = 0;
    while (d < Dim && o[d] == 1) o[d++] = -1;
    if (d == Dim) break;
    ++o[d];
  }
}

}  // namespace

template <int Dim>
BondList<Dim> build_bonds(const std::vector<Vec<Dim>>& x, double dx, double delta) {
  if (!(std::isfinite(dx) && dx > 0.0)) throw std::invalid_argument("build_bonds: dx must be positive");
  if (!(std::isfinite(delta) && delta > 0.0))
    throw std::invalid_argument("build_bonds: delta must be positive");
  if (x.size() > static_cast<std::size_t>(std::numeric_limits<int32_t>::max()))
    throw std::invalid_argument("build_bonds: too many points for 32-bit bond indices");
  BondList<Dim> b;
  if (x.empty()) return b;
  const double cutoff = delta + 0.5 * dx;
  const double full = delta - 0.5 * dx;
  const CellGrid<Dim> g = make_grid(x, cutoff);
  const std::size_t n = x.size();
  const bool par = worth_parallel(n);

  // Pass 1: bonds per point (j > i); pass 2: fill each point's slice, sorted by j.
  std::vector<std::size_t> offset(n + 1, 0);
  bool coincident = false;
#pragma omp parallel for schedule(dynamic, 256) if (par) reduction(|| : coincident)
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t cnt = 0;
    for_each_neighbour(g, x, i, cutoff, [&](int32_t, double len) {
      ++cnt;
      coincident = coincident || len == 0.0;
    });
    offset[i + 1] = cnt;
  }
  if (coincident) throw std::invalid_argument("build_bonds: coincident points");
  for (std::size_t i = 0; i < n; ++i) offset[i + 1] += offset[i];
  const std::size_t nb = offset[n];
  b.i.resize(nb);
  b.j.resize(nb);
  b.xi_len.resize(nb);
  b.vol_factor.resize(nb);
  b.intact.assign(nb, 1);
#pragma omp parallel if (par)
  {
    std::vector<std::pair<int32_t, double>> local;
#pragma omp for schedule(dynamic, 256)
    for (std::size_t i = 0; i < n; ++i) {
      local.clear();
      for_each_neighbour(g, x, i, cutoff, [&](int32_t j, double len) { local.emplace_back(j, len); });
      std::sort(local.begin(), local.end());
      std::size_t k = offset[i];
      for (const auto& [j, len] : local) {
        b.i[k] = static_cast<int32_t>(i);
        b.j[k] = j;
        b.xi_len[k] = len;
        b.vol_factor[k] = len <= full ? 1.0 : std::min(1.0, (cutoff - len) / dx);
        ++k;
      }
    }
  }
  return b;
}

template <int Dim>
double stable_dt(const BondList<Dim>& bonds, const std::vector<double>& volume, double c, double rho,
                 std::size_t n_points) {
  if (volume.size() != n_points) throw std::invalid_argument("stable_dt: volume size != n_points");
  if (!(std::isfinite(c) && c > 0.0)) throw std::invalid_argument("stable_dt: c must be positive");
  if (!(std::isfinite(rho) && rho > 0.0)) throw std::invalid_argument("stable_dt: rho must be positive");
  // Serial accumulation in bond order: deterministic, and cheap next to one force evaluation.
  std::vector<double> stiff(n_points, 0.0);
  for (std::size_t k = 0; k < bonds.size(); ++k) {
    if (!bonds.intact[k]) continue;
    const auto i = static_cast<std::size_t>(bonds.i[k]);
    const auto j = static_cast<std::size_t>(bonds.j[k]);
    if (bonds.i[k] < 0 || bonds.j[k] < 0 || i >= n_points || j >= n_points)
      throw std::invalid_argument("stable_dt: bond index out of range");
    const double cij = bonds.vol_factor[k] * c / bonds.xi_len[k];
    stiff[i] += cij * volume[j];
    stiff[j] += cij * volume[i];
  }
  double max_stiff = 0.0;
  for (double s : stiff) max_stiff = std::max(max_stiff, s);
  if (max_stiff <= 0.0) return std::numeric_limits<double>::infinity();
  return std::sqrt(2.0 * rho / max_stiff);
}

template struct BondList<2>;
template struct BondList<3>;
template BondList<2> build_bonds<2>(const std::vector<Vec<2>>&, double, double);
template BondList<3> build_bonds<3>(const std::vector<Vec<3>>&, double, double);
template double stable_dt<2>(const BondList<2>&, const std::vector<double>&, double, double, std::size_t);
template double stable_dt<3>(const BondList<3>&, const std::vector<double>&, double, double, std::size_t);

}  // namespace cleave::pd
