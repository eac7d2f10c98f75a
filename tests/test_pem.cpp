// The particle equilibrium method (seed 004, docs/pem.md): the calibration of the pair network, the
// force laws, and the method on small scenes (validation.md §6): the cantilever against Timoshenko,
// a tension block's E and nu, pre-cracks, equilibrium and separation, determinism, bad input.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "libmpm/core/error.hpp"
#include <filesystem>
#include <fstream>

#include "libmpm/method/method.hpp"
#include "libmpm/method/run_loop.hpp"
#include "libmpm/pem/calibration.hpp"
#include "libmpm/pem/pair_law.hpp"
#include "libmpm/pem/pem_scene.hpp"
#include "libmpm/pem/pem_solver.hpp"
#include "files.hpp"

namespace {

using nlohmann::json;
using namespace cleave;
using namespace cleave::pem;

template <int Dim>
std::vector<Vec<Dim>> directions(const std::vector<Vec<Dim>>& x) {
  std::vector<Vec<Dim>> t;
  for (std::size_t a = 0; a < x.size(); ++a)
    for (std::size_t b = a + 1; b < x.size(); ++b) t.push_back((x[b] - x[a]).normalized());
  return t;
}

template <int Dim>
NetworkTensor<Dim> fitted(const std::vector<Vec<Dim>>& x, double V, double mu) {
  const auto t = directions(x);
  const auto a = fit_element_pairs<Dim>(t, V, mu);
  NetworkTensor<Dim> T;
  T.volume = V;
  for (std::size_t q = 0; q < t.size(); ++q) T.add(t[q], a[q]);
  return T;
}

TEST(PemCalibration, AnEquilateralTrianglesPairsStoreTheIsotropicContinuumExactly) {
  const double mu = 3e9, V = 0.5;
  const auto T = fitted<2>({Vec<2>(0, 0), Vec<2>(1, 0), Vec<2>(0.5, std::sqrt(3.0) / 2)}, V, mu);
  double lambda, m, aniso;
  T.isotropic(lambda, m, aniso);
  EXPECT_NEAR(m, mu, 1e-9 * mu);
  EXPECT_NEAR(lambda, mu, 1e-9 * mu);  // Cauchy: lambda = mu
  EXPECT_LT(aniso, 1e-12);
}

TEST(PemCalibration, ASquaresSidesAndDiagonalsStoreTheIsotropicContinuumExactly) {
  const double mu = 1.0;
  const auto T = fitted<2>({Vec<2>(0, 0), Vec<2>(1, 0), Vec<2>(1, 1), Vec<2>(0, 1)}, 1.0, mu);
  double lambda, m, aniso;
  T.isotropic(lambda, m, aniso);
  EXPECT_NEAR(m, mu, 1e-12);
  EXPECT_NEAR(lambda, mu, 1e-12);
  EXPECT_LT(aniso, 1e-12);
}

// The six edges of a regular tetrahedron run along the face diagonals of a cube: their tensor is
// cubic (xxxx = 2 xxyy), not isotropic, so 3D networks are isotropic only on average over many
// orientations (the 3D tension test below), and the fit says how far one element is.
TEST(PemCalibration, ARegularTetrahedronsPairsAreCubicAndTheFitSaysSo) {
  const auto T = fitted<3>({Vec<3>(1, 1, 1), Vec<3>(1, -1, -1), Vec<3>(-1, 1, -1), Vec<3>(-1, -1, 1)}, 8.0 / 3.0, 2.0);
  double lambda, m, aniso;
  T.isotropic(lambda, m, aniso);
  EXPECT_NEAR(T.c[0] / T.c[0 * 27 + 0 * 9 + 1 * 3 + 1], 2.0, 1e-12);  // c_xxxx / c_xxyy
  EXPECT_GT(aniso, 0.1);
}

// A right triangle's three pairs cannot be isotropic: the fit says how far it is, and stays >= 0.
TEST(PemCalibration, ARightTrianglesFitIsNonNegativeAndReportsItsAnisotropy) {
  const auto t = directions<2>({Vec<2>(0, 0), Vec<2>(1, 0), Vec<2>(0, 1)});
  const auto a = fit_element_pairs<2>(t, 0.5, 1.0);
  for (double v : a) EXPECT_GE(v, 0.0);
  NetworkTensor<2> T;
  T.volume = 0.5;
  for (std::size_t q = 0; q < t.size(); ++q) T.add(t[q], a[q]);
  double lambda, m, aniso;
  T.isotropic(lambda, m, aniso);
  EXPECT_GT(aniso, 0.05);
}

TEST(PemCalibration, NonNegativeLeastSquaresClampsWhatTheFreeSolutionWouldMakeNegative) {
  // min 1/2 a^T G a - b^T a with G = I, b = (1, -2): a = (1, 0).
  const auto a = nnls_normal({1, 0, 0, 1}, {1, -2}, 2);
  EXPECT_DOUBLE_EQ(a[0], 1.0);
  EXPECT_DOUBLE_EQ(a[1], 0.0);
}

TEST(PemCalibration, CentralForceNetworksHaveTheCauchyPoissonsRatio) {
  double E, nu;
  young_poisson(1.0, 1.0, true, E, nu);
  EXPECT_NEAR(nu, 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(E, 8.0 / 3.0, 1e-15);
  young_poisson(1.0, 1.0, false, E, nu);
  EXPECT_NEAR(nu, 0.25, 1e-15);
  EXPECT_NEAR(E, 2.5, 1e-15);
}

TEST(PemPairLaw, TheElasticLawRisesWithOneSlopeAndFallsWithTheSecondToZeroAtTheCutoff) {
  PairLaw law;
  law.eps_peak = 0.01, law.eps_cut = 0.03;
  const double k = 2.0, l0 = 1.0;
  EXPECT_DOUBLE_EQ(elastic_force(k, l0, -0.02, law), -0.04);  // repulsion
  EXPECT_DOUBLE_EQ(elastic_force(k, l0, 0.01, law), 0.02);    // the peak
  EXPECT_NEAR(elastic_force(k, l0, 0.02, law), 0.01, 1e-15);  // half way down
  EXPECT_NEAR(elastic_force(k, l0, 0.03, law), 0.0, 1e-15);
  // The energy is the force's integral: its derivative is the force, and at the cutoff it is the
  // work to break the pair, k l0^2 eps_p eps_c / 2.
  for (double dl : {-0.01, 0.005, 0.015, 0.025}) {
    const double h = 1e-7;
    EXPECT_NEAR((elastic_energy(k, l0, dl + h, law) - elastic_energy(k, l0, dl - h, law)) / (2 * h),
                elastic_force(k, l0, dl, law), 1e-8);
  }
  EXPECT_NEAR(elastic_energy(k, l0, 0.03, law), 0.5 * k * 0.01 * 0.03, 1e-15);
}

TEST(PemPairLaw, ThePlasticLawShiftsTheBalanceDistanceAtTheYieldForce) {
  PairLaw law;
  law.eps_yield = 0.01;
  const double k = 1.0, l0 = 1.0;
  double b, alpha;
  // Stretched to 3 yield strains: the force stays at the yield force, the balance length moves 0.02.
  const double f = plastic_force(k, l0, 1.03, law, 1.0, 0.0, b, alpha);
  EXPECT_NEAR(f, 0.01, 1e-15);
  EXPECT_NEAR(b, 1.02, 1e-15);
  // Unloading to the old balance length pushes back elastically from the new one.
  double b2, a2;
  EXPECT_NEAR(plastic_force(k, l0, 1.015, law, b, alpha, b2, a2), -0.005, 1e-15);
  EXPECT_NEAR(b2, b, 1e-15);
}

// --- the method on scenes ---------------------------------------------------------------------

json scene_file(const std::string& name) {
  std::ifstream in(std::string(CLEAVE_SOURCE_DIR) + "/data/scenes/" + name);
  return json::parse(in);
}

// Steps the scene's method until it ends (equilibrium, separation, static) or time.end.
std::unique_ptr<Method<2>> run_to_end(const json& scene) {
  auto m = build_method<2>(scene);
  const double end = m->settings().end_time;
  while (!m->static_reached() && m->time() < end * (1 - 1e-12)) m->step();
  return m;
}

// Reference positions and displacements of the particle frame.
struct Field {
  std::vector<Vec<2>> x0, u;
};
Field field(Method<2>& m) {
  const io::PointSet ps = m.frame(0);
  const io::PointArray* disp = nullptr;
  for (const auto& a : ps.arrays)
    if (a.name == "displacement") disp = &a;
  Field f;
  for (std::size_t p = 0; p < ps.size(); ++p) {
    const Vec<2> u(disp->values[3 * p], disp->values[3 * p + 1]);
    f.u.push_back(u);
    f.x0.push_back(Vec<2>(ps.points[3 * p], ps.points[3 * p + 1]) - u);
  }
  return f;
}

// Seed 004 §4.1 (validation.md §6): the 8 m x 1 m cantilever of 81 x 11 particles under 10 kN/m,
// clamped. Timoshenko with shear (kappa 5/6, G = 3E/8 for the network's nu = 1/3): the tip within
// 3 %, the deflection line of the mid-plane within 5 % of the tip deflection (near the clamp the
// whole clamped face is stiffer than beam theory's root: docs/validation.md, "PEM").
TEST(PemCantilever, TipDeflectionIsTimoshenkosWithinThreePercentAndTheRunEndsAtEquilibrium) {
  auto m = run_to_end(scene_file("pem_cantilever.json"));
  EXPECT_EQ(m->run_info()["end"], "equilibrium");
  const Field f = field(*m);
  ASSERT_EQ(f.x0.size(), 891u);
  const double E = 3e10, I = 1.0 / 12, q = 1e4, L = 8, G = 3 * E / 8, kappa = 5.0 / 6;
  auto timoshenko = [&](double x) {
    return q * x * x * (6 * L * L - 4 * L * x + x * x) / (24 * E * I) + q * (L * x - x * x / 2) / (kappa * G * 1.0);
  };
  double tip = 0, ntip = 0, worst = 0;
  for (std::size_t p = 0; p < f.x0.size(); ++p) {
    if (std::fabs(f.x0[p].x() - L) < 1e-9) tip += -f.u[p].y(), ++ntip;
    if (std::fabs(f.x0[p].y() - 0.5) < 1e-9) worst = std::max(worst, std::fabs(-f.u[p].y() - timoshenko(f.x0[p].x())));
  }
  tip /= ntip;
  EXPECT_NEAR(tip / timoshenko(L), 1.0, 0.03) << "tip " << tip;
  EXPECT_LT(worst / timoshenko(L), 0.05);
}

// validation.md §6: a uniaxial-tension block (unstructured triangles) strains uniformly; E within
// 2 % of the scene's, nu within 2 % of what the calibration reports for the network.
TEST(PemTension, TheBlocksYoungsModulusIsTheScenesWithinTwoPercentAndNuTheNetworks) {
  const json s = scene_file("pem_tension.json");
  auto m = run_to_end(s);
  EXPECT_EQ(m->run_info()["end"], "equilibrium");
  const double nu_network = m->run_info()["pair_network"][0]["nu"];
  const Field f = field(*m);
  const double L = 0.2, H = 0.1, sigma = 10e6, E = 70e9;
  double ux = 0, n_right = 0, top = 0, n_top = 0, bottom = 0, n_bottom = 0;
  for (std::size_t p = 0; p < f.x0.size(); ++p) {
    if (std::fabs(f.x0[p].x() - L) < 1e-9) ux += f.u[p].x(), ++n_right;
    if (std::fabs(f.x0[p].y() - H) < 1e-9) top += f.u[p].y(), ++n_top;
    if (std::fabs(f.x0[p].y()) < 1e-9) bottom += f.u[p].y(), ++n_bottom;
  }
  const double ex = ux / n_right / L, ey = (top / n_top - bottom / n_bottom) / H;
  EXPECT_NEAR(sigma / ex / E, 1.0, 0.02);
  EXPECT_NEAR(-ey / ex / nu_network, 1.0, 0.02);
  // Uniform: u_x = ex x everywhere within 2 % of the end's displacement.
  double worst = 0;
  for (std::size_t p = 0; p < f.x0.size(); ++p) worst = std::max(worst, std::fabs(f.u[p].x() - ex * f.x0[p].x()));
  EXPECT_LT(worst / (ex * L), 0.02);
}

// The same in 3D (unstructured tetrahedra, network nu 1/4): a 0.4 x 0.1 x 0.1 m steel bar on three
// symmetry planes pulled by 100 MPa. E within 2 % of the scene's.
TEST(PemTension, ASolidBarsYoungsModulusIsTheScenesWithinTwoPercent) {
  const json s = json::parse(R"({"method": "pem", "analysis": {"type": "3d"}, "resolution": 0.02,
    "pem": {"equilibrium": {"velocity": 1e-6, "residual": 1e-5}},
    "materials": [{"name": "steel", "type": "linear_elastic", "E": 2e11, "density": 7800}],
    "bodies": [{"name": "bar", "material": "steel", "shape": {"type": "box", "min": [0, 0, 0], "max": [0.4, 0.1, 0.1]}}],
    "loads": [{"type": "symmetry", "axis": "x", "position": 0}, {"type": "symmetry", "axis": "y", "position": 0},
              {"type": "symmetry", "axis": "z", "position": 0}, {"type": "traction", "face": "+x", "traction": [1e8, 0, 0]}],
    "damping": {"kinetic": 3e4}, "time": {"end": 2e-3, "cfl": 0.9}, "output": {"interval": 1e-4}})");
  auto m = build_method<3>(s);
  while (!m->static_reached() && m->time() < 2e-3) m->step();
  EXPECT_EQ(m->run_info()["end"], "equilibrium");
  const io::PointSet ps = m->frame(0);
  const io::PointArray* disp = nullptr;
  for (const auto& a : ps.arrays)
    if (a.name == "displacement") disp = &a;
  double ux = 0, n = 0;
  for (std::size_t p = 0; p < ps.size(); ++p) {
    const double x0 = ps.points[3 * p] - disp->values[3 * p];
    if (std::fabs(x0 - 0.4) < 1e-9) ux += disp->values[3 * p], ++n;
  }
  EXPECT_NEAR(1e8 / (ux / n / 0.4) / 2e11, 1.0, 0.02);
}

// Seed 004 §4.2 (validation.md §6): the disc with a central crack of length r at 20 degrees to the
// load. Cracks start at the pre-crack's tips and run towards the loading points, and the run ends when
// the disc separates. The initiation angle is printed, not asserted: it misses the maximum hoop
// stress prediction (docs/validation.md, "PEM", with the figures).
TEST(PemBrazilianCracked, CracksStartAtTheTipsAndRunToTheLoadingPointsUntilTheDiscSeparates) {
  const json s = scene_file("pem_brazilian_cracked.json");
  auto m = build_method<2>(s);
  const double R = 0.05;
  const Vec<2> tip(0.025 * std::sin(20 * M_PI / 180), 0.025 * std::cos(20 * M_PI / 180));
  bool first_seen = false;
  double first_distance = 0;
  while (!m->static_reached() && m->time() < m->settings().end_time) {
    m->step();
    if (!first_seen && m->step_count() % 50 == 0) {
      const io::PointSet c = m->frame(1);  // crack pieces; "initial" = 0: broken during the run
      for (std::size_t p = 0; p < c.size(); ++p)
        if (c.arrays[0].values[p] == 0.0) {
          const Vec<2> x(c.points[3 * p], c.points[3 * p + 1]);
          const double d = std::min((x - tip).norm(), (x + tip).norm());
          first_distance = first_seen ? std::min(first_distance, d) : d;
          first_seen = true;
        }
    }
  }
  EXPECT_EQ(m->run_info()["end"], "separated");
  ASSERT_TRUE(first_seen);
  EXPECT_LT(first_distance, 0.003) << "the first cracks start away from the pre-crack's tips";
  // The cracks reach both loading points (within 0.2 R of (0, +-R)).
  const io::PointSet c = m->frame(1);
  double top = 1, bottom = 1;
  for (std::size_t p = 0; p < c.size(); ++p) {
    const Vec<2> x(c.points[3 * p], c.points[3 * p + 1]);
    top = std::min(top, (x - Vec<2>(0, R)).norm());
    bottom = std::min(bottom, (x - Vec<2>(0, -R)).norm());
  }
  EXPECT_LT(top, 0.2 * R);
  EXPECT_LT(bottom, 0.2 * R);
}

// Validation 3's initiation angle (validation.md §6): the maximum hoop stress criterion with MPM's
// K_II/K_I on the same geometry puts the kink at 67.7 degrees from the crack line, towards the load;
// the issue asks for 10 degrees. With tip growth (the scene's) both tips start there on the shipped
// 1 mm triangles and on 1.5 mm triangles and 1 mm quadrangles (the pair rule read -3 to +85 degrees
// over such meshes), and the disc separates.
TEST(PemBrazilianCracked, BothTipsKinkWithin10DegreesOfTheMaximumHoopStressAngleOnEveryMesh) {
  for (const char* mesh : {"shipped", "1.5 mm", "quadrangles"}) {
    SCOPED_TRACE(mesh);
    json s = scene_file("pem_brazilian_cracked.json");
    if (std::string(mesh) == "1.5 mm") s["resolution"] = 1.5;
    if (std::string(mesh) == "quadrangles") s["pem"]["elements"] = "quadrangles";
    auto m = run_to_end(s);
    const json info = m->run_info();
    EXPECT_EQ(info["end"], "separated");
    ASSERT_EQ(info["tips"].size(), 2u);
    for (const auto& tip : info["tips"]) {
      ASSERT_FALSE(tip["kink_deg"].is_null());
      std::printf("%s: tip kinks %.1f deg (K_I %.3g, K_II %.3g Pa sqrt(m) when it started)\n", mesh,
                  tip["kink_deg"].get<double>(), tip["K_I_at_start_Pa_sqrt_m"].get<double>(),
                  tip["K_II_at_start_Pa_sqrt_m"].get<double>());
      EXPECT_NEAR(tip["kink_deg"].get<double>(), 67.7, 10.0);
    }
  }
}

// Seed 004 §4.3 (validation.md §6): the concrete beam's cracks run through the interface phase: most
// pairs broken during the run are interface pairs (the interface holds 17 % of the pairs).
TEST(PemConcreteBeam, MostBrokenPairsLieInTheInterfacePhase) {
  auto m = run_to_end(scene_file("pem_three_point_bend.json"));
  const json info = m->run_info();
  const double itz = info["broken_pairs_by_material"]["interface"], mortar = info["broken_pairs_by_material"]["mortar"],
               aggregate = info["broken_pairs_by_material"]["aggregate"];
  const double share = double(info["pairs_by_material"]["interface"]) /
                       (double(info["pairs_by_material"]["interface"]) + double(info["pairs_by_material"]["mortar"]) +
                        double(info["pairs_by_material"]["aggregate"]));
  std::printf("broken pairs: interface %g, mortar %g, aggregate %g; interface pairs %.1f %% of all\n", itz, mortar,
              aggregate, 100 * share);
  EXPECT_GT(itz + mortar + aggregate, 50.0);
  EXPECT_GT(itz / (itz + mortar + aggregate), 0.5);
}

// The plastic law (seed 004 fig. 5) on a plate pulled at 1 m/s (0.5 %/ms): linear at the scene's E,
// then flowing at the yield stress. The pairs along the load yield first; those at an angle are
// stretched less and yield later, so the network's plateau lies a little above yield_stress (+1.4 %
// at 0.6 % strain, +2.0 % at 1 %): asserted within 3 % there, and E within 2 % before yield.
TEST(PemPlastic, APlatePulledInTensionFlowsAtTheYieldStress) {
  json s = scene_file("pem_tension.json");
  s["materials"][0] = {{"name", "aluminium"}, {"type", "elastic_plastic"}, {"E", 70000}, {"density", 2700},
                       {"yield_stress", 200}};
  s["loads"] = json::parse(R"([{"type": "symmetry", "axis": "x", "position": 0},
    {"type": "velocity", "region": {"min": [-0.01, -0.01], "max": [0.01, 0.01]}, "velocity": [null, 0]},
    {"type": "velocity", "region": {"min": [199.99, -1], "max": [200.01, 101]}, "velocity": [1.0, null]}])");
  s["pem"].erase("equilibrium");
  s["time"] = {{"end", 1.2}, {"cfl", 0.9}};
  auto m = build_method<2>(s);
  auto mean_sxx = [&] {
    const io::PointSet ps = m->frame(0);
    const io::PointArray *disp = nullptr, *stress = nullptr;
    for (const auto& a : ps.arrays) {
      if (a.name == "displacement") disp = &a;
      if (a.name == "stress") stress = &a;
    }
    double sum = 0, n = 0, ux = 0, nr = 0;
    for (std::size_t p = 0; p < ps.size(); ++p) {
      const double x0 = ps.points[3 * p] - disp->values[3 * p];
      if (x0 > 0.02 && x0 < 0.18) sum += stress->values[6 * p], ++n;
      if (std::fabs(x0 - 0.2) < 1e-9) ux += disp->values[3 * p], ++nr;
    }
    return std::make_pair(sum / n, ux / nr / 0.2);
  };
  while (m->time() < 0.2e-3) m->step();  // 0.1 % strain: elastic
  const auto [s1, e1] = mean_sxx();
  EXPECT_NEAR(s1 / e1 / 70e9, 1.0, 0.02);
  while (m->time() < 1.2e-3 * (1 - 1e-9)) m->step();  // 0.6 % strain, three times the yield strain
  const auto [s2, e2] = mean_sxx();
  EXPECT_NEAR(e2, 0.006, 2e-4);
  EXPECT_GE(s2, 200e6);
  EXPECT_LT(s2, 1.03 * 200e6);
}

