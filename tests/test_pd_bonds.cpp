// Bond-based peridynamics groundwork: material constants, bond lists, stable time step.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "libmpm/pd/bonds.hpp"
#include "libmpm/pd/constants.hpp"

using namespace cleave;
using namespace cleave::pd;

namespace {

constexpr double kPi = std::numbers::pi;

// Regular lattice of n^Dim points with spacing dx, optionally perturbed by up to +-jitter*dx.
template <int Dim> std::vector<Vec<Dim>> lattice(int n, double dx, double jitter = 0.0, unsigned seed = 1) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter * dx, jitter * dx);
  std::vector<Vec<Dim>> x;
  const int nz = Dim == 3 ? n : 1;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        Vec<Dim> p;
        p[0] = i * dx;
        p[1] = j * dx;
        if constexpr (Dim == 3) p[2] = k * dx;
        if (jitter > 0.0)
          for (int d = 0; d < Dim; ++d) p[d] += u(rng);
        x.push_back(p);
      }
  return x;
}

using BondTuple = std::tuple<int32_t, int32_t, double, double>;

template <int Dim> std::vector<BondTuple> as_tuples(const BondList<Dim>& b) {
  std::vector<BondTuple> t;
  for (std::size_t k = 0; k < b.size(); ++k) t.emplace_back(b.i[k], b.j[k], b.xi_len[k], b.vol_factor[k]);
  return t;
}

// O(N^2) reference with the same inclusion rule and the same floating-point expressions.
template <int Dim> std::vector<BondTuple> brute_force(const std::vector<Vec<Dim>>& x, double dx, double delta) {
  std::vector<BondTuple> t;
  const double cutoff = delta + 0.5 * dx;
  for (std::size_t i = 0; i < x.size(); ++i)
    for (std::size_t j = i + 1; j < x.size(); ++j) {
      const double len = (x[j] - x[i]).norm();
      if (len < cutoff) {
        const double beta = len <= delta - 0.5 * dx ? 1.0 : std::min(1.0, (cutoff - len) / dx);
        t.emplace_back(static_cast<int32_t>(i), static_cast<int32_t>(j), len, beta);
      }
    }
  return t;
}

template <int Dim> void expect_well_formed(const BondList<Dim>& b) {
  ASSERT_EQ(b.j.size(), b.size());
  ASSERT_EQ(b.xi_len.size(), b.size());
  ASSERT_EQ(b.vol_factor.size(), b.size());
  ASSERT_EQ(b.intact.size(), b.size());
  for (std::size_t k = 0; k < b.size(); ++k) {
    EXPECT_LT(b.i[k], b.j[k]);
    EXPECT_GT(b.vol_factor[k], 0.0);
    EXPECT_LE(b.vol_factor[k], 1.0);
    EXPECT_EQ(b.intact[k], 1);
    if (k > 0) {  // strictly increasing (i, j): sorted and unique
      EXPECT_TRUE(std::make_pair(b.i[k - 1], b.j[k - 1]) < std::make_pair(b.i[k], b.j[k])) << k;
    }
  }
}

}  // namespace

