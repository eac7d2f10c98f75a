// Bond-based peridynamics (issue 6): wave speeds, static tension, energy conservation, branching,
// pre-cracks in 2D and 3D, determinism, checkpoint resume, scene errors. Tolerances: docs/validation.md.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <cstdio>
#include <sstream>

#include "libmpm/core/error.hpp"
#include "libmpm/pd/bonds.hpp"
#include "libmpm/pd/pd_method.hpp"
#include "libmpm/pd/pd_scene.hpp"
#include "libmpm/pd/pd_solver.hpp"
#include "libmpm/crack/surface.hpp"
#include "libmpm/crack/surface3d.hpp"
#include "libmpm/pd/tips.hpp"
#include "libmpm/method/run_scene.hpp"
#include "libmpm/mpm/mpm_scene.hpp"

using namespace cleave;
using namespace cleave::pd;
using crack::segment_hits_triangle;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kE = 65e9, kRho = 2235.0;

// A rectangular (2D) or box (3D) glass specimen in SI units, no loads.
json specimen(int dim, std::vector<double> hi, double dx, int m, double end) {
  json s;
  s["method"] = "peridynamics";
  s["analysis"] = dim == 2 ? json{{"type", "plane_stress"}, {"thickness", 0.001}} : json{{"type", "3d"}};
  s["peridynamics"] = {{"spacing", dx}, {"horizon_factor", m}};
  s["materials"] = json::array({{{"name", "glass"}, {"type", "linear_elastic"}, {"E", kE}, {"density", kRho},
                                  {"fracture_energy", 204.0}}});
  json lo = dim == 2 ? json::array({0, 0}) : json::array({0, 0, 0});
  s["bodies"] = json::array({{{"name", "b"}, {"material", "glass"},
                              {"shape", {{"type", dim == 2 ? "rectangle" : "box"}, {"min", lo}, {"max", hi}}}}});
  s["time"] = {{"end", end}, {"cfl", 0.5}};
  return s;
}

// Time of the k-th zero crossing (k = 0, 1, ...) of q(t), linearly interpolated; NaN if none.
template <int Dim, class Q>
std::vector<double> zero_crossings(PdSystem<Dim>& m, PdSolver<Dim>& s, Q&& q, int wanted, long max_steps) {
  std::vector<double> t;
  double prev = q();
  for (long k = 0; k < max_steps && static_cast<int>(t.size()) < wanted; ++k) {
    const double t0 = s.time();
    s.step();
    const double now = q();
    if ((prev > 0) != (now > 0)) t.push_back(t0 + m.dt * prev / (prev - now));
    prev = now;
  }
  return t;
}

// Period of the free-free fundamental mode u_x ~ cos(pi x / L) of a plate [0, L] x [0, H], from
// the modal velocity sum m v_x cos(pi x / L): crossings at T/4, 3T/4, 5T/4.
double measured_wave_speed(bool hold_y) {
  const double L = 0.4, H = 0.06, dx = 0.002;
  json s = specimen(2, {L, H}, dx, 3, 1.0);
  if (hold_y)
    s["loads"] = json::array({{{"type", "velocity"}, {"region", {{"min", {0, 0}}, {"max", {L, H}}}},
                               {"velocity", {nullptr, 0.0}}}});
  auto m = build_pd_system<2>(s);
  for (std::size_t p = 0; p < m.points.size(); ++p) m.points.v[p][0] = 1e-3 * std::cos(kPi * m.points.x0[p][0] / L);
  PdSolver<2> solver(m);
  auto q = [&]() {
    double sum = 0;
    for (std::size_t p = 0; p < m.points.size(); ++p)
      sum += m.points.mass[p] * m.points.v[p][0] * std::cos(kPi * m.points.x0[p][0] / L);
    return sum;
  };
  const auto t = zero_crossings(m, solver, q, 3, 100000);
  EXPECT_EQ(t.size(), 3u);
  if (t.size() < 3) return 0;
  const double period = t[2] - t[0];  // one period between the 1st and 3rd crossing
  return 2.0 * L / period;
}

}  // namespace