// Seed 004 §3 step 4: a step that would break more pairs than pem.break_limit allows is redone as
// two half steps (down to max_halvings); with a limit of one pair per step the cracking disc halves
// steps, and ends at the same time as an unhalved run.
TEST(PemSolver, AStepBreakingTooManyPairsIsRedoneInHalves) {
  json s = scene_file("pem_brazilian_cracked.json");
  s["pem"].erase("tip_growth");  // seed 004's pair rule: pairs break on their own stretch
  s["time"]["end"] = 0.6;
  s["pem"]["break_limit"] = 1e-6;  // at least one pair: two in one step halve it
  auto m = run_to_end(s);
  EXPECT_GT(m->run_info()["halved_steps"].get<long>(), 0);
  EXPECT_NEAR(m->time(), 0.6e-3, m->settings().dt);  // the step that passes time.end is whole
}

// Bad input: exit 2 material, with the key and the reason.
std::string refusal(const json& s) {
  try {
    build_pem_system<2>(s);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(PemSceneErrors, BadInputIsRefusedNamingTheKeyAndTheReason) {
  const json base = scene_file("pem_tension.json");
  json s = base;
  s["materials"][0]["cutoff_strain"] = 0;
  EXPECT_EQ(refusal(s), "materials[0].cutoff_strain: the cutoff distance must lie beyond the balance distance (a cutoff "
                        "strain > 0; got 0)");
  s = base;
  s["materials"][0]["tensile_strength"] = 100;  // MPa
  s["materials"][0]["fracture_energy"] = 1e-6;  // MPa mm = 1 mJ/m^2
  EXPECT_EQ(refusal(s).rfind("materials[0].fracture_energy: the cutoff falls below the peak", 0), 0u) << refusal(s);
  s = base;
  s["pem"]["elements"] = "hexagons";
  EXPECT_EQ(refusal(s).rfind("pem.elements: unknown element kind 'hexagons'", 0), 0u) << refusal(s);
  s = base;
  s["pem"]["mesh_file"] = "missing.msh";
  EXPECT_EQ(refusal(s).rfind("pem.mesh_file: give bodies (meshed by Gmsh) or pem.mesh_file, not both", 0), 0u);
  s = base;
  s.erase("bodies");
  s["pem"]["mesh_file"] = "no/such/file.msh";
  EXPECT_NE(refusal(s).find("no/such/file.msh"), std::string::npos) << refusal(s);
  EXPECT_EQ(refusal(s).rfind("pem.mesh_file", 0), 0u) << refusal(s);
  s = base;
  s["materials"][0]["type"] = "rubber";
  EXPECT_EQ(refusal(s).rfind("materials[0].type: unknown material type 'rubber' for pem; valid: elastic_plastic, "
                             "linear_elastic", 0), 0u) << refusal(s);
  s = base;
  s["bodies"].push_back({{"name", "over"}, {"material", "aluminium"},
                         {"shape", {{"type", "rectangle"}, {"min", {100, 50}}, {"max", {300, 150}}}}});
  EXPECT_EQ(refusal(s).rfind("bodies[1].shape", 0), 0u) << refusal(s);
  s = base;
  s["materials"][0]["nu"] = 0.2;  // a warning, not an error: the network's nu is 1/3 here
  const auto m = build_pem_system<2>(s);
  ASSERT_FALSE(m.warnings.empty());
  EXPECT_NE(m.warnings.back().find("materials[0].nu = 0.2 cannot be met: a central-force pair network gives nu = 0.333"),
            std::string::npos) << m.warnings.back();
}

// pem.tip_growth's keys and what it needs (the cracked disc at 3 mm elements, to build quickly).
TEST(PemSceneErrors, TipGrowthIsRefusedWhereItCannotWorkNamingTheKey) {
  json base = scene_file("pem_brazilian_cracked.json");
  base["resolution"] = 3.0;
  EXPECT_EQ(build_pem_system<2>(base).tips.size(), 2u);
  json s = base;
  s["pem"]["tip_growth"]["radius"] = 5;  // mm: under 2 mesh sizes
  EXPECT_EQ(refusal(s).rfind("pem.tip_growth.radius: at least 2 mesh sizes", 0), 0u) << refusal(s);
  s = base;
  s["pem"]["tip_growth"]["length"] = 20;
  EXPECT_EQ(refusal(s), "pem.tip_growth.length: between 0.25 and 4 mesh sizes");
  s = base;
  s["pem"]["tip_growth"]["speed"] = 1;
  EXPECT_EQ(refusal(s).rfind("pem.tip_growth.speed: unknown key; valid keys: radius, length, max_speed", 0), 0u)
      << refusal(s);
  s = base;
  s.erase("cracks");
  EXPECT_EQ(refusal(s), "pem.tip_growth: the scene declares no cracks to grow");
  s = base;
  s["materials"][0].erase("fracture_energy");
  EXPECT_EQ(refusal(s), "pem.tip_growth: the material 'rock' at a tip of crack 'centre' gives no fracture_energy: "
                        "the tips grow when K reaches sqrt(E' G_c)");
  s = base;
  s["cracks"][0]["points"] = {{60, 0}, {70, 0}};  // outside the disc
  EXPECT_EQ(refusal(s), "pem.tip_growth: no crack has a tip inside the bodies");
  const json bar = json::parse(R"({"method": "pem", "analysis": {"type": "3d"}, "resolution": 0.05,
    "pem": {"tip_growth": {}},
    "materials": [{"name": "steel", "type": "linear_elastic", "E": 2e11, "density": 7800, "fracture_energy": 1e4}],
    "bodies": [{"name": "bar", "material": "steel", "shape": {"type": "box", "min": [0, 0, 0], "max": [0.4, 0.1, 0.1]}}],
    "time": {"end": 1e-4}})");
  std::string why = "(accepted)";
  try {
    build_pem_system<3>(bar);
  } catch (const SceneError& e) {
    why = e.what();
  }
  EXPECT_EQ(why, "pem.tip_growth: tip growth is 2D only (3D pem cracks grow by pairs breaking)");
}

// A mesh drawn elsewhere: a Gmsh .msh file whose physical groups are the bodies, each mapped to a
// material by pem.regions; loads name the groups. Two unit squares of two materials (2 x 2 triangles).
TEST(PemMeshFile, PhysicalGroupsBecomeBodiesWithTheirMaterials) {
  const auto dir = std::filesystem::path(CLEAVE_BINARY_DIR) / "test_out" / "pem_mesh_file";
  std::filesystem::create_directories(dir);
  const auto file = dir / "two_squares.msh";
  std::ofstream(file) << R"($MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
2
2 1 "left"
2 2 "right"
$EndPhysicalNames
$Nodes
6
1 0 0 0
2 1 0 0
3 2 0 0
4 0 1 0
5 1 1 0
6 2 1 0
$EndNodes
$Elements
4
1 2 2 1 1 1 2 5
2 2 2 1 1 1 5 4
3 2 2 2 2 2 3 6
4 2 2 2 2 2 6 5
$EndElements
)";
  json s = json::parse(R"({"method": "pem", "analysis": {"type": "plane_stress", "thickness": 0.1},
    "materials": [{"name": "soft", "type": "linear_elastic", "E": 1e9, "density": 1000},
                  {"name": "hard", "type": "linear_elastic", "E": 4e9, "density": 3000}],
    "loads": [{"type": "traction", "body": "right", "face": "+x", "traction": [1e6, 0]},
              {"type": "velocity", "region": {"min": [-0.1, -0.1], "max": [0.1, 1.1]}, "velocity": [0, 0]}],
    "time": {"end": 1e-3}})");
  s["pem"] = {{"mesh_file", file.string()}, {"regions", {{"left", "soft"}, {"right", "hard"}}}};
  const PemSystem<2> m = build_pem_system<2>(s);
  EXPECT_EQ(m.regions, (std::vector<std::string>{"left", "right"}));
  ASSERT_EQ(m.points.x0.size(), 6u);
  EXPECT_EQ(m.pair_count, 9u);  // 4 triangles share 3 inner edges: 12 - 3
  // Masses: each node takes a third of each of its triangles' masses (0.5 m^2 x 0.1 m each).
  double mass = 0;
  for (double v : m.points.mass) mass += v;
  EXPECT_NEAR(mass, 1000 * 0.1 + 3000 * 0.1, 1e-9);
  // The traction on the right group's +x face: 1e6 Pa x 1 m x 0.1 m on the two nodes at x = 2.
  ASSERT_EQ(m.loads.size(), 1u);
  double fx = 0;
  for (const auto& f : m.loads[0].force) fx += f.x();
  EXPECT_NEAR(fx, 1e5, 1e-6);
  s["pem"]["regions"] = {{"left", "soft"}, {"middle", "hard"}};
  EXPECT_EQ(refusal(s).rfind("pem.regions.middle: no region of that name in", 0), 0u) << refusal(s);
  s["pem"]["regions"] = {{"left", "soft"}};
  EXPECT_EQ(refusal(s).rfind("pem.regions: region 'right' of", 0), 0u) << refusal(s);
}

