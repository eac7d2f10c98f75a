// The along-front part of the 3D J's out-of-plane term (libmpm/crack/front_along_term.hpp): its
// closed form against the near-tip fields, and the term on fronts whose K_II K_III vary or not.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "libmpm/crack/front_along_term.hpp"
#include "williams_fields.hpp"

using namespace cleave;

namespace {
constexpr double kPi = 3.14159265358979323846;

// The near-tip fields of modes I, II (plane strain) and III in a front's frame (williams_fields.hpp),
// x3 along the front: displacements, and the stresses sigma_i3 the term needs.
struct NearTipField {
  double KI, KII, KIII, mu, nu;
  Vec<3> u(double x1, double x2) const { return test::williams_displacement(KI, KII, KIII, mu, nu, x1, x2); }
  // sigma_13, sigma_23, sigma_33 (plane strain: sigma_33 = nu (sigma_11 + sigma_22)).
  Vec<3> sigma3(double x1, double x2) const {
    const double r = std::hypot(x1, x2), t = std::atan2(x2, x1), g = 1 / std::sqrt(2 * kPi * r);
    const double c = std::cos(t / 2), s = std::sin(t / 2);
    return {-KIII * g * s, KIII * g * c, nu * 2 * g * (KI * c - KII * s)};
  }
  // q = sigma_i3 u_i,1 (central differences, far below r).
  double q(double x1, double x2) const {
    const double d = 1e-7 * std::hypot(x1, x2);
    const Vec<3> du = (u(x1 + d, x2) - u(x1 - d, x2)) / (2 * d);
    return sigma3(x1, x2).dot(du);
  }
  // int q dA over the circle of radius r (square: of half-side r), polar midpoint rule.
  double area_integral(double r, bool square) const {
    const int nt = 1440, nr = 100;
    double sum = 0.0;
    for (int i = 0; i < nt; ++i) {
      const double t = -kPi + (i + 0.5) * 2 * kPi / nt;
      const double rho = square ? r / std::max(std::fabs(std::cos(t)), std::fabs(std::sin(t))) : r;
      for (int j = 0; j < nr; ++j) {
        const double rr = (j + 0.5) * rho / nr;
        sum += q(rr * std::cos(t), rr * std::sin(t)) * rr * (rho / nr) * (2 * kPi / nt);
      }
    }
    return sum;
  }
};

crack::TipSettings contour(bool square) {
  crack::TipSettings s;
  s.contour = square ? crack::TipSettings::Contour::Rectangle : crack::TipSettings::Contour::Circle;
  s.radius = 2.0;
  return s;
}

// A closed circular front of radius a in the plane z = 0 (e1 outwards, e2 = +z, e3 = e1 x e2), nodes
// at angles phi_k = 2 pi k / n (reversed: -phi_k), each with K given by K(phi) and J1 = G(K) + extra(phi).
template <class KOf, class Extra>
std::vector<crack::AlongFrontNode> circular_front(double a, int n, double mu, double nu, KOf&& K, Extra&& extra,
                                                  bool reversed = false) {
  std::vector<crack::AlongFrontNode> nodes;
  for (int k = 0; k < n; ++k) {
    const double phi = (reversed ? -1.0 : 1.0) * 2 * kPi * k / n;
    crack::AlongFrontNode d;
    d.x = a * Vec<3>(std::cos(phi), std::sin(phi), 0);
    d.e3 = Vec<3>(std::cos(phi), std::sin(phi), 0).cross(Vec<3>::UnitZ());
    d.s = a * 2 * kPi * k / n;
    const Vec<3> k3 = K(phi);
    d.cod_I = k3[0], d.cod_II = k3[1], d.cod_III = k3[2] / (1 - nu);  // K_III / K_I = (1 - nu) cod_III / cod_I
    d.J1 = ((1 - nu) * (k3[0] * k3[0] + k3[1] * k3[1]) + k3[2] * k3[2]) / (2 * mu) + extra(phi);
    d.mu = mu, d.nu = nu;
    nodes.push_back(d);
  }
  return nodes;
}
}  // namespace

TEST(AlongFrontTerm, TheAreaIntegralOfTheNearTipFieldsIsLTimesOneEighthPlusNuOverMuTimesKIIKIII) {
  const double mu = 0.77e9, r = 4e-3, h = 2e-3;
  for (const double nu : {0.0, 0.298, 0.45})
    for (const bool square : {false, true}) {
      // Mode I alongside changes nothing: its products with II and III are odd in the angle.
      const NearTipField f{3e6, 2e6, 1.5e6, mu, nu};
      const double expected = crack::along_front_length(contour(square), h) * (0.125 + nu) / mu * f.KII * f.KIII;
      EXPECT_NEAR(f.area_integral(r, square), expected, 2e-4 * std::fabs(expected)) << "nu " << nu << " square " << square;
      // Each mode alone, or I with II or III: nothing.
      for (const NearTipField g : {NearTipField{3e6, 0, 0, mu, nu}, NearTipField{0, 2e6, 0, mu, nu},
                                   NearTipField{0, 0, 1.5e6, mu, nu}, NearTipField{3e6, 2e6, 0, mu, nu},
                                   NearTipField{3e6, 0, 1.5e6, mu, nu}})
        EXPECT_NEAR(g.area_integral(r, square), 0.0, 2e-4 * std::fabs(expected));
    }
}

