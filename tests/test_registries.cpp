// The name registries (core/registry.hpp): for each one, an unknown name is answered with exactly
// the registered names, and every registered name builds. A style added without a sample here
// fails the "builds" test on purpose: give it one.
#include <gtest/gtest.h>

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "libmpm/core/error.hpp"
#include "libmpm/core/registry.hpp"
#include "libmpm/crack/crack2d.hpp"
#include "libmpm/geometry/shape_reader.hpp"
#include "libmpm/method/method.hpp"
#include "libmpm/mpm/mpm_scene.hpp"
#include "libmpm/mpm/mpm_step.hpp"
#include "libmpm/pd/pd_scene.hpp"
#include "libmpm/scene/loads.hpp"
#include "support.hpp"

namespace {

using nlohmann::json;
using cleave::SceneError;
using cleave::test::error_of;

// A valid plane-strain MPM scene: a 0.1 x 0.05 m steel block, 1 cm cells, explicit grid.
json mpm_scene() {
  return json::parse(R"({
    "analysis": {"type": "plane_strain"},
    "grid": {"cell_size": 0.01, "min": [-0.05, -0.05], "max": [0.15, 0.10]},
    "materials": [{"name": "steel", "type": "linear_elastic", "E": 2e11, "nu": 0.3, "density": 7800}],
    "bodies": [{"name": "block", "material": "steel",
                "shape": {"type": "rectangle", "min": [0, 0], "max": [0.1, 0.05]}}],
    "time": {"end": 1e-5}
  })");
}

// The same block as a peridynamic specimen.
json pd_scene() {
  return json::parse(R"({
    "method": "peridynamics",
    "analysis": {"type": "plane_stress", "thickness": 0.001},
    "peridynamics": {"spacing": 0.005},
    "materials": [{"name": "glass", "type": "linear_elastic", "E": 65e9, "density": 2235, "fracture_energy": 204}],
    "bodies": [{"name": "block", "material": "glass",
                "shape": {"type": "rectangle", "min": [0, 0], "max": [0.1, 0.05]}}],
    "time": {"end": 1e-6}
  })");
}

// --- methods ------------------------------------------------------------------------------------

TEST(Registries, UnknownMethodListsTheRegisteredOnes) {
  json s = mpm_scene();
  s["method"] = "fem";
  const SceneError e = error_of([&] { cleave::build_method<2>(s); });
  EXPECT_EQ(e.key_path(), "method");
  EXPECT_EQ(e.reason(), "unknown method 'fem'; valid: " + cleave::MethodRegistry<2>::instance().names_joined());
  EXPECT_EQ(cleave::MethodRegistry<2>::instance().names(), (std::vector<std::string>{"mpm", "pem", "peridynamics"}));
}

// A second style under a taken name would replace the first silently (which one won depended on
// the link order): it is refused at registration, naming the table and the name.
TEST(Registries, ADuplicateRegistrationIsAnErrorNamingTheTableAndTheName) {
  struct Tag {};
  cleave::NameTable<int, Tag> table;
  EXPECT_TRUE(table.add("one", 1));
  try {
    table.add("one", 2);
    ADD_FAILURE() << "no error";
  } catch (const std::logic_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'one'"), std::string::npos) << what;
    EXPECT_NE(what.find("duplicate registration"), std::string::npos) << what;
    EXPECT_NE(what.find("Tag"), std::string::npos) << what;
  }
  EXPECT_EQ(table.at("one"), 1);  // the first stays
  auto& methods = cleave::MethodRegistry<2>::instance();
  try {
    methods.add("mpm", [](const json&) { return std::unique_ptr<cleave::Method<2>>(); });
    ADD_FAILURE() << "no error";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("cleave::Method<2>"), std::string::npos) << e.what();
  }
}

// --- materials ----------------------------------------------------------------------------------

TEST(Registries, UnknownMaterialListsTheRegisteredOnes) {
  json s = mpm_scene();
  s["materials"][0]["type"] = "johnson_cook";
  const SceneError e = error_of([&] { cleave::build_model<2>(s); });
  EXPECT_EQ(e.key_path(), "materials[0].type");
  EXPECT_EQ(e.reason(), "unknown material type 'johnson_cook'; valid: linear_elastic");
}

TEST(Registries, EveryRegisteredMaterialBuilds) {
  // Keys each style needs besides name and type.
  const std::map<std::string, json> samples = {{"linear_elastic", {{"E", 2e11}, {"nu", 0.3}, {"density", 7800}}}};
  for (const auto& name : cleave::MaterialRegistry<2>::instance().names()) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(samples.count(name)) << "no sample for material '" << name << "': add one to this test";
    json s = mpm_scene();
    s["materials"][0] = samples.at(name);
    s["materials"][0]["name"] = "steel";
    s["materials"][0]["type"] = name;
    EXPECT_EQ(cleave::build_model<2>(s).materials.size(), 1u);
  }
}

