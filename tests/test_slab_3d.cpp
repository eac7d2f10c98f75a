// A 3D slab one cell thick between two symmetry planes is a plane-strain body: the 3D solver must
// reproduce the 2D plane-strain run particle by particle (issue validation 4), for both shape
// functions. It also exercises tractions, fixed supports and symmetry planes in both dimensions.
#include <gtest/gtest.h>

#include "support.hpp"

namespace cleave {
namespace {

using test::json;

json scene(int dim, const std::string& sf) {
  const double h = 0.005;
  json s;
  s["analysis"] = {{"type", dim == 2 ? "plane_strain" : "3d"}};
  s["grid"] = {{"cell_size", h}};
  s["mpm"] = {{"shape_function", sf}, {"stress_update", "USAVG"}};
  s["materials"] = json::array({test::material("m", 1e9, 0.3, 1000)});
  json shape = dim == 2 ? json{{"type", "rectangle"}, {"min", {0, 0}}, {"max", {0.04, 0.02}}}
                        : json{{"type", "box"}, {"min", {0, 0, 0}}, {"max", {0.04, 0.02, h}}};
  s["bodies"] = json::array({{{"name", "b"}, {"material", "m"}, {"shape", shape},
                              {"velocity", dim == 2 ? json{0.5, 2.0} : json{0.5, 2.0, 0.0}}}});
  json fixed = dim == 2 ? json{0, 0} : json{0, 0, nullptr};
  json lo = dim == 2 ? json{0, -1} : json{0, -1, -1}, hi = dim == 2 ? json{0, 1} : json{0, 1, 1};
  s["loads"] = json::array({{{"type", "velocity"}, {"region", {{"min", lo}, {"max", hi}}}, {"velocity", fixed}},
                            {{"type", "traction"}, {"face", "+x"},
                             {"traction", dim == 2 ? json{1e6, -2e6} : json{1e6, -2e6, 0}}, {"rise_time", 1e-5}}});
  if (dim == 3) {
    s["loads"].push_back({{"type", "symmetry"}, {"axis", "z"}, {"position", 0.0}});
    s["loads"].push_back({{"type", "symmetry"}, {"axis", "z"}, {"position", h}});
  }
  s["time"] = {{"end", 1.0}, {"cfl", 0.4}};
  return s;
}

class Slab : public ::testing::TestWithParam<std::string> {};

TEST_P(Slab, ReproducesPlaneStrain) {
  Model<2> m2 = build_model<2>(scene(2, GetParam()));
  Model<3> m3 = build_model<3>(scene(3, GetParam()));
  ASSERT_EQ(m3.particles.size(), 2 * m2.particles.size());
  ASSERT_DOUBLE_EQ(m2.dt, m3.dt);
  auto s2 = make_stepper<2>(m2);
  auto s3 = make_stepper<3>(m3);
  const long steps = 150;
  ASSERT_FALSE(test::advance(*s2, steps));
  ASSERT_FALSE(test::advance(*s3, steps));
  s3->sync_strain();  // (a linear elastic run carries only the stress: particle_strain.hpp)
  double smax = 0, umax = 0;
  for (std::size_t p = 0; p < m2.particles.size(); ++p) {
    smax = std::max(smax, m2.particles.stress[p].cwiseAbs().maxCoeff());
    umax = std::max(umax, m2.particles.u[p].norm());
  }
  ASSERT_GT(smax, 1e5);  // the run did load the body
  double ds = 0, du = 0, dv = 0, shear_out = 0, eps_zz = 0;
  for (std::size_t p3 = 0; p3 < m3.particles.size(); ++p3) {
    const std::size_t p2 = p3 / 2;  // z is the innermost lattice loop: two layers per 2D particle
    const auto& a = m2.particles;
    const auto& b = m3.particles;
    du = std::max(du, (b.u[p3].head<2>() - a.u[p2]).norm());
    dv = std::max(dv, (b.v[p3].head<2>() - a.v[p2]).norm() + std::fabs(b.v[p3][2]));
    for (int k = 0; k < 4; ++k) ds = std::max(ds, std::fabs(b.stress[p3][k] - a.stress[p2][k]));
    shear_out = std::max({shear_out, std::fabs(b.stress[p3][4]), std::fabs(b.stress[p3][5])});
    eps_zz = std::max(eps_zz, std::fabs(b.strain[p3][2]));
  }
  // Same arithmetic up to summation order: agreement to round-off, relative 1e-10.
  EXPECT_LT(ds, 1e-10 * smax);
  EXPECT_LT(shear_out, 1e-10 * smax);
  EXPECT_LT(du, 1e-10 * umax);
  EXPECT_LT(eps_zz, 1e-14);
  EXPECT_LT(dv, 1e-10 * 2.0);
}

INSTANTIATE_TEST_SUITE_P(Mpm, Slab, ::testing::Values("linear", "ugimp"));

}  // namespace
}  // namespace cleave
