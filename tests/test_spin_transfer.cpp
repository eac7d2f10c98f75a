// A spinning body's nodal velocities carried with its spin (mpm.spin_transfer, libmpm/mpm/spin_transfer.hpp):
// a plate that spins builds only its centrifugal stress, conserves momentum, and runs the same on 1
// and 2 threads. Figures: docs/validation.md, "Spinning bodies".
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "libmpm/mpm/mpm_method.hpp"
#include "support.hpp"

namespace cleave {
namespace {

using nlohmann::json;

// An aluminium plate 100 x 36 mm (E = 70 GPa, nu = 0.33, rho = 2700 kg/m3), plane stress, 2 mm cells,
// linear shape functions, spinning about its centre at omega (rad/ms), free.
json spinning_plate(double omega, bool transfer) {
  return {{"units", {{"length", "mm"}, {"stress", "Pa"}, {"density", "g/cm3"}, {"velocity", "m/s"},
                     {"time", "ms"}, {"inverse_time", "1/ms"}}},
          {"analysis", {{"type", "plane_stress"}, {"thickness", 1}}},
          {"resolution", 2},
          {"grid", {{"min", {-10, -30}}, {"max", {110, 30}}}},
          {"mpm", {{"shape_function", "linear"}, {"stress_update", "USAVG"}, {"spin_transfer", transfer}}},
          {"materials", {test::material("aluminium", 70e9, 0.33, 2.7)}},
          {"bodies", {{{"name", "plate"}, {"material", "aluminium"},
                       {"shape", {{"type", "rectangle"}, {"min", {0, -18}}, {"max", {100, 18}}}},
                       {"particles_per_cell", 2}, {"angular_velocity", omega}, {"rotation_center", {50, 0}}}}},
          {"time", {{"end", 1.0}, {"cfl", 0.5}}}};
}

struct SpinRun {
  double max_mises = 0;  // Pa, over particles and steps
  double momentum = 0;   // max |p(t) - p(0)| over the run, kg m/s
  Model<2> model;
};

SpinRun spin_plate(double omega, bool transfer, double t_end_ms) {
  SpinRun r{0, 0, build_model<2>(spinning_plate(omega, transfer))};
  auto st = make_stepper<2>(r.model);
  const auto p0 = st->global_state().momentum;
  const long steps = std::lround(t_end_ms * 1e-3 / r.model.dt);
  const auto& P = r.model.particles;
  for (long k = 1; k <= steps; ++k) {
    if (st->step()) break;
    r.momentum = std::max(r.momentum, (st->global_state().momentum - p0).norm());
    for (std::size_t p = 0; p < P.size(); ++p) {
      const auto& s = P.stress[p];
      r.max_mises = std::max(r.max_mises, std::sqrt(s[0] * s[0] + s[1] * s[1] - s[0] * s[1] + 3 * s[3] * s[3]));
    }
  }
  return r;
}

// The plate spinning at 0.1 rad/ms for 0.5 ms. Its centrifugal stress: a free bar of half-length
// a = 50 mm spinning at omega carries sigma_xx = rho omega^2 (a^2 - x^2) / 2, at most 33.8 kPa at its
// centre; started impulsively (unstressed at full speed) it overshoots to at most twice that,
// 67.5 kPa. Asserted: below 2 rho omega^2 a^2 = 135 kPa (the overshoot bound with a factor 2 for the
// 2 mm discretisation). Without the transfer the plate's edges carried 8.8 MPa of von Mises stress
// (their nodes moved with the spin of their particles' mass centres, half a cell inside). About 3 s.
TEST(SpinTransfer, APlateSpinningAtATenthOfARadianPerMillisecondCarriesOnlyItsCentrifugalStress) {
  const double omega = 100.0, rho = 2700.0, a = 0.05;  // rad/s, kg/m3, m
  const SpinRun with = spin_plate(0.1, true, 0.5), without = spin_plate(0.1, false, 0.5);
  std::printf("spinning plate, 0.5 ms at 0.1 rad/ms: max von Mises %.4g kPa with spin_transfer, %.4g kPa without; "
              "bound 2 rho w^2 a^2 = %.4g kPa\n",
              with.max_mises / 1e3, without.max_mises / 1e3, 2 * rho * omega * omega * a * a / 1e3);
  EXPECT_LT(with.max_mises, 2 * rho * omega * omega * a * a);
  EXPECT_TRUE(with.model.spin_transfer);
}

// The nodal velocities change, the momenta do not: momentum is conserved to round-off (its total is
// zero; the particles' |m v| add up to about 0.3 kg m/s at 1 rad/ms), and 1 and 2 threads give the
// same particles bit for bit.
TEST(SpinTransfer, ConservesMomentumAndGivesTheSameParticlesOnOneAndTwoThreads) {
  omp_set_num_threads(1);
  const SpinRun one = spin_plate(1.0, true, 0.05);
  omp_set_num_threads(2);
  const SpinRun two = spin_plate(1.0, true, 0.05);
  EXPECT_LT(one.momentum, 1e-14);
  const auto& A = one.model.particles;
  const auto& B = two.model.particles;
  ASSERT_EQ(A.size(), B.size());
  for (std::size_t p = 0; p < A.size(); ++p) {
    ASSERT_EQ(A.x[p], B.x[p]) << p;
    ASSERT_EQ(A.v[p], B.v[p]) << p;
    ASSERT_EQ(A.stress[p], B.stress[p]) << p;
  }
}

// 3D: an aluminium cube of 20 mm (2 mm cells, linear) spinning at 1 rad/ms about the axis (1, 2, 3)
// through its centre, for 0.05 ms. Its centrifugal stress is of order rho omega^2 R^2 (R = 17.3 mm,
// the half-diagonal: 0.81 MPa); asserted below twice that (the impulsive start's overshoot bound).
// Without the transfer the cube's faces strained with the spin of their nodes' mass centres.
TEST(SpinTransfer, ACubeSpinningAboutASkewAxisCarriesOnlyItsCentrifugalStress3D) {
  const auto run = [](bool transfer) {
    const double w = 1.0 / std::sqrt(14.0);
    json j = {{"units", {{"length", "mm"}, {"stress", "Pa"}, {"density", "g/cm3"}, {"velocity", "m/s"},
                         {"time", "ms"}, {"inverse_time", "1/ms"}}},
              {"analysis", {{"type", "3d"}}},
              {"resolution", 2},
              {"grid", {{"min", {-8, -8, -8}}, {"max", {28, 28, 28}}}},
              {"mpm", {{"shape_function", "linear"}, {"stress_update", "USAVG"}, {"spin_transfer", transfer}}},
              {"materials", {test::material("aluminium", 70e9, 0.33, 2.7)}},
              {"bodies", {{{"name", "cube"}, {"material", "aluminium"},
                           {"shape", {{"type", "box"}, {"min", {0, 0, 0}}, {"max", {20, 20, 20}}}},
                           {"particles_per_cell", 2}, {"angular_velocity", {w, 2 * w, 3 * w}},
                           {"rotation_center", {10, 10, 10}}}}},
              {"time", {{"end", 1.0}, {"cfl", 0.5}}}};
    Model<3> m = build_model<3>(j);
    auto st = make_stepper<3>(m);
    const long steps = std::lround(0.05e-3 / m.dt);
    double worst = 0.0;
    for (long k = 1; k <= steps; ++k) {
      if (st->step()) break;
      for (const auto& s : m.particles.stress) {
        const double mises = std::sqrt(0.5 * ((s[0] - s[1]) * (s[0] - s[1]) + (s[1] - s[2]) * (s[1] - s[2]) +
                                              (s[2] - s[0]) * (s[2] - s[0])) +
                                       3.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
        worst = std::max(worst, mises);
      }
    }
    return worst;
  };
  const double with = run(true), without = run(false);
  const double bound = 2 * 2700.0 * 1e6 * 3 * 0.01 * 0.01;  // 2 rho omega^2 R^2, R^2 = 3 (10 mm)^2
  std::printf("spinning cube, 0.05 ms at 1 rad/ms: max von Mises %.4g MPa with spin_transfer, %.4g MPa without; "
              "bound %.4g MPa\n",
              with / 1e6, without / 1e6, bound / 1e6);
  EXPECT_LT(with, bound);
}

// The scene key: on where a body spins, off otherwise, and a wrong type is refused naming it.
TEST(SpinTransfer, IsOnWhereABodySpinsAndRefusesANonBoolean) {
  json j = spinning_plate(0.1, true);
  j["mpm"].erase("spin_transfer");
  EXPECT_TRUE(build_model<2>(j).spin_transfer);
  j["bodies"][0].erase("angular_velocity");
  j["bodies"][0].erase("rotation_center");
  EXPECT_FALSE(build_model<2>(j).spin_transfer);
  j["mpm"]["spin_transfer"] = "yes";
  try {
    build_model<2>(j);
    FAIL() << "a string spin_transfer was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("mpm.spin_transfer"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace cleave