// 1 and 2 threads, and a run stopped at a frame and resumed, give the same files bit for bit (the
// cracked disc at 1 mm, 9 339 particles: above the parallel threshold, through the start of cracking),
// with the tips growing (the scene's pem.tip_growth; the run split after both tips grew) and with
// seed 004's pair rule (tip growth off: pairs break on their own stretch, from about 0.5 ms).
TEST(PemDeterminism, ThreadCountAndResumeGiveTheSameFilesBitForBit) {
  for (const bool tips : {true, false}) {
    SCOPED_TRACE(tips ? "tip growth" : "pair rule");
    const auto base = std::filesystem::path(CLEAVE_BINARY_DIR) / "test_out" / (tips ? "pem_determinism_tips" : "pem_determinism");
    std::filesystem::remove_all(base);
    json s = scene_file("pem_brazilian_cracked.json");
    if (!tips) s["pem"].erase("tip_growth");
    s["time"]["end"] = tips ? 0.5 : 0.6;  // ms
    s["output"]["interval"] = 0.1;
    auto run = [&](const json& scene, const std::string& dir, bool resume, int threads) {
      const int was = omp_get_max_threads();
      omp_set_num_threads(threads);
      RunOptions opt;
      opt.out = base / dir;
      opt.resume = resume;
      run_method<2>(*build_method<2>(scene), opt);
      omp_set_num_threads(was);
    };
    run(s, "two", false, 2);
    json first = s;
    first["time"]["end"] = tips ? 0.4 : 0.3;
    run(first, "split", false, 2);
    run(s, "split", true, 2);
    run(s, "one", false, 1);
    const std::string whole = test::read_text(base / "two" / "global.csv");
    EXPECT_GT(std::count(whole.begin(), whole.end(), '\n'), 100);
    EXPECT_EQ(test::read_text(base / "one" / "global.csv"), whole);
    EXPECT_EQ(test::read_text(base / "split" / "global.csv"), whole);
    const std::string last = tips ? "000005" : "000006";
    for (const std::string& f : {"particles_" + last + ".vtu", "cracks_" + last + ".vtu"}) {
      EXPECT_EQ(test::read_text(base / "one" / f), test::read_text(base / "two" / f)) << f;
      EXPECT_EQ(test::read_text(base / "split" / f), test::read_text(base / "two" / f)) << f;
    }
    if (tips) {  // both tips grew before the split and after it
      const json info = json::parse(test::read_text(base / "split" / "run.json"));
      for (const auto& tip : info["tips"]) EXPECT_LT(tip["started_s"].get<double>(), 0.4e-3);
      EXPECT_EQ(info["tips"], json::parse(test::read_text(base / "two" / "run.json"))["tips"]);
    }
  }
}

}  // namespace
