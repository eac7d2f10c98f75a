// J1 by the equivalent domain integral along 3D crack fronts (crack_tips.integral "domain";
// libmpm/mpm/crack_front_domain.hpp): the front's polyline and its weights, the integral on an exact
// field, path independence on the rod of seed 000 §4.1, the scene keys. Figures: docs/validation.md,
// "Crack-front parameters (3D)", "The domain integral".
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <utility>
#include <string>
#include <vector>

#include "libmpm/core/error.hpp"
#include "libmpm/crack/front_parameters.hpp"
#include "libmpm/mpm/crack_front_domain.hpp"
#include "libmpm/mpm/crack_front_eval.hpp"
#include "libmpm/mpm/mpm_method.hpp"
#include "libmpm/mpm/mpm_scene.hpp"
#include "support.hpp"

namespace cleave {
namespace {

using nlohmann::json;
constexpr double kPi = 3.14159265358979323846;

TEST(FrontDomain, APolylinesNearestPointAndItsWeightsIntegralAreExact) {
  // A straight front along z, nodes every 0.5 mm, as a crack's front would give them.
  const Model<3> m = build_model<3>(test::dcb_slab_scene(3, 0.1));
  const detail::FrontPolyline line(m.cracks[0], 0);
  ASSERT_GE(line.x.size(), 3u);
  const Vec<3> a = line.x.front(), b = line.x.back();
  const Vec<3> mid = 0.5 * (a + b), off = line.e1[0] * 1e-3 + Vec<3>(0, 0.4e-3, 0);
  const auto n = line.nearest(mid + off);
  EXPECT_NEAR(n.r, off.norm(), 1e-15);
  EXPECT_NEAR(n.s, 0.5 * line.length, 1e-15);
  EXPECT_NEAR(n.e1.dot(line.e1[0]), 1.0, 1e-15);
  // Beyond an end the nearest point is the end.
  EXPECT_NEAR(line.nearest(a + (a - b)).s, 0.0, 1e-15);
  // The weight along the front, the smooth step b(|s - s_j| / L) = 1 - 10 u^3 + 15 u^4 - 6 u^5: L at an
  // interior node far from the ends, L / 2 at an end node; a weight longer than the front from node 0:
  // L (u - 2.5 u^4 + 3 u^5 - u^6) with u = length / L.
  const double L = 0.25 * line.length;
  EXPECT_NEAR(line.psi_integral(line.s[line.x.size() / 2], L), L, 1e-12 * L);
  EXPECT_NEAR(line.psi_integral(0.0, L), 0.5 * L, 1e-12 * L);
  const double L2 = 4 * line.length, u = 0.25;
  EXPECT_NEAR(line.psi_integral(0.0, L2), L2 * (u - 2.5 * std::pow(u, 4) + 3 * std::pow(u, 5) - std::pow(u, 6)), 1e-12 * L2);
  // With the slab's symmetry planes z = 0 and 2 mm (the front's end nodes lie on them) each end is
  // continued by the mirror image of the front: node 0 stays node 0, the planes cross at the end nodes.
  const detail::FrontPolyline mirrored(m.cracks[0], 0, m.symmetry_planes, m.grid.h, 1e-3);
  ASSERT_EQ(mirrored.planes.size(), 2u);
  ASSERT_GT(mirrored.first, 0u);
  EXPECT_EQ(mirrored.x[mirrored.first], a);
  EXPECT_NEAR(mirrored.x[mirrored.first - 1].z(), 2 * a.z() - line.x[1].z(), 1e-15);  // node 1's image
  EXPECT_NEAR(mirrored.planes[0], mirrored.node_s(0), 1e-15);
  EXPECT_NEAR(mirrored.planes[1], mirrored.node_s(line.x.size() - 1), 1e-15);
  const Vec<3> beyond = a + (a - b).normalized() * 2e-4 + Vec<3>(0, 1e-4, 0);  // beyond the plane: the image
  EXPECT_NEAR(mirrored.nearest(beyond).r, 1e-4, 1e-15);
  EXPECT_EQ(detail::smooth_step(0.0), 1.0);
  EXPECT_EQ(detail::smooth_step(1.0), 0.0);
  EXPECT_NEAR(detail::smooth_step(0.5), 0.5, 1e-15);
  EXPECT_NEAR(detail::smooth_step_slope(0.5), -1.875, 1e-15);
}

// The tube (FrontTube) against the weight taken particle by particle about each node: q = phi psi e1
// and its gradient from the whole front's nearest point, the node's rigid rotation taken out of the
// displacement gradient, on the rod's quarter-elliptical front (mirrored at both symmetry planes) with
// made-up fields. The tube reads each particle once for all nodes and searches only the segments near
// its cell: the same particles and the same sums to round-off.
TEST(FrontDomain, ATubeReadsEachParticleOnceAndGivesTheSumOfTheWeightsTakenParticleByParticle) {
  const Model<3> m = build_model<3>(load_scene_file(CLEAVE_SOURCE_DIR "/data/scenes/rod_elliptical_crack.json"));
  const auto& P = m.particles;
  const double h = m.grid.h, R = 2 * h, R_in = h, L = 3 * h;
  const detail::FrontPolyline line(m.cracks[0], 0, m.symmetry_planes, h, R + L + 2 * h);
  ASSERT_EQ(line.planes.size(), 2u);
  const auto made_up = [&](std::size_t p) {
    const Vec<3> x = P.x[p] * 50.0;
    detail::TubeInput in;
    in.volume = strained_volume<3>(P.volume0[p], P.strain[p]), in.mass = P.mass[p], in.W = 1.0 + x.squaredNorm();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        in.stress(i, j) = std::sin(x[i] + 2.0 * x[j] + x[i] * x[j]);
        in.grad_u(i, j) = std::cos(3.0 * x[i] - x[j] + i);
      }
    in.stress = 0.5 * (in.stress + in.stress.transpose()).eval();
    in.accel = Vec<3>(std::sin(x.x()), std::cos(x.y()), x.z());
    return in;
  };
  detail::CellBins bins;
  bins.build(m.grid, P.x, Vec<3>::Constant(-1.0), Vec<3>::Constant(1.0));  // (the whole grid)
  detail::FrontTube tube(line, R, R_in);
  tube.build(m.grid, bins, P.x, [&](int32_t p) { return made_up(static_cast<std::size_t>(p)); });
  std::size_t inside = 0;
  for (std::size_t p = 0; p < P.size(); ++p) inside += line.nearest(P.x[p]).r < R;
  EXPECT_EQ(tube.particles().size(), inside);
  ASSERT_GT(inside, 100u);
  const Vec<3> theta(1e-3, -2e-3, 3e-3);
  const std::size_t nodes = m.cracks[0].fronts[0].nodes.size();
  for (const std::size_t j : {std::size_t{0}, nodes / 2, nodes - 1}) {
    const double sj = line.node_s(j);
    std::vector<double> centres{sj};
    for (const double plane : line.planes)
      if (std::fabs(plane - sj) < L) centres.push_back(2 * plane - sj);
    double sum = 0.0, scale = 0.0;
    for (std::size_t p = 0; p < P.size(); ++p) {
      const auto nr = line.nearest(P.x[p]);
      if (!(nr.r < R)) continue;
      double psi = 0.0, dpsi = 0.0;
      for (const double c : centres) {
        const double ds = nr.s - c, u = std::fabs(ds) / L;
        psi += detail::smooth_step(u), dpsi += detail::smooth_step_slope(u) * (ds > 0 ? 1.0 : -1.0) / L;
      }
      const double u = (nr.r - R_in) / (R - R_in);
      const double phi = detail::smooth_step(u), dphi = detail::smooth_step_slope(u) / (R - R_in);
      const Vec<3> q = phi * psi * nr.e1;
      const Mat<3> Q = nr.e1 * (dphi * psi * nr.away + phi * dpsi * nr.grad_s).transpose() +
                       phi * psi * nr.de1_ds * nr.grad_s.transpose();
      const detail::TubeInput in = made_up(p);
      const Mat<3> gu = in.grad_u - detail::displacement_gradient(Sym<3>::Zero(), theta);
      const double f = in.volume * ((gu.transpose() * in.stress).cwiseProduct(Q).sum() - in.W * Q.trace()) +
                       in.mass * (gu.transpose() * in.accel).dot(q);
      sum += f, scale += std::fabs(f);
    }
    ASSERT_GT(scale, 0.0);
    const double J1 = tube.read(j, L, theta).J1 * line.psi_integral(sj, L);
    EXPECT_NEAR(J1, sum, 1e-12 * scale) << "node " << j;
  }
}

// Williams' plane-strain mode-I field about a straight front (e1 ahead, e2 the crack's normal), in
// global axes: stress, displacement and its gradient at x.
struct WilliamsModeI {
  Vec<3> x0, e1, e2;
  double K, E, nu;
  double mu() const { return E / (2 * (1 + nu)); }
  Vec<3> u(const Vec<3>& x) const {
    const Vec<3> d = x - x0;
    const double X = d.dot(e1), Y = d.dot(e2), r = std::hypot(X, Y), t = std::atan2(Y, X), k = 3 - 4 * nu;
    const double c = K / (2 * mu()) * std::sqrt(r / (2 * kPi));
    return c * std::cos(t / 2) * (k - 1 + 2 * std::pow(std::sin(t / 2), 2)) * e1 +
           c * std::sin(t / 2) * (k + 1 - 2 * std::pow(std::cos(t / 2), 2)) * e2;
  }
  Mat<3> grad_u(const Vec<3>& x, double step) const {
    Mat<3> g;
    for (int j = 0; j < 3; ++j) {
      Vec<3> dx = Vec<3>::Zero();
      dx[j] = step;
      g.col(j) = (u(x + dx) - u(x - dx)) / (2 * step);
    }
    return g;
  }
};

// Validation of the domain integral on an exact field: the particles of a block carry Williams'
// mode-I field about a straight front (stress from the strain by Hooke's law, the displacement and its
// rotation), along a grid axis and turned 30 degrees in the crack's plane. J1 = K^2 (1 - nu^2) / E at
// every front node whose tube lies in the material, within 2 % (the 2D evaluator's tolerance on an
// exact field; docs/validation.md): the particles' midpoint rule of a smooth weight.
TEST(FrontDomain, RecoversJOfAnExactModeOneFieldAlongAStraightFrontAtAnyAngleToTheGrid) {
  for (const double angle : {0.0, 30.0}) {
    const double a = angle * kPi / 180, E = 3e9, nu = 0.3, K = 1e6;
    const Vec<3> t(std::sin(a), 0, std::cos(a)), e2(0, 1, 0), e1 = e2.cross(t);  // e1 = (cos, 0, -sin)
    const Vec<3> x0(20e-3, 0, 12e-3);  // a point of the front
    // The crack: 40 mm behind the front (in mm), 60 mm along it, centred on x0; only its front edge
    // lies in the block.
    const Vec<3> start = x0 * 1e3 - 30 * t, corner = start - 40 * e1;
    json s = json::parse(R"({
      "units": {"length": "mm", "stress": "MPa", "density": "g/cm3", "time": "us"},
      "analysis": {"type": "3d"}, "resolution": 1,
      "grid": {"min": [-4, -20, -4], "max": [44, 20, 28]},
      "mpm": {"shape_function": "linear", "stress_update": "USAVG"},
      "materials": [{"name": "m", "type": "linear_elastic", "E": 3000, "nu": 0.3, "density": 1.19}],
      "bodies": [{"name": "b", "material": "m", "shape": {"type": "box", "min": [0, -16, 0], "max": [40, 16, 24]}}],
      "time": {"end": 1}})");
    s["cracks"] = {{{"name", "c"},
                    {"rectangle", {{"corner", {corner.x(), corner.y(), corner.z()}},
                                   {"edges", {{60 * t.x(), 0, 60 * t.z()}, {40 * e1.x(), 0, 40 * e1.z()}}}}}}};  // (normal +y)
    s["crack_tips"] = {{"radius", 4}, {"integral", "domain"}, {"along", 2}};
    Model<3> m = build_model<3>(s);
    const WilliamsModeI w{x0, e1, e2, K, E, nu};
    auto& P = m.particles;
    const double lam = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = w.mu();
    for (std::size_t p = 0; p < P.size(); ++p) {
      const Mat<3> g = w.grad_u(P.x[p], 1e-9);
      const Mat<3> e = 0.5 * (g + g.transpose()), W = 0.5 * (g - g.transpose());
      const Mat<3> sigma = lam * e.trace() * Mat<3>::Identity() + 2 * mu * e;
      P.strain[p] << e(0, 0), e(1, 1), e(2, 2), e(0, 1), e(1, 2), e(0, 2);
      P.stress[p] << sigma(0, 0), sigma(1, 1), sigma(2, 2), sigma(0, 1), sigma(1, 2), sigma(0, 2);
      P.rotation3[p] = Vec<3>(W(2, 1), W(0, 2), W(1, 0));
      P.u[p] = w.u(P.x[p]);
      P.v[p].setZero();
    }
    ASSERT_TRUE(detail::displacement_gradient(P.strain[0], P.rotation3[0]).isApprox(w.grad_u(P.x[0], 1e-9), 1e-12));
    const double J = K * K * (1 - nu * nu) / E;
    const auto zero = [](std::size_t) { return Vec<3>::Zero(); };
    int checked = 0;
    for (const bool inertia : {false, true}) {  // (no acceleration: the inertia term adds nothing)
      crack::TipSettings ts = *m.crack_tips;
      ts.volume_term = inertia;
      for (const auto& r : crack_front_records<LinearShape>(m, ts, zero)) {
        // (Nodes whose tube and weight along the front lie 4 mm or more inside the block's faces z = 0 and 24 mm.)
        if (r.flag != 0 || r.x.z() < 8e-3 || r.x.z() > 16e-3) continue;
        std::printf("%g deg, node %d at (%.2f, %.2f) mm: J1 / J = %.4f, |K_I| / K = %.4f, K_II %.2g, K_III %.2g\n", angle,
                    r.node, r.x.x() * 1e3, r.x.z() * 1e3, r.J1 / J, std::fabs(r.KI) / K, r.KII / K, r.KIII / K);
        EXPECT_NEAR(r.J1 / J, 1.0, 0.02) << angle << " deg, node " << r.node;
        ++checked;
      }
    }
    EXPECT_GE(checked, 10) << angle << " deg";  // (the nodes whose tube and weight lie in the block)
  }
}

