// The pieces of cleave study: closed forms against their formulas in validation.md, Richardson
// extrapolation, reading tables, and the study file's checks (each bad key named).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "files.hpp"
#include "libmpm/reference/closed_form.hpp"
#include "study/analysis.hpp"
#include "study/study_spec.hpp"

namespace cleave::study {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;
using reference::make_closed_form;

double closed(const std::string& name, const reference::Values& v, double t = 0) {
  const auto f = make_closed_form(name);
  return f->value(reference::complete_values(*f, v), t);
}

TEST(ClosedForms, FreundsKIGrowsWithTheRootOfTimeAfterTheOnsetAndIsZeroBefore) {
  const reference::Values v{{"pressure", 200e6}, {"E", 200e9}, {"nu", 0.3}, {"density", 7900}, {"onset", 3e-6}};
  const double cd = std::sqrt(200e9 * 0.7 / (1.3 * 0.4 * 7900));
  EXPECT_EQ(closed("freund_KI", v, 2e-6), 0.0);
  EXPECT_NEAR(closed("freund_KI", v, 7e-6), 2 * 200e6 / 0.7 * std::sqrt(cd * 4e-6 * 0.4 / M_PI), 1e-6);
}

TEST(ClosedForms, TheCentreCrackTakesFeddersensWidthCorrectionAndThePennyItsOwnForm) {
  EXPECT_NEAR(closed("centre_crack_KI", {{"stress", 1e6}, {"half_length", 0.01}}), 1e6 * std::sqrt(M_PI * 0.01), 1e-6);
  const double feddersen = closed("centre_crack_KI", {{"stress", 3.30859e6}, {"half_length", 8.9e-3}, {"width", 52e-3}});
  EXPECT_NEAR(feddersen, 0.59696e6, 0.00001e6);  // the strip of docs/photoelasticity.md
  EXPECT_NEAR(closed("penny_KI", {{"stress", 1e6}, {"radius", 0.01}}), 2e6 * std::sqrt(0.01 / M_PI), 1e-6);
}

// At the centre sx = 2P / (pi D t), sy = -6P / (pi D t), sxy = 0 (validation.md section 7).
TEST(ClosedForms, TheBrazilianDiskGivesTheTextbookStressesAtItsCentre) {
  const auto f = make_closed_form("brazilian_disk");
  ASSERT_TRUE(f->field());
  const auto v = reference::complete_values(*f, {{"force", 800}, {"radius", 0.02}, {"thickness", 0.005}});
  const auto s = f->stress(v, 0, 0);
  const double c = 800 / (M_PI * 0.04 * 0.005);
  EXPECT_NEAR(s[0], 2 * c, 1e-9 * c);
  EXPECT_NEAR(s[1], -6 * c, 1e-9 * c);
  EXPECT_NEAR(s[2], 0, 1e-9 * c);
  EXPECT_THROW(f->value(v, 0), std::logic_error);
}

TEST(ClosedForms, BeamsBarsAndTheDcbFollowTheirFormulas) {
  // Cantilever 100 x 10 x 5 mm, 10 N, steel: bending P L^3 / 3 E I plus shear P L / (5/6 G A).
  const double I = 5e-3 * 1e-6 / 12, G = 2e11 / 2.6;
  EXPECT_NEAR(closed("cantilever_deflection", {{"force", 10}, {"length", 0.1}, {"height", 0.01}, {"thickness", 5e-3},
                                               {"E", 2e11}, {"nu", 0.3}}),
              10 * 1e-3 / (3 * 2e11 * I) + 10 * 0.1 / (5.0 / 6.0 * G * 5e-5), 1e-15);
  EXPECT_NEAR(closed("bar_wave_speed", {{"E", 2e11}, {"density", 8000}}), 5000, 1e-9);
  const reference::Values dcb{{"force", 4e-4}, {"crack_length", 0.05}, {"arm_height", 0.018},
                              {"thickness", 1e-3}, {"E", 1e5}, {"nu", 0.33}};
  const double Gs = 1e5 / 2.66;
  EXPECT_NEAR(closed("dcb_G", dcb), 12 * 1.6e-7 * 2.5e-3 / (1e5 * 1e-6 * std::pow(0.018, 3)) +
                                        6 * 1.6e-7 / (5 * Gs * 1e-6 * 0.018), 1e-12);
}

TEST(ClosedForms, AMissingValueOrAnUnknownNameIsNamed) {
  EXPECT_THROW(make_closed_form("no_such"), std::invalid_argument);
  try {
    reference::complete_values(*make_closed_form("penny_KI"), {{"stress", 1}});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'radius'"), std::string::npos) << e.what();
  }
}

TEST(Richardson, RecoversTheOrderAndTheLimitOfAnExactPowerLaw) {
  const double h[3] = {2, 1, 0.5}, q[3] = {1 + 3 * 4.0, 1 + 3 * 1.0, 1 + 3 * 0.25};
  double p = 0, q0 = 0;
  ASSERT_TRUE(richardson(h, q, p, q0));
  EXPECT_NEAR(p, 2, 1e-9);
  EXPECT_NEAR(q0, 1, 1e-9);
  const double h2[3] = {3, 2, 0.5}, r[3] = {5 - 2 * std::pow(3, 1.5), 5 - 2 * std::pow(2, 1.5), 5 - 2 * std::pow(0.5, 1.5)};
  ASSERT_TRUE(richardson(h2, r, p, q0));  // unequal ratios
  EXPECT_NEAR(p, 1.5, 1e-9);
  EXPECT_NEAR(q0, 5, 1e-9);
}

TEST(Richardson, RefusesValuesThatDoNotConvergeMonotonically) {
  const double h[3] = {2, 1, 0.5}, q[3] = {1, 2, 1.5};
  double p = 0, q0 = 0;
  EXPECT_FALSE(richardson(h, q, p, q0));
}

// Three runs at cells 2, 1, 0.5 whose quantity follows q = 1 + C h^p, against the finest run.
std::vector<OrderFit> finest_fits(double p, std::vector<RunPlan>& plans, std::vector<RunRecord>& runs) {
  Study st;
  st.cell_key = "resolution";
  st.varied_keys = {"resolution"};
  QuantitySpec q;
  q.name = "q";
  q.reference.kind = Reference::Kind::Finest;
  st.quantities = {q};
  plans.clear(), runs.clear();
  for (double h : {2.0, 1.0, 0.5}) plans.push_back({"h", "", {}, {{"resolution", h}}, std::nullopt});
  for (auto& plan : plans) {
    RunRecord r;
    r.plan = &plan;
    r.status = "complete";
    Measurement m;
    m.value = 1 + 0.3 * std::pow(plan.varied[0].value.get<double>(), p);
    r.q = {m};
    runs.push_back(r);
  }
  return compute_errors(st, runs);
}

TEST(FinestReference, IsRichardsonsLimitInTheAsymptoticRangeAndTheFinestRunOutsideIt) {
  std::vector<RunPlan> plans;
  std::vector<RunRecord> runs;
  auto fits = finest_fits(2, plans, runs);
  ASSERT_EQ(fits.size(), 1u);
  EXPECT_NEAR(fits[0].richardson, 1, 1e-9);
  EXPECT_NEAR(fits[0].order, 2, 1e-9);  // errors against the true limit
  EXPECT_NEAR(runs[2].error[0], 0.3 * 0.25, 1e-9);
  // p = 0.42: the extrapolation would move the value more than the last halving did; the finest run
  // is the reference, its own error zero and left out of the order fit.
  fits = finest_fits(0.42, plans, runs);
  EXPECT_TRUE(std::isnan(fits[0].richardson));
  EXPECT_NEAR(fits[0].richardson_order, 0.42, 1e-9);
  EXPECT_EQ(runs[2].error[0], 0.0);
  EXPECT_EQ(fits[0].points, 2);
}

class StudyFile : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::fresh_dir(test::per_test_path("study_file")); }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write(const json& j) {
    std::ofstream(dir_ / "s.json") << j.dump();
    return dir_ / "s.json";
  }
  std::string error_key(const json& j) {
    try {
      read_study(write(j));
    } catch (const StudyError& e) {
      return e.key();
    }
    return "(accepted)";
  }
  fs::path dir_;
};

