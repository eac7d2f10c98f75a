// Contact between bodies (issue 18, "contact between bodies"; the scene's "contact" key): each body in
// a declared pair moves on a velocity field of its own where it meets another, coupled by the pair's
// law. Validation 5 of the issue in 2D: colliding disks come apart with momentum conserved, and a block
// slides down an inclined block at g (sin theta - mu cos theta). Figures: docs/validation.md,
// "Contact between bodies".
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "libmpm/mpm/mpm_scene.hpp"
#include "hertz_spheres.hpp"
#include "support.hpp"

namespace cleave {
namespace {

using nlohmann::json;

// Seed 002's soft disks (E = 0.1 MPa, nu = 0.33, rho = 1.5 g/cm3), 30 mm across, 1 mm thick in plane
// stress, moving towards each other at 1 m/s each from 2 mm apart, uncracked; `contact` as the
// scene's key (null: none).
json colliding_disks(const json& contact, const std::string& shape, double cell = 1.0) {
  json s = {{"units", {{"length", "mm"}, {"stress", "Pa"}, {"density", "g/cm3"}, {"velocity", "m/s"}, {"time", "ms"}}},
            {"analysis", {{"type", "plane_stress"}, {"thickness", 1}}},
            {"resolution", cell},
            {"grid", {{"min", {-30, -20}}, {"max", {62, 20}}}},
            {"mpm", {{"shape_function", shape}, {"stress_update", "USAVG"}}},
            {"materials", {test::material("soft", 1e5, 0.33, 1.5)}},
            {"bodies", {{{"name", "left"}, {"material", "soft"},
                         {"shape", {{"type", "disk"}, {"center", {0, 0}}, {"radius", 15}}}, {"velocity", {1, 0}}},
                        {{"name", "right"}, {"material", "soft"},
                         {"shape", {{"type", "disk"}, {"center", {32, 0}}, {"radius", 15}}}, {"velocity", {-1, 0}}}}},
            {"time", {{"end", 20}, {"cfl", 0.5}}}};
  if (!contact.is_null()) s["contact"] = contact;
  return s;
}

struct Collision {
  double momentum = 0;   // max |total momentum| over the run, relative to one disk's initial momentum
  double gain = 0;       // max (E - E0) / E0
  double loss = 0;       // (E0 - E_end) / E0
  double overlap = 0;    // deepest overlap of the particles' domains across the contact line, in cells
  double apart = 0;      // separation speed at the end over the approach speed (mass-centre velocities)
  double gap_end = 0;    // gap between the disks' particle domains at the end, in cells
};

Collision collide(const json& scene) {
  Model<2> m = build_model<2>(scene);
  auto st = make_stepper<2>(m);
  const auto& P = m.particles;
  const Body &L = m.bodies[0], &R = m.bodies[1];
  double mass_l = 0;
  for (std::size_t p = L.first; p < L.first + L.count; ++p) mass_l += P.mass[p];
  const double p0 = mass_l * 1.0;
  const double e0 = st->global_state().total();
  const double half = 0.5 * std::sqrt(P.volume0[0] / L.thickness);  // half a particle's spacing
  auto gap = [&] {  // along the line of centres: the right disk's leftmost domain edge less the left's rightmost
    double xl = -1e300, xr = 1e300;
    for (std::size_t p = L.first; p < L.first + L.count; ++p) xl = std::max(xl, P.x[p].x() + half);
    for (std::size_t p = R.first; p < R.first + R.count; ++p) xr = std::min(xr, P.x[p].x() - half);
    return (xr - xl) / m.grid.h;
  };
  Collision c;
  const long steps = std::lround(m.end_time / m.dt);
  for (long k = 0; k < steps; ++k) {
    EXPECT_FALSE(st->step());
    const auto g = st->global_state();
    c.momentum = std::max(c.momentum, g.momentum.norm() / p0);
    c.gain = std::max(c.gain, (g.total() - e0) / e0);
    c.overlap = std::max(c.overlap, -gap());
  }
  c.loss = (e0 - st->global_state().total()) / e0;
  auto mean_vx = [&](const Body& b) {
    double mv = 0, mm = 0;
    for (std::size_t p = b.first; p < b.first + b.count; ++p) mv += P.mass[p] * P.v[p].x(), mm += P.mass[p];
    return mv / mm;
  };
  c.apart = (mean_vx(R) - mean_vx(L)) / 2.0;
  c.gap_end = gap();
  return c;
}

// Momentum: each exchange moves dp from one field to the other, so the total is conserved to
// rounding (the issue asks 1e-10). Energy: a contact exchange equalises the fields' normal velocities,
// which can only take kinetic energy away; measured -0.27 % (uGIMP) and -0.30 % (linear) at 1 mm,
// -0.19 % and +0.04 % at 0.5 mm (docs/validation.md): no energy made beyond 1e-3 (rounding and the
// particle-grid transfer), and a loss below 1 %. The disks must come apart: moving away from each
// other, with a gap, their domains never overlapping by half a cell (position detection stops the
// fields 0.8 cell apart at a node, about where two bodies' mass centres lie when they touch).
void expect_elastic_collision(const Collision& c) {
  EXPECT_LT(c.momentum, 1e-10);
  EXPECT_LT(c.gain, 1e-3);
  EXPECT_LT(c.loss, 0.01);
  EXPECT_GT(c.apart, 0.5) << "the disks must rebound";
  EXPECT_GT(c.gap_end, 1.0);
  EXPECT_LT(c.overlap, 0.5);
}

TEST(BodyContact, TwoDisksCollidingHeadOnComeApartWithMomentumConservedAndNoEnergyMadeUGimp) {
  const json contact = json::array({{{"bodies", {"left", "right"}}, {"law", "frictionless"}}});
  const Collision c = collide(colliding_disks(contact, "ugimp"));
  expect_elastic_collision(c);
  RecordProperty("energy_loss", std::to_string(c.loss));
}

TEST(BodyContact, TwoDisksCollidingHeadOnComeApartWithMomentumConservedAndNoEnergyMadeLinear) {
  const json contact = json::array({{{"bodies", "all"}, {"law", "frictionless"}}});
  expect_elastic_collision(collide(colliding_disks(contact, "linear")));
}

// A block (10 x 5 mm) resting on a longer one (70 x 10 mm, its bottom rows held) under gravity tilted
// by theta = 30 degrees, so that the top face is the slope; a soft rubber (E = 10 MPa, rho = 1 g/cm3)
// lets the step be long, and g = 100 m/s^2 makes the slide a few cells in 12 ms. The base's face gives
// the normal ("normal": "base"). Returns the slider's acceleration along the slope, fitted to its
// mass-centre velocity from 2 ms (after the blocks settle under the load) to 12 ms.
double slide(const std::string& law, double mu, const std::string& shape = "ugimp") {
  constexpr double kTheta = M_PI / 6, kG = 100.0;
  json contact = {{"bodies", {"base", "slider"}}, {"law", law}, {"normal", "base"}};
  if (law == "friction") contact["mu"] = mu;
  const json scene = {
      {"units", {{"length", "mm"}, {"stress", "MPa"}, {"density", "g/cm3"}, {"velocity", "m/s"}, {"time", "ms"},
                 {"acceleration", "m/s2"}}},
      {"analysis", {{"type", "plane_strain"}}},
      {"resolution", 1},
      {"grid", {{"min", {-5, -5}}, {"max", {75, 25}}}},
      {"mpm", {{"shape_function", shape}, {"stress_update", "USAVG"}}},
      {"materials", {test::material("rubber", 10, 0.3, 1.0)}},
      {"bodies", {{{"name", "base"}, {"material", "rubber"}, {"shape", {{"type", "rectangle"}, {"min", {0, 0}}, {"max", {70, 10}}}}},
                  {{"name", "slider"}, {"material", "rubber"}, {"shape", {{"type", "rectangle"}, {"min", {5, 10}}, {"max", {15, 15}}}}}}},
      {"contact", {contact}},
      {"loads", {{{"type", "body_force"}, {"acceleration", {kG * std::sin(kTheta), -kG * std::cos(kTheta)}}},
                 {{"type", "velocity"}, {"region", {{"min", {-1, 0}}, {"max", {71, 2}}}}, {"velocity", {0, 0}}}}},
      {"time", {{"end", 12}, {"cfl", 0.5}}}};
  Model<2> m = build_model<2>(scene);
  auto st = make_stepper<2>(m);
  const Body& S = m.bodies[1];
  std::vector<double> t, v;
  const long steps = std::lround(m.end_time / m.dt);
  for (long k = 1; k <= steps; ++k) {
    EXPECT_FALSE(st->step());
    if (k % 20) continue;
    double mv = 0, mm = 0;
    for (std::size_t p = S.first; p < S.first + S.count; ++p) mv += m.particles.mass[p] * m.particles.v[p].x(), mm += m.particles.mass[p];
    if (k * m.dt >= 2e-3) t.push_back(k * m.dt), v.push_back(mv / mm);
  }
  double st_ = 0, sv = 0, stt = 0, stv = 0;
  const double n = static_cast<double>(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) st_ += t[i], sv += v[i], stt += t[i] * t[i], stv += t[i] * v[i];
  return (n * stv - st_ * sv) / (n * stt - st_ * st_);
}

// The tolerance: within 2 % of g (sin theta - mu cos theta). Measured (docs/validation.md):
// frictionless -0.02 %, mu = 0.3 -0.06 % (uGIMP), +0.03 % (linear).
TEST(BodyContact, ABlockSlidingOnAnInclinedBlockAcceleratesAtGTimesSinThetaWithoutFriction) {
  const double a = slide("frictionless", 0), ref = 100.0 * std::sin(M_PI / 6);
  EXPECT_NEAR(a / ref, 1.0, 0.02) << "a = " << a << " m/s^2, expected " << ref;
}

TEST(BodyContact, ABlockSlidingOnAnInclinedBlockWithCoulombFrictionAcceleratesAtGTimesSinMinusMuCos) {
  for (const char* shape : {"ugimp", "linear"}) {
    const double a = slide("friction", 0.3, shape), ref = 100.0 * (std::sin(M_PI / 6) - 0.3 * std::cos(M_PI / 6));
    EXPECT_NEAR(a / ref, 1.0, 0.02) << shape << ": a = " << a << " m/s^2, expected " << ref;
  }
}

// mu = 0.7 > tan 30 degrees: friction holds the block (measured 1.4 % of g sin theta: the settling's
// vibration, not a slide).
TEST(BodyContact, ABlockOnASlopeLessSteepThanItsFrictionAngleStaysPut) {
  const double a = slide("friction", 0.7);
  EXPECT_LT(std::fabs(a), 0.02 * 100.0 * std::sin(M_PI / 6)) << "a = " << a << " m/s^2";
}

// Only what the scene requires: bodies in declared contact that never come within reach of each other
// take no multi-field path, so the run is bit for bit the run without the key.
TEST(BodyContact, BodiesThatNeverMeetRunExactlyAsWithoutContact) {
  auto run = [](bool contact) {
    json s = colliding_disks(contact ? json::array({{{"bodies", {"left", "right"}}, {"law", "frictionless"}}}) : json(), "ugimp");
    s["bodies"][0]["velocity"] = {0, 1};  // side by side, 10 mm apart, both moving up
    s["bodies"][1]["velocity"] = {0, 1};
    s["bodies"][1]["shape"]["center"] = {40, 0};
    s["grid"]["max"] = {70, 20};
    s["time"]["end"] = 2;
    Model<2> m = build_model<2>(s);
    auto st = make_stepper<2>(m);
    EXPECT_FALSE(test::advance(*st, 60));
    return m.particles;
  };
  const Particles<2> a = run(true), b = run(false);
  std::size_t diff = 0;
  for (std::size_t p = 0; p < a.size(); ++p) diff += (a.x[p] != b.x[p]) + (a.v[p] != b.v[p]) + (a.stress[p] != b.stress[p]);
  EXPECT_EQ(diff, 0u);
}

TEST(BodyContact, ContactBetweenBodiesGivesTheSameBitsOnOneAndTwoThreads) {
  const json contact = json::array({{{"bodies", {"left", "right"}}, {"law", "friction"}, {"mu", 0.2}}});
  json s = colliding_disks(contact, "ugimp", 0.5);  // 22 600 particles: the loops go parallel
  s["bodies"][1]["shape"]["center"] = {31, 4};     // off-centre: friction acts
  s["grid"] = {{"min", {-30, -30}}, {"max", {62, 30}}};
  auto run = [&](int threads) {
    omp_set_num_threads(threads);
    Model<2> m = build_model<2>(s);
    auto st = make_stepper<2>(m);
    EXPECT_FALSE(test::advance(*st, 300));  // through first contact
    return m.particles;
  };
  const Particles<2> a = run(1), b = run(2);
  omp_set_num_threads(2);
  std::size_t diff = 0;
  for (std::size_t p = 0; p < a.size(); ++p) diff += (a.x[p] != b.x[p]) + (a.v[p] != b.v[p]) + (a.stress[p] != b.stress[p]);
  EXPECT_EQ(diff, 0u);
}

// Bad input names the key and the reason.
TEST(BodyContact, ABadContactEntryIsRefusedNamingItsKey) {
  auto error = [](const json& contact) {
    return test::error_of([&] { build_model<2>(colliding_disks(contact, "ugimp")); });
  };
  auto expect = [&](const json& contact, const std::string& key, const std::string& words) {
    const SceneError e = error(contact);
    EXPECT_EQ(e.key_path(), key) << e.what();
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  };
  expect({{"bodies", {"left", "right"}}}, "contact", "expected an array");
  expect(json::array({{{"bodies", {"left", "middle"}}, {"law", "stick"}}}), "contact[0].bodies[1]", "no body is named");
  expect(json::array({{{"bodies", {"left"}}, {"law", "stick"}}}), "contact[0].bodies", "at least two");
  expect(json::array({{{"bodies", {"left", "left"}}, {"law", "stick"}}}), "contact[0].bodies[1]", "named twice");
  expect(json::array({{{"law", "stick"}}}), "contact[0].bodies", "missing");
  expect(json::array({{{"bodies", "all"}, {"law", "glue"}}}), "contact[0].law", "unknown contact law");
  expect(json::array({{{"bodies", "all"}, {"law", "frictionless"}, {"detection", "displacement"}}}),
         "contact[0].detection", "crack faces");
  expect(json::array({{{"bodies", "all"}, {"law", "frictionless"}, {"d_contact", 3}}}), "contact[0].d_contact", "(0, 2]");
  expect(json::array({{{"bodies", "all"}, {"law", "frictionless"}, {"v_sep", 0.8}}}), "contact[0].v_sep",
         "only valid with detection \"volume\"");
  expect(json::array({{{"bodies", "all"}, {"law", "frictionless"}, {"normal", "floor"}}}), "contact[0].normal",
         "not one of this entry's bodies");
  expect(json::array({{{"bodies", "all"}, {"law", "friction"}}}), "contact[0].mu", "missing");
}

// The tolerance: within 10 % of Hertz's duration.
TEST(BodyContact, TwoElasticSpheresCollidingHeadOnTouchForHertzsDurationWithinTenPercent) {
  EXPECT_NEAR(test::hertz_duration_ratio(1.0), 1.0, 0.10);
}

}  // namespace
}  // namespace cleave