TEST(Registries, UnknownPeridynamicMaterialListsTheRegisteredOnes) {
  json s = pd_scene();
  s["materials"][0]["type"] = "johnson_cook";
  const SceneError e = error_of([&] { cleave::pd::build_pd_system<2>(s); });
  EXPECT_EQ(e.key_path(), "materials[0].type");
  EXPECT_EQ(e.reason(), "unknown material type 'johnson_cook' for peridynamics; valid: linear_elastic");
  s["materials"][0]["type"] = "linear_elastic";
  EXPECT_EQ(cleave::pd::build_pd_system<2>(s).materials.size(), 1u);
}

// --- body shapes --------------------------------------------------------------------------------

TEST(Registries, UnknownShapeListsTheRegisteredOnes) {
  const SceneError e2 = error_of([] { cleave::geom::parse_shape<2>(json{{"type", "circle"}}, "s", 1.0); });
  EXPECT_EQ(e2.key_path(), "s.type");
  EXPECT_EQ(e2.reason(), "unknown shape type 'circle'; valid 2D types: rectangle, disk, ellipse, polygon, union, "
                         "difference");
  const SceneError e3 = error_of([] { cleave::geom::parse_shape<3>(json{{"type", "cube"}}, "s", 1.0); });
  EXPECT_EQ(e3.reason(), "unknown shape type 'cube'; valid 3D types: box, sphere, cylinder, ellipsoid, prism, union, "
                         "difference");
}

TEST(Registries, EveryRegisteredShapeBuilds) {
  const json disk = {{"type", "disk"}, {"center", {0, 0}}, {"radius", 1}};
  const json sphere = {{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}};
  const json outline = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  const std::map<std::string, std::pair<json, json>> samples = {  // (2D, 3D); null: not in that dimension
      {"rectangle", {{{"min", {0, 0}}, {"max", {1, 1}}}, nullptr}},
      {"disk", {{{"center", {0, 0}}, {"radius", 1}}, nullptr}},
      {"ellipse", {{{"center", {0, 0}}, {"semi_axes", {2, 1}}, {"angle", 30}}, nullptr}},
      {"polygon", {{{"points", outline}}, nullptr}},
      {"box", {nullptr, {{"min", {0, 0, 0}}, {"max", {1, 1, 1}}}}},
      {"sphere", {nullptr, {{"center", {0, 0, 0}}, {"radius", 1}}}},
      {"cylinder", {nullptr, {{"center", {0, 0, 0}}, {"axis", {0, 0, 1}}, {"radius", 1}, {"length", 2}}}},
      {"ellipsoid", {nullptr, {{"center", {0, 0, 0}}, {"semi_axes", {1, 2, 3}}}}},
      {"prism", {nullptr, {{"points", outline}, {"z", {0, 1}}}}},
      {"union", {{{"shapes", {disk}}}, {{"shapes", {sphere}}}}},
      {"difference", {{{"shapes", {disk, disk}}}, {{"shapes", {sphere, sphere}}}}},
  };
  cleave::geom::ShapeKinds::instance().each([&](const std::string& name, const cleave::geom::ShapeKind& kind) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(samples.count(name)) << "no sample for shape '" << name << "': add one to this test";
    auto [j2, j3] = samples.at(name);
    EXPECT_EQ(kind.dim == 3, j2.is_null());
    EXPECT_EQ(kind.dim == 2, j3.is_null());
    if (!j2.is_null()) {
      j2["type"] = name;
      EXPECT_FALSE(cleave::geom::parse_shape<2>(j2, "s", 1.0)->bounds().empty());
    }
    if (!j3.is_null()) {
      j3["type"] = name;
      EXPECT_FALSE(cleave::geom::parse_shape<3>(j3, "s", 1.0)->bounds().empty());
    }
  });
}

// --- contact laws -------------------------------------------------------------------------------

json crack_with(json contact) {
  return json::array({{{"name", "c"}, {"points", {{0, 0}, {1, 0}}}, {"contact", std::move(contact)}}});
}

TEST(Registries, UnknownContactLawListsTheRegisteredOnes) {
  const SceneError e = error_of([] { cleave::crack::parse_cracks(crack_with({{"law", "glue"}}), "cracks", 1.0); });
  EXPECT_EQ(e.key_path(), "cracks[0].contact.law");
  EXPECT_EQ(e.reason(), "unknown contact law \"glue\"; valid laws: stick, frictionless, friction, none");
}

TEST(Registries, EveryRegisteredContactLawBuildsAndKeepsItsName) {
  using cleave::crack::ContactLawStyle;
  cleave::crack::ContactLaws::instance().each([](const std::string& name, const ContactLawStyle& style) {
    SCOPED_TRACE(name);
    json contact = {{"law", name}};
    if (style.takes_mu) contact["mu"] = 0.3;
    const auto cracks = cleave::crack::parse_cracks(crack_with(contact), "cracks", 1.0);
    ASSERT_EQ(cracks.size(), 1u);
    EXPECT_EQ(cracks[0].contact_law, style.law);
    EXPECT_EQ(cleave::crack::contact_law_name(style.law), name);
  });
}