// Validation 1a: bar (plane stress, free edges): c = sqrt(E / rho). A 60 mm wide strip is long
// (L / H = 6.7, wavelength 0.8 m): the lateral-inertia (Rayleigh-Love) correction is < 0.1 %.
TEST(PdValidation, BarWaveSpeedWithin3Percent) {
  const double c = measured_wave_speed(false), ref = std::sqrt(kE / kRho);
  std::printf("bar: %.1f m/s, reference %.1f m/s, ratio %.4f\n", c, ref, c / ref);
  EXPECT_NEAR(c / ref, 1.0, 0.03) << "measured " << c << " m/s, bar speed " << ref << " m/s";
}

// Validation 1b: plate, lateral motion held (uniaxial strain): c = sqrt(E / (rho (1 - nu^2))) with
// the implied nu = 1/3 of bond-based plane stress.
TEST(PdValidation, PlateWaveSpeedWithin3Percent) {
  const double c = measured_wave_speed(true), nu = 1.0 / 3.0, ref = std::sqrt(kE / (kRho * (1 - nu * nu)));
  std::printf("plate: %.1f m/s, reference %.1f m/s, ratio %.4f\n", c, ref, c / ref);
  EXPECT_NEAR(c / ref, 1.0, 0.03) << "measured " << c << " m/s, plane-stress P-wave speed " << ref << " m/s";
}

// Validation 2: damped static tension, plane stress (nu = 1/3): far-from-edge strain = sigma / E.
// Horizon 4 dx: with 3 dx the one-point lattice quadrature (partial volumes) is 4.5 % too stiff
// along the lattice axes (lattice sums of xi_x^4 / |xi|^3 and xi_x^2 xi_y^2 / |xi|^3 against the
// horizon integrals), 1.9 % with 4 dx; the 3 dx figure (3.3 % miss) is in docs/validation.md.
// With `relax`, the scene's static solve (dynamic relaxation: "static", no damping key) instead of
// the hand-chosen damping, stepped until static.
double static_tension_strain_ratio(int m_factor, bool relax = false) {
  const double Lx = 0.1, Ly = 0.05, sigma = 1e6;
  json s = specimen(2, {Lx, Ly}, 0.001, m_factor, 3e-4);
  s["loads"] = json::array({{{"type", "traction"}, {"face", "+x"}, {"traction", {sigma, 0}}, {"rise_time", 2e-5}},
                            {{"type", "traction"}, {"face", "-x"}, {"traction", {-sigma, 0}}, {"rise_time", 2e-5}}});
  if (relax) {
    s["static"] = json::object();
    s["time"].erase("cfl");  // the static default, 0.9
  } else {
    s["damping"] = {{"kinetic", 2e5}};
  }
  auto m = build_pd_system<2>(s);
  PdSolver<2> solver(m);
  if (relax) {
    auto method = make_pd_method<2>(m);
    while (method->time() < m.end_time && !method->static_reached()) method->step();
    EXPECT_TRUE(method->static_reached()) << method->relaxation_state();
    std::printf("static solve: %ld steps to %.4g s (hand-damped: %.0f steps to 3e-4 s); %s\n", method->step_count(),
                method->time(), std::ceil(3e-4 / (0.5 * m.stable_dt)), method->relaxation_state().c_str());
  } else {
    while (solver.time() < m.end_time) solver.step();
  }
  // Mean u_x of the columns nearest x = 30 mm and 70 mm, rows 15..35 mm.
  double ua = 0, ub = 0, xa = 0, xb = 0;
  int na = 0, nb = 0;
  for (std::size_t p = 0; p < m.points.size(); ++p) {
    const auto& x = m.points.x0[p];
    if (x.y() < 0.015 || x.y() > 0.035) continue;
    if (std::fabs(x.x() - 0.0305) < 1e-6) ua += m.points.u[p].x(), xa += x.x(), ++na;
    if (std::fabs(x.x() - 0.0695) < 1e-6) ub += m.points.u[p].x(), xb += x.x(), ++nb;
  }
  EXPECT_GT(na, 0);
  EXPECT_GT(nb, 0);
  if (!na || !nb) return std::nan("");
  const double strain = (ub / nb - ua / na) / (xb / nb - xa / na);
  // Converged: the kinetic energy is negligible against the strain energy.
  if (!relax) {
    const auto g = solver.global_state();
    EXPECT_LT(g.kinetic, 1e-6 * g.strain);
  }
  std::printf("static tension, horizon %d dx: strain / (sigma / E) = %.4f\n", m_factor, strain / (sigma / kE));
  return strain / (sigma / kE);
}
TEST(PdValidation, StaticTensionStrainWithin3Percent) { EXPECT_NEAR(static_tension_strain_ratio(4), 1.0, 0.03); }
TEST(PdValidation, StaticSolveByRelaxationGivesTheDampedRunsStrainWithin1e3) {
  EXPECT_NEAR(static_tension_strain_ratio(4, true) / static_tension_strain_ratio(4), 1.0, 1e-3);
}