// The rod of seed 000 §4.1 at the seed's 3 mm cells, undamped, to end_us; and the front node at its deepest
// point A (x = 0, y = 20 mm).
json rod_at_three_millimetres(double end_us) {
  json s = load_scene_file(CLEAVE_SOURCE_DIR "/data/scenes/rod_elliptical_crack.json");
  s["resolution"] = 3;
  s["time"]["end"] = end_us;
  s.erase("output");
  return s;
}
crack::FrontRecord at_A(const std::vector<crack::FrontRecord>& fronts) {
  const auto A = std::min_element(fronts.begin(), fronts.end(), [](const auto& a, const auto& b) {
    return (a.x - Vec<3>(0, 0.02, 0)).norm() < (b.x - Vec<3>(0, 0.02, 0)).norm();
  });
  EXPECT_LT((A->x - Vec<3>(0, 0.02, 0)).norm(), 1e-4);
  return *A;
}

// Validation 3's path independence: the rod of seed 000 §4.1 at 3 mm cells (the seed's; about 20 s on two
// cores), undamped under its step load, at 60 us (near the peak of K_I(t)) and 90 us. The domain integral (crack_tips.integral
// "domain", eq. 33's inertia term) over tubes of the seed's radii 6, 9 and 18 mm about the front gives
// K_I at the deepest point A within 3 % of the 6 mm tube's (the issue's tolerance). The plane contour
// (eq. 33 with the out-of-plane term) of the same states is printed, not asserted: it parts by up to
// 13 % in K_I at 18 mm (docs/validation.md, "The domain integral").
TEST(CrackFrontK, RodsDomainIntegralOverTubesOfSixNineAndEighteenMillimetresGivesTheSameKIAtTheDeepestPoint) {
  Model<3> m = build_model<3>(rod_at_three_millimetres(90));
  auto st = make_stepper<3>(m);
  long done = 0;
  for (const double t_us : {60.0, 90.0}) {
    const long steps = std::lround(t_us * 1e-6 / m.dt);
    ASSERT_FALSE(test::advance(*st, steps - done));
    done = steps;
    double K6[2] = {0, 0};
    for (const bool domain : {true, false})
      for (const double r_mm : {6.0, 9.0, 18.0}) {
        crack::TipSettings ts = *m.crack_tips;
        ts.radius = r_mm / 3.0, ts.volume_term = true;
        ts.integral = domain ? crack::TipSettings::Integral::Domain : crack::TipSettings::Integral::Contour;
        const auto A = at_A(st->crack_front_parameters(ts));
        if (r_mm == 6.0) K6[domain] = A.KI;
        std::printf("%g us, %s %g mm: K_I(A) %.4g MPa m^1/2 (%+.2f %% of the 6 mm one), J1 %.4g J/m^2, flag %d\n", t_us,
                    domain ? "domain, tube" : "contour (eq. 33)", r_mm, A.KI / 1e6, 100 * (A.KI / K6[domain] - 1), A.J1,
                    A.flag);
        if (!domain) continue;
        EXPECT_EQ(A.flag, 0) << t_us << " us, " << r_mm << " mm";
        EXPECT_NEAR(A.KI / K6[1], 1.0, 0.03) << t_us << " us, " << r_mm << " mm";
      }
  }
}

