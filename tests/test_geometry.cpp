// Geometry: membership and bounds of every shape type, CSG, unit scaling, and the exact scene key
// path of every validation error.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "libmpm/core/error.hpp"
#include "libmpm/geometry/polygon.hpp"
#include "libmpm/geometry/shape.hpp"

namespace {

using cleave::SceneError;
using cleave::Vec;
using cleave::geom::Box;
using cleave::geom::parse_shape;
using cleave::geom::Shape;
using json = nlohmann::json;

const std::string kRoot = "bodies[0].shape";
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

template <int Dim>
std::unique_ptr<Shape<Dim>> parse(const json& j, double scale = 1.0) {
  return parse_shape<Dim>(j, kRoot, scale);
}

Vec<2> v2(double x, double y) { return Vec<2>(x, y); }
Vec<3> v3(double x, double y, double z) { return Vec<3>(x, y, z); }

template <int Dim>
void expect_box(const Box<Dim>& b, const Vec<Dim>& lo, const Vec<Dim>& hi, double tol = 1e-12) {
  for (int i = 0; i < Dim; ++i) {
    EXPECT_NEAR(b.lo[i], lo[i], tol) << "lo[" << i << "]";
    EXPECT_NEAR(b.hi[i], hi[i], tol) << "hi[" << i << "]";
  }
}

// Every point a shape contains must lie in its bounds; sampled on a lattice around the bounds.
template <int Dim>
void expect_bounds_hold(const Shape<Dim>& s, int per_axis = 41) {
  const Box<Dim> b = s.bounds();
  const Vec<Dim> pad = 0.25 * (b.hi - b.lo);
  const Vec<Dim> lo = b.lo - pad, step = (b.hi - b.lo + 2 * pad) / (per_axis - 1);
  int inside = 0, total = 1;
  for (int d = 0; d < Dim; ++d) total *= per_axis;
  for (int n = 0; n < total; ++n) {
    Vec<Dim> x;
    for (int d = 0, r = n; d < Dim; ++d, r /= per_axis) x[d] = lo[d] + (r % per_axis) * step[d];
    if (!s.contains(x)) continue;
    ++inside;
    EXPECT_TRUE(b.contains(x)) << "point outside bounds: " << x.transpose();
  }
  EXPECT_GT(inside, 0);
}

// ---------------------------------------------------------------- Box

TEST(Box, DefaultIsEmptyAndIdentityOfUnion) {
  Box<2> e;
  EXPECT_TRUE(e.empty());
  Box<2> b{v2(0, 1), v2(2, 3)};
  EXPECT_FALSE(b.empty());
  expect_box<2>(e.united(b), v2(0, 1), v2(2, 3));
  expect_box<2>(b.united(e), v2(0, 1), v2(2, 3));
  expect_box<2>(b.united(Box<2>{v2(-1, 2), v2(1, 5)}), v2(-1, 1), v2(2, 5));
  EXPECT_FALSE((Box<3>{v3(1, 1, 1), v3(1, 1, 1)}).empty());  // a point is a closed, non-empty box
  EXPECT_TRUE((Box<3>{v3(0, 0, 1), v3(1, 1, 0)}).empty());
}

// ---------------------------------------------------------------- 2D primitives

TEST(Shape2D, Rectangle) {
  auto s = parse<2>({{"type", "rectangle"}, {"min", {0, -1}}, {"max", {2, 1}}});
  EXPECT_TRUE(s->contains(v2(1, 0)));
  EXPECT_TRUE(s->contains(v2(2, 1)));  // closed
  EXPECT_FALSE(s->contains(v2(2.01, 0)));
  EXPECT_FALSE(s->contains(v2(1, -1.01)));
  expect_box<2>(s->bounds(), v2(0, -1), v2(2, 1));
}

TEST(Shape2D, Disk) {
  auto s = parse<2>({{"type", "disk"}, {"center", {1, 2}}, {"radius", 0.5}});
  EXPECT_TRUE(s->contains(v2(1, 2)));
  EXPECT_TRUE(s->contains(v2(1.49, 2)));
  EXPECT_FALSE(s->contains(v2(1.36, 2.36)));  // inside the box, outside the circle
  expect_box<2>(s->bounds(), v2(0.5, 1.5), v2(1.5, 2.5));
  expect_bounds_hold(*s);
}

TEST(Shape2D, EllipseAxisAligned) {
  auto s = parse<2>({{"type", "ellipse"}, {"center", {0, 0}}, {"semi_axes", {2, 1}}});
  EXPECT_TRUE(s->contains(v2(1.9, 0)));
  EXPECT_FALSE(s->contains(v2(0, 1.1)));
  expect_box<2>(s->bounds(), v2(-2, -1), v2(2, 1));
}

TEST(Shape2D, EllipseRotated) {
  // 90 degrees: the long axis a = 2 now runs along y.
  auto s = parse<2>({{"type", "ellipse"}, {"center", {1, 1}}, {"semi_axes", {2, 1}}, {"angle", 90}});
  EXPECT_TRUE(s->contains(v2(1, 2.9)));
  EXPECT_FALSE(s->contains(v2(2.9, 1)));
  expect_box<2>(s->bounds(), v2(0, -1), v2(2, 3));

  // 45 degrees: a along the diagonal (1, 1), b along (-1, 1).
  auto r = parse<2>({{"type", "ellipse"}, {"center", {0, 0}}, {"semi_axes", {2, 1}}, {"angle", 45}});
  const double c = std::sqrt(0.5);
  EXPECT_TRUE(r->contains(1.9 * v2(c, c)));
  EXPECT_FALSE(r->contains(2.1 * v2(c, c)));
  EXPECT_TRUE(r->contains(0.9 * v2(-c, c)));
  EXPECT_FALSE(r->contains(1.1 * v2(-c, c)));
  EXPECT_FALSE(r->contains(1.5 * v2(c, -c)));  // would be inside if the rotation were ignored
  const double h = std::sqrt(2.5);             // sqrt(a^2 cos^2 + b^2 sin^2)
  expect_box<2>(r->bounds(), v2(-h, -h), v2(h, h));
  expect_bounds_hold(*r);
}

const json kLShape = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};