// Validation 3: no failure, no loads, no damping: KE + SE conserved within 0.5 % over 1000 steps.
template <int Dim>
void energy_conserved() {
  json s = Dim == 2 ? specimen(2, {0.05, 0.03}, 0.001, 3, 1.0) : specimen(3, {0.02, 0.012, 0.01}, 0.001, 3, 1.0);
  auto m = build_pd_system<Dim>(s);
  for (std::size_t p = 0; p < m.points.size(); ++p) {
    const auto& x = m.points.x0[p];
    m.points.v[p][0] = 0.5 * std::sin(2 * kPi * x[0] / 0.05) * std::cos(kPi * x[1] / 0.03);
    m.points.v[p][1] = 0.3 * std::cos(3 * kPi * x[0] / 0.05);
  }
  PdSolver<Dim> solver(m);
  const double e0 = solver.global_state().total();
  double worst = 0;
  for (int k = 0; k < 1000; ++k) {
    solver.step();
    if (k % 10 == 9) worst = std::max(worst, std::fabs(solver.global_state().total() - e0) / e0);
  }
  EXPECT_EQ(solver.global_state().broken, 0u);
  std::printf("%dD energy: max relative change over 1000 steps %.3g\n", Dim, worst);
  EXPECT_LT(worst, 0.005) << Dim << "D: max relative energy change " << worst;
}
TEST(PdValidation, EnergyConserved2D) { energy_conserved<2>(); }
TEST(PdValidation, EnergyConserved3D) { energy_conserved<3>(); }