// Study (not run in the suite; about a minute on two cores): validation 3's path independence in J with
// the domain integral's weight varied on the same states: the rod at 3 mm cells, undamped, every 5 us from
// 30 to 100 us, J1 at A with tubes of 9 and 18 mm against 6 mm, for each pair of CLEAVE_DOMAIN_ALONG and
// CLEAVE_DOMAIN_INNER (lists, "4,6" and "0.5,0.5" by default), with eq. 33's inertia (CLEAVE_DOMAIN_INERTIA=0:
// without).
TEST(FrontDomainStudy, DISABLED_PathIndependenceByWeight) {
  Model<3> m = build_model<3>(rod_at_three_millimetres(100));
  auto st = make_stepper<3>(m);
  const std::vector<double> along = test::env_numbers("CLEAVE_DOMAIN_ALONG", "4,6"),
                            inner = test::env_numbers("CLEAVE_DOMAIN_INNER", "0.5,0.5");
  ASSERT_EQ(along.size(), inner.size());
  std::vector<std::pair<double, double>> weights;
  for (std::size_t w = 0; w < along.size(); ++w) weights.push_back({along[w], inner[w]});
  const char* inertia_env = std::getenv("CLEAVE_DOMAIN_INERTIA");
  const bool inertia = !inertia_env || std::string(inertia_env) != "0";
  // CLEAVE_DOMAIN_CENTRED=1: the accelerations centred on the state, (v(n + 1) - v(n - 1)) / 2 dt, instead of
  // the last step's (one more step and a copy of the model per sample).
  // CLEAVE_DOMAIN_CENTRED=2: the next step's, (v(n + 1) - v(n)) / dt, from the stresses of the state.
  const int accel_mode = std::getenv("CLEAVE_DOMAIN_CENTRED") ? std::atoi(std::getenv("CLEAVE_DOMAIN_CENTRED")) : 0;
  const bool centred = accel_mode == 1 || accel_mode == 2;
  std::vector<std::array<double, 2>> worst(weights.size(), {0.0, 0.0});
  long done = 0;
  for (int t_us = 30; t_us <= 100; t_us += 5) {
    const long steps = std::lround(t_us * 1e-6 / m.dt);
    ASSERT_FALSE(test::advance(*st, steps - done - 1));
    const std::vector<Vec<3>> v_before = m.particles.v;
    ASSERT_FALSE(test::advance(*st, 1));
    done = steps;
    // (centred: the state's particles and cracks kept, swapped in for the evaluations, then back.)
    std::optional<Particles<3>> particles;
    std::optional<decltype(m.cracks)> cracks;
    std::vector<Vec<3>> a_centred;
    if (centred) {
      particles.emplace(m.particles), cracks.emplace(m.cracks);
      const std::vector<Vec<3>> v_state = m.particles.v;
      ASSERT_FALSE(test::advance(*st, 1));
      ++done;
      a_centred.resize(m.particles.size());
      for (std::size_t p = 0; p < a_centred.size(); ++p)
        a_centred[p] = accel_mode == 1 ? Vec<3>((m.particles.v[p] - v_before[p]) / (2 * m.dt))
                                       : Vec<3>((m.particles.v[p] - v_state[p]) / m.dt);
      std::swap(m.particles, *particles), std::swap(m.cracks, *cracks);
    }
    std::printf("%3d us:", t_us);
    for (std::size_t w = 0; w < weights.size(); ++w) {
      double J[3] = {0, 0, 0};
      int i = 0;
      for (const double r_mm : {6.0, 9.0, 18.0}) {
        crack::TipSettings ts = *m.crack_tips;
        ts.radius = r_mm / 3.0, ts.volume_term = inertia, ts.along = weights[w].first, ts.inner = weights[w].second;
        ts.integral = crack::TipSettings::Integral::Domain;
        const auto fronts = centred ? crack_front_records<LinearShape>(m, ts, [&](std::size_t p) { return a_centred[p]; })
                                    : st->crack_front_parameters(ts);
        J[i++] = at_A(fronts).J1;
      }
      for (int k = 0; k < 2; ++k) worst[w][k] = std::max(worst[w][k], std::fabs(J[k + 1] / J[0] - 1));
      std::printf("  [%g:%g] J6 %.4g, 9 %+.1f %%, 18 %+.1f %%", weights[w].first, weights[w].second, J[0],
                  100 * (J[1] / J[0] - 1), 100 * (J[2] / J[0] - 1));
    }
    std::printf("\n");
    if (centred) std::swap(m.particles, *particles), std::swap(m.cracks, *cracks);
  }
  for (std::size_t w = 0; w < weights.size(); ++w)
    std::printf("along %g, inner %g: largest difference from 6 mm, 9 mm %.1f %%, 18 mm %.1f %%\n", weights[w].first,
                weights[w].second, 100 * worst[w][0], 100 * worst[w][1]);
}

