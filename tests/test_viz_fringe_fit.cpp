// K from fringes (viz/fit): the Williams series, the multi-point fringe-order fit and Irwin's
// two-point estimate, on synthetic fringes whose K is known exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "viz/fit/fringe_fit.hpp"
#include "viz/fit/williams.hpp"

using namespace cleave::viz;
namespace {
const double kPi = std::numbers::pi;
// Polycarbonate at 546 nm and the strip of issue 21: f_sigma = 7 N/mm/fringe, t = 5.7 mm.
const double kF = 7e3, kT = 5.7e-3;

std::array<double, 3> cartesian_term(int n, double A, double B, double x, double y) {
  return williams_term(n, A, B, std::hypot(x, y), std::atan2(y, x));
}

// Points on the fringe loops of `field` (orders 1, 1.5, ... up to the highest met) between r0 and r1
// from the tip, every `step` degrees: what a user digitises along the fringes' centre lines.
std::vector<FringePoint> loop_points(const TipField& field, double r0, double r1, double step_deg = 5) {
  std::vector<FringePoint> pts;
  const double S = kF / kT;
  for (double deg = -175; deg <= 175.01; deg += step_deg) {
    const double th = field.alpha + deg * kPi / 180;
    auto N = [&](double r) { return field.stress_difference(field.x0 + r * std::cos(th), field.y0 + r * std::sin(th)) / S; };
    const int n = 400;
    double ra = r0, Na = N(ra);
    for (int i = 1; i <= n; ++i) {
      const double rb = r0 * std::pow(r1 / r0, double(i) / n), Nb = N(rb);
      for (double order = 0.5; order < 40; order += 0.5) {
        if ((Na - order) * (Nb - order) >= 0) continue;
        double lo = ra, hi = rb;
        for (int it = 0; it < 60; ++it) {
          const double mid = 0.5 * (lo + hi);
          ((N(lo) - order) * (N(mid) - order) <= 0 ? hi : lo) = mid;
        }
        const double r = 0.5 * (lo + hi);
        pts.push_back({field.x0 + r * std::cos(th), field.y0 + r * std::sin(th), order});
      }
      ra = rb, Na = Nb;
    }
  }
  return pts;
}

TipField strip_like_field() {
  TipField f = tip_field_from_K(0.0089, 0.0, 0.0, 0.55e6, 0.12e6, -1.5e6);  // K_I, K_II in Pa m^0.5, T in Pa
  f.a.push_back(2.0e7), f.b.push_back(-0.8e7);                             // A_3, B_3 (Pa m^-0.5)
  return f;
}

FringeFitOptions options_for(const TipField& f, int terms) {
  FringeFitOptions o;
  o.terms = terms, o.x0 = f.x0, o.y0 = f.y0, o.alpha = f.alpha, o.fringe_constant = kF, o.thickness = kT;
  return o;
}
}  // namespace

TEST(WilliamsSeries, EveryTermIsFreeOfTractionOnTheFacesInEquilibriumAndCompatible) {
  for (int n = 1; n <= 6; ++n)
    for (auto [A, B] : {std::pair{1.0, 0.0}, std::pair{0.0, 1.0}}) {
      for (double th : {kPi - 1e-13, -kPi + 1e-13}) {
        const auto s = williams_term(n, A, B, 0.7, th);
        EXPECT_NEAR(s[1], 0, 1e-11) << "n " << n;
        EXPECT_NEAR(s[2], 0, 1e-11) << "n " << n;
      }
      const double x = 0.3, y = 0.4, h = 1e-5;
      auto d = [&](int i, double dx, double dy) {
        return (cartesian_term(n, A, B, x + dx, y + dy)[i] - cartesian_term(n, A, B, x - dx, y - dy)[i]) / (2 * std::hypot(dx, dy));
      };
      EXPECT_NEAR(d(0, h, 0) + d(2, 0, h), 0, 1e-6) << "n " << n;  // d sxx/dx + d sxy/dy
      EXPECT_NEAR(d(2, h, 0) + d(1, 0, h), 0, 1e-6) << "n " << n;  // d sxy/dx + d syy/dy
      auto trace = [&](double px, double py) {
        const auto s = cartesian_term(n, A, B, px, py);
        return s[0] + s[1];
      };
      const double g = 1e-3;
      const double lap = (trace(x + g, y) + trace(x - g, y) + trace(x, y + g) + trace(x, y - g) - 4 * trace(x, y)) / (g * g);
      EXPECT_NEAR(lap, 0, 1e-4) << "n " << n;  // plane elasticity: the trace is harmonic
    }
}

