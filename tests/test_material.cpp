// The linear elastic material's incremental update: the hypoelastic increment, and the stress and
// strain carried round with the material's spin (SpinRotation), in 2D and 3D, and the strain taken
// from the stress.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>

#include "libmpm/material/linear_elastic.hpp"

namespace cleave {
namespace {

template <int Dim>
LinearElastic<Dim> steel(Analysis a) {
  const nlohmann::json j = {{"name", "steel"}, {"type", "linear_elastic"}, {"E", 200e9}, {"nu", 0.3}, {"density", 7800}};
  const UnitSystem si;
  return LinearElastic<Dim>(MaterialArgs{j, "materials[0]", si, a});
}

// A pure spin: L = omega (e_1 e_0 - e_0 e_1) about z.
template <int Dim>
Mat<Dim> spin_z(double omega) {
  Mat<Dim> L = Mat<Dim>::Zero();
  L(1, 0) = omega, L(0, 1) = -omega;
  return L;
}

// Turns stress s and strain e a quarter turn about z with material m: n steps of a pure spin (1 000:
// |q| = 7.9e-4 a step, where cayley_scale divides; 200 000: 3.9e-6, where it takes its series).
template <int Dim>
void quarter_turn(const LinearElastic<Dim>& m, Sym<Dim>& s, Sym<Dim>& e, int n = 1000) {
  const double dt = 1e-3, omega = M_PI / 2 / (n * dt);
  for (int k = 0; k < n; ++k) m.update(s, e, spin_z<Dim>(omega), dt);
}

TEST(LinearElasticUpdate, AStretchWithoutSpinAddsTheHookeIncrement) {
  const auto m = steel<2>(Analysis::PlaneStrain);
  Sym<2> s = Sym<2>::Zero(), e = Sym<2>::Zero();
  Mat<2> L = Mat<2>::Zero();
  L(0, 0) = 1e-3;  // 1/s, for 1 s
  m.update(s, e, L, 1.0);
  const double G = 200e9 / 2.6, lambda = 200e9 * 0.3 / (1.3 * 0.4);
  EXPECT_NEAR(s[0], (lambda + 2 * G) * 1e-3, 1e-9 * s[0]);
  EXPECT_NEAR(s[1], lambda * 1e-3, 1e-9 * s[0]);
  EXPECT_NEAR(s[2], lambda * 1e-3, 1e-9 * s[0]);  // plane strain: sigma_zz
  EXPECT_EQ(s[3], 0.0);
  EXPECT_DOUBLE_EQ(e[0], 1e-3);
}

// A bar under sigma_xx = 100 MPa turned a quarter turn by a pure spin (1 000 steps): its stress is
// then sigma_yy = 100 MPa, as the material's own axes now lie along y. Without the rotation the
// stress stayed sigma_xx: a body that turns while loaded kept its stress in the fixed axes. The Cayley
// rotation is second-order accurate: 1 000 steps of pi/2000 miss the angle by about 1e-7 relative.
TEST(LinearElasticUpdate, AStressedBarTurnedAQuarterTurnCarriesItsStressRound2D) {
  const auto m = steel<2>(Analysis::PlaneStress);
  for (int n : {1000, 200000}) {
    Sym<2> s(100e6, 0.0, 0.0, 0.0), e(5e-4, -1.5e-4, -1.5e-4, 0.0);
    quarter_turn(m, s, e, n);
    EXPECT_NEAR(s[0], 0.0, 1e-6 * 100e6) << n << " steps";
    EXPECT_NEAR(s[1], 100e6, 1e-6 * 100e6) << n << " steps";
    EXPECT_NEAR(s[3], 0.0, 1e-6 * 100e6) << n << " steps";
    EXPECT_NEAR(e[0], -1.5e-4, 1e-6 * 5e-4) << n << " steps";
    EXPECT_NEAR(e[1], 5e-4, 1e-6 * 5e-4) << n << " steps";
    EXPECT_EQ(e[2], -1.5e-4);  // out of plane: untouched by an in-plane spin
  }
}

// The series cayley_scale takes for small turns equals the division it replaces to round-off, on
// both sides of where it switches (q^2 = 1e-8).
TEST(LinearElasticUpdate, TheRotationsSeriesForSmallTurnsEqualsTheCayleyDivisionToRoundOff) {
  for (double q2 = 1e-16; q2 < 1e-7; q2 *= 1.7) {
    const double exact = 2.0 / (1.0 + q2);
    EXPECT_NEAR(cayley_scale(q2), exact, 2.5e-16 * exact) << "q^2 = " << q2;
  }
}

TEST(LinearElasticUpdate, AStressedBarTurnedAQuarterTurnCarriesItsStressRound3D) {
  const auto m = steel<3>(Analysis::ThreeD);
  // sigma_xx = 100 MPa and a shear sigma_xz = 20 MPa, turned about z: x -> y, z stays.
  for (int n : {1000, 200000}) {
    Sym<3> s, e = Sym<3>::Zero();
    s << 100e6, 0.0, 0.0, 0.0, 0.0, 20e6;
    quarter_turn(m, s, e, n);
    EXPECT_NEAR(s[0], 0.0, 1e-6 * 100e6) << n << " steps";
    EXPECT_NEAR(s[1], 100e6, 1e-6 * 100e6) << n << " steps";
    EXPECT_NEAR(s[2], 0.0, 1e-6 * 100e6) << n << " steps";
    EXPECT_NEAR(s[3], 0.0, 1e-6 * 100e6) << n << " steps";
    EXPECT_NEAR(s[4], 20e6, 1e-6 * 100e6) << n << " steps";  // xz turned into yz
    EXPECT_NEAR(s[5], 0.0, 1e-6 * 100e6) << n << " steps";
  }
}

// The rotation is exactly orthogonal: a stress spun for 100 000 steps keeps its invariants to
// round-off (a linearised Jaumann step, t += dt (W t - t W), grows its norm by about (omega dt)^2 / 2
// per step: 3.5e-7 here, 3.5 % over the run, energy from nothing in a long spin).
TEST(LinearElasticUpdate, ASpinningStressKeepsItsInvariants) {
  const auto m = steel<3>(Analysis::ThreeD);
  Sym<3> s, e = Sym<3>::Zero();
  s << 30e6, -10e6, 5e6, 7e6, -3e6, 2e6;
  Mat<3> L;
  L << 0.0, -0.7, 0.2, 0.7, 0.0, -0.4, -0.2, 0.4, 0.0;  // a spin about (0.4, 0.2, 0.7)
  const auto invariants = [](const Sym<3>& t) {
    Mat<3> T;
    T << t[0], t[3], t[5], t[3], t[1], t[4], t[5], t[4], t[2];
    return Vec<3>(T.trace(), (T * T).trace(), T.determinant());
  };
  const Vec<3> i0 = invariants(s);
  for (int k = 0; k < 100000; ++k) m.update(s, e, L, 1e-3);
  const Vec<3> i1 = invariants(s);
  EXPECT_NEAR(i1[0], i0[0], 1e-9 * 30e6);
  EXPECT_NEAR(i1[1], i0[1], 1e-9 * i0[1]);
  EXPECT_NEAR(i1[2], i0[2], 1e-9 * std::abs(i0[2]));
}

// The strain the solver takes from the stress (strain_from_stress, where it does not carry it) is
// the strain the full update carries, after a run of random stretches, shears and spins from rest, in
// plane strain, plane stress and 3D; and the stress-only update gives the full update's stress.
template <int Dim>
void expect_strain_from_stress(Analysis a) {
  const auto m = steel<Dim>(a);
  Sym<Dim> s = Sym<Dim>::Zero(), e = Sym<Dim>::Zero(), s_only = Sym<Dim>::Zero();
  uint64_t state = 11;
  const auto uniform = [&] { return state = state * 6364136223846793005ULL + 1442695040888963407ULL, double(state >> 11) * 0x1.0p-53 - 0.5; };
  for (int k = 0; k < 2000; ++k) {
    Mat<Dim> L;
    for (int i = 0; i < Dim; ++i)
      for (int j = 0; j < Dim; ++j) L(i, j) = 2e-3 * uniform();
    L += spin_z<Dim>(0.5 * uniform());  // (spins far larger than the strain rates)
    m.update_inline(s, e, L, 1e-3);
    m.update_stress_inline(s_only, L, 1e-3);
  }
  Sym<Dim> derived;
  ASSERT_TRUE(m.strain_from_stress(s, derived));
  const double scale = e.cwiseAbs().maxCoeff();
  ASSERT_GT(scale, 1e-5);
  for (int i = 0; i < Sym<Dim>::RowsAtCompileTime; ++i) {
    EXPECT_NEAR(derived[i], e[i], 1e-12 * scale) << "component " << i;
    EXPECT_EQ(s_only[i], s[i]) << "component " << i;
  }
}
TEST(LinearElasticUpdate, TheStrainTakenFromTheStressIsTheStrainTheUpdateCarries) {
  expect_strain_from_stress<2>(Analysis::PlaneStrain);
  expect_strain_from_stress<2>(Analysis::PlaneStress);
  expect_strain_from_stress<3>(Analysis::ThreeD);
}

}  // namespace
}  // namespace cleave