TEST(AlongFrontTerm, LeavesJAndKAsTheyAreWhereKIIOrKIIIIsZeroAllAlongTheFront) {
  const double mu = 1e9, nu = 0.3, a = 10e-3;
  const auto none = [](double) { return 0.0; };
  for (const auto& K : {std::function<Vec<3>(double)>([](double) { return Vec<3>(1e6, 0, 0); }),
                        std::function<Vec<3>(double)>([](double phi) { return Vec<3>(1e6, 0.5e6 * std::cos(phi), 0); }),
                        std::function<Vec<3>(double)>([](double phi) { return Vec<3>(1e6, 0, 0.3e6 * std::sin(phi)); })}) {
    const auto nodes = circular_front(a, 64, mu, nu, K, none);
    const auto out = crack::subtract_along_front_term(nodes, true, 2 * kPi * a, 4e-3, 4e-3);
    for (std::size_t k = 0; k < nodes.size(); ++k) {
      EXPECT_TRUE(out[k].applied);
      EXPECT_EQ(out[k].J1, nodes[k].J1);
      const Vec<3> k3 = K(2 * kPi * double(k) / 64);
      EXPECT_NEAR(out[k].KI, k3[0], 1e-9 * 1e6);
      EXPECT_NEAR(out[k].KII, k3[1], 1e-9 * 1e6);
      EXPECT_NEAR(out[k].KIII, k3[2], 1e-9 * 1e6);
    }
  }
}

TEST(AlongFrontTerm, OnAnInclinedPennyCrackItTakesOutTheSlopeOfKIIKIIIAlongTheFrontInEitherNodeOrder) {
  // Tada's inclined penny: K_II ~ cos phi, K_III ~ sin phi. J on the contour = G(K) + the term, which
  // the function must take out again: L (1/8 + nu) / mu d(K_II K_III)/dx3, x3 along e3 = -d/ds here
  // (e3 = e1 x e2 runs against increasing phi).
  const double mu = 0.77e9, nu = 0.298, a = 10e-3, L = 4e-3;
  const double kI = 0.75e6, kII = 0.509e6, kIII = 0.357e6;
  const auto K = [&](double phi) { return Vec<3>(kI, kII * std::cos(phi), kIII * std::sin(phi)); };
  const auto term = [&](double phi) {  // d(K_II K_III)/ds = kII kIII cos(2 phi) / a; d/dx3 = -d/ds
    return -L * (0.125 + nu) / mu * kII * kIII * std::cos(2 * phi) / a;
  };
  for (const bool reversed : {false, true}) {
    // 720 nodes, reach 0.1 mm: the least-squares slope of cos 2 phi over +-0.01 rad is exact to 1e-4.
    const auto nodes = circular_front(a, 720, mu, nu, K, term, reversed);
    const auto out = crack::subtract_along_front_term(nodes, true, 2 * kPi * a, L, 0.1e-3);
    for (std::size_t k = 0; k < nodes.size(); k += 45) {
      const double phi = (reversed ? -1.0 : 1.0) * 2 * kPi * double(k) / 720;
      const Vec<3> k3 = K(phi);
      ASSERT_TRUE(out[k].applied);
      EXPECT_NEAR(out[k].J1, nodes[k].J1 - term(phi), 1e-3 * std::fabs(term(0))) << "node " << k;
      EXPECT_NEAR(out[k].KI, k3[0], 1e-3 * kI);
      EXPECT_NEAR(out[k].KII, k3[1], 1e-3 * kI);
      EXPECT_NEAR(out[k].KIII, k3[2], 1e-3 * kI);
    }
    // A (phi = 0) gains, C (90 degrees) loses.
    EXPECT_GT(out[0].J1, nodes[0].J1);
    EXPECT_LT(out[180].J1, nodes[180].J1);
  }
}

TEST(AlongFrontTerm, ANodeWithFewerThanThreeNeighboursInReachKeepsItsJ) {
  const double mu = 1e9, nu = 0.3, a = 10e-3;
  const auto K = [](double phi) { return Vec<3>(1e6, 0.5e6 * std::cos(phi), 0.3e6 * std::sin(phi)); };
  auto nodes = circular_front(a, 64, mu, nu, K, [](double) { return 0.0; });
  // A reach shorter than the node spacing (1 mm): only the node itself.
  auto out = crack::subtract_along_front_term(nodes, true, 2 * kPi * a, 4e-3, 0.5e-3);
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    EXPECT_FALSE(out[k].applied);
    EXPECT_EQ(out[k].J1, nodes[k].J1);
  }
  // Flagged neighbours do not count.
  for (std::size_t k = 0; k < nodes.size(); ++k) nodes[k].fit = k % 4 == 0;
  out = crack::subtract_along_front_term(nodes, true, 2 * kPi * a, 4e-3, 1.5e-3);
  for (std::size_t k = 0; k < nodes.size(); ++k) EXPECT_FALSE(out[k].applied);
}