TEST(WilliamsSeries, TheFirstTermsAreIrwinsSingularFieldsAndTheTStress) {
  const double K = 1.3e6, r = 2e-3, th = 0.6, c = K / std::sqrt(2 * kPi * r);
  const TipField I = tip_field_from_K(0, 0, 0, K, 0, 0), II = tip_field_from_K(0, 0, 0, 0, K, 0);
  const auto sI = I.tip_frame_stress(r * std::cos(th), r * std::sin(th));
  EXPECT_NEAR(sI[0], c * std::cos(th / 2) * (1 - std::sin(th / 2) * std::sin(1.5 * th)), 1e-9 * c);
  EXPECT_NEAR(sI[1], c * std::cos(th / 2) * (1 + std::sin(th / 2) * std::sin(1.5 * th)), 1e-9 * c);
  EXPECT_NEAR(sI[2], c * std::sin(th / 2) * std::cos(th / 2) * std::cos(1.5 * th), 1e-9 * c);
  const auto sII = II.tip_frame_stress(r * std::cos(th), r * std::sin(th));
  EXPECT_NEAR(sII[0], -c * std::sin(th / 2) * (2 + std::cos(th / 2) * std::cos(1.5 * th)), 1e-9 * c);
  EXPECT_NEAR(sII[1], c * std::sin(th / 2) * std::cos(th / 2) * std::cos(1.5 * th), 1e-9 * c);
  EXPECT_NEAR(sII[2], c * std::cos(th / 2) * (1 - std::sin(th / 2) * std::sin(1.5 * th)), 1e-9 * c);
  const auto sT = tip_field_from_K(0, 0, 0, 0, 0, -2e6).tip_frame_stress(1e-3, 2e-3);
  EXPECT_DOUBLE_EQ(sT[0], -2e6);
  EXPECT_DOUBLE_EQ(sT[1], 0.0);
  EXPECT_DOUBLE_EQ(sT[2], 0.0);
  EXPECT_NEAR(I.KI(), K, 1e-9 * K);
  EXPECT_NEAR(II.KII(), K, 1e-9 * K);
}

TEST(WilliamsSeries, ARotatedTipFrameGivesTheSameFringesAsTheRotatedPoints) {
  TipField a = strip_like_field(), b = a;
  b.alpha = 0.7, b.x0 = 0.01, b.y0 = -0.02;
  const double r = 4e-3, th = 1.1;
  EXPECT_NEAR(a.stress_difference(a.x0 + r * std::cos(th), a.y0 + r * std::sin(th)),
              b.stress_difference(b.x0 + r * std::cos(th + 0.7), b.y0 + r * std::sin(th + 0.7)), 1e-6);
}

TEST(FringeFit, NoiseFreeFringeLoopsGiveBackKITAndKIIWithin1Percent) {
  const TipField truth = strip_like_field();
  const auto pts = loop_points(truth, 1e-3, 9e-3);
  ASSERT_GT(pts.size(), 100u);
  const auto r = fit_fringe_orders(pts, options_for(truth, 3));
  EXPECT_NEAR(r.parameter("K_I").value, truth.KI(), 0.01 * truth.KI());
  EXPECT_NEAR(r.parameter("K_II").value, truth.KII(), 0.01 * truth.KI());
  EXPECT_NEAR(r.parameter("T").value, truth.T(), 0.01 * std::abs(truth.T()));
  EXPECT_LT(r.rms, 1e-6);  // exact data, the same series: fitted exactly
  EXPECT_EQ(r.degrees_of_freedom, int(pts.size()) - 5);
}

TEST(FringeFit, TenthOfAFringeOfNoiseGivesKWithin5PercentAndIntervalsThatCoverTheTruth) {
  const TipField truth = strip_like_field();
  const auto clean = loop_points(truth, 1e-3, 9e-3, 10);
  int covered = 0, runs = 40, worst_pct = 0;
  for (int seed = 1; seed <= runs; ++seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, 0.1);
    auto pts = clean;
    for (auto& p : pts) p.N += noise(rng);
    const auto r = fit_fringe_orders(pts, options_for(truth, 3));
    const auto& K = r.parameter("K_I");
    EXPECT_NEAR(K.value, truth.KI(), 0.05 * truth.KI()) << "seed " << seed;
    EXPECT_NEAR(r.parameter("K_II").value, truth.KII(), 0.05 * truth.KI()) << "seed " << seed;
    worst_pct = std::max(worst_pct, int(std::ceil(100 * std::abs(K.value / truth.KI() - 1))));
    if (std::abs(K.value - truth.KI()) <= 1.96 * K.std_error) ++covered;
    EXPECT_NEAR(r.rms, 0.1, 0.02);  // the residual is the noise
  }
  // 95 % intervals: at least 34 of 40 cover (binomial, p = 0.95: P(fewer than 34) < 1 %).
  EXPECT_GE(covered, 34) << "worst K_I error " << worst_pct << " %";
}

