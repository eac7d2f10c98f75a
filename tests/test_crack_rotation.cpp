// Cracks under rigid rotation (issue 14, items 1-3): a cracked body that spins keeps its energy, its
// crack closed, and its J and K at zero, whatever the contact detection and law; a loaded DCB gives
// the same J spinning as at rest. Figures and causes: docs/validation.md, "Cracks under rigid
// rotation (issue 14)".
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "libmpm/crack/tip_parameters.hpp"
#include "libmpm/io/crack_output.hpp"
#include "libmpm/mpm/mpm_method.hpp"
#include "support.hpp"

namespace cleave {
namespace {

using nlohmann::json;

// The disk: aluminium (E = 70 GPa, nu = 0.33, rho = 2700 kg/m3), plane stress, R = 15 mm,
// 1 mm cells, an interior crack 2a = 10 mm through the centre, no load, spinning about its centre at
// omega (rad/ms). law "none" turns contact off.
json spinning_disk(double omega, const std::string& law, const std::string& detection, const std::string& shape) {
  json crack = {{"name", "interior"}, {"from", {-5, 0}}, {"to", {5, 0}}, {"segment_length", 1}};
  crack["contact"] = {{"law", law}};
  if (law != "none") crack["contact"]["detection"] = detection;
  if (law == "friction") crack["contact"]["mu"] = 0.3;
  return {{"units", {{"length", "mm"}, {"stress", "Pa"}, {"density", "g/cm3"}, {"velocity", "m/s"},
                     {"time", "ms"}, {"inverse_time", "1/ms"}}},
          {"analysis", {{"type", "plane_stress"}, {"thickness", 1}}},
          {"resolution", 1},
          {"grid", {{"min", {-20, -20}}, {"max", {20, 20}}}},
          {"mpm", {{"shape_function", shape}, {"stress_update", "USAVG"}}},
          {"materials", {test::material("aluminium", 70e9, 0.33, 2.7)}},
          {"bodies", {{{"name", "disk"}, {"material", "aluminium"},
                       {"shape", {{"type", "disk"}, {"center", {0, 0}}, {"radius", 15}}},
                       {"angular_velocity", omega}, {"rotation_center", {0, 0}}}}},
          {"cracks", {crack}},
          {"time", {{"end", 1.0}, {"cfl", 0.5}}}};
}

struct SpinResult {
  double drift = 0;        // max |E(t) - E(0)| / E(0)
  double opening = 0;      // max |crack opening| (normal and tangential) over points and samples, in cells
  double J = 0;            // max |J1| over samples and tips, J/m^2
  double KI0 = 0, J0 = 0;  // max |K_I| and |J1| at t = 0 over both tips
  double angle = 0;        // radians turned
  double seconds = 0;      // wall time
};

// Runs the disk through `angle` radians; energies every step, openings and J every `every` steps.
SpinResult spin(double omega, double angle, const std::string& law, const std::string& detection,
                const std::string& shape, bool tips = true, int every = 20) {
  const auto t0 = std::chrono::steady_clock::now();
  Model<2> m = build_model<2>(spinning_disk(omega, law, detection, shape));
  auto st = make_stepper<2>(m);
  const double h = m.grid.h;
  SpinResult r;
  const crack::TipSettings ts;  // the defaults: 2-cell circle, eq. 32
  auto sample_tips = [&](bool first) {
    for (const auto& t : st->crack_tip_parameters(ts)) {
      r.J = std::max(r.J, std::fabs(t.J1));
      if (first) r.KI0 = std::max(r.KI0, std::fabs(t.KI)), r.J0 = std::max(r.J0, std::fabs(t.J1));
    }
  };
  if (tips) sample_tips(true);
  const double e0 = st->global_state().total();
  const long steps = std::lround(angle / (omega * 1e3) / m.dt);
  for (long k = 1; k <= steps; ++k) {
    if (st->step()) break;
    const double e = st->global_state().total();
    r.drift = std::max(r.drift, std::fabs(e - e0) / e0);
    if (!std::isfinite(e) || r.drift > 1.0) break;  // the run loop would stop: energy blow-up
    if (k % every == 0 || k == steps) {
      const auto& c = m.cracks[0];
      for (std::size_t i = 0; i < c.points.size(); ++i)
        r.opening = std::max(r.opening, io::crack_opening(c, i).cwiseAbs().maxCoeff() / h);
      if (tips) sample_tips(false);
    }
    r.angle = omega * 1e3 * st->time();
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

void print(const char* what, const SpinResult& r) {
  std::printf("%-44s angle %.3f rad: energy drift %.3e, max opening %.2e cell, J(0) %.3e, K_I(0) %.3e, "
              "max J %.3e J/m^2 (%.1f s)\n",
              what, r.angle, r.drift, r.opening, r.J0, r.KI0, r.J, r.seconds);
  std::fflush(stdout);
}

// Item 3: J and K are objective. The unloaded disk spinning at 1 rad/ms with contact off: J is evaluated
// relative to the rigid motion of the contour's material, so J stays below 1 J/m^2 over one radian
// (0.67 J/m^2; it was 1.06e4 J/m^2 with the absolute gradients and velocities) and K_I is zero at t = 0
// (4.7e-2 Pa m^0.5, from J = 3e-14 J/m^2). The crack stays closed (4.8e-4 cell; 1.5e-2 cell before the
// fields' velocities were carried to their nodes) and the energy constant (6.9e-5). About 3 s.
TEST(CrackRotation, SpinningDiskHasNoJAndStaysClosedWithoutContact) {
  const SpinResult r = spin(1.0, 1.0, "none", "volume", "linear");
  print("w 1.0 rad/ms linear none", r);
  EXPECT_NEAR(r.angle, 1.0, 1e-3);
  EXPECT_LT(r.J0, 1e-6);
  EXPECT_LT(r.KI0, 1.0);  // Pa m^0.5: zero up to the round-off of J
  EXPECT_LT(r.J, 1.0);    // J/m^2 (the physical centrifugal J is about 0.01 J/m^2)
  EXPECT_LT(r.opening, 0.01);
  EXPECT_LT(r.drift, 1e-3);
}

// Items 1-2: every contact law and detection, 1 rad/ms over one radian: energy within the issue's
// 0.1 % (at most 2.9e-4), crack opening below 1 % of a cell (6e-4), J below 1 J/m^2 (0.64).
// Before contact kept its pairs for the whole step (contact.hpp), displacement detection blew up
// with every law at 0.11-0.73 rad and volume detection with stick drifted 15 % (uGIMP) or blew up
// (linear). About 25 s (linear) and 40 s (uGIMP).
void every_law_and_detection_keeps_the_spinning_disk_still(const char* shape) {
  for (const char* det : {"volume", "displacement"})
    for (const char* law : {"stick", "frictionless", "friction"}) {
      const SpinResult r = spin(1.0, 1.0, law, det, shape);
      const std::string what = std::string("w 1.0 rad/ms ") + shape + " " + det + " " + law;
      print(what.c_str(), r);
      EXPECT_NEAR(r.angle, 1.0, 1e-3) << what;
      EXPECT_LT(r.drift, 1e-3) << what;
      EXPECT_LT(r.opening, 0.01) << what;
      EXPECT_LT(r.J, 1.0) << what;
    }
}
TEST(CrackRotation, SpinningDiskKeepsItsEnergyAndItsCrackClosedWithEveryContactLawLinear) {
  every_law_and_detection_keeps_the_spinning_disk_still("linear");
}
TEST(CrackRotation, SpinningDiskKeepsItsEnergyAndItsCrackClosedWithEveryContactLawUGimp) {
  every_law_and_detection_keeps_the_spinning_disk_still("ugimp");
}

// The second wish: a loaded DCB at rest and the same DCB spinning slowly give the same J. An
// aluminium DCB (100 x 36 mm, plane stress) cracked along its mid-plane to x = 50 mm, its arms opened
// by shear tractions on their -x faces ramped over 0.5 ms, run to 1 ms: once at rest, once spinning
// at 0.1 rad/ms about its crack tip (0.1 rad turned by the end; the tractions keep their global
// direction: an axial pair of +-sin(angle) of the load on the arms, whose share of J is of order
// angle^2 (h/a)^2 / 24, 6e-5). Coriolis forces are 2 omega / (the arms' 37 000 rad/s) = 0.5 % of
// the inertial ones. Defaults: 0.6 MPa, 2 mm cells, linear shape functions (the tests set theirs).
json loaded_dcb(double omega, double traction = 6e5, double cell = 2.0, const char* shape = "linear") {
  json b = {{"name", "dcb"}, {"material", "aluminium"},
            {"shape", {{"type", "rectangle"}, {"min", {0, -18}}, {"max", {100, 18}}}}, {"particles_per_cell", 2}};
  if (omega != 0.0) b["angular_velocity"] = omega, b["rotation_center"] = {50, 0};
  const auto arm = [&](double y0, double y1, double sign) {
    return json{{"type", "traction"}, {"body", "dcb"}, {"face", "-x"},
                {"region", {{"min", {-1, y0}}, {"max", {1, y1}}}}, {"traction", {0, sign * traction}}, {"rise_time", 0.5}};
  };
  return {{"units", {{"length", "mm"}, {"stress", "Pa"}, {"density", "g/cm3"}, {"velocity", "m/s"},
                     {"time", "ms"}, {"inverse_time", "1/ms"}}},
          {"analysis", {{"type", "plane_stress"}, {"thickness", 1}}},
          {"resolution", cell},
          {"grid", {{"min", {-10, -30}}, {"max", {110, 30}}}},
          {"mpm", {{"shape_function", shape}, {"stress_update", "USAVG"}}},
          {"materials", {test::material("aluminium", 70e9, 0.33, 2.7)}},
          {"bodies", {b}},
          {"cracks", {{{"name", "midplane"}, {"from", {-2, 0}}, {"to", {50, 0}}, {"segment_length", cell},
                       {"contact", {{"law", "frictionless"}, {"detection", "displacement"}}}}}},
          {"loads", {arm(0, 18, 1.0), arm(-18, 0, -1.0)}},
          {"time", {{"end", 1.0}, {"cfl", 0.5}}}};
}

// J at the inner tip every `every` steps to 1 ms, with the default contour: (time in ms, J1). CLEAVE_DCB_OPENING prints each
// sample with the load-point opening.
std::vector<std::pair<double, double>> dcb_J_history(const json& scene, int every = 25) {
  Model<2> m = build_model<2>(scene);
  auto st = make_stepper<2>(m);
  crack::TipSettings ts;  // a 2D scene's default: a circle of 4 cells, eq. 33
  ts.radius = 4, ts.volume_term = true;
  std::vector<std::pair<double, double>> out;
  const long steps = std::lround(1.0e-3 / m.dt);
  for (long k = 1; k <= steps; ++k) {
    if (st->step()) break;
    if (k % every == 0)
      for (const auto& t : st->crack_tip_parameters(ts)) {
        out.emplace_back(st->time() * 1e3, t.J1);
        if (std::getenv("CLEAVE_DCB_OPENING"))
          std::printf("O %.4f %.4f %.6e\n", st->time() * 1e3, t.J1, test::dcb_load_point_opening(m.particles));
      }
  }
  return out;
}

// The largest relative difference of the spinning J from the J at rest (linear between its samples:
// a spinning body's time step can differ, its particles' speed enters the CFL limit) once the load
// is full (0.5 - 1 ms), and its time. CLEAVE_DCB_TRACE prints every sample: t, J at rest, spinning.
struct JDifference {
  double worst = 0.0, at = 0.0, Jmax = 0.0;
  std::size_t samples = 0;
};
JDifference spinning_against_rest(const std::vector<std::pair<double, double>>& rest,
                                  const std::vector<std::pair<double, double>>& spin) {
  JDifference d;
  if (rest.size() < 2) return d;
  const auto rest_at = [&](double t) {
    std::size_t i = 1;
    while (i + 1 < rest.size() && rest[i].first < t) ++i;
    const auto& [t0, j0] = rest[i - 1];
    const auto& [t1, j1] = rest[i];
    return j0 + (j1 - j0) * (t - t0) / (t1 - t0);
  };
  for (const auto& [t, J] : rest) d.Jmax = std::max(d.Jmax, J);
  for (const auto& [t, J] : spin) {
    const double Jr = rest_at(t);
    if (std::getenv("CLEAVE_DCB_TRACE")) std::printf("%.4f %.5f %.5f\n", t, Jr, J);
    if (t < 0.5 || t > rest.back().first) continue;
    ++d.samples;
    const double e = std::fabs(J - Jr) / std::fabs(Jr);
    if (e > d.worst) d.worst = e, d.at = t;
  }
  return d;
}

// Asserted: J spinning within the 2 % of J at rest at every sample from 0.5 ms (full load)
// to 1 ms, with the defaults (uGIMP, the 4-cell contour with eq. 33) at 1 mm cells and 6 MPa
// tractions: 0.79 %. Why this load and these cells (docs/validation.md, "Spinning bodies"):
// - the spin's own physics: started spinning at once, the arms (cantilevers whose centres lie 9 mm
//   off the crack's axis) carry the centrifugal load rho omega^2 y and swing open, J up to 7e-3 J/m^2
//   unloaded. Superposed on a loaded crack it changes K by the root of the ratio of the two J's: at
//   0.6 MPa (J 14 J/m^2) +-4.6 % of J, measured 5.1 %; at 6 MPa (J 1400 J/m^2) +-0.45 %. The issue's
//   comparison assumes the spin adds nothing, which holds at the higher load;
// - the crack turns off its node line about the tip (8 mm behind it by 0.8 mm at 0.1 rad), and the
//   discrete crack's J depends on where the line lies in its cells: at rest, the crack 0.2 of a 2 mm
//   cell off the node line reads J up to +1.08 %. The difference converges with the cell: 1.97 % at
//   2 mm, 0.79 % at 1 mm.
// Linear shape functions MISS (23 % at 1 mm, 13 % at 2 mm: the spinning J rings from sample to sample
// while at rest it is smooth): particles crossing cells in a loaded body, the linear functions' known
// grid-crossing noise (the same DCB translated at 1 m/s: 74 % once its particles cross node lines).
// About 35 s.
TEST(CrackRotation, ALoadedDcbSpinningAtATenthOfARadianPerMillisecondHasTheJItHasAtRest) {
  const auto rest = dcb_J_history(loaded_dcb(0.0, 6e6, 1.0, "ugimp"));
  const auto spin = dcb_J_history(loaded_dcb(0.1, 6e6, 1.0, "ugimp"));
  const JDifference d = spinning_against_rest(rest, spin);
  std::printf("loaded DCB (6 MPa, 1 mm, uGIMP), J at 1 ms: at rest %.2f, spinning %.2f J/m^2; largest difference "
              "%.3f %% at %.3f ms (J up to %.1f J/m^2)\n",
              rest.back().second, spin.back().second, 100 * d.worst, d.at, d.Jmax);
  EXPECT_GT(d.Jmax, 1000.0);  // loaded: about 1400 J/m^2
  EXPECT_GT(d.samples, 50u);
  EXPECT_LT(d.worst, 0.02) << "at t = " << d.at << " ms";
}

// The comparison above for other settings (--gtest_also_run_disabled_tests). Environment:
// CLEAVE_DCB_TRACTION (Pa, default 6e5), CLEAVE_DCB_CELL (mm, 2), CLEAVE_DCB_SHAPE (linear),
// CLEAVE_DCB_LAW (frictionless), CLEAVE_DCB_OMEGA (rad/ms, 0.1); CLEAVE_DCB_VX (m/s) translates the
// second run instead of spinning it; CLEAVE_DCB_TIP (mm) ends the crack there; CLEAVE_DCB_SHIFT (mm)
// puts the second run's crack that far off its node line; CLEAVE_DCB_SPLIT (line, node) is the
// crack's tip_split in both runs.
TEST(CrackRotation, DISABLED_LoadedDcbStudy) {
  const auto number = test::env_number;
  const double omega = number("CLEAVE_DCB_OMEGA", 0.1);
  const auto scene = [&](double w) {
    const char* shape = std::getenv("CLEAVE_DCB_SHAPE");
    json s = loaded_dcb(w, number("CLEAVE_DCB_TRACTION", 6e5), number("CLEAVE_DCB_CELL", 2.0), shape ? shape : "linear");
    if (const char* law = std::getenv("CLEAVE_DCB_LAW")) s["cracks"][0]["contact"]["law"] = law;
    if (const char* tip = std::getenv("CLEAVE_DCB_TIP")) s["cracks"][0]["to"][0] = std::atof(tip);
    if (const char* split = std::getenv("CLEAVE_DCB_SPLIT")) s["cracks"][0]["tip_split"] = split;
    if (w == 0.0) return s;
    if (const char* vx = std::getenv("CLEAVE_DCB_VX")) {
      s["bodies"][0].erase("angular_velocity"), s["bodies"][0].erase("rotation_center");
      s["bodies"][0]["velocity"] = {std::atof(vx), 0.0};
    }
    if (const char* d = std::getenv("CLEAVE_DCB_SHIFT")) {
      const double dy = std::atof(d);
      s["cracks"][0]["from"][1] = dy, s["cracks"][0]["to"][1] = dy;
      s["loads"][0]["region"]["min"][1] = dy, s["loads"][1]["region"]["max"][1] = dy;
    }
    return s;
  };
  const auto rest = dcb_J_history(scene(0.0)), spin = dcb_J_history(scene(omega));
  ASSERT_FALSE(rest.empty());
  ASSERT_FALSE(spin.empty());
  const JDifference d = spinning_against_rest(rest, spin);
  std::printf("loaded DCB, J at 1 ms: at rest %.4f, second run %.4f J/m^2; largest difference %.3f %% at %.3f ms "
              "(J up to %.3f J/m^2)\n",
              rest.back().second, spin.back().second, 100 * d.worst, d.at, d.Jmax);
}

// The DCB's crack is drawn from x = -2 mm, a cell beyond the loaded edge: its first point lies
// outside the material. Its tracked surfaces followed fields that the arms' end particles graze, and
// in the spinning DCB they drifted shut (5 cm/s); contact then held the mouth's nodes from 0.52 ms on
// and the arms stopped vibrating (J up to 15 % off the same run without contact). The faces stay
// apart in this run once loaded (at the start, still closed, contact may act: 2e-8 of J measured), so
// frictionless contact must leave it as it is without contact, to 1e-6 of J. uGIMP (the default shape
// functions): about 10 s.
TEST(CrackRotation, ASpinningDcbWhoseFacesStayApartRunsAsItDoesWithoutContact) {
  const auto run = [](const char* law) {
    json scene = loaded_dcb(0.1);
    scene["mpm"]["shape_function"] = "ugimp";
    scene["cracks"][0]["contact"]["law"] = law;
    return dcb_J_history(scene, 50);
  };
  const auto with = run("frictionless"), without = run("none");
  ASSERT_EQ(with.size(), without.size());
  ASSERT_FALSE(with.empty());
  double Jmax = 0.0;
  for (const auto& [t, J] : without) Jmax = std::max(Jmax, J);
  EXPECT_GT(Jmax, 1.0);  // loaded
  for (std::size_t i = 0; i < with.size(); ++i)
    EXPECT_NEAR(with[i].second, without[i].second, 1e-6 * Jmax) << "t = " << with[i].first << " ms";
}

// The split of J into K_I and K_II reads the faces' openings behind the tip from each face's field,
// whose mass centre lies about 3/8 of a cell off the crack on its side: turned with the body, the
// centres' separation read as an opening (tangential: the turned angle times 3/4 of a cell, ten
// times the DCB's normal opening by 0.09 rad; K_II / K_I = -11). A DCB loaded in mode I splits into
// K_I alone whether it spins or not, up to the discrete crack's own K_II off the grid's axes: the DCB
// at rest turned 30 degrees reads K_II / K_I = -3.7 % (docs/validation.md, "The defaults", a miss of
// the 1 %). Asserted: |K_II| / K_I below that 3.7 % once loaded (from 0.5 ms; largest
// measured 1.05 %; 5 samples above 1 %). uGIMP: about 5 s.
TEST(CrackRotation, ASpinningDcbLoadedInModeOneHasNoKII) {
  json scene = loaded_dcb(0.1);
  scene["mpm"]["shape_function"] = "ugimp";
  Model<2> m = build_model<2>(scene);
  auto st = make_stepper<2>(m);
  const crack::TipSettings ts;
  const long steps = std::lround(1.0e-3 / m.dt);
  int read = 0;
  for (long k = 1; k <= steps; ++k) {
    ASSERT_FALSE(st->step());
    if (k % 50 != 0 || st->time() < 0.5e-3) continue;
    for (const auto& t : st->crack_tip_parameters(ts)) {
      ++read;
      EXPECT_GT(t.KI, 0.0) << "t = " << st->time() * 1e3 << " ms";
      EXPECT_LT(std::fabs(t.KII), 0.037 * t.KI) << "t = " << st->time() * 1e3 << " ms: K_I " << t.KI << ", K_II " << t.KII;
    }
  }
  EXPECT_GT(read, 20);
}

// The study behind the figures: every law and detection, linear and uGIMP, at 0.1 and 1 rad/ms.
// Environment: CLEAVE_SPIN_ANGLE (radians, default 1), CLEAVE_SPIN_OMEGA (rad/ms; default both).
// Run with --gtest_also_run_disabled_tests --gtest_filter='CrackRotation.DISABLED_Study'.
TEST(CrackRotation, DISABLED_Study) {
  const double angle = test::env_number("CLEAVE_SPIN_ANGLE", 1.0);
  std::vector<double> omegas = {1.0, 0.1};
  if (std::getenv("CLEAVE_SPIN_OMEGA")) omegas = {std::atof(std::getenv("CLEAVE_SPIN_OMEGA"))};
  for (double w : omegas)
    for (const char* shape : {"linear", "ugimp"}) {
      char what[128];
      std::snprintf(what, sizeof what, "w %.1f rad/ms %s none", w, shape);
      print(what, spin(w, angle, "none", "volume", shape));
      for (const char* det : {"volume", "displacement"})
        for (const char* law : {"stick", "frictionless", "friction"}) {
          std::snprintf(what, sizeof what, "w %.1f rad/ms %s %s %s", w, shape, det, law);
          print(what, spin(w, angle, law, det, shape));
        }
    }
}

}  // namespace
}  // namespace cleave