TEST(Shape2D, ConcavePolygonBothOrientations) {
  json reversed = json::array();
  for (auto it = kLShape.rbegin(); it != kLShape.rend(); ++it) reversed.push_back(*it);
  for (const json& pts : {kLShape, reversed}) {
    auto s = parse<2>({{"type", "polygon"}, {"points", pts}});
    EXPECT_TRUE(s->contains(v2(0.5, 0.5)));
    EXPECT_TRUE(s->contains(v2(1.5, 0.5)));
    EXPECT_TRUE(s->contains(v2(0.5, 1.5)));
    EXPECT_FALSE(s->contains(v2(1.5, 1.5)));  // the notch
    EXPECT_FALSE(s->contains(v2(-0.1, 0.5)));
    EXPECT_FALSE(s->contains(v2(2.1, 0.5)));
    // Closed set: edges and vertices belong to it.
    EXPECT_TRUE(s->contains(v2(1, 1.5)));
    EXPECT_TRUE(s->contains(v2(2, 0.5)));
    EXPECT_TRUE(s->contains(v2(1, 1)));
    // Horizontal rays through vertices must count each crossing once.
    EXPECT_TRUE(s->contains(v2(0.5, 1)));
    EXPECT_FALSE(s->contains(v2(2.5, 1)));
    EXPECT_FALSE(s->contains(v2(-0.5, 1)));
    EXPECT_FALSE(s->contains(v2(-0.5, 2)));
    EXPECT_FALSE(s->contains(v2(-0.5, 0)));
    EXPECT_FALSE(s->contains(v2(1.5, 2)));  // inside the bounds, level with the top vertices
    expect_box<2>(s->bounds(), v2(0, 0), v2(2, 2));

    // Agrees with the same L built from two rectangles at points off the boundary.
    auto u = parse<2>({{"type", "union"},
                       {"shapes",
                        {{{"type", "rectangle"}, {"min", {0, 0}}, {"max", {2, 1}}},
                         {{"type", "rectangle"}, {"min", {0, 0}}, {"max", {1, 2}}}}}});
    for (double x = -0.45; x < 2.5; x += 0.1)
      for (double y = -0.45; y < 2.5; y += 0.1) EXPECT_EQ(s->contains(v2(x, y)), u->contains(v2(x, y))) << x << "," << y;
    // Exactly on vertex heights and edges too: both are closed sets, so they must still agree.
    for (int i = -1; i <= 5; ++i)
      for (int k = -1; k <= 5; ++k) {
        const Vec<2> x = v2(0.5 * i, 0.5 * k);
        EXPECT_EQ(s->contains(x), u->contains(x)) << x.transpose();
      }
  }
}

