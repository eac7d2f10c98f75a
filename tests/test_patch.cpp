// Patch tests (issue: validation 1): rigid translation and a uniform stress state held by
// consistent tractions are reproduced exactly, to round-off, by both shape functions in 2D and 3D.
#include <gtest/gtest.h>

#include <cmath>

#include "support.hpp"

namespace cleave {
namespace {

using test::json;

json base_scene(int dim, const std::string& sf) {
  json s;
  s["analysis"] = {{"type", dim == 2 ? "plane_strain" : "3d"}};
  s["grid"] = {{"cell_size", 0.01}};
  s["mpm"] = {{"shape_function", sf}, {"stress_update", "USAVG"}};
  s["materials"] = json::array({test::material("m", 1e9, 0.3, 1000)});
  s["time"] = {{"end", 1.0}, {"cfl", 0.4}};
  return s;
}

class ShapeFns : public ::testing::TestWithParam<std::string> {};

template <int Dim>
void rigid_translation(const std::string& sf) {
  json s = base_scene(Dim, sf);
  // A disk/sphere: its boundary cuts cells, so nodes at the edge have partial support.
  json shape = Dim == 2 ? json{{"type", "disk"}, {"center", {0.031, 0.047}}, {"radius", 0.052}}
                        : json{{"type", "sphere"}, {"center", {0.031, 0.047, 0.013}}, {"radius", 0.041}};
  json v = Dim == 2 ? json{3.0, -4.0} : json{3.0, -4.0, 1.5};
  s["bodies"] = json::array({{{"name", "b"}, {"material", "m"}, {"shape", shape}, {"velocity", v}}});
  s["grid"]["margin_cells"] = 8;
  Model<Dim> m = build_model<Dim>(s);
  const auto x0 = m.particles.x;
  auto st = make_stepper<Dim>(m);
  const long n = 40;
  ASSERT_FALSE(test::advance(*st, n));
  st->sync_strain();  // (a linear elastic run carries only the stress: particle_strain.hpp)
  Vec<Dim> vel;
  for (int d = 0; d < Dim; ++d) vel[d] = v[d].get<double>();
  const double t = st->time();
  double max_dx = 0, max_dv = 0, max_strain = 0;
  for (std::size_t p = 0; p < m.particles.size(); ++p) {
    max_dx = std::max(max_dx, (m.particles.x[p] - x0[p] - vel * t).norm());
    max_dv = std::max(max_dv, (m.particles.v[p] - vel).norm());
    max_strain = std::max(max_strain, m.particles.strain[p].cwiseAbs().maxCoeff());
  }
  // Round-off of ~n operations on O(1) numbers.
  EXPECT_LT(max_dx, 1e-13 * (vel.norm() * t + 0.05));
  EXPECT_LT(max_dv, 1e-13 * vel.norm());
  EXPECT_LT(max_strain, 1e-13);
}

TEST_P(ShapeFns, RigidTranslation2D) { rigid_translation<2>(GetParam()); }
TEST_P(ShapeFns, RigidTranslation3D) { rigid_translation<3>(GetParam()); }

// A block under a uniform stress sigma0 with tractions sigma0 . n on every face: internal and
// external nodal forces cancel exactly (the body's edges lie on grid lines, 2 particles per cell),
// so nothing moves and the stress stays sigma0.
template <int Dim>
void uniform_stress(const std::string& sf) {
  json s = base_scene(Dim, sf);
  Mat<Dim> sig;
  if constexpr (Dim == 2) sig << 3e6, 1e6, 1e6, -2e6;
  else sig << 3e6, 1e6, 0.5e6, 1e6, -2e6, 0.7e6, 0.5e6, 0.7e6, 1.5e6;
  json lo = Dim == 2 ? json{0.0, 0.0} : json{0.0, 0.0, 0.0};
  json hi = Dim == 2 ? json{0.08, 0.05} : json{0.06, 0.05, 0.04};
  s["bodies"] = json::array({{{"name", "b"}, {"material", "m"},
                              {"shape", {{"type", Dim == 2 ? "rectangle" : "box"}, {"min", lo}, {"max", hi}}}}});
  s["loads"] = json::array();
  const char* axes = "xyz";
  for (int d = 0; d < Dim; ++d)
    for (int side : {-1, 1}) {
      json t = json::array();
      for (int k = 0; k < Dim; ++k) t.push_back(side * sig(k, d));
      s["loads"].push_back({{"type", "traction"}, {"face", std::string(side > 0 ? "+" : "-") + axes[d]},
                            {"traction", t}});
    }
  Model<Dim> m = build_model<Dim>(s);
  Sym<Dim> s0;
  if constexpr (Dim == 2) s0 << sig(0, 0), sig(1, 1), 0.0, sig(0, 1);
  else s0 << sig(0, 0), sig(1, 1), sig(2, 2), sig(0, 1), sig(1, 2), sig(0, 2);
  for (auto& st : m.particles.stress) st = s0;
  const auto x0 = m.particles.x;
  auto st = make_stepper<Dim>(m);
  ASSERT_FALSE(test::advance(*st, 30));
  // Scale of a velocity error: one unbalanced force ~ sigma * h^(Dim-1) acting on a node mass ~ rho h^Dim.
  const double vscale = 3e6 / (1000 * 0.01) * m.dt;
  double max_v = 0, max_ds = 0, max_dx = 0;
  for (std::size_t p = 0; p < m.particles.size(); ++p) {
    max_v = std::max(max_v, m.particles.v[p].norm());
    max_dx = std::max(max_dx, (m.particles.x[p] - x0[p]).norm());
    Sym<Dim> d = m.particles.stress[p] - s0;
    if constexpr (Dim == 2) d[2] = 0;  // sigma_zz is not prescribed in plane strain
    max_ds = std::max(max_ds, d.cwiseAbs().maxCoeff());
  }
  EXPECT_LT(max_v, 1e-12 * vscale) << "particles accelerated: forces do not balance";
  EXPECT_LT(max_dx, 1e-12 * 0.01);
  EXPECT_LT(max_ds, 1e-10 * 3e6);
}

TEST_P(ShapeFns, UniformStress2D) { uniform_stress<2>(GetParam()); }
TEST_P(ShapeFns, UniformStress3D) { uniform_stress<3>(GetParam()); }

INSTANTIATE_TEST_SUITE_P(Patch, ShapeFns, ::testing::Values("linear", "ugimp"));

}  // namespace
}  // namespace cleave