TEST(FringeFit, TheTipPositionAndTheCrackDirectionCanBeUnknowns) {
  const TipField truth = strip_like_field();
  const auto pts = loop_points(truth, 1e-3, 9e-3);
  auto o = options_for(truth, 3);
  o.x0 += 0.4e-3, o.y0 -= 0.3e-3, o.alpha = 0.05;  // a tip marked 0.5 mm and 3 degrees off
  o.fit_tip = o.fit_angle = true;
  const auto r = fit_fringe_orders(pts, o);
  EXPECT_NEAR(r.parameter("x0").value, truth.x0, 1e-6);
  EXPECT_NEAR(r.parameter("y0").value, truth.y0, 1e-6);
  EXPECT_NEAR(r.parameter("alpha").value, truth.alpha, 1e-4);
  EXPECT_NEAR(r.parameter("K_I").value, truth.KI(), 0.01 * truth.KI());
}

TEST(FringeFit, ResidualsAreReportedPerPointAndPerFringeOrder) {
  const TipField truth = strip_like_field();
  auto pts = loop_points(truth, 1e-3, 9e-3);
  pts[3].N += 0.5;  // one misread point
  const auto r = fit_fringe_orders(pts, options_for(truth, 3));
  ASSERT_EQ(r.residual.size(), pts.size());
  EXPECT_GT(std::abs(r.residual[3]), 0.3);
  std::size_t n = 0;
  for (const auto& o : r.orders) n += o.count;
  EXPECT_EQ(n, pts.size());
}

TEST(IrwinTwoPoint, TheApogeeSolutionEqualsTheReferencesClosedForm) {
  // validation.md section 7: K = (N f/t) sqrt(2 pi r_m)/sin th_m [1 + (2/(3 tan th_m))^2]^-1/2
  //                                 [1 + 2 tan(3 th_m/2)/(3 tan th_m)]
  for (double deg : {75.0, 85.0, 95.0, 110.0, 130.0}) {
    const double th = deg * kPi / 180, N = 3, r = 4e-3;
    const auto e = irwin_from_apogee(N, r, th, kF, kT);
    const double ref = N * kF / kT * std::sqrt(2 * kPi * r) / std::sin(th) *
                       std::pow(1 + std::pow(2 / (3 * std::tan(th)), 2), -0.5) *
                       (1 + 2 * std::tan(1.5 * th) / (3 * std::tan(th)));
    EXPECT_NEAR(e.KI, ref, 1e-9 * std::abs(ref)) << deg << " deg";
  }
}

TEST(IrwinTwoPoint, LoopsOfATwoParameterFieldGiveItsKWithin1Percent) {
  // Irwin's field: K and a uniform sigma_ox along the crack (T = -sigma_ox).
  const TipField f = tip_field_from_K(0, 0, 0, 0.55e6, 0, -0.8e6);
  const auto pts = loop_points(f, 1e-3, 9e-3, 1);
  const auto est = irwin_two_point(pts, 0, 0, 0, kF, kT);
  ASSERT_GE(est.size(), 3u);
  for (const auto& e : est) {
    EXPECT_NEAR(e.KI, f.KI(), 0.01 * f.KI()) << "order " << e.N;
    EXPECT_NEAR(e.sigma_ox, 0.8e6, 0.05 * 0.8e6) << "order " << e.N;
  }
}

TEST(FringeFit, BadInputIsRefusedWithTheReason) {
  const TipField truth = strip_like_field();
  auto o = options_for(truth, 3);
  std::vector<FringePoint> few(5, FringePoint{0.01, 0.002, 3});
  EXPECT_THROW(fit_fringe_orders(few, o), std::invalid_argument);  // 5 unknowns, 5 points
  auto pts = loop_points(truth, 1e-3, 9e-3);
  auto on_tip = pts;
  on_tip.push_back({truth.x0, truth.y0, 2});
  EXPECT_THROW(fit_fringe_orders(on_tip, o), std::invalid_argument);
  // Every point on one ray ahead of the tip: the angular terms are not determined.
  std::vector<FringePoint> ray;
  for (int i = 1; i <= 30; ++i) ray.push_back({truth.x0 + 3e-4 * i, truth.y0, 3.0 / std::sqrt(i)});
  try {
    fit_fringe_orders(ray, o);
    ADD_FAILURE() << "points on one ray accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("do not determine"), std::string::npos) << e.what();
  }
  auto bad = o;
  bad.fringe_constant = 0;
  EXPECT_THROW(fit_fringe_orders(pts, bad), std::invalid_argument);
  bad = o, bad.max_iterations = 1;
  EXPECT_THROW(fit_fringe_orders(pts, bad), FitNotConverged);
}
