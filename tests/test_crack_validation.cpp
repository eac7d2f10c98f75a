// 2D explicit cracks (seed 002; issue validations 1-4). Figures and the finer runs behind them:
// docs/validation.md, section "2D cracks".
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <array>
#include <map>

#include <Eigen/Geometry>

#include "libmpm/crack/tip_parameters.hpp"
#include "libmpm/io/crack_output.hpp"
#include "support.hpp"

namespace cleave {
namespace {

using nlohmann::json;

json scene(const char* name) { return load_scene_file(std::string(CLEAVE_SOURCE_DIR "/data/scenes/") + name); }

// Validation 1, the crack patch test (seed 002 §3.1): the top half of the cracked DCB equals the
// half model with symmetry conditions on the ligament, particle by particle, over the whole run.
// Contact is off in the full model ("none"): the half model has no way to keep its crack face from
// crossing the mid-plane, and under the dynamic load it does cross it (by up to 0.95 um, found by
// running it: flexural waves close the faces briefly), which frictionless contact in the full model
// rightly prevents. Linear shape functions, as in the paper: with uGIMP a particle whose domain
// reaches below the mid-plane couples the two halves through nodes the half model lacks.
TEST(CrackPatch, TopHalfOfCrackedDcbEqualsHalfModelWithSymmetry) {
  json full = scene("dcb_crack.json"), half = scene("dcb_half.json");
  full["cracks"][0]["contact"] = {{"law", "none"}};
  Model<2> mf = build_model<2>(full), mh = build_model<2>(half);
  ASSERT_EQ(mf.particles.size(), 2 * mh.particles.size());
  ASSERT_EQ(mf.dt, mh.dt);
  const std::vector<std::size_t> twin = test::twins(mf.particles, mh.particles);
  ASSERT_EQ(twin.size(), mh.particles.size());  // every particle of the half model has its twin
  auto sf = make_stepper<2>(mf), sh = make_stepper<2>(mh);
  test::TwinDifference<2> d;
  const long steps = std::lround(mf.end_time / mf.dt);
  for (long k = 0; k < steps; ++k) {
    ASSERT_FALSE(sf->step());
    ASSERT_FALSE(sh->step());
    if (k % 100 == 99 || k == steps - 1) d.add(mf.particles, mh.particles, twin, 0.1);  // length 100 mm
  }
  const double worst_x = d.x, worst_s = d.stress;
  EXPECT_LT(worst_x, 1e-10);
  EXPECT_LT(worst_s, 1e-10);
  std::printf("crack patch test over %ld steps: max relative difference %.2e (positions), %.2e (stresses)\n", steps,
              worst_x, worst_s);
}

// Validation 2: static DCB opening (damped) against beam theory with shear and root rotation
// (validation.md §3: C = 8a^3/(E b h^3) + 12a/(5 G b h) with a -> a + 0.64 h), within 5 % in
// compliance. The load-point deflection is the mean displacement of the end column of particles.
TEST(CrackDcb, StaticComplianceMatchesBeamTheoryWithShear) {
  Model<2> m = build_model<2>(scene("dcb_crack.json"));
  auto st = make_stepper<2>(m);
  while (st->time() < m.end_time - 1e-9 * m.dt) ASSERT_FALSE(st->step());
  const double opening = test::dcb_load_point_opening(m.particles);
  const double P_load = 0.4e-3, E = 1e5, nu = 0.33, G = E / (2 * (1 + nu)), b = 1e-3, h = 18e-3;
  const double a = 50e-3 + 0.64 * h;
  const double C_theory = 8 * a * a * a / (E * b * h * h * h) + 12 * a / (5 * G * b * h);
  const double C = opening / P_load;
  std::printf("DCB compliance: MPM %.4f m/N, beam theory with shear and root rotation %.4f m/N (%+.2f %%)\n", C,
              C_theory, 100 * (C / C_theory - 1));
  EXPECT_NEAR(C / C_theory, 1.0, 0.05);
}

// Validation 3: colliding cracked disks (seed 002 §3.2). Total momentum is conserved to 1e-10 of
// the disks' momentum magnitude with every contact law and both detection methods: contact changes
// the momenta of the two fields by equal and opposite amounts.
struct Collision {
  double momentum_error = 0;  // max |sum m v| / sum m |v0|
  double min_gap = 1e300;     // min normal opening over all crack points and steps (m)
  long contacts = 0;
};

Collision collide(const std::string& law, const std::string& detection) {
  json s = scene("colliding_disks.json");
  s["time"]["end"] = 12.0;  // ms: impact, rebound and the first vibrations of both cracks
  for (auto& c : s["cracks"]) {
    c["contact"] = {{"law", law}, {"detection", detection}};
    if (law == "friction") c["contact"]["mu"] = 0.3;
  }
  Model<2> m = build_model<2>(s);
  double scale = 0;
  for (std::size_t p = 0; p < m.particles.size(); ++p) scale += m.particles.mass[p] * m.particles.v[p].norm();
  auto st = make_stepper<2>(m);
  Collision r;
  while (st->time() < m.end_time - 1e-9 * m.dt) {
    EXPECT_FALSE(st->step());
    Vec<2> mom = Vec<2>::Zero();
    for (std::size_t p = 0; p < m.particles.size(); ++p) mom += m.particles.mass[p] * m.particles.v[p];
    r.momentum_error = std::max(r.momentum_error, mom.norm() / scale);
    for (const auto& c : m.cracks)
      for (std::size_t i = 0; i < c.points.size(); ++i) r.min_gap = std::min(r.min_gap, io::crack_opening(c, i)[0]);
  }
  return r;
}

// (law, detection); strings so that CTest names show the values rather than pointers.
using LawDetection = std::pair<std::string, std::string>;
class CollidingDisks : public ::testing::TestWithParam<LawDetection> {};

TEST_P(CollidingDisks, ConserveMomentum) {
  const auto [law, detection] = GetParam();
  const Collision r = collide(law, detection);
  std::printf("colliding disks, %s contact, %s detection: momentum error %.2e, min crack-face gap %.4f cells\n",
              law.c_str(), detection.c_str(), r.momentum_error, r.min_gap / 1e-3);
  EXPECT_LT(r.momentum_error, 1e-10);
}

// The criterion: crack faces never cross, i.e. the minimum signed normal gap between the
// tracked crack surfaces (crack.above / crack.below, what cracks_*.vtu shows as the faces) over the
// run is >= -1 % of a cell. Contact detection therefore also reads these surfaces
// (CrackFields::flag_closing_surfaces): with the node-averaged indicators alone the faces near the
// left crack's tips crossed by 12 % (volume) and 15 % (displacement) of a cell while closing after
// the wide opening (docs/validation.md).
TEST_P(CollidingDisks, CrackFacesNeverCross) {
  const auto [law, detection] = GetParam();
  const Collision r = collide(law, detection);
  std::printf("colliding disks, %s contact, %s detection: min crack-face gap %.4f cells\n", law.c_str(),
              detection.c_str(), r.min_gap / 1e-3);
  EXPECT_GE(r.min_gap, -0.01 * 1e-3);
}

INSTANTIATE_TEST_SUITE_P(LawsAndDetections, CollidingDisks,
                         ::testing::Values(LawDetection{"stick", "volume"}, LawDetection{"frictionless", "volume"},
                                           LawDetection{"friction", "volume"}, LawDetection{"stick", "displacement"},
                                           LawDetection{"frictionless", "displacement"},
                                           LawDetection{"friction", "displacement"}),
                         [](const auto& info) { return info.param.first + "_" + info.param.second; });

// Validation 4: a cracked plate whose two halves are set moving apart (the crack opens, the
// ligaments stretch, and after about 4 ms the crack closes again) gives the same crack-relative
// result when the whole plate also translates and rotates rigidly. Both runs use the same time step
// (the stable step depends on the particle speed: a CFL-chosen step would differ by 8 %).
struct MotionRun {
  std::vector<std::vector<Vec<2>>> opening;  // per step, per crack point: (normal, tangential)
  // Per contour setting, per K sample, per tip (start, end): K_I and J1.
  std::vector<std::vector<std::array<double, 2>>> KI, J;
};

MotionRun crack_motion(double h, double vx, double omega, double end_ms, int k_samples,
                       const std::vector<crack::TipSettings>& ts, const std::string& detection = "volume") {
  json s = {{"units", {{"length", "mm"}, {"stress", "Pa"}, {"density", "g/cm3"}, {"velocity", "mm/s"},
                       {"time", "ms"}, {"inverse_time", "1/ms"}}},
            {"analysis", {{"type", "plane_stress"}, {"thickness", 1}}},
            {"grid", {{"cell_size", h}, {"min", {-30, -30}}, {"max", {30, 30}}}},
            {"mpm", {{"shape_function", "ugimp"}, {"stress_update", "USAVG"}}},
            {"materials", {test::material("soft", 1e5, 0.33, 1.5)}},
            {"cracks", {{{"name", "centre"}, {"from", {-6, 0}}, {"to", {6, 0}}, {"segment_length", h},
                          {"contact", {{"law", "frictionless"}, {"detection", detection}}}}}},
            {"time", {{"end", end_ms}, {"dt", 0.03125 * h}}}};  // CFL 0.34 with the moving plate's speed
  // (Studies: CLEAVE_MOTION_TIP_CUT and CLEAVE_MOTION_TIP_SPLIT set the crack's tip_cut and tip_split,
  // CLEAVE_MOTION_SHAPE the shape functions, CLEAVE_MOTION_LAW the contact law.)
  if (std::getenv("CLEAVE_MOTION_TIP_CUT")) s["cracks"][0]["tip_cut"] = test::env_number("CLEAVE_MOTION_TIP_CUT", 0.45);
  if (const char* split = std::getenv("CLEAVE_MOTION_TIP_SPLIT")) s["cracks"][0]["tip_split"] = split;
  if (const char* shape = std::getenv("CLEAVE_MOTION_SHAPE")) s["mpm"]["shape_function"] = shape;
  if (const char* law = std::getenv("CLEAVE_MOTION_LAW")) s["cracks"][0]["contact"]["law"] = law;
  const double w = omega;  // rad/ms about the plate centre
  s["bodies"] = {{{"name", "top"}, {"material", "soft"}, {"shape", {{"type", "rectangle"}, {"min", {-15, 0}}, {"max", {15, 15}}}},
                  {"velocity", {vx, 100}}, {"angular_velocity", w}, {"rotation_center", {0, 0}}},
                 {{"name", "bottom"}, {"material", "soft"}, {"shape", {{"type", "rectangle"}, {"min", {-15, -15}}, {"max", {15, 0}}}},
                  {"velocity", {vx, -100}}, {"angular_velocity", w}, {"rotation_center", {0, 0}}}};
  Model<2> m = build_model<2>(s);
  auto st = make_stepper<2>(m);
  const long steps = std::lround(m.end_time / m.dt);
  const long k_every = k_samples > 0 ? steps / k_samples : 0;
  MotionRun r;
  r.KI.resize(ts.size());
  r.J.resize(ts.size());
  // CLEAVE_MOTION_POINT = i: every 20 steps, crack point i's tracked opening (normal, tangential) and the
  // material's: the mean positions of the particles that started within a cell above and below it,
  // their separation less its start value turned with the body (w t), in the crack's frame.
  const long probe = std::lround(test::env_number("CLEAVE_MOTION_POINT", -1));
  std::vector<std::size_t> up, down;
  Vec<2> sep0 = Vec<2>::Zero();
  const auto mean_of = [&](const std::vector<std::size_t>& set) {
    Vec<2> x = Vec<2>::Zero();
    for (std::size_t p : set) x += m.particles.x[p];
    return Vec<2>(x / static_cast<double>(set.size()));
  };
  if (probe >= 0) {
    const Vec<2> xi = m.cracks[0].points[static_cast<std::size_t>(probe)];
    for (std::size_t p = 0; p < m.particles.size(); ++p) {
      const Vec<2> r = m.particles.x[p] - xi;
      if (std::fabs(r.x()) < 0.5e-3 * h && std::fabs(r.y()) < 1e-3 * h) (r.y() > 0 ? up : down).push_back(p);
    }
    sep0 = mean_of(up) - mean_of(down);
  }
  for (long k = 1; k <= steps; ++k) {
    EXPECT_FALSE(st->step());
    if (probe >= 0 && k % 20 == 0) {
      const auto& c = m.cracks[0];
      const std::size_t i = static_cast<std::size_t>(probe);
      const Vec<2> t = (c.points[i + 1] - c.points[i - 1]).normalized(), n(-t.y(), t.x());
      const Vec<2> d = mean_of(up) - mean_of(down) - Eigen::Rotation2Dd(w * st->time() * 1e3) * sep0;
      const Vec<2> o = io::crack_opening(c, i);
      std::printf("P %ld %.3f ms: tracked (%.5f, %.5f) mm, material (%.5f, %.5f) mm\n", k, st->time() * 1e3, o.x() * 1e3,
                  o.y() * 1e3, d.dot(n) * 1e3, d.dot(t) * 1e3);
    }
    std::vector<Vec<2>> o;
    for (std::size_t i = 0; i < m.cracks[0].points.size(); ++i) o.push_back(io::crack_opening(m.cracks[0], i));
    r.opening.push_back(std::move(o));
    if (k_every > 0 && k % k_every == 0)
      for (std::size_t c = 0; c < ts.size(); ++c) {
        std::array<double, 2> KI{0, 0}, J{0, 0};
        for (const auto& t : st->crack_tip_parameters(ts[c])) KI[t.end] = t.KI, J[t.end] = t.J1;
        r.KI[c].push_back(KI);
        r.J[c].push_back(J);
      }
  }
  return r;
}

// Largest difference between two runs over the first `fraction` of the history (all crack points,
// tips included), relative to the first run's peak over the same window.
struct MotionDifference {
  double peak_opening = 0, opening = 0;  // opening: max over steps and crack points of |Δ(n, t)|
  double peak_K = 0, K = 0;              // K_I at both tips, over the samples
  double peak_J = 0, J = 0;
};

MotionDifference motion_difference(const MotionRun& rest, const MotionRun& moving, double fraction = 1.0,
                                   std::size_t c = 0) {
  MotionDifference d;
  const auto upto = [&](std::size_t n) { return static_cast<std::size_t>(std::lround(fraction * n)); };
  for (std::size_t k = 0; k < upto(rest.opening.size()); ++k)
    for (std::size_t i = 0; i < rest.opening[k].size(); ++i) {
      d.peak_opening = std::max(d.peak_opening, rest.opening[k][i].norm());
      const double e = (moving.opening[k][i] - rest.opening[k][i]).norm();
      if (e > d.opening && std::getenv("CLEAVE_MOTION_WHERE"))
        std::printf("  larger difference %.4g mm at step %zu, point %zu of %zu: rest (%.4g, %.4g), moving (%.4g, %.4g) mm\n",
                    e * 1e3, k, i, rest.opening[k].size(), rest.opening[k][i].x() * 1e3, rest.opening[k][i].y() * 1e3,
                    moving.opening[k][i].x() * 1e3, moving.opening[k][i].y() * 1e3);
      d.opening = std::max(d.opening, e);
    }
  if (c < rest.KI.size())
    for (std::size_t k = 0; k < upto(rest.KI[c].size()); ++k)
      for (int e = 0; e < 2; ++e) {
        d.peak_K = std::max(d.peak_K, std::fabs(rest.KI[c][k][e]));
        d.K = std::max(d.K, std::fabs(moving.KI[c][k][e] - rest.KI[c][k][e]));
        d.peak_J = std::max(d.peak_J, std::fabs(rest.J[c][k][e]));
        d.J = std::max(d.J, std::fabs(moving.J[c][k][e] - rest.J[c][k][e]));
      }
  return d;
}

// The tolerance. Which particle-node lines a tip cuts depends on where it sits in its cell, so the
// discrete crack's effective tip is uncertain by about half a cell, δa = h/2, and the moving
// crack's tips sweep through the cells while the resting crack's stay put. For an opening profile
// w ∝ sqrt(a² − x²) (peak ∝ a) a shift δa changes w by a δa / sqrt(a² − x²); at the last crack point
// before a tip (x = a − h) that is δw / w_peak = δa / sqrt(2 a h) = sqrt(h / (8 a)): 14.4 % at
// h = 1 mm, a = 6 mm, shrinking as sqrt(h). The convergence study (DISABLED_ConvergenceStudy,
// docs/validation.md) finds 8.3 / 6.1 / 5.3 % at 1 / 0.5 / 0.25 mm over the opening phase (translation
// alone 8.6 / 8.2 / 5.4 %), under the bound at every cell size, though converging more slowly (order
// about 0.33). K_I and J are not compared: their differences stall well above the effective-tip
// estimate h / (4a) = 1 % at 0.25 mm (figures in docs/validation.md).
double opening_tolerance(double h, double a) { return std::sqrt(h / (8 * a)); }

// Moving/rotating vs resting plate over 0-end_ms with the given contact detection: prints the
// difference and expects it under the bound.
void expect_crack_as_at_rest(double h, double end_ms, const std::string& detection) {
  const double a = 6.0;
  const auto rest = crack_motion(h, 0, 0, end_ms, 0, {}, detection);
  const auto moving = crack_motion(h, 500, 0.01, end_ms, 0, {}, detection);  // 500 mm/s, 0.01 rad/ms
  const MotionDifference d = motion_difference(rest, moving);
  std::printf("moving/rotating cracked plate, %s detection, h %.2f mm, 0-%g ms: peak opening %.4f mm, max "
              "difference %.2f %% (bound %.2f %%)\n",
              detection.c_str(), h, end_ms, d.peak_opening * 1e3, 100 * d.opening / d.peak_opening,
              100 * opening_tolerance(h, a));
  ASSERT_GT(d.peak_opening, 0.1e-3);
  EXPECT_LT(d.opening / d.peak_opening, opening_tolerance(h, a));
}

// Opening phase, 0-4 ms (the crack opens to its peak and starts to close; its faces stay at least
// 0.08 mm apart behind the tips at every cell size, so crack contact never acts). 1 mm cells, the
// default (volume) detection: 13.01 % against 14.4 % (session 27; 13.58 % in session 25; the study read 8.31 %). 2 mm and
// 2.3 degrees over the run.
TEST(CrackMotion, RigidlyMovingAndRotatingBodyOpensItsCrackAsAtRest) { expect_crack_as_at_rest(1.0, 4, "volume"); }

// The whole 6 ms, through the closing phase where crack contact acts, with displacement detection
// (seed 000 App. B: the faces touch when their nodal displacements overlap; the crack starts
// closed, as that criterion assumes). 0.5 mm cells: 6.26 % against 10.2 % (session 27, the crack points moved at the
// discrete crack; 6.63 % before; tip_split node: 11.14 %, 10.35 % before; 1 mm: 11.23 % against
// 14.4 %; 0.25 mm: 5.99 % against 7.2 %; DISABLED_ClosingDetectionStudy). About 4 s on one thread.
TEST(CrackMotion, RigidlyMovingAndRotatingBodyClosesItsCrackAsAtRest) {
  expect_crack_as_at_rest(0.5, 6, "displacement");
}

// The same with volume detection (seed 002, the default): 6.79 % against 10.2 % at 0.5 mm (1 mm:
// 14.01 % against 14.4 %). It missed (17.78 %) while the criterion compared the volume's deficit with a
// whole cell (V_rel >= v_sep): an opening g removes g h (1 - d/h) of volume from a node at distance d
// from the crack, so approaching faces touched at g <= 0.1 h / (1 - d/h), 0.1 cell on the resting
// crack's node row and up to 0.2 cell and more where the turned crack crosses the rows. The deficit is
// now measured against the crack's own weight in the node (contact.hpp, crack_line_weight): 0.1 cell
// wherever the crack lies. About 4 s on one thread.
TEST(CrackMotion, RigidlyMovingAndRotatingBodyClosesItsCrackAsAtRestWithVolumeDetection) {
  expect_crack_as_at_rest(0.5, 6, "volume");
}

// The convergence study behind the tolerance: moving vs resting plate at 1, 0.5 and 0.25 mm cells
// over 6 ms, openings every step (over 0-4 ms and 0-6 ms), K_I and J1 at both tips every 0.25 ms with
// three contour settings. Prints the table; asserts nothing (about 3 minutes at 2 threads). Run with
// --gtest_also_run_disabled_tests --gtest_filter='CrackMotion.DISABLED_ConvergenceStudy'.
TEST(CrackMotion, DISABLED_ConvergenceStudy) {
  std::vector<crack::TipSettings> ts(3);
  ts[1].volume_term = true;
  ts[2].volume_term = true, ts[2].radius = 4;
  const char* names[3] = {"eq32 r2", "eq33 r2", "eq33 r4"};
  for (double h : {1.0, 0.5, 0.25}) {
    const auto rest = crack_motion(h, 0, 0, 6, 24, ts);
    const auto trans = crack_motion(h, 500, 0, 6, 24, ts);
    const auto both = crack_motion(h, 500, 0.01, 6, 24, ts);
    for (const auto* mv : {&trans, &both}) {
      const char* what = mv == &trans ? "translating" : "translating+rotating";
      const MotionDifference d4 = motion_difference(rest, *mv, 4.0 / 6.0), d6 = motion_difference(rest, *mv);
      std::printf("h %.2f mm, %-20s: opening 0-4 ms %.2f %%, 0-6 ms %.2f %% (bound %.2f %%)\n", h, what,
                  100 * d4.opening / d4.peak_opening, 100 * d6.opening / d6.peak_opening,
                  100 * opening_tolerance(h, 6.0));
      for (std::size_t c = 0; c < ts.size(); ++c) {
        const MotionDifference k4 = motion_difference(rest, *mv, 4.0 / 6.0, c), k6 = motion_difference(rest, *mv, 1.0, c);
        std::printf("    %s: K_I peak %.4g Pa m^0.5, diff 0-4 ms %.2f %%, 0-6 ms %.2f %% | J1 diff 0-4 ms %.2f %%, "
                    "0-6 ms %.2f %%\n",
                    names[c], k6.peak_K, 100 * k4.K / k4.peak_K, 100 * k6.K / k6.peak_K, 100 * k4.J / k4.peak_J,
                    100 * k6.J / k6.peak_J);
      }
      std::fflush(stdout);
    }
  }
}

// The closing phase with each contact detection: moving vs resting plate at 1, 0.5 and 0.25 mm
// cells (0-4 and 0-6 ms), and where the faces stop: the normal opening at 6 ms over the crack points
// behind the tips, in cells. Prints; asserts nothing (about 1 minute on one thread). Run with
// --gtest_also_run_disabled_tests --gtest_filter='CrackMotion.DISABLED_ClosingDetectionStudy'.
// CLEAVE_MOTION_CELLS (mm, comma-separated) replaces the cell sizes, CLEAVE_MOTION_DETECTION the two detections.
TEST(CrackMotion, DISABLED_ClosingDetectionStudy) {
  const char* only = std::getenv("CLEAVE_MOTION_DETECTION");
  for (double h : test::env_numbers("CLEAVE_MOTION_CELLS", "1,0.5,0.25"))
    for (const char* det : {"volume", "displacement"}) {
      if (only && std::string(only) != det) continue;
      const auto rest = crack_motion(h, 0, 0, 6, 0, {}, det);
      const auto moving = crack_motion(h, test::env_number("CLEAVE_MOTION_VX", 500),
                                       test::env_number("CLEAVE_MOTION_OMEGA", 0.01), 6, 0, {}, det);
      const MotionDifference d4 = motion_difference(rest, moving, 4.0 / 6.0), d6 = motion_difference(rest, moving);
      auto range = [&](const MotionRun& r) {  // min and max normal opening at 6 ms, interior points, / h
        const auto& o = r.opening.back();
        double lo = 1e300, hi = -1e300;
        for (std::size_t i = 1; i + 1 < o.size(); ++i) lo = std::min(lo, o[i][0]), hi = std::max(hi, o[i][0]);
        return std::array<double, 2>{lo * 1e3 / h, hi * 1e3 / h};
      };
      const auto rr = range(rest), rm = range(moving);
      std::printf("h %.2f mm, %-12s: opening 0-4 ms %.2f %%, 0-6 ms %.2f %% (bound %.2f %%); opening at 6 ms "
                  "[%.3f, %.3f] cell at rest, [%.3f, %.3f] cell moving\n",
                  h, det, 100 * d4.opening / d4.peak_opening, 100 * d6.opening / d6.peak_opening,
                  100 * opening_tolerance(h, 6.0), rr[0], rr[1], rm[0], rm[1]);
      std::fflush(stdout);
    }
}

}  // namespace
}  // namespace cleave