TEST(PolygonMath, SignedAreaAndSimplicity) {
  cleave::geom::Polyline sq = {v2(0, 0), v2(1, 0), v2(1, 1), v2(0, 1)};
  EXPECT_DOUBLE_EQ(cleave::geom::signed_area(sq), 1.0);
  std::reverse(sq.begin(), sq.end());
  EXPECT_DOUBLE_EQ(cleave::geom::signed_area(sq), -1.0);
  EXPECT_FALSE(cleave::geom::find_self_intersection(sq).has_value());
  cleave::geom::Polyline bowtie = {v2(0, 0), v2(1, 1), v2(1, 0), v2(0, 1)};
  auto hit = cleave::geom::find_self_intersection(bowtie);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(*hit, std::make_pair(0, 2));
  EXPECT_TRUE(cleave::geom::all_collinear({v2(0, 0), v2(1, 1), v2(3, 3)}, 1e-12));
}

TEST(PolygonMath, RaysThroughVerticesCountOnce) {
  // polygon_contains has no bounding-box shortcut, so points left of the polygon exercise the
  // vertex rule: a ray through a vertex must not be counted twice (or not at all).
  const cleave::geom::Polyline diamond = {v2(0, -1), v2(1, 0), v2(0, 1), v2(-1, 0)};
  const cleave::geom::Polyline zigzag = {v2(0, 0), v2(4, 0), v2(4, 2), v2(3, 1), v2(2, 2), v2(1, 1), v2(0, 2)};
  for (double y : {-1.0, 0.0, 1.0}) EXPECT_FALSE(cleave::geom::polygon_contains(diamond, v2(-3, y))) << y;
  for (double y : {-1.0, 0.0, 1.0}) EXPECT_FALSE(cleave::geom::polygon_contains(diamond, v2(3, y))) << y;
  EXPECT_TRUE(cleave::geom::polygon_contains(diamond, v2(0.5, 0)));
  EXPECT_TRUE(cleave::geom::polygon_contains(diamond, v2(0, 1)));  // vertex, closed set
  // Level with the spike tips, between them (outside) and beyond them.
  for (double x : {-1.0, 1.5, 2.5, 3.5, 5.0}) EXPECT_FALSE(cleave::geom::polygon_contains(zigzag, v2(x, 2))) << x;
  for (double x : {0.0, 2.0, 4.0}) EXPECT_TRUE(cleave::geom::polygon_contains(zigzag, v2(x, 2))) << x;
  EXPECT_TRUE(cleave::geom::polygon_contains(zigzag, v2(0.5, 1)));   // ray through two notch vertices
  EXPECT_FALSE(cleave::geom::polygon_contains(zigzag, v2(-0.5, 1)));
  EXPECT_TRUE(cleave::geom::polygon_contains(zigzag, v2(2, 1)));
}

// ---------------------------------------------------------------- 3D primitives

TEST(Shape3D, Box) {
  auto s = parse<3>({{"type", "box"}, {"min", {0, 0, 0}}, {"max", {1, 2, 3}}});
  EXPECT_TRUE(s->contains(v3(0.5, 1, 2.9)));
  EXPECT_TRUE(s->contains(v3(1, 2, 3)));
  EXPECT_FALSE(s->contains(v3(0.5, 1, 3.1)));
  expect_box<3>(s->bounds(), v3(0, 0, 0), v3(1, 2, 3));
}

TEST(Shape3D, Sphere) {
  auto s = parse<3>({{"type", "sphere"}, {"center", {0, 0, 1}}, {"radius", 2}});
  EXPECT_TRUE(s->contains(v3(1.1, 1.1, 1.1)));
  EXPECT_FALSE(s->contains(v3(1.2, 1.2, 2.2)));
  expect_box<3>(s->bounds(), v3(-2, -2, -1), v3(2, 2, 3));
  expect_bounds_hold(*s, 21);
}