// Validation 4 (coarse copy of data/scenes/pd_branching.json, dx = 1 mm, horizon 4 dx = 4 mm,
// dt = 0.1 us): the crack runs from the notch and branches before the right edge, the tip speed
// between successive 1 us records stays below the Rayleigh speed of the implied plane-stress
// material (nu = 1/3: c_R = 0.9194 c_s, from the Rayleigh equation with nu' = nu / (1 + nu) = 1/4).
TEST(PdValidation, BranchingPlateCoarse) {
  json s = load_scene_file(fs::path(CLEAVE_SOURCE_DIR) / "data/scenes/pd_branching.json");
  s["resolution"] = 1;
  s["time"]["dt"] = 0.1;
  s["output"]["interval"] = 46;  // first and last frame only
  auto m = build_pd_system<2>(s);
  const fs::path out = fs::path(CLEAVE_BINARY_DIR) / "test_out" / "pd_branching_coarse";
  fs::remove_all(out);
  RunOptions opt;
  opt.out = out;
  const auto sum = run_pd<2>(m, opt);
  EXPECT_NEAR(sum.time, 46e-6, 1e-12);
  std::ifstream rj(out / "run.json");
  const json r = json::parse(rj);
  ASSERT_TRUE(r["branching"].is_object()) << "no branching detected";
  const double tb = r["branching"]["time"], xb = r["branching"]["x"], yb = r["branching"]["y"];
  std::printf("coarse branching: t = %.1f us at (%.2f, %.2f) mm\n", tb * 1e6, xb * 1e3, yb * 1e3);
  EXPECT_GT(xb, 0.055);  // ahead of the notch tip (50 mm) ...
  EXPECT_LT(xb, 0.095);  // ... and before the right edge
  EXPECT_NEAR(yb, 0.02, 0.004);
  const double cs = std::sqrt(kE / (2 * (1 + 1.0 / 3.0) * kRho)), cR = 0.9194 * cs;
  std::ifstream tips(out / "crack_tips.csv");
  std::string line;
  std::getline(tips, line);
  EXPECT_EQ(line, "time_s,crack,tip,x_m,y_m,speed_m_per_s");
  double vmax = 0, xmax = 0;
  int rows = 0;
  while (std::getline(tips, line)) {
    std::stringstream ss(line);
    std::vector<double> v;
    for (std::string f; std::getline(ss, f, ',');) v.push_back(std::stod(f));
    ASSERT_EQ(v.size(), 6u);
    vmax = std::max(vmax, v[5]);
    xmax = std::max(xmax, v[3]);
    ++rows;
  }
  EXPECT_GT(rows, 20);
  EXPECT_GT(xmax, 0.085);  // the branches ran on towards the right edge
  EXPECT_GT(vmax, 500.0);  // the crack did run
  std::printf("coarse branching: max tip speed %.0f m/s, Rayleigh %.0f m/s\n", vmax, cR);
  EXPECT_LT(vmax, cR) << "tip speed " << vmax << " m/s >= Rayleigh speed " << cR << " m/s";
}

// Same result for 1 and 2 threads, bit for bit (16,000 points: the loops do run in parallel).
TEST(PdSolver, DeterministicForOneAndTwoThreads) {
  json s = load_scene_file(fs::path(CLEAVE_SOURCE_DIR) / "data/scenes/pd_branching.json");
  s["time"]["end"] = 14;  // the crack starts at about 9 us
  auto run = [&](int threads) {
    omp_set_num_threads(threads);
    auto m = build_pd_system<2>(s);
    PdSolver<2> solver(m);
    while (solver.time() < m.end_time - 1e-12) solver.step();
    omp_set_num_threads(omp_get_num_procs());
    return std::make_pair(m.points.u, m.nb.intact);
  };
  const auto a = run(1), b = run(2);
  ASSERT_EQ(a.first.size(), b.first.size());
  std::size_t broken = 0;
  for (uint8_t x : a.second) broken += !x;
  EXPECT_GT(broken, 0u) << "no bond broke: the comparison would not cover breaking";
  EXPECT_TRUE(a.second == b.second);
  for (std::size_t p = 0; p < a.first.size(); ++p) ASSERT_TRUE(a.first[p] == b.first[p]) << "point " << p;
}

// Bodies are read once for every method (scene/bodies.hpp): a peridynamic body spins as an MPM body
// does, v = v0 + w x (x - c).
TEST(PdScene, BodyAngularVelocityIsTheSharedRigidRotation) {
  json s = specimen(2, {0.01, 0.01}, 0.001, 3, 1e-6);
  s["bodies"][0]["velocity"] = {1.0, 0.0};
  s["bodies"][0]["angular_velocity"] = 100.0;  // 1/s
  s["bodies"][0]["rotation_center"] = {0.005, 0.005};
  const auto m = build_pd_system<2>(s);
  ASSERT_GT(m.points.size(), 0u);
  for (std::size_t p = 0; p < m.points.size(); ++p) {
    const Vec<2> r = m.points.x0[p] - Vec<2>(0.005, 0.005);
    EXPECT_NEAR((m.points.v[p] - Vec<2>(1.0 - 100.0 * r.y(), 100.0 * r.x())).norm(), 0.0, 1e-12);
  }
  s["bodies"][0].erase("angular_velocity");
  try {
    build_pd_system<2>(s);
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key_path(), "bodies[0].rotation_center");
  }
}

