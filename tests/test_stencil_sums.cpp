// The stencil's row-factored sums (the velocity gradient and the internal force's shares, which the
// stress passes use) against the node-by-node sums over for_each, in 2D and 3D, linear and uGIMP.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "libmpm/mpm/grid.hpp"
#include "libmpm/mpm/stencil.hpp"
#include "libmpm/shape/shape_function.hpp"

namespace cleave {
namespace {

template <int Dim, class SF>
void check_row_sums(unsigned seed) {
  GridGeometry<Dim> G;
  G.h = 0.002;
  for (int d = 0; d < Dim; ++d) G.origin[d] = -0.01 * (d + 1), G.nodes[d] = 12;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), inside(0.3, 0.7);
  std::vector<Vec<Dim>> velocity(G.node_count());
  for (auto& v : velocity)
    for (int d = 0; d < Dim; ++d) v[d] = u(rng);
  Sym<Dim> s;
  for (int c = 0; c < kSymComponents<Dim>; ++c) s[c] = 1e6 * u(rng);
  for (int trial = 0; trial < 50; ++trial) {
    Vec<Dim> x;  // anywhere in the middle of the grid, so that every stencil fits
    for (int d = 0; d < Dim; ++d) x[d] = G.origin[d] + G.h * (G.nodes[d] - 1) * inside(rng);
    Stencil<Dim, SF> st;
    st.eval(G, G.strides(), 1.0 / G.h, x, 0.25);
    Mat<Dim> L = Mat<Dim>::Zero();
    std::vector<Vec<Dim>> force(G.node_count(), Vec<Dim>::Zero()), factored(G.node_count(), Vec<Dim>::Zero());
    st.for_each([&](int64_t n, double, const Vec<Dim>& g) {
      L += velocity[n] * g.transpose();
      force[n] += sym_dot<Dim>(s, g);
    });
    const Mat<Dim> L2 = st.gradient([&](int64_t n) -> const Vec<Dim>& { return velocity[n]; });
    EXPECT_LE((L2 - L).norm(), 1e-13 * L.norm()) << "trial " << trial;
    st.for_each_divergence(s, [&](int64_t n, const Vec<Dim>& f) { factored[n] += f; });
    for (std::size_t n = 0; n < force.size(); ++n)
      EXPECT_LE((factored[n] - force[n]).norm(), 1e-13 * s.norm() / G.h) << "trial " << trial << " node " << n;
  }
}

TEST(StencilRowSums, TheFactoredVelocityGradientAndForcesEqualTheNodeByNodeSums2D) {
  check_row_sums<2, LinearShape>(1);
  check_row_sums<2, UGimpShape>(2);
}

TEST(StencilRowSums, TheFactoredVelocityGradientAndForcesEqualTheNodeByNodeSums3D) {
  check_row_sums<3, LinearShape>(3);
  check_row_sums<3, UGimpShape>(4);
}

}  // namespace
}  // namespace cleave