TEST(FrontDomain, ItsKeysAreCheckedAndBelongToTheDomainIntegralOf3DScenesOnly) {
  json s = test::penny_block_scene(2.0);
  s["crack_tips"]["integral"] = "tube";
  EXPECT_EQ(test::error_of([&] { build_model<3>(s); }).key_path(), "crack_tips.integral");
  s["crack_tips"]["integral"] = "contour";
  s["crack_tips"]["along"] = 3;
  EXPECT_EQ(test::error_of([&] { build_model<3>(s); }).key_path(), "crack_tips.along");
  s["crack_tips"]["integral"] = "domain";
  s["crack_tips"]["along"] = 0.5;
  EXPECT_EQ(test::error_of([&] { build_model<3>(s); }).key_path(), "crack_tips.along");
  s["crack_tips"]["along"] = 3;
  s["crack_tips"]["inner"] = 1;
  EXPECT_EQ(test::error_of([&] { build_model<3>(s); }).key_path(), "crack_tips.inner");
  s["crack_tips"]["inner"] = 0.25;
  const Model<3> m = build_model<3>(s);
  EXPECT_EQ(m.crack_tips->integral, crack::TipSettings::Integral::Domain);
  EXPECT_EQ(m.crack_tips->along, 3.0);
  EXPECT_EQ(m.crack_tips->inner, 0.25);
  json d = load_scene_file(CLEAVE_SOURCE_DIR "/data/scenes/dcb_crack.json");
  d["crack_tips"] = {{"integral", "domain"}};
  EXPECT_EQ(test::error_of([&] { build_model<2>(d); }).key_path(), "crack_tips.integral");
}

}  // namespace
}  // namespace cleave