// A stopped run resumed from its checkpoint ends in the same state as an uninterrupted run.
TEST(PdRun, ResumeFromCheckpointIsExact) {
  json s = load_scene_file(fs::path(CLEAVE_SOURCE_DIR) / "data/scenes/pd_branching.json");
  s["resolution"] = 1;
  s["time"] = {{"end", 16}, {"dt", 0.1}};
  s["output"] = {{"interval", 4}, {"global_interval", 1}};
  const fs::path base = fs::path(CLEAVE_BINARY_DIR) / "test_out";
  RunOptions opt;
  opt.out = base / "pd_resume_full";
  fs::remove_all(opt.out);
  auto full = build_pd_system<2>(s);
  run_pd<2>(full, opt);

  opt.out = base / "pd_resume_cut";
  fs::remove_all(opt.out);
  auto cut = build_pd_system<2>(s);
  opt.progress_interval_s = 0;
  opt.progress = [](const RunProgress& p) {
    if (p.step == 100) throw std::runtime_error("stop");  // between the frames at 8 and 12 us
  };
  EXPECT_THROW(run_pd<2>(cut, opt), std::runtime_error);
  opt.progress = nullptr;
  opt.resume = true;
  auto resumed = build_pd_system<2>(s);
  run_pd<2>(resumed, opt);
  for (std::size_t p = 0; p < full.points.size(); ++p) ASSERT_TRUE(full.points.u[p] == resumed.points.u[p]);
  EXPECT_TRUE(full.nb.intact == resumed.nb.intact);
  // The series files hold each time once.
  std::ifstream g(opt.out / "global.csv");
  std::string line;
  int rows = -1;
  while (std::getline(g, line)) ++rows;
  EXPECT_EQ(rows, 17);  // t = 0, 1, ..., 16 us
}

// Pre-cracks: a 2D polyline removes exactly the bonds whose segment crosses it; the 3D quad
// likewise (checked against a direct plane test).
TEST(PdPrecrack, PolylineAndQuadRemoveCrossingBonds) {
  {
    json s = specimen(2, {0.02, 0.02}, 0.001, 3, 1.0);
    s["cracks"] = json::array({{{"name", "c"}, {"points", {{-0.001, 0.01}, {0.0102, 0.01}}}}});
    auto m = build_pd_system<2>(s);
    const auto all = build_bonds<2>(m.points.x0, m.dx, m.delta);
    std::size_t expected = 0;
    for (std::size_t k = 0; k < all.size(); ++k) {
      const auto &a = m.points.x0[all.i[k]], &b = m.points.x0[all.j[k]];
      if ((a.y() - 0.01) * (b.y() - 0.01) >= 0) continue;
      const double t = (0.01 - a.y()) / (b.y() - a.y());
      if (a.x() + t * (b.x() - a.x()) <= 0.0102) ++expected;
    }
    EXPECT_GT(expected, 0u);
    EXPECT_EQ(m.precrack_bonds, expected);
    EXPECT_EQ(m.bond_count + m.precrack_bonds, all.size());
  }
  {
    json s = specimen(3, {0.01, 0.01, 0.01}, 0.001, 3, 1.0);
    s["cracks"] = json::array({{{"name", "q"}, {"quad", {{-0.001, -0.001, 0.005}, {0.0052, -0.001, 0.005},
                                                          {0.0052, 0.011, 0.005}, {-0.001, 0.011, 0.005}}}}});
    auto m = build_pd_system<3>(s);
    const auto all = build_bonds<3>(m.points.x0, m.dx, m.delta);
    std::size_t expected = 0;
    for (std::size_t k = 0; k < all.size(); ++k) {
      const auto &a = m.points.x0[all.i[k]], &b = m.points.x0[all.j[k]];
      if ((a.z() - 0.005) * (b.z() - 0.005) >= 0) continue;
      const double t = (0.005 - a.z()) / (b.z() - a.z());
      if (a.x() + t * (b.x() - a.x()) <= 0.0052) ++expected;
    }
    EXPECT_GT(expected, 0u);
    EXPECT_EQ(m.precrack_bonds, expected);
  }
  const Vec<3> a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_TRUE(segment_hits_triangle(Vec<3>(0.2, 0.2, -1), Vec<3>(0.2, 0.2, 1), a, b, c));
  EXPECT_FALSE(segment_hits_triangle(Vec<3>(0.6, 0.6, -1), Vec<3>(0.6, 0.6, 1), a, b, c));
  EXPECT_FALSE(segment_hits_triangle(Vec<3>(0.2, 0.2, 0.1), Vec<3>(0.2, 0.2, 1), a, b, c));
  EXPECT_FALSE(segment_hits_triangle(Vec<3>(0.1, 0.1, 0), Vec<3>(0.3, 0.1, 0), a, b, c));  // in the plane
}