// --- shape functions ----------------------------------------------------------------------------

TEST(Registries, UnknownShapeFunctionListsTheRegisteredOnes) {
  json s = mpm_scene();
  s["mpm"] = {{"shape_function", "cubic_bspline"}};
  const SceneError e = error_of([&] { cleave::build_model<2>(s); });
  EXPECT_EQ(e.key_path(), "mpm.shape_function");
  EXPECT_EQ(e.reason(), "unknown shape function 'cubic_bspline'; valid: linear, ugimp");
}

TEST(Registries, EveryRegisteredShapeFunctionBuildsAStepperThatSteps) {
  cleave::ShapeFunctions::instance().each([](const std::string& name, const cleave::ShapeFunctionStyle& style) {
    SCOPED_TRACE(name);
    json s = mpm_scene();
    s["mpm"] = {{"shape_function", name}};
    auto m = cleave::build_model<2>(s);
    EXPECT_EQ(m.shape_function, style.kind);
    EXPECT_EQ(&cleave::shape_function_style(m.shape_function), &style);
    auto stepper = cleave::make_stepper<2>(m);
    ASSERT_NE(stepper, nullptr);
    EXPECT_FALSE(stepper->step());
    EXPECT_EQ(stepper->step_count(), 1);
  });
}

// --- load kinds ---------------------------------------------------------------------------------

TEST(Registries, UnknownLoadKindListsTheKindsTheMethodResolves) {
  json s = mpm_scene();
  s["loads"] = json::array({{{"type", "pressure"}}});
  SceneError e = error_of([&] { cleave::build_model<2>(s); });
  EXPECT_EQ(e.key_path(), "loads[0].type");
  EXPECT_EQ(e.reason(), "unknown load type 'pressure'; valid: traction, body_force, velocity, symmetry");
  s["loads"] = json::array({json::object()});
  e = error_of([&] { cleave::build_model<2>(s); });
  EXPECT_EQ(e.reason(), "missing (traction, body_force, velocity or symmetry)");

  json p = pd_scene();
  p["loads"] = json::array({{{"type", "pressure"}}});
  e = error_of([&] { cleave::pd::build_pd_system<2>(p); });
  EXPECT_EQ(e.key_path(), "loads[0].type");
  EXPECT_EQ(e.reason(), "unknown load type 'pressure'; valid: traction, body_force, velocity");
  p["loads"] = json::array({json::object()});
  e = error_of([&] { cleave::pd::build_pd_system<2>(p); });
  EXPECT_EQ(e.reason(), "missing (traction, body_force or velocity)");
}

TEST(Registries, PeridynamicsRefusesSymmetryWithItsReason) {
  json p = pd_scene();
  p["loads"] = json::array({{{"type", "symmetry"}, {"axis", "x"}, {"position", 0}}});
  const SceneError e = error_of([&] { cleave::pd::build_pd_system<2>(p); });
  EXPECT_EQ(e.key_path(), "loads[0].type");
  EXPECT_EQ(e.reason().rfind("symmetry is not available with peridynamics", 0), 0u) << e.reason();
}

TEST(Registries, EveryRegisteredLoadKindBuilds) {
  const json region = {{"min", {-0.001, -0.001}}, {"max", {0.101, 0.003}}};  // grid line y = 0, lattice row y = dx/2
  const std::map<std::string, json> samples = {
      {"traction", {{"face", "+y"}, {"traction", {0, -1e6}}, {"rise_time", 1e-6}}},
      {"body_force", {{"acceleration", {0, -9.81}}}},
      {"velocity", {{"region", region}, {"velocity", {nullptr, 0}}}},
      {"symmetry", {{"axis", "x"}, {"position", 0}}},
  };
  for (const auto& name : cleave::scene::LoadKinds::instance().names()) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(samples.count(name)) << "no sample for load kind '" << name << "': add one to this test";
    json load = samples.at(name);
    load["type"] = name;
    json s = mpm_scene();
    s["loads"] = json::array({load});
    const auto m = cleave::build_model<2>(s);
    EXPECT_TRUE(!m.tractions.empty() || m.gravity.norm() > 0 || !m.conditions.node.empty());
    json p = pd_scene();
    p["loads"] = json::array({load});
    if (name == "symmetry") continue;  // refused by peridynamics (above)
    const auto pd = cleave::pd::build_pd_system<2>(p);
    EXPECT_TRUE(!pd.loads.empty() || pd.gravity.norm() > 0 || pd.points.fixed[0] != 0);
  }
}

}  // namespace