TEST(Shape3D, Ellipsoid) {
  auto s = parse<3>({{"type", "ellipsoid"}, {"center", {1, 0, 0}}, {"semi_axes", {3, 2, 1}}});
  EXPECT_TRUE(s->contains(v3(3.9, 0, 0)));
  EXPECT_TRUE(s->contains(v3(1, 1.9, 0)));
  EXPECT_FALSE(s->contains(v3(1, 0, 1.1)));
  EXPECT_FALSE(s->contains(v3(3, 1.5, 0)));
  expect_box<3>(s->bounds(), v3(-2, -2, -1), v3(4, 2, 1));
}

TEST(Shape3D, CylinderAlongZ) {
  // The axis is given unnormalised on purpose.
  auto s = parse<3>({{"type", "cylinder"}, {"center", {0, 0, 0}}, {"axis", {0, 0, 5}}, {"radius", 1}, {"length", 4}});
  EXPECT_TRUE(s->contains(v3(0.6, 0.6, 1.9)));
  EXPECT_FALSE(s->contains(v3(0, 0, 2.1)));
  EXPECT_FALSE(s->contains(v3(0.8, 0.8, 0)));
  expect_box<3>(s->bounds(), v3(-1, -1, -2), v3(1, 1, 2));
}

TEST(Shape3D, CylinderTilted) {
  auto s = parse<3>({{"type", "cylinder"}, {"center", {1, 1, 1}}, {"axis", {1, 1, 0}}, {"radius", 1}, {"length", 4}});
  const Vec<3> c = v3(1, 1, 1), a = v3(1, 1, 0).normalized(), p = v3(-1, 1, 0).normalized();
  EXPECT_TRUE(s->contains(c + 1.9 * a));
  EXPECT_FALSE(s->contains(c + 2.1 * a));
  EXPECT_TRUE(s->contains(c + 0.9 * p + 1.5 * a));
  EXPECT_FALSE(s->contains(c + 1.1 * p));
  EXPECT_TRUE(s->contains(c + v3(0, 0, 0.99)));
  EXPECT_FALSE(s->contains(c + v3(0, 0, 1.01)));
  const double h = 2 * std::sqrt(0.5) + std::sqrt(0.5);  // (L/2)|a_i| + r sqrt(1 - a_i^2)
  expect_box<3>(s->bounds(), c - v3(h, h, 1), c + v3(h, h, 1));
  expect_bounds_hold(*s, 21);
}

TEST(Shape3D, Prism) {
  auto s = parse<3>({{"type", "prism"}, {"points", kLShape}, {"z", {-1, 3}}});
  EXPECT_TRUE(s->contains(v3(1.5, 0.5, 0)));
  EXPECT_TRUE(s->contains(v3(0.5, 1.5, 3)));
  EXPECT_FALSE(s->contains(v3(1.5, 1.5, 1)));  // the notch, all the way through
  EXPECT_FALSE(s->contains(v3(0.5, 0.5, 3.1)));
  EXPECT_FALSE(s->contains(v3(0.5, 0.5, -1.1)));
  expect_box<3>(s->bounds(), v3(0, 0, -1), v3(2, 2, 3));
}

// ---------------------------------------------------------------- CSG

TEST(Csg, Union) {
  auto s = parse<2>({{"type", "union"},
                     {"shapes",
                      {{{"type", "disk"}, {"center", {0, 0}}, {"radius", 1}},
                       {{"type", "disk"}, {"center", {3, 0}}, {"radius", 1}}}}});
  EXPECT_TRUE(s->contains(v2(0.5, 0)));
  EXPECT_TRUE(s->contains(v2(3.5, 0)));
  EXPECT_FALSE(s->contains(v2(1.5, 0)));
  expect_box<2>(s->bounds(), v2(-1, -1), v2(4, 1));

  auto one = parse<3>({{"type", "union"}, {"shapes", {{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}}}}});
  EXPECT_TRUE(one->contains(v3(0, 0, 0.9)));
  expect_box<3>(one->bounds(), v3(-1, -1, -1), v3(1, 1, 1));
}

TEST(Csg, DifferenceRing) {
  auto s = parse<2>({{"type", "difference"},
                     {"shapes",
                      {{{"type", "disk"}, {"center", {0, 0}}, {"radius", 2}},
                       {{"type", "disk"}, {"center", {0, 0}}, {"radius", 1}}}}});
  EXPECT_TRUE(s->contains(v2(1.5, 0)));
  EXPECT_TRUE(s->contains(v2(0, -1.5)));
  EXPECT_FALSE(s->contains(v2(0.5, 0)));
  EXPECT_FALSE(s->contains(v2(0, 0)));
  EXPECT_FALSE(s->contains(v2(2.5, 0)));
  expect_box<2>(s->bounds(), v2(-2, -2), v2(2, 2));
}