// A 3D specimen with a through pre-crack runs, breaks bonds ahead of the crack front and writes
// its outputs (crack_tips.csv with z).
TEST(PdSolver, ThreeDimensionalCrackedBlockRuns) {
  json s = specimen(3, {0.02, 0.01, 0.004}, 0.0005, 3, 4e-6);
  s["cracks"] = json::array({{{"name", "q"}, {"quad", {{-0.001, 0.005, -0.001}, {0.008, 0.005, -0.001},
                                                        {0.008, 0.005, 0.005}, {-0.001, 0.005, 0.005}}}}});
  s["loads"] = json::array({{{"type", "velocity"}, {"region", {{"min", {0, 0.0095, 0}}, {"max", {0.02, 0.01, 0.004}}}},
                             {"velocity", {nullptr, 20.0, nullptr}}},
                            {{"type", "velocity"}, {"region", {{"min", {0, 0, 0}}, {"max", {0.02, 0.0005, 0.004}}}},
                             {"velocity", {nullptr, -20.0, nullptr}}}});
  s["output"] = {{"interval", 2e-6}, {"global_interval", 5e-7}};
  auto m = build_pd_system<3>(s);
  EXPECT_GT(m.precrack_bonds, 0u);
  const fs::path out = fs::path(CLEAVE_BINARY_DIR) / "test_out" / "pd_3d_block";
  fs::remove_all(out);
  RunOptions opt;
  opt.out = out;
  run_pd<3>(m, opt);
  std::ifstream tips(out / "crack_tips.csv");
  std::string header, row;
  std::getline(tips, header);
  EXPECT_EQ(header, "time_s,crack,tip,x_m,y_m,z_m,speed_m_per_s");
  EXPECT_TRUE(static_cast<bool>(std::getline(tips, row))) << "no damaged point was ever tracked";
  EXPECT_TRUE(fs::exists(out / "particles.pvd"));
  std::size_t broken = 0;
  for (uint8_t x : m.nb.intact) broken += !x;
  EXPECT_GT(broken, 0u);
}

