// OpenMP runs are deterministic: 1 and 2 threads give the same result (issue: solver). The strip
// colouring of the scatter passes and chunked sums make it bit-identical, which is what we assert.
#include <gtest/gtest.h>
#include <omp.h>

#include "support.hpp"

namespace cleave {
namespace {

template <int Dim>
struct Snapshot {
  std::vector<Vec<Dim>> x, v;
  std::vector<Sym<Dim>> stress;
  GlobalState<Dim> g;
};

template <int Dim>
Snapshot<Dim> run(const nlohmann::json& scene, int threads, long steps) {
  omp_set_num_threads(threads);
  Model<Dim> m = build_model<Dim>(scene);
  auto st = make_stepper<Dim>(m);
  EXPECT_FALSE(test::advance(*st, steps));
  return {m.particles.x, m.particles.v, m.particles.stress, st->global_state()};
}

template <int Dim>
void expect_identical(const Snapshot<Dim>& a, const Snapshot<Dim>& b) {
  ASSERT_EQ(a.x.size(), b.x.size());
  std::size_t diff = 0;
  for (std::size_t p = 0; p < a.x.size(); ++p)
    diff += (a.x[p] != b.x[p]) + (a.v[p] != b.v[p]) + (a.stress[p] != b.stress[p]);
  EXPECT_EQ(diff, 0u) << "particle values differ between 1 and 2 threads";
  EXPECT_EQ(a.g.kinetic, b.g.kinetic);
  EXPECT_EQ(a.g.strain, b.g.strain);
}

TEST(Determinism, BeamImpactOneVsTwoThreads) {
  // The shipped scene (9712 particles: above the size at which loops go parallel).
  nlohmann::json s = load_scene_file(CLEAVE_SOURCE_DIR "/data/scenes/beam_impact.json");
  s["bodies"][1]["shape"]["center"] = {0, 11.1};  // 0.1 mm gap: contact after ~400 steps
  for (const char* scheme : {"USAVG", "MUSL"}) {
    s["mpm"]["stress_update"] = scheme;
    const auto a = run<2>(s, 1, 700);
    const auto b = run<2>(s, 2, 700);
    expect_identical(a, b);
  }
}

// A cracked scene stepped at 1 and at 2 threads: the same particles, energies and crack geometry
// (its one crack with enough points that the loops over them run in parallel). Returns the crack.
template <int Dim>
crack::ExplicitCrack<Dim> expect_cracked_run_identical(const nlohmann::json& s, long steps, const char* what) {
  std::vector<crack::ExplicitCrack<Dim>> cracks[2];
  Snapshot<Dim> snap[2];
  for (int t = 0; t < 2; ++t) {
    omp_set_num_threads(t + 1);
    Model<Dim> m = build_model<Dim>(s);
    auto st = make_stepper<Dim>(m);
    EXPECT_FALSE(test::advance(*st, steps));
    snap[t] = {m.particles.x, m.particles.v, m.particles.stress, st->global_state()};
    cracks[t] = m.cracks;
  }
  expect_identical(snap[0], snap[1]);
  EXPECT_EQ(cracks[0].size(), 1u);
  if (cracks[0].empty()) return {};
  EXPECT_GT(cracks[0][0].points.size(), 128u);  // the parallel loops over crack points ran
  EXPECT_TRUE(cracks[0][0].points == cracks[1][0].points && cracks[0][0].above == cracks[1][0].above &&
              cracks[0][0].below == cracks[1][0].below)
      << what << ": crack geometry differs between 1 and 2 threads";
  return cracks[0][0];
}

TEST(Determinism, CrackedDcbOneVsTwoThreads) {
  // The DCB with its explicit crack, refined so that the near particles run in the strip-ordered
  // parallel passes (more than 8 192 particles in all) and the crack module's loops over crack points
  // and multi-field nodes run in parallel (more than 128 of each: 209 crack points, segments of half
  // a cell).
  nlohmann::json s = load_scene_file(CLEAVE_SOURCE_DIR "/data/scenes/dcb_crack.json");
  s["resolution"] = 0.5;
  s["cracks"][0]["segment_length"] = 0.25;
  s["bodies"][0]["particles_per_cell"] = 4;
  s["mpm"]["shape_function"] = "ugimp";
  for (const char* scheme : {"USAVG", "USF"}) {  // re-extrapolating; moving in Task 5
    s["mpm"]["stress_update"] = scheme;
    expect_cracked_run_identical<2>(s, 20, scheme);
  }
}

TEST(Determinism, CrackedBlock3DOneVsTwoThreads) {
  // The penny-cracked block (32 000 particles; about 300 crack points: the loops over particles, crack
  // points and multi-field nodes all run in parallel), stepped until its crack has opened and moved.
  const nlohmann::json s = load_scene_file(CLEAVE_SOURCE_DIR "/data/scenes/block_penny_crack.json");
  const auto c = expect_cracked_run_identical<3>(s, 50, "penny block");
  double opening = 0.0;
  for (std::size_t i = 0; i < c.points.size(); ++i) opening = std::max(opening, (c.above[i] - c.below[i]).norm());
  EXPECT_GT(opening, 0.0) << "the crack has not opened: the test does not exercise a moving crack";
}

TEST(Determinism, Solid3DOneVsTwoThreads) {
  nlohmann::json s;
  s["analysis"] = {{"type", "3d"}};
  s["grid"] = {{"cell_size", 0.01}};
  s["materials"] = nlohmann::json::array({test::material("m", 1e9, 0.3, 1000)});
  s["bodies"] = nlohmann::json::array(
      {{{"name", "b"}, {"material", "m"}, {"velocity", {1.0, -2.0, 0.5}},
        {"shape", {{"type", "cylinder"}, {"center", {0.0, 0.0, 0.0}}, {"axis", {1, 1, 0}}, {"radius", 0.05}, {"length", 0.2}}}}});
  s["loads"] = nlohmann::json::array({{{"type", "symmetry"}, {"axis", "x"}, {"position", 0.0}}});
  s["time"] = {{"end", 1.0}, {"cfl", 0.5}};
  const auto a = run<3>(s, 1, 40);
  const auto b = run<3>(s, 2, 40);
  ASSERT_GT(a.x.size(), 8192u);
  expect_identical(a, b);
}

}  // namespace
}  // namespace cleave