TEST(Csg, DifferenceWithSeveralCutsAndNesting) {
  // A plate with a notch and a hole; the base is itself a union.
  auto s = parse<3>({{"type", "difference"},
                     {"shapes",
                      {{{"type", "union"},
                        {"shapes",
                         {{{"type", "box"}, {"min", {0, 0, 0}}, {"max", {4, 2, 1}}},
                          {{"type", "box"}, {"min", {4, 0, 0}}, {"max", {6, 2, 1}}}}}},
                       {{"type", "cylinder"}, {"center", {3, 1, 0.5}}, {"axis", {0, 0, 1}}, {"radius", 0.5}, {"length", 2}},
                       {{"type", "box"}, {"min", {-1, 0.9, -1}}, {"max", {1, 1.1, 2}}}}}});
  EXPECT_TRUE(s->contains(v3(5, 1, 0.5)));
  EXPECT_FALSE(s->contains(v3(3, 1, 0.5)));  // hole
  EXPECT_FALSE(s->contains(v3(0.5, 1, 0.5)));  // notch
  EXPECT_TRUE(s->contains(v3(0.5, 0.5, 0.5)));
  expect_box<3>(s->bounds(), v3(0, 0, 0), v3(6, 2, 1));
}

// ---------------------------------------------------------------- units

TEST(Units, MillimetresToMetres) {
  const double mm = 1e-3;
  auto r = parse<2>({{"type", "rectangle"}, {"min", {0, 0}}, {"max", {10, 20}}}, mm);
  expect_box<2>(r->bounds(), v2(0, 0), v2(0.01, 0.02), 1e-15);
  EXPECT_TRUE(r->contains(v2(0.005, 0.015)));
  EXPECT_FALSE(r->contains(v2(5, 15)));

  auto d = parse<2>({{"type", "disk"}, {"center", {5, 5}}, {"radius", 2}}, mm);
  EXPECT_TRUE(d->contains(v2(0.0065, 0.005)));
  EXPECT_FALSE(d->contains(v2(0.0075, 0.005)));

  // Angles are not lengths: a 90-degree ellipse stays a 90-degree ellipse.
  auto e = parse<2>({{"type", "ellipse"}, {"center", {0, 0}}, {"semi_axes", {20, 10}}, {"angle", 90}}, mm);
  expect_box<2>(e->bounds(), v2(-0.01, -0.02), v2(0.01, 0.02), 1e-15);

  auto p = parse<3>({{"type", "prism"}, {"points", kLShape}, {"z", {0, 5}}}, mm);
  expect_box<3>(p->bounds(), v3(0, 0, 0), v3(0.002, 0.002, 0.005), 1e-15);
  EXPECT_TRUE(p->contains(v3(0.0015, 0.0005, 0.004)));
  EXPECT_FALSE(p->contains(v3(0.0015, 0.0015, 0.004)));

  // The axis is a direction, the radius and length are lengths.
  auto c = parse<3>({{"type", "cylinder"}, {"center", {0, 0, 0}}, {"axis", {0, 0, 1}}, {"radius", 1}, {"length", 4}}, mm);
  expect_box<3>(c->bounds(), v3(-0.001, -0.001, -0.002), v3(0.001, 0.001, 0.002), 1e-15);

  auto u = parse<3>({{"type", "union"}, {"shapes", {{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 3}}}}}, mm);
  expect_box<3>(u->bounds(), v3(-0.003, -0.003, -0.003), v3(0.003, 0.003, 0.003), 1e-15);
}

TEST(Units, BadLengthScaleIsACallerBug) {
  const json disk = {{"type", "disk"}, {"center", {0, 0}}, {"radius", 1}};
  EXPECT_THROW(parse<2>(disk, 0.0), std::invalid_argument);
  EXPECT_THROW(parse<2>(disk, -1.0), std::invalid_argument);
  EXPECT_THROW(parse<2>(disk, kNaN), std::invalid_argument);
}

// ---------------------------------------------------------------- errors

