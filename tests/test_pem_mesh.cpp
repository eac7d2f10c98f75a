// The PEM mesh (libmpm/pem/mesh.hpp): bodies meshed by Gmsh, meshes read from .msh and .vtu files,
// element measures. The .msh files are written here with Gmsh's own API (the library libmpm links).
#include <gmsh.h>
#include <gtest/gtest.h>
#include <omp.h>
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <clocale>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "libmpm/core/error.hpp"
#include "libmpm/pem/mesh.hpp"

namespace {

namespace fs = std::filesystem;
using cleave::SceneError;
using cleave::pem::BodyShape;
using cleave::pem::Mesh;
using cleave::pem::MeshOptions;
using nlohmann::json;
constexpr double kPi = std::numbers::pi;

struct Body {
  std::string name;
  json shape;
};

template <int Dim>
Mesh<Dim> mesh_of(const std::vector<Body>& bodies, double size, bool quads = false, bool structured = false,
                  double scale = 1.0, std::size_t max_nodes = 10'000'000) {
  std::vector<BodyShape> shapes;
  for (std::size_t i = 0; i < bodies.size(); ++i)
    shapes.push_back({bodies[i].name, &bodies[i].shape, "bodies[" + std::to_string(i) + "].shape"});
  MeshOptions opt;
  opt.size = size;
  opt.quads = quads;
  opt.structured = structured;
  return cleave::pem::mesh_bodies<Dim>(shapes, scale, opt, "pem.mesh_size", max_nodes);
}

template <int Dim>
double total_measure(const Mesh<Dim>& m) {
  double s = 0.0;
  for (std::size_t e = 0; e < m.element_count(); ++e) s += cleave::pem::element_measure(m, e);
  return s;
}

template <int Dim>
void expect_all_positive(const Mesh<Dim>& m) {
  for (std::size_t e = 0; e < m.element_count(); ++e)
    ASSERT_GT(cleave::pem::element_measure(m, e), 0.0) << "element " << e;
}

template <int Dim>
std::size_t count_of(const Mesh<Dim>& m, int nodes) {
  std::size_t n = 0;
  for (std::size_t e = 0; e < m.element_count(); ++e) n += m.nodes_of(e) == nodes;
  return n;
}

// A directory of this test's own in the build tree (CTest runs tests concurrently).
fs::path scratch() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path d = fs::path(CLEAVE_BINARY_DIR) / "test_out" / "pem_mesh" /
                     (std::string(info->name()) + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

void write(const fs::path& f, const std::string& text) { std::ofstream(f) << text; }

// An ASCII .vtu: points (x y z ...), cells (connectivity per cell), VTK types, an optional Int32
// cell array "region".
std::string vtu(const std::vector<double>& xyz, const std::vector<std::vector<int>>& cells, const std::vector<int>& types,
                const std::vector<int>& region = {}) {
  std::string points, conn, offsets, tys, reg;
  for (double v : xyz) points += std::to_string(v) + " ";
  int off = 0;
  for (const auto& c : cells) {
    for (int p : c) conn += std::to_string(p) + " ";
    offsets += std::to_string(off += static_cast<int>(c.size())) + " ";
  }
  for (int t : types) tys += std::to_string(t) + " ";
  for (int r : region) reg += std::to_string(r) + " ";
  return "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
         "<UnstructuredGrid><Piece NumberOfPoints=\"" + std::to_string(xyz.size() / 3) + "\" NumberOfCells=\"" +
         std::to_string(cells.size()) + "\">\n<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">" +
         points + "</DataArray></Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">" + conn +
         "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">" + offsets +
         "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">" + tys + "</DataArray>\n</Cells>\n" +
         (region.empty() ? "" : "<CellData><DataArray type=\"Int32\" Name=\"region\" format=\"ascii\">" + reg +
                                    "</DataArray></CellData>\n") +
         "</Piece></UnstructuredGrid></VTKFile>\n";
}

// The SceneError `f` throws (fails the test when it throws none).
template <class F>
SceneError error_of(F&& f) {
  try {
    f();
  } catch (const SceneError& e) {
    return e;
  }
  ADD_FAILURE() << "no SceneError";
  return SceneError("", "");
}

const json kDisk = json::parse(R"({"type": "disk", "center": [0, 0], "radius": 1})");

// --- meshing the bodies ------------------------------------------------------------------------

TEST(PemMesh, StructuredRectangleGivesTheCantileversEightyOneByElevenNodes) {
  const auto m = mesh_of<2>({{"beam", json::parse(R"({"type": "rectangle", "min": [0, 0], "max": [8, 1]})")}}, 0.1,
                            false, true);
  EXPECT_EQ(m.nodes.size(), 891u);
  EXPECT_EQ(m.element_count(), 1600u);
  EXPECT_EQ(count_of(m, 3), 1600u);
  EXPECT_NEAR(total_measure(m), 8.0, 1e-12);
  expect_all_positive(m);
  EXPECT_EQ(m.regions, std::vector<std::string>{"beam"});
  // The grid's columns: 81 distinct x, 11 distinct y.
  std::set<long> xs, ys;
  for (const auto& x : m.nodes) xs.insert(std::lround(x.x() * 1e6)), ys.insert(std::lround(x.y() * 1e6));
  EXPECT_EQ(xs.size(), 81u);
  EXPECT_EQ(ys.size(), 11u);
}

TEST(PemMesh, StructuredRectangleWithQuadsGivesEightHundredQuadrangles) {
  const auto m = mesh_of<2>({{"beam", json::parse(R"({"type": "rectangle", "min": [0, 0], "max": [8, 1]})")}}, 0.1,
                            true, true);
  EXPECT_EQ(m.nodes.size(), 891u);
  EXPECT_EQ(m.element_count(), 800u);
  EXPECT_EQ(count_of(m, 4), 800u);
  EXPECT_NEAR(total_measure(m), 8.0, 1e-12);
  expect_all_positive(m);
}

TEST(PemMesh, DiskAreaIsWithinHalfAPercentAndEveryElementIsPositive) {
  const auto m = mesh_of<2>({{"disk", kDisk}}, 0.1);
  EXPECT_NEAR(total_measure(m), kPi, 0.005 * kPi);
  expect_all_positive(m);
  EXPECT_EQ(count_of(m, 3), m.element_count());
  for (const auto& x : m.nodes) EXPECT_LE(x.norm(), 1.0 + 1e-9);
  // Unstructured quadrangles: recombined, the area stays.
  const auto q = mesh_of<2>({{"disk", kDisk}}, 0.1, true);
  EXPECT_GT(count_of(q, 4), q.element_count() * 9 / 10);
  EXPECT_NEAR(total_measure(q), kPi, 0.005 * kPi);
  expect_all_positive(q);
}

TEST(PemMesh, TouchingRectanglesShareTheNodesOfTheirCommonEdge) {
  const auto m = mesh_of<2>({{"left", json::parse(R"({"type": "rectangle", "min": [0, 0], "max": [1, 1]})")},
                             {"right", json::parse(R"({"type": "rectangle", "min": [1, 0], "max": [2, 1]})")}},
                            0.1);
  EXPECT_EQ(m.regions, (std::vector<std::string>{"left", "right"}));
  EXPECT_NEAR(total_measure(m), 2.0, 1e-12);
  // Each node of the edge x = 1 is used by elements of both bodies, and no two nodes coincide.
  std::vector<std::set<int>> used_by(m.nodes.size());
  for (std::size_t e = 0; e < m.element_count(); ++e)
    for (int k = 0; k < m.nodes_of(e); ++k) used_by[static_cast<std::size_t>(m.element(e)[k])].insert(m.element_region[e]);
  std::size_t on_edge = 0;
  for (std::size_t p = 0; p < m.nodes.size(); ++p) {
    if (std::abs(m.nodes[p].x() - 1.0) > 1e-12) continue;
    ++on_edge;
    EXPECT_EQ(used_by[p], (std::set<int>{0, 1})) << "node at y = " << m.nodes[p].y();
  }
  EXPECT_EQ(on_edge, 11u);
  std::set<std::pair<long, long>> at;
  for (const auto& x : m.nodes) at.insert({std::lround(x.x() * 1e9), std::lround(x.y() * 1e9)});
  EXPECT_EQ(at.size(), m.nodes.size());
}

TEST(PemMesh, OverlappingBodiesAreRefusedAtTheLaterBody) {
  const auto e = error_of([] {
    mesh_of<2>({{"plate", json::parse(R"({"type": "rectangle", "min": [0, 0], "max": [2, 1]})")},
                {"punch", json::parse(R"({"type": "disk", "center": [2, 0.5], "radius": 0.3})")}},
               0.1);
  });
  EXPECT_EQ(e.key_path(), "bodies[1].shape");
  EXPECT_NE(e.reason().find("'punch' overlaps body 'plate'"), std::string::npos) << e.what();
  // A body wholly inside another overlaps it too.
  const auto inside = error_of([] {
    mesh_of<2>({{"a", json::parse(R"({"type": "rectangle", "min": [0, 0], "max": [2, 2]})")},
                {"b", kDisk}, {"c", json::parse(R"({"type": "disk", "center": [1, 1], "radius": 0.2})")}},
               0.1);
  });
  EXPECT_EQ(inside.key_path(), "bodies[1].shape") << inside.what();
}

TEST(PemMesh, UnionAndDifferenceGiveTheirAreas) {
  const auto u = mesh_of<2>({{"u", json::parse(R"({"type": "union", "shapes": [
      {"type": "rectangle", "min": [0, 0], "max": [2, 1]}, {"type": "rectangle", "min": [1, 0], "max": [3, 1]}]})")}},
                            0.1);
  EXPECT_NEAR(total_measure(u), 3.0, 1e-12);
  expect_all_positive(u);
  const auto d = mesh_of<2>({{"d", json::parse(R"({"type": "difference", "shapes": [
      {"type": "rectangle", "min": [0, 0], "max": [2, 2]}, {"type": "disk", "center": [1, 1], "radius": 0.5}]})")}},
                            0.05);
  EXPECT_NEAR(total_measure(d), 4.0 - kPi / 4, 0.002 * (4.0 - kPi / 4));
  expect_all_positive(d);
  for (const auto& x : d.nodes) EXPECT_GE((x - cleave::Vec<2>(1, 1)).norm(), 0.5 - 1e-9);
  const auto none = error_of([] {
    mesh_of<2>({{"d", json::parse(R"({"type": "difference", "shapes": [
        {"type": "disk", "center": [0, 0], "radius": 0.5}, {"type": "rectangle", "min": [-1, -1], "max": [1, 1]}]})")}},
               0.1);
  });
  EXPECT_EQ(none.key_path(), "bodies[0].shape.shapes") << none.what();
}

TEST(PemMesh, EllipseAngleIsInDegreesAndPolygonsMeshEitherWay) {
  // a = 2 along x turned 90 degrees: 1 wide, 2 tall; a tall one (a < b) turned 0: the same.
  for (const char* text : {R"({"type": "ellipse", "center": [0, 0], "semi_axes": [2, 1], "angle": 90})",
                           R"({"type": "ellipse", "center": [0, 0], "semi_axes": [1, 2]})"}) {
    const auto m = mesh_of<2>({{"e", json::parse(text)}}, 0.05);
    EXPECT_NEAR(total_measure(m), 2.0 * kPi, 0.005 * 2.0 * kPi) << text;
    double xmax = 0, ymax = 0;
    for (const auto& x : m.nodes) xmax = std::max(xmax, std::abs(x.x())), ymax = std::max(ymax, std::abs(x.y()));
    EXPECT_NEAR(xmax, 1.0, 1e-3) << text;  // boundary nodes need not fall on the vertices
    EXPECT_NEAR(ymax, 2.0, 1e-3) << text;
    expect_all_positive(m);
  }
  // An L, counter-clockwise and clockwise: area 3, elements positive.
  for (const char* text : {R"({"type": "polygon", "points": [[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]]})",
                           R"({"type": "polygon", "points": [[0, 2], [1, 2], [1, 1], [2, 1], [2, 0], [0, 0]]})"}) {
    const auto m = mesh_of<2>({{"l", json::parse(text)}}, 0.1);
    EXPECT_NEAR(total_measure(m), 3.0, 1e-12) << text;
    expect_all_positive(m);
  }
}

TEST(PemMesh, BoxAndSphereHaveTheirVolumesInPositiveTetrahedra) {
  const auto b = mesh_of<3>({{"box", json::parse(R"({"type": "box", "min": [0, 0, 0], "max": [1, 0.5, 0.3]})")}}, 0.1);
  EXPECT_NEAR(total_measure(b), 0.15, 1e-12);
  EXPECT_EQ(count_of(b, 4), b.element_count());
  expect_all_positive(b);
  const auto s = mesh_of<3>({{"ball", json::parse(R"({"type": "sphere", "center": [0, 0, 0], "radius": 1})")}}, 0.1);
  EXPECT_NEAR(total_measure(s), 4.0 / 3.0 * kPi, 0.02 * 4.0 / 3.0 * kPi);
  expect_all_positive(s);
}

TEST(PemMesh, StructuredBoxGivesHexahedraWithQuadsAndTetrahedraWithout) {
  const json box = json::parse(R"({"type": "box", "min": [0, 0, 0], "max": [1, 0.5, 0.3]})");
  const auto h = mesh_of<3>({{"box", box}}, 0.1, true, true);
  EXPECT_EQ(h.nodes.size(), 11u * 6u * 4u);
  EXPECT_EQ(count_of(h, 8), 150u);
  EXPECT_EQ(h.element_count(), 150u);
  EXPECT_NEAR(total_measure(h), 0.15, 1e-12);
  expect_all_positive(h);
  const auto t = mesh_of<3>({{"box", box}}, 0.1, false, true);
  EXPECT_EQ(t.nodes.size(), 264u);
  EXPECT_EQ(count_of(t, 4), t.element_count());
  EXPECT_NEAR(total_measure(t), 0.15, 1e-12);
  expect_all_positive(t);
}

TEST(PemMesh, CylinderEllipsoidAndPrismHaveTheirVolumes) {
  const auto c = mesh_of<3>({{"c", json::parse(R"({"type": "cylinder", "center": [1, 1, 1], "axis": [0, 0, 2],
                                                   "radius": 0.5, "length": 2})")}}, 0.1);
  EXPECT_NEAR(total_measure(c), kPi * 0.25 * 2.0, 0.02 * kPi * 0.5);
  double zlo = 1e9, zhi = -1e9;
  for (const auto& x : c.nodes) zlo = std::min(zlo, x.z()), zhi = std::max(zhi, x.z());
  EXPECT_NEAR(zlo, 0.0, 1e-9);
  EXPECT_NEAR(zhi, 2.0, 1e-9);
  const auto e = mesh_of<3>({{"e", json::parse(R"({"type": "ellipsoid", "center": [0, 0, 0], "semi_axes": [1, 0.6, 0.4]})")}}, 0.08);
  EXPECT_NEAR(total_measure(e), 4.0 / 3.0 * kPi * 0.24, 0.03 * 4.0 / 3.0 * kPi * 0.24);
  expect_all_positive(e);
  const auto p = mesh_of<3>({{"p", json::parse(R"({"type": "prism", "points": [[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]],
                                                   "z": [0.5, 1]})")}}, 0.1);
  EXPECT_NEAR(total_measure(p), 1.5, 1e-12);
  expect_all_positive(p);
}

TEST(PemMesh, LengthScaleConvertsSceneUnitsToMetres) {
  // A 20 mm disk written in millimetres meshes as the same disk written in metres.
  const auto mm = mesh_of<2>({{"d", json::parse(R"({"type": "disk", "center": [5, 0], "radius": 20})")}}, 0.002,
                             false, false, 1e-3);
  const auto m = mesh_of<2>({{"d", json::parse(R"({"type": "disk", "center": [0.005, 0], "radius": 0.02})")}}, 0.002);
  ASSERT_EQ(mm.nodes.size(), m.nodes.size());
  for (std::size_t p = 0; p < m.nodes.size(); ++p) EXPECT_NEAR((mm.nodes[p] - m.nodes[p]).norm(), 0.0, 1e-15);
  EXPECT_NEAR(total_measure(mm), kPi * 4e-4, 0.005 * kPi * 4e-4);
}

TEST(PemMesh, MeshingTheSameDiskTwiceGivesIdenticalNodes) {
  const auto a = mesh_of<2>({{"disk", kDisk}}, 0.05);
  const auto b = mesh_of<2>({{"disk", kDisk}}, 0.05);
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (std::size_t p = 0; p < a.nodes.size(); ++p) ASSERT_EQ(a.nodes[p], b.nodes[p]) << p;
  EXPECT_EQ(a.element_nodes, b.element_nodes);
}

TEST(PemMesh, TooManyNodesAndBadShapesAreRefusedAtTheirKeys) {
  const auto many = error_of([] { mesh_of<2>({{"disk", kDisk}}, 0.01, false, false, 1.0, 1000); });
  EXPECT_EQ(many.key_path(), "pem.mesh_size");
  EXPECT_NE(many.reason().find("more than the 1000 allowed"), std::string::npos) << many.what();
  const auto bad = error_of([] { mesh_of<2>({{"disk", json::parse(R"({"type": "disk", "center": [0, 0], "radius": -1})")}}, 0.1); });
  EXPECT_EQ(bad.key_path(), "bodies[0].shape.radius");
  const auto zero = error_of([] { mesh_of<2>({{"disk", kDisk}}, 0.0); });
  EXPECT_EQ(zero.key_path(), "pem.mesh_size");
}

TEST(PemMesh, MeshingLeavesTheProcessAsItWas) {
  // Gmsh 4.8 sets OpenMP's threads to its own count (1), LC_NUMERIC, the stack limit, PATH and
  // PYTHONPATH; the solver that runs next must find them as they were.
  const int threads = omp_get_max_threads();
  omp_set_num_threads(3);
  const std::string path = std::getenv("PATH") ? std::getenv("PATH") : "";
  const bool python_path = std::getenv("PYTHONPATH") != nullptr;
  const std::string numeric = std::setlocale(LC_NUMERIC, nullptr);
  rlimit before{}, after{};
  getrlimit(RLIMIT_STACK, &before);
  mesh_of<2>({{"disk", kDisk}}, 0.2);
  getrlimit(RLIMIT_STACK, &after);
  EXPECT_EQ(omp_get_max_threads(), 3);
  EXPECT_EQ(std::getenv("PATH") ? std::getenv("PATH") : "", path);
  EXPECT_EQ(std::getenv("PYTHONPATH") != nullptr, python_path);
  EXPECT_EQ(std::string(std::setlocale(LC_NUMERIC, nullptr)), numeric);
  EXPECT_EQ(after.rlim_cur, before.rlim_cur);
  omp_set_num_threads(threads);
}

// The time is printed, not asserted (no test asserts wall time: a loaded machine must not fail CI).
TEST(PemMesh, TheBrazilianDisksMeshAtHalfAMillimetreHasItsArea) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto m = mesh_of<2>({{"d", json::parse(R"({"type": "disk", "center": [0, 0], "radius": 20})")}}, 0.0005,
                            false, false, 1e-3);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("disk r = 20 mm at 0.5 mm: %zu nodes, %zu elements, %.3f s\n", m.nodes.size(), m.element_count(), s);
  EXPECT_NEAR(total_measure(m), kPi * 4e-4, 0.001 * kPi * 4e-4);
}

// --- mesh files ----------------------------------------------------------------------------------

// Two unit squares side by side, groups "aggregate" and "mortar", and a group of boundary lines.
void write_two_group_msh(const fs::path& f, int order, double z = 0.0) {
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  const int a = gmsh::model::occ::addRectangle(0, 0, z, 1, 1);
  const int b = gmsh::model::occ::addRectangle(1, 0, z, 1, 1);
  gmsh::vectorpair out;
  std::vector<gmsh::vectorpair> map;
  gmsh::model::occ::fragment({{2, a}}, {{2, b}}, out, map);
  gmsh::model::occ::synchronize();
  gmsh::model::setPhysicalName(2, gmsh::model::addPhysicalGroup(2, {map[0][0].second}), "aggregate");
  gmsh::model::setPhysicalName(2, gmsh::model::addPhysicalGroup(2, {map[1][0].second}), "mortar");
  gmsh::model::setPhysicalName(1, gmsh::model::addPhysicalGroup(1, {1, 2}), "edges");
  gmsh::option::setNumber("Mesh.MeshSizeMax", 0.25);
  gmsh::model::mesh::generate(2);
  if (order > 1) gmsh::model::mesh::setOrder(order);
  gmsh::write(f.string());
  gmsh::finalize();
}

TEST(PemMeshFile, MshFileWithTwoPhysicalGroupsGivesNamedRegions) {
  const fs::path f = scratch() / "two.msh";
  write_two_group_msh(f, 1);
  const auto m = cleave::pem::read_mesh_file<2>(f.string(), "pem.mesh_file", 1e-3);
  EXPECT_EQ(m.regions, (std::vector<std::string>{"aggregate", "mortar"}));
  EXPECT_NEAR(total_measure(m), 2e-6, 1e-18);
  expect_all_positive(m);
  std::set<int32_t> regions(m.element_region.begin(), m.element_region.end());
  EXPECT_EQ(regions, (std::set<int32_t>{0, 1}));
  for (const auto& x : m.nodes) EXPECT_LE(x.x(), 2e-3 + 1e-15);
}

TEST(PemMeshFile, SecondOrderTrianglesAreRefusedNamingTheirKind) {
  const fs::path f = scratch() / "quadratic.msh";
  write_two_group_msh(f, 2);
  const auto e = error_of([&] { cleave::pem::read_mesh_file<2>(f.string(), "pem.mesh_file", 1.0); });
  EXPECT_EQ(e.key_path(), "pem.mesh_file");
  EXPECT_NE(e.reason().find("Triangle 6"), std::string::npos) << e.what();
  EXPECT_NE(e.reason().find(f.string()), std::string::npos) << e.what();
}

TEST(PemMeshFile, A3DMshFileGivesItsTetrahedraAndA2DSceneRefusesIt) {
  const fs::path f = scratch() / "box.msh";
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::model::occ::addBox(0, 0, 0, 1, 1, 1);
  gmsh::model::occ::synchronize();
  gmsh::option::setNumber("Mesh.MeshSizeMax", 0.3);
  gmsh::model::mesh::generate(3);
  gmsh::write(f.string());
  gmsh::finalize();
  const auto m = cleave::pem::read_mesh_file<3>(f.string(), "k", 1.0);
  EXPECT_NEAR(total_measure(m), 1.0, 1e-12);
  EXPECT_EQ(m.regions, std::vector<std::string>{""});  // no physical group
  expect_all_positive(m);
  const auto e = error_of([&] { cleave::pem::read_mesh_file<2>(f.string(), "k", 1.0); });
  EXPECT_NE(e.reason().find("3D elements"), std::string::npos) << e.what();
}

TEST(PemMeshFile, VtuWithARegionArrayIsReadAndUnusedPointsAndLinesDropped) {
  const fs::path f = scratch() / "square.vtu";
  // Unit square: a quad (region 7) on the right half, two triangles (region 3) on the left, a
  // boundary line, and a point no cell uses.
  write(f, vtu({0, 0, 0, 0.5, 0, 0, 1, 0, 0, 1, 1, 0, 0.5, 1, 0, 0, 1, 0, 9, 9, 0},
               {{0, 1, 4}, {0, 4, 5}, {1, 2, 3, 4}, {0, 1}}, {5, 5, 9, 3}, {3, 3, 7, 3}));
  const auto m = cleave::pem::read_mesh_file<2>(f.string(), "pem.mesh_file", 2.0);
  EXPECT_EQ(m.nodes.size(), 6u);
  EXPECT_EQ(m.element_count(), 3u);
  EXPECT_EQ(m.regions, (std::vector<std::string>{"3", "7"}));
  EXPECT_EQ(m.element_region, (std::vector<int32_t>{0, 0, 1}));
  EXPECT_NEAR(total_measure(m), 4.0, 1e-12);
  EXPECT_NEAR(cleave::pem::element_measure(m, 2), 2.0, 1e-12);
  // Without the array: one region "".
  write(f, vtu({0, 0, 0, 1, 0, 0, 0, 1, 0}, {{0, 1, 2}}, {5}));
  EXPECT_EQ(cleave::pem::read_mesh_file<2>(f.string(), "k", 1.0).regions, std::vector<std::string>{""});
}

TEST(PemMeshFile, ClockwiseTrianglesAreReorientedNotRefused) {
  const fs::path f = scratch() / "clockwise.vtu";
  write(f, vtu({0, 0, 5, 1, 0, 5, 0, 1, 5, 1, 1, 5}, {{0, 2, 1}, {1, 2, 3}}, {5, 5}));  // z = 5: a plane
  const auto m = cleave::pem::read_mesh_file<2>(f.string(), "k", 1.0);
  EXPECT_NEAR(cleave::pem::element_measure(m, 0), 0.5, 1e-15);
  EXPECT_NEAR(cleave::pem::element_measure(m, 1), 0.5, 1e-15);
  // A clockwise quadrangle too; a tangled one (a bow tie) is refused.
  write(f, vtu({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, {{0, 3, 2, 1}}, {9}));
  EXPECT_NEAR(total_measure(cleave::pem::read_mesh_file<2>(f.string(), "k", 1.0)), 1.0, 1e-15);
  write(f, vtu({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, {{0, 2, 1, 3}}, {9}));
  const auto e = error_of([&] { cleave::pem::read_mesh_file<2>(f.string(), "k", 1.0); });
  EXPECT_NE(e.reason().find("element 0 (cell 0, a quadrangle) is inverted"), std::string::npos) << e.what();
}

TEST(PemMeshFile, ZeroAreaTriangleAndTiltedMeshAreRefused) {
  const fs::path f = scratch() / "flat.vtu";
  write(f, vtu({0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0}, {{0, 1, 2}, {0, 1, 3}}, {5, 5}));
  const auto e = error_of([&] { cleave::pem::read_mesh_file<2>(f.string(), "pem.mesh_file", 1.0); });
  EXPECT_EQ(e.key_path(), "pem.mesh_file");
  EXPECT_NE(e.reason().find("element 1 (cell 1, a triangle) has zero area (0 m^2)"), std::string::npos) << e.what();
  write(f, vtu({0, 0, 0, 1, 0, 0, 0, 1, 0.5}, {{0, 1, 2}}, {5}));
  const auto t = error_of([&] { cleave::pem::read_mesh_file<2>(f.string(), "k", 1.0); });
  EXPECT_NE(t.reason().find("plane z = constant"), std::string::npos) << t.what();
  // A zero-volume tetrahedron in 3D.
  write(f, vtu({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}, {{0, 1, 2, 3}}, {10}));
  const auto v = error_of([&] { cleave::pem::read_mesh_file<3>(f.string(), "k", 1.0); });
  EXPECT_NE(v.reason().find("element 0 (cell 0, a tetrahedron) has zero volume"), std::string::npos) << v.what();
}

TEST(PemMeshFile, MissingFilesDirectoriesAndUnknownExtensionsAreRefusedNamingTheFile) {
  const fs::path d = scratch();
  const auto missing = error_of([&] { cleave::pem::read_mesh_file<2>((d / "none.msh").string(), "pem.mesh_file", 1.0); });
  EXPECT_EQ(missing.key_path(), "pem.mesh_file");
  EXPECT_NE(missing.reason().find((d / "none.msh").string() + ": cannot open"), std::string::npos) << missing.what();
  fs::create_directories(d / "dir.vtu");
  const auto dir = error_of([&] { cleave::pem::read_mesh_file<2>((d / "dir.vtu").string(), "k", 1.0); });
  EXPECT_NE(dir.reason().find("dir.vtu: cannot open: is a directory"), std::string::npos) << dir.what();
  write(d / "mesh.stl", "solid x\nendsolid x\n");
  const auto ext = error_of([&] { cleave::pem::read_mesh_file<2>((d / "mesh.stl").string(), "k", 1.0); });
  EXPECT_NE(ext.reason().find("mesh.stl: unknown mesh file extension '.stl'"), std::string::npos) << ext.what();
  write(d / "junk.vtu", "not xml at all");
  const auto junk = error_of([&] { cleave::pem::read_mesh_file<2>((d / "junk.vtu").string(), "k", 1.0); });
  EXPECT_NE(junk.reason().find("junk.vtu: "), std::string::npos) << junk.what();
  write(d / "junk.msh", "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\nrubbish\n");
  const auto jm = error_of([&] { cleave::pem::read_mesh_file<2>((d / "junk.msh").string(), "k", 1.0); });
  EXPECT_NE(jm.reason().find("junk.msh: "), std::string::npos) << jm.what();
  const auto dev = error_of([&] { cleave::pem::read_mesh_file<2>("/dev/null", "k", 1.0); });
  EXPECT_NE(dev.reason().find("not a regular file"), std::string::npos) << dev.what();
}

}  // namespace