// The stable step of seed 003 eq. 15 matches the groundwork's stable_dt, and the stress estimate
// gives sigma = 3/2 E eps for equibiaxial strain (plane stress, nu = 1/3) at an interior point.
TEST(PdSolver, StableStepAndStressEstimate) {
  json s = specimen(2, {0.03, 0.03}, 0.001, 3, 1.0);
  auto m = build_pd_system<2>(s);
  const auto bl = build_bonds<2>(m.points.x0, m.dx, m.delta);
  EXPECT_DOUBLE_EQ(m.stable_dt, stable_dt<2>(bl, m.points.volume, m.materials[0].k.c, kRho, m.points.size()));
  EXPECT_NEAR(m.dt, 0.5 * m.stable_dt, 1e-20);
  const double eps = 1e-5;
  for (std::size_t p = 0; p < m.points.size(); ++p) m.points.u[p] = eps * m.points.x0[p];
  PdSolver<2> solver(m);
  const auto sig = solver.stress();
  std::size_t centre = 0;
  for (std::size_t p = 0; p < m.points.size(); ++p)
    if ((m.points.x0[p] - Vec<2>(0.0145, 0.0145)).norm() < 1e-9) centre = p;
  // The lattice sum with partial volumes approximates the horizon integral to about 2 %.
  EXPECT_NEAR(sig[centre][0] / (1.5 * kE * eps), 1.0, 0.03);
  EXPECT_NEAR(sig[centre][1] / (1.5 * kE * eps), 1.0, 0.03);
  EXPECT_NEAR(sig[centre][3] / (kE * eps), 0.0, 1e-9);
}

// Bad input: SceneError naming the key path.
TEST(PdScene, ErrorsNameTheKeyPath) {
  auto key_of = [](const json& s) -> std::string {
    try {
      build_pd_system<2>(s);
    } catch (const SceneError& e) {
      return e.key_path();
    }
    return "(no error)";
  };
  json base = specimen(2, {0.01, 0.01}, 0.001, 3, 1e-6);
  json s = base;
  s["time"] = {{"end", 1e-6}, {"dt", 1e-6}};
  EXPECT_EQ(key_of(s), "time.dt");
  s = base;
  s["materials"][0].erase("fracture_energy");
  EXPECT_EQ(key_of(s), "materials[0].fracture_energy");
  s = base;
  s["loads"] = json::array({{{"type", "symmetry"}, {"axis", "x"}, {"position", 0}}});
  EXPECT_EQ(key_of(s), "loads[0].type");
  s = base;
  s["bodies"][0]["particles_per_cell"] = 2;  // an MPM key: a warning, so one scene runs under every method
  EXPECT_EQ(key_of(s), "(no error)");
  EXPECT_EQ(pd::build_pd_system<2>(s).warnings.back(),
            "bodies[0].particles_per_cell is ignored: it is an MPM key (peridynamics' lattice spacing is \"resolution\")");
  s = base;
  s["peridynamics"]["horizon_factor"] = 0;
  EXPECT_EQ(key_of(s), "peridynamics.horizon_factor");
  s = base;
  s["peridynamics"]["crack_tips"] = json::array({{{"direction", {0, 0}}}});
  EXPECT_EQ(key_of(s), "peridynamics.crack_tips[0].direction");
  s = base;
  s["grid"] = {{"cell_size", 1}};
  EXPECT_EQ(key_of(s), "grid");
  s = base;  // the one discretisation key: "resolution" is the lattice spacing, exclusive with the own key
  s["resolution"] = s["peridynamics"]["spacing"];
  EXPECT_EQ(key_of(s), "peridynamics.spacing");
  s["peridynamics"].erase("spacing");
  EXPECT_EQ(build_pd_system<2>(s).dx, build_pd_system<2>(base).dx);
  s.erase("resolution");
  EXPECT_EQ(key_of(s), "resolution");
  s = base;
  s["method"] = "sph";
  EXPECT_THROW(SceneMethod::build(s), SceneError);
  json s3 = specimen(3, {0.01, 0.01, 0.01}, 0.001, 3, 1e-6);
  s3["cracks"] = json::array({{{"name", "q"}, {"quad", {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}}}});
  try {
    build_pd_system<3>(s3);
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key_path(), "cracks[0].quad");
  }
}