struct BadCase {
  std::string name;
  json shape;
  std::string path;    // expected SceneError::key_path()
  std::string reason;  // substring expected in SceneError::reason()
};

template <int Dim>
void expect_errors(const std::vector<BadCase>& cases, double scale = 1.0) {
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name + ": " + c.shape.dump());
    try {
      parse<Dim>(c.shape, scale);
      ADD_FAILURE() << "no SceneError";
    } catch (const SceneError& e) {
      EXPECT_EQ(e.key_path(), c.path);
      EXPECT_NE(e.reason().find(c.reason), std::string::npos) << "reason: " << e.reason();
      EXPECT_EQ(std::string(e.what()), e.key_path() + ": " + e.reason());
    }
  }
}

json disk(json center, json radius) { return {{"type", "disk"}, {"center", center}, {"radius", radius}}; }
json poly(json points) { return {{"type", "polygon"}, {"points", points}}; }

TEST(Errors, TypeAndDimension2D) {
  expect_errors<2>({
      {"not an object", json::array({1, 2}), "bodies[0].shape", "expected a shape object"},
      {"missing type", {{"center", {0, 0}}, {"radius", 1}}, "bodies[0].shape.type", "missing required key 'type'"},
      {"type not a string", {{"type", 5}}, "bodies[0].shape.type", "valid 2D types"},
      {"unknown type", {{"type", "circle"}}, "bodies[0].shape.type",
       "unknown shape type 'circle'; valid 2D types: rectangle, disk, ellipse, polygon, union, difference"},
      {"3D type", {{"type", "box"}, {"min", {0, 0, 0}}, {"max", {1, 1, 1}}}, "bodies[0].shape.type",
       "'box' is a 3D shape; this is a 2D scene"},
      {"3D type sphere", json{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}}, "bodies[0].shape.type",
       "'sphere' is a 3D shape; this is a 2D scene"},
  });
}

TEST(Errors, TwoDimensionalTypeIn3D) {
  expect_errors<3>({
      {"polygon", poly(kLShape), "bodies[0].shape.type", "'polygon' is a 2D shape; this is a 3D scene"},
      {"rectangle", {{"type", "rectangle"}, {"min", {0, 0}}, {"max", {1, 1}}}, "bodies[0].shape.type",
       "counterpart is box"},
      {"disk", disk({0, 0}, 1), "bodies[0].shape.type", "valid 3D types: box, sphere, cylinder, ellipsoid, prism"},
      {"nested", {{"type", "union"}, {"shapes", {disk({0, 0}, 1)}}}, "bodies[0].shape.shapes[0].type",
       "'disk' is a 2D shape"},
  });
}

TEST(Errors, KeysAndNumbers) {
  json nan_center = disk({0, 0}, 1);
  nan_center["center"][1] = kNaN;
  expect_errors<2>({
      {"unknown key", {{"type", "disk"}, {"center", {0, 0}}, {"radus", 1}}, "bodies[0].shape.radus",
       "unknown key 'radus'; valid keys: type, center, radius"},
      {"missing radius", {{"type", "disk"}, {"center", {0, 0}}}, "bodies[0].shape.radius",
       "missing required key 'radius'"},
      {"missing center", {{"type", "disk"}, {"radius", 1}}, "bodies[0].shape.center", "missing required key 'center'"},
      {"center too long", disk({0, 0, 0}, 1), "bodies[0].shape.center", "expected 2 numbers [x, y], got 3 elements"},
      {"center not array", disk("0,0", 1), "bodies[0].shape.center", "expected 2 numbers [x, y], got the string"},
      {"center string element", disk({"a", 0}, 1), "bodies[0].shape.center[0]", "expected a number"},
      {"center boolean element", disk({0, true}, 1), "bodies[0].shape.center[1]", "expected a number, got true"},
      {"center NaN", nan_center, "bodies[0].shape.center[1]", "expected a finite number"},
      {"radius string", disk({0, 0}, "1"), "bodies[0].shape.radius", "expected a number"},
      {"radius infinite", disk({0, 0}, kInf), "bodies[0].shape.radius", "expected a finite number, got the number inf"},
      {"radius zero", disk({0, 0}, 0), "bodies[0].shape.radius", "radius must be > 0, got 0"},
      {"radius negative", disk({0, 0}, -1.5), "bodies[0].shape.radius", "radius must be > 0, got -1.5"},
      {"rectangle min = max", {{"type", "rectangle"}, {"min", {0, 0}}, {"max", {0, 1}}}, "bodies[0].shape.max[0]",
       "max[0] must be greater than min[0] = 0, got 0"},
      {"rectangle min > max", {{"type", "rectangle"}, {"min", {0, 2}}, {"max", {1, 1}}}, "bodies[0].shape.max[1]",
       "must be greater than min[1]"},
      {"rectangle missing max", {{"type", "rectangle"}, {"min", {0, 0}}}, "bodies[0].shape.max", "missing"},
      {"ellipse semi-axis zero", {{"type", "ellipse"}, {"center", {0, 0}}, {"semi_axes", {1, 0}}},
       "bodies[0].shape.semi_axes[1]", "must be > 0"},
      {"ellipse semi-axes length", {{"type", "ellipse"}, {"center", {0, 0}}, {"semi_axes", {1, 2, 3}}},
       "bodies[0].shape.semi_axes", "expected 2 numbers [a, b]"},
      {"ellipse angle string", {{"type", "ellipse"}, {"center", {0, 0}}, {"semi_axes", {1, 2}}, {"angle", "45deg"}},
       "bodies[0].shape.angle", "expected a number"},
      {"ellipse unknown key", {{"type", "ellipse"}, {"center", {0, 0}}, {"semi_axes", {1, 2}}, {"rotation", 4}},
       "bodies[0].shape.rotation", "valid keys: type, center, semi_axes, angle"},
  });
}