TEST_F(StudyFile, VariedKeysMakeTheCartesianProductFirstKeyOutermost) {
  const Study st = read_study(write({{"scene", "x.json"},
                                     {"set", {{"time.end", 1}}},
                                     {"vary", {{{"key", "mpm.shape_function"}, {"values", {"linear", "ugimp"}}},
                                               {{"key", "resolution"}, {"values", {2, 1, 0.5}}}}}}));
  ASSERT_EQ(st.runs.size(), 6u);
  EXPECT_EQ(st.cell_key, "resolution");
  EXPECT_EQ(st.series_keys, std::vector<std::string>{"mpm.shape_function"});
  EXPECT_EQ(st.runs[0].label, "mpm.shape_function_linear__resolution_2");
  EXPECT_EQ(st.runs[5].label, "mpm.shape_function_ugimp__resolution_0.5");
  ASSERT_EQ(st.runs[4].settings.size(), 3u);
  EXPECT_EQ(st.runs[4].settings[0].key, "time.end");
  EXPECT_EQ(settings_text(st.runs[4].varied), "mpm.shape_function=ugimp, resolution=1");
  EXPECT_EQ(st.runs[0].scene, (dir_ / "x.json").lexically_normal());
}

TEST_F(StudyFile, EveryBadKeyIsNamed) {
  const json vary = {{{"key", "resolution"}, {"values", {1}}}};
  EXPECT_EQ(error_key({{"scene", "x.json"}}), "vary");
  EXPECT_EQ(error_key({{"scene", "x.json"}, {"vary", json::array()}}), "vary");
  EXPECT_EQ(error_key({{"scene", "x.json"}, {"vary", {{{"key", "a"}, {"values", json::array()}}}}}), "vary[0].values");
  EXPECT_EQ(error_key({{"scene", "x.json"}, {"vary", vary}, {"cell_size", "mpm.x"}}), "cell_size");
  EXPECT_EQ(error_key({{"scene", "x.json"}, {"vary", vary}, {"quantities", {{{"name", "q"}, {"kind", "magic"}}}}}),
            "quantities[0].kind");
  EXPECT_EQ(error_key({{"scene", "x.json"}, {"vary", vary},
                       {"quantities", {{{"name", "q"}, {"column", "c"}, {"file", "other.csv"}}}}}),
            "quantities[0].file");
  EXPECT_EQ(error_key({{"scene", "x.json"}, {"vary", vary},
                       {"quantities", {{{"name", "q"}, {"column", "c"}, {"reference", {{"closed_form", "penny_KI"}, {"values", {{"sigma", 1}}}}}}}}}),
            "quantities[0].reference.values.sigma");
  EXPECT_EQ(error_key({{"scene", "x.json"}, {"vary", vary},
                       {"quantities", {{{"name", "q"}, {"column", "c"}, {"tolerances", {0.01}}}}}}),
            "quantities[0].tolerances");
  EXPECT_EQ(error_key({{"scene", "x.json"}, {"vary", vary},
                       {"quantities", {{{"name", "q"}, {"column", "c"}, {"window", {2, 1}}}}}}),
            "quantities[0].window");
  EXPECT_EQ(error_key({{"scene", "x.json"}, {"runs", {{{"label", "a"}, {"expect", "explode"}}}}}), "runs[0].expect");
  EXPECT_EQ(error_key({{"scene", "x.json"}, {"runs", {{{"label", "a"}}, {{"label", "a"}}}}}), "runs[1].label");
  EXPECT_EQ(error_key({{"scene", "x.json"}, {"vary", vary},
                       {"quantities", {{{"name", "f"}, {"kind", "fringe_rms"}, {"at", 1}, {"fringe_constant", 7000},
                                        {"thickness", 0.005}, {"reference", {{"closed_form", "penny_KI"}}},
                                        {"grid", 1e-3}, {"radius", 0.01}, {"centre", {0, 0}}}}}}),
            "quantities[0].reference.closed_form");
}

}  // namespace
}  // namespace cleave::study