namespace cleave {
namespace {

// J at a crack tip counts only the cracked body: a plate (crack tip 2 cells from its right edge)
// sliding past a block at rest 0.5 mm away, frictionless, translates, so J is zero (2D cracks pass
// translation exactly; alone it reads 7e-33 J/m^2); the block's particles within the contour's reach, at
// rest while the tip moves, read J = 1.38 J/m^2 when they counted.
TEST(BodyContact, JAtACrackTipCountsOnlyTheCrackedBody) {
  auto J = [](bool block) {
    json s = {{"units", {{"length", "mm"}, {"stress", "MPa"}, {"density", "g/cm3"}, {"velocity", "m/s"}, {"time", "ms"}}},
              {"analysis", {{"type", "plane_strain"}}},
              {"resolution", 1},
              {"grid", {{"min", {-15, -10}}, {"max", {10, 10}}}},
              {"mpm", {{"shape_function", "ugimp"}, {"stress_update", "USAVG"}}},
              {"materials", {test::material("steel", 200e3, 0.3, 7.8)}},
              {"bodies", {{{"name", "plate"}, {"material", "steel"},
                           {"shape", {{"type", "rectangle"}, {"min", {-10, -5}}, {"max", {0, 5}}}}, {"velocity", {0, 1}}}}},
              {"cracks", {{{"name", "c"}, {"from", {-10, 0}}, {"to", {-2, 0}}, {"segment_length", 1}}}},
              {"crack_tips", json::object()},
              {"time", {{"end", 1e-3}, {"cfl", 0.5}}}};
    if (block) {
      s["bodies"].push_back({{"name", "block"}, {"material", "steel"},
                             {"shape", {{"type", "rectangle"}, {"min", {0.5, -5}}, {"max", {5, 5}}}}});
      s["contact"] = {{{"bodies", {"plate", "block"}}, {"law", "frictionless"}}};
    }
    Model<2> m = build_model<2>(s);
    auto st = make_stepper<2>(m);
    EXPECT_FALSE(test::advance(*st, 5));
    double j = 0;
    for (const auto& t : st->crack_tip_parameters(*m.crack_tips)) j = std::max(j, std::fabs(t.J1));
    return j;
  };
  const double alone = J(false), beside = J(true);
  EXPECT_LT(beside, 1e-6) << "alone " << alone;
}

// Bodies that overlap with contact between them each keep their own field there: nothing pushes them
// apart (contact acts only while they approach), and the warning says so rather than promising it.
TEST(BodyContact, OverlappingBodiesInContactAreWarnedThatTheOverlapStays) {
  json s = colliding_disks(json::array({{{"bodies", {"left", "right"}}, {"law", "frictionless"}}}), "ugimp");
  s["bodies"][0]["velocity"] = {0, 0};
  s["bodies"][1]["velocity"] = {0, 0};
  s["bodies"][1]["shape"]["center"] = {28, 0};  // 2 mm into the left disk
  Model<2> m = build_model<2>(s);
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_NE(m.warnings[0].find("the overlap stays"), std::string::npos) << m.warnings[0];
  auto st = make_stepper<2>(m);
  EXPECT_FALSE(test::advance(*st, 50));
  EXPECT_EQ(st->global_state().kinetic, 0.0);
}

}  // namespace
}  // namespace cleave