TEST(PdConstants, PlaneStressHandComputed) {
  // E = 65 GPa, G0 = 204 J/m^2, delta = 2 mm, t = 1 mm (values from an independent calculator).
  const auto k = pd_constants(PdModel::PlaneStress, 65e9, 204.0, 2e-3, 1e-3);
  EXPECT_NEAR(k.c / 2.3276410427189693e+22, 1.0, 1e-12);
  EXPECT_NEAR(k.s0 / 0.0014802227844937462, 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(k.implied_nu, 1.0 / 3.0);
  // Seed 003 form: c = 6E/(pi delta^3 (1 - nu)) per unit thickness, at nu = 1/3.
  const double nu = k.implied_nu;
  EXPECT_NEAR(k.c * 1e-3 / (6.0 * 65e9 / (kPi * 8e-9 * (1.0 - nu))), 1.0, 1e-12);
}

TEST(PdConstants, PlaneStrainHandComputed) {
  const auto k = pd_constants(PdModel::PlaneStrain, 65e9, 204.0, 2e-3, 1e-3);
  EXPECT_NEAR(k.c / 2.482817112233567e+22, 1.0, 1e-12);
  EXPECT_NEAR(k.s0 / 0.0014332195482552625, 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(k.implied_nu, 0.25);
}

TEST(PdConstants, ThreeDHandComputed) {
  // K = 50 GPa; thickness is ignored in 3D.
  const auto k = pd_constants(PdModel::ThreeD, 50e9, 204.0, 2e-3, 0.0);
  EXPECT_NEAR(k.c / 1.7904931097838222e+22, 1.0, 1e-12);
  EXPECT_NEAR(k.s0 / 0.001064581294844754, 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(k.implied_nu, 0.25);
}

TEST(PdConstants, RejectsNonPositiveInputs) {
  for (auto m : {PdModel::PlaneStress, PdModel::PlaneStrain, PdModel::ThreeD}) {
    EXPECT_THROW(pd_constants(m, 0.0, 204.0, 2e-3, 1e-3), std::invalid_argument);
    EXPECT_THROW(pd_constants(m, 65e9, -1.0, 2e-3, 1e-3), std::invalid_argument);
    EXPECT_THROW(pd_constants(m, 65e9, 204.0, 0.0, 1e-3), std::invalid_argument);
    EXPECT_THROW(pd_constants(m, std::nan(""), 204.0, 2e-3, 1e-3), std::invalid_argument);
  }
  EXPECT_THROW(pd_constants(PdModel::PlaneStress, 65e9, 204.0, 2e-3, 0.0), std::invalid_argument);
  EXPECT_THROW(pd_constants(PdModel::PlaneStrain, 65e9, 204.0, 2e-3, -1.0), std::invalid_argument);
}

TEST(PdBonds, Lattice2DInteriorPointsAllAlike) {
  const int n = 30, m = 3;
  const double dx = 1e-3, delta = m * dx;
  const auto x = lattice<2>(n, dx);
  const auto b = build_bonds<2>(x, dx, delta);
  expect_well_formed(b);

  // Expected neighbour count and partial volume of an interior point, by enumerating offsets.
  int expected_count = 0;
  double expected_beta = 0.0;
  for (int a = -m - 1; a <= m + 1; ++a)
    for (int c = -m - 1; c <= m + 1; ++c) {
      if (a == 0 && c == 0) continue;
      const double r = std::hypot(a, c);
      if (r < m + 0.5) {
        ++expected_count;
        expected_beta += r <= m - 0.5 ? 1.0 : (m + 0.5 - r);
      }
    }
  ASSERT_GT(expected_count, 0);

  std::vector<int> count(x.size(), 0);
  std::vector<double> beta(x.size(), 0.0);
  for (std::size_t k = 0; k < b.size(); ++k) {
    ++count[b.i[k]];
    ++count[b.j[k]];
    beta[b.i[k]] += b.vol_factor[k];
    beta[b.j[k]] += b.vol_factor[k];
  }
  int interior = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if (i < m + 1 || j < m + 1 || i >= n - m - 1 || j >= n - m - 1) continue;
      const int p = j * n + i;
      ++interior;
      EXPECT_EQ(count[p], expected_count) << i << "," << j;
      EXPECT_NEAR(beta[p], expected_beta, 1e-9) << i << "," << j;
    }
  EXPECT_EQ(interior, (n - 2 * m - 2) * (n - 2 * m - 2));
  // The partial volumes approximate the horizon area: pi m^2 cells, minus the point's own cell.
  EXPECT_NEAR(expected_beta, kPi * m * m - 1.0, 0.06 * kPi * m * m);
}

TEST(PdBonds, MatchesBruteForce2DPerturbed) {
  const double dx = 0.5e-3;
  const auto x = lattice<2>(18, dx, 0.2, 7);
  for (double m : {1.0, 3.0, 4.0}) {
    const auto b = build_bonds<2>(x, dx, m * dx);
    expect_well_formed(b);
    EXPECT_EQ(as_tuples(b), brute_force<2>(x, dx, m * dx)) << "m = " << m;
  }
}

TEST(PdBonds, MatchesBruteForce3DPerturbed) {
  const double dx = 1.0;
  const auto x = lattice<3>(9, dx, 0.2, 11);
  const auto b = build_bonds<3>(x, dx, 3.0 * dx);
  expect_well_formed(b);
  EXPECT_EQ(as_tuples(b), brute_force<3>(x, dx, 3.0 * dx));
}

TEST(PdBonds, Lattice3DInteriorPoint) {
  const int n = 9, m = 2;
  const double dx = 1.0, delta = m * dx;
  const auto x = lattice<3>(n, dx);
  const auto b = build_bonds<3>(x, dx, delta);
  expect_well_formed(b);
  int expected_count = 0;
  for (int a = -m - 1; a <= m + 1; ++a)
    for (int c = -m - 1; c <= m + 1; ++c)
      for (int e = -m - 1; e <= m + 1; ++e)
        if ((a || c || e) && std::sqrt(double(a * a + c * c + e * e)) < m + 0.5) ++expected_count;
  std::vector<int> count(x.size(), 0);
  for (std::size_t k = 0; k < b.size(); ++k) {
    ++count[b.i[k]];
    ++count[b.j[k]];
  }
  const int centre = (4 * n + 4) * n + 4;
  EXPECT_EQ(count[centre], expected_count);
  EXPECT_EQ(count[0], *std::min_element(count.begin(), count.end()));  // a corner has the fewest
}

TEST(PdBonds, ThreadCountDoesNotChangeTheList) {
  // 110^2 points is above the parallel threshold (worth_parallel).
  const double dx = 1.0;
  const auto x = lattice<2>(110, dx, 0.1, 3);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const auto serial = build_bonds<2>(x, dx, 3.0 * dx);
  omp_set_num_threads(std::max(threads, 4));
  const auto parallel = build_bonds<2>(x, dx, 3.0 * dx);
  omp_set_num_threads(threads);
  expect_well_formed(parallel);
  EXPECT_EQ(serial.i, parallel.i);
  EXPECT_EQ(serial.j, parallel.j);
  EXPECT_EQ(serial.xi_len, parallel.xi_len);
  EXPECT_EQ(serial.vol_factor, parallel.vol_factor);
}

TEST(PdBonds, RejectsBadInput) {
  const auto x = lattice<2>(4, 1.0);
  EXPECT_THROW(build_bonds<2>(x, 0.0, 3.0), std::invalid_argument);
  EXPECT_THROW(build_bonds<2>(x, 1.0, -1.0), std::invalid_argument);
  auto dup = x;
  dup.push_back(x[5]);
  EXPECT_THROW(build_bonds<2>(dup, 1.0, 3.0), std::invalid_argument);
  EXPECT_EQ(build_bonds<2>({}, 1.0, 3.0).size(), 0u);
}

TEST(PdStableDt, PositiveAndShrinksWithSpacing) {
  const double E = 65e9, G0 = 204.0, rho = 2235.0, t = 1e-3;
  auto dt_for = [&](double dx) {
    const double delta = 4.0 * dx;
    const auto x = lattice<2>(20, dx);
    const auto b = build_bonds<2>(x, dx, delta);
    const std::vector<double> vol(x.size(), dx * dx * t);
    const auto k = pd_constants(PdModel::PlaneStress, E, G0, delta, t);
    return stable_dt<2>(b, vol, k.c, rho, x.size());
  };
  const double coarse = dt_for(1e-3), fine = dt_for(0.5e-3);
  EXPECT_GT(coarse, 0.0);
  EXPECT_TRUE(std::isfinite(coarse));
  EXPECT_LT(fine, coarse);
  EXPECT_NEAR(fine / coarse, 0.5, 1e-9);  // same m: the step scales with dx
  // Order of magnitude: Ha & Bobaru use 50 ns at dx = 0.5 mm, m = 4, well inside the limit.
  EXPECT_GT(fine, 50e-9);
  EXPECT_LT(fine, 1e-6);
}

TEST(PdStableDt, BrokenBondsAndBadInput) {
  const auto x = lattice<2>(5, 1.0);
  auto b = build_bonds<2>(x, 1.0, 2.0);
  const std::vector<double> vol(x.size(), 1.0);
  const double dt = stable_dt<2>(b, vol, 1.0, 1.0, x.size());
  std::fill(b.intact.begin(), b.intact.end(), uint8_t{0});
  EXPECT_TRUE(std::isinf(stable_dt<2>(b, vol, 1.0, 1.0, x.size())));
  b.intact[0] = 1;
  EXPECT_GT(stable_dt<2>(b, vol, 1.0, 1.0, x.size()), dt);
  EXPECT_THROW(stable_dt<2>(b, vol, 1.0, 1.0, x.size() + 1), std::invalid_argument);
  EXPECT_THROW(stable_dt<2>(b, vol, 0.0, 1.0, x.size()), std::invalid_argument);
  EXPECT_THROW(stable_dt<2>(b, vol, 1.0, -1.0, x.size()), std::invalid_argument);
}