TEST(Errors, Polygon) {
  expect_errors<2>({
      {"missing points", {{"type", "polygon"}}, "bodies[0].shape.points", "missing"},
      {"points not array", poly(3), "bodies[0].shape.points", "at least 3 points"},
      {"two points", poly({{0, 0}, {1, 0}}), "bodies[0].shape.points", "at least 3 points [[x, y], ...], got 2"},
      {"point too long", poly({{0, 0}, {1, 0, 0}, {0, 1}}), "bodies[0].shape.points[1]", "expected 2 numbers [x, y]"},
      {"point not array", poly({{0, 0}, 1, {0, 1}}), "bodies[0].shape.points[1]", "expected 2 numbers [x, y]"},
      {"point element", poly({{0, 0}, {1, 0}, {0, nullptr}}), "bodies[0].shape.points[2][1]", "expected a number"},
      {"collinear", poly({{0, 0}, {1, 1}, {3, 3}, {2, 2}}), "bodies[0].shape.points", "zero area"},
      {"repeated point", poly({{0, 0}, {1, 0}, {1, 0}, {0, 1}}), "bodies[0].shape.points[2]", "repeats points[1]"},
      {"closing point repeated", poly({{0, 0}, {1, 0}, {0, 1}, {0, 0}}), "bodies[0].shape.points[3]",
       "repeats points[0]; the outline closes by itself"},
      {"bow tie", poly({{0, 0}, {1, 1}, {1, 0}, {0, 1}}), "bodies[0].shape.points",
       "edge points[0]-points[1] and edge points[2]-points[3] intersect"},
      {"vertex on an edge", poly({{0, 0}, {4, 0}, {4, 2}, {2, 0}, {0, 2}}), "bodies[0].shape.points", "not simple"},
      {"spike", poly({{0, 0}, {2, 0}, {1, 0}, {1, 1}}), "bodies[0].shape.points", "not simple"},
      {"crossing last edge", poly({{0, 0}, {2, 0}, {2, 2}, {1, -1}, {0, 2}}), "bodies[0].shape.points", "not simple"},
  });
}

TEST(Errors, Csg) {
  expect_errors<2>({
      {"union missing shapes", {{"type", "union"}}, "bodies[0].shape.shapes", "missing"},
      {"union shapes not array", {{"type", "union"}, {"shapes", disk({0, 0}, 1)}}, "bodies[0].shape.shapes",
       "expected an array of shape objects"},
      {"union empty", {{"type", "union"}, {"shapes", json::array()}}, "bodies[0].shape.shapes", "at least 1 shape"},
      {"difference of one", {{"type", "difference"}, {"shapes", {disk({0, 0}, 1)}}}, "bodies[0].shape.shapes",
       ">= 2 shapes"},
      {"nested radius", {{"type", "union"}, {"shapes", {disk({0, 0}, 1), disk({0, 0}, -1)}}},
       "bodies[0].shape.shapes[1].radius", "must be > 0"},
      {"deeply nested type",
       {{"type", "difference"},
        {"shapes", {{{"type", "union"}, {"shapes", {disk({0, 0}, 2), {{"type", "circle"}}}}}, disk({0, 0}, 1)}}},
       "bodies[0].shape.shapes[0].shapes[1].type", "unknown shape type 'circle'"},
      {"union unknown key", {{"type", "union"}, {"shapes", {disk({0, 0}, 1)}}, {"shape", 1}}, "bodies[0].shape.shape",
       "unknown key 'shape'; valid keys: type, shapes"},
  });
}

TEST(Errors, ThreeDimensional) {
  json cyl = {{"type", "cylinder"}, {"center", {0, 0, 0}}, {"axis", {0, 0, 1}}, {"radius", 1}, {"length", 2}};
  auto with = [](json j, const std::string& key, json value) {
    j[key] = std::move(value);
    return j;
  };
  auto without = [](json j, const std::string& key) {
    j.erase(key);
    return j;
  };
  json prism = {{"type", "prism"}, {"points", kLShape}, {"z", {0, 1}}};
  expect_errors<3>({
      {"unknown type", {{"type", "cube"}}, "bodies[0].shape.type",
       "valid 3D types: box, sphere, cylinder, ellipsoid, prism, union, difference"},
      {"sphere 2D center", {{"type", "sphere"}, {"center", {0, 0}}, {"radius", 1}}, "bodies[0].shape.center",
       "expected 3 numbers [x, y, z]"},
      {"box min = max in z", {{"type", "box"}, {"min", {0, 0, 1}}, {"max", {1, 1, 1}}}, "bodies[0].shape.max[2]",
       "max[2] must be greater than min[2]"},
      {"cylinder zero axis", with(cyl, "axis", {0, 0, 0}), "bodies[0].shape.axis", "non-zero direction"},
      {"cylinder axis length", with(cyl, "axis", {0, 1}), "bodies[0].shape.axis", "expected 3 numbers"},
      {"cylinder axis element", with(cyl, "axis", {0, "z", 1}), "bodies[0].shape.axis[1]", "expected a number"},
      {"cylinder zero length", with(cyl, "length", 0), "bodies[0].shape.length", "length must be > 0"},
      {"cylinder missing radius", without(cyl, "radius"), "bodies[0].shape.radius", "missing required key 'radius'"},
      {"cylinder unknown key", with(cyl, "height", 2), "bodies[0].shape.height",
       "valid keys: type, center, axis, radius, length"},
      {"ellipsoid semi-axis", {{"type", "ellipsoid"}, {"center", {0, 0, 0}}, {"semi_axes", {1, 1, -1}}},
       "bodies[0].shape.semi_axes[2]", "must be > 0"},
      {"ellipsoid rotated", {{"type", "ellipsoid"}, {"center", {0, 0, 0}}, {"semi_axes", {1, 1, 1}}, {"angle", 5}},
       "bodies[0].shape.angle", "unknown key 'angle'"},
      {"prism z order", with(prism, "z", {1, 1}), "bodies[0].shape.z", "zmax must be greater than zmin"},
      {"prism z length", with(prism, "z", {1, 2, 3}), "bodies[0].shape.z", "expected 2 numbers [zmin, zmax]"},
      {"prism missing z", without(prism, "z"), "bodies[0].shape.z", "missing"},
      {"prism bow tie", with(prism, "points", {{0, 0}, {1, 1}, {1, 0}, {0, 1}}), "bodies[0].shape.points",
       "not simple"},
      {"prism 3D points", with(prism, "points", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}), "bodies[0].shape.points[0]",
       "expected 2 numbers [x, y]"},
  });
}

TEST(Errors, ValueOverflowsUnitConversion) {
  expect_errors<3>({{"huge radius", {{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1e300}},
                     "bodies[0].shape.radius", "out of range once converted to metres"}},
                   1e10);
}

TEST(Errors, KeyPathRootIsUsedVerbatim) {
  try {
    parse_shape<2>(disk({0, 0}, 0), "scene.bodies[3].shape", 1.0);
    FAIL() << "no SceneError";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key_path(), "scene.bodies[3].shape.radius");
  }
}

}  // namespace
