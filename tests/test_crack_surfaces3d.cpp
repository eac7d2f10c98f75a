// 3D crack surfaces (issue 16): the scene's forms (triangles, quad, indexed mesh, rectangle,
// ellipse, STL and Gmsh files) meshed to an element size, the checks every surface passes, and the
// fronts with their frames.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>

#include <sys/stat.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "libmpm/core/error.hpp"
#include "libmpm/crack/fronts.hpp"
#include "libmpm/crack/mesh3d.hpp"
#include "libmpm/crack/mesh_files.hpp"
#include "libmpm/crack/surface3d.hpp"

namespace {

using cleave::SceneError;
using cleave::Vec;
using nlohmann::json;
using namespace cleave::crack;
using V3 = Vec<3>;

double area(const TriMesh& m, V3* normal_sum = nullptr) {
  double a = 0.0;
  for (const auto& t : m.triangles) {
    const V3 n = (m.points[t[1]] - m.points[t[0]]).cross(m.points[t[2]] - m.points[t[0]]);
    a += 0.5 * n.norm();
    if (normal_sum) *normal_sum += n;
  }
  return a;
}
double longest_edge(const TriMesh& m) {
  double l = 0.0;
  for (const auto& t : m.triangles)
    for (int e = 0; e < 3; ++e) l = std::max(l, (m.points[t[(e + 1) % 3]] - m.points[t[e]]).norm());
  return l;
}
Surface<3> surface_of(const TriMesh& m) {
  Surface<3> s;
  s.name = "c";
  s.points = m.points, s.simplices = m.triangles;
  s.update_extent();
  return s;
}
std::string error_of(const json& cracks, SurfaceMeshing meshing = {0.25, true}) {
  try {
    parse_surfaces3d(cracks, "cracks", 1.0, meshing);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

TEST(CrackSurfaces3D, ARectangleIsMeshedAtTheElementSizeWithItsAreaAndNormal) {
  const V3 e1(2.0, 0.0, 0.0), e2(0.0, 1.0, 0.5);
  const TriMesh m = rectangle_mesh(V3(0.1, 0.2, 0.3), e1, e2, 0.25);
  EXPECT_NEAR(area(m), e1.cross(e2).norm(), 1e-12);
  for (const auto& t : m.triangles) {
    const V3 n = (m.points[t[1]] - m.points[t[0]]).cross(m.points[t[2]] - m.points[t[0]]);
    EXPECT_GT(n.normalized().dot(e1.cross(e2).normalized()), 1.0 - 1e-12);
  }
  EXPECT_LE(longest_edge(m), 0.25 * std::sqrt(2.0) * 1.0000001);  // cells of at most size x size: diagonals
  EXPECT_NO_THROW(check_surface_mesh(m, "cracks[0].rectangle"));
  EXPECT_EQ(surface_of(m).boundary().size(), 2u * (8 + 5));  // |e1| / 0.25 = 8, |e2| / 0.25 = 4.47 -> 5
}

TEST(CrackSurfaces3D, AnEllipseIsMeshedInRingsWhoseAreaConvergesToPiAB) {
  const double a = 2.0, b = 1.0;
  for (const double size : {0.5, 0.2, 0.1}) {
    // A circle's edges are about the size: radial steps of size, rim steps of pi / 3 size, and the
    // diagonals between rings, up to 1.43 size where the rings' points fall half a step apart.
    EXPECT_LE(longest_edge(ellipse_mesh(V3(0, 0, 0), V3(0, 0, 1), V3(1, 0, 0), a, a, size)), 1.5 * size);
    V3 nsum = V3::Zero();
    const TriMesh m = ellipse_mesh(V3(1, 2, 3), V3(0, 0, 2), V3(1, 1, 0), a, b, size);
    const double A = area(m, &nsum);
    // The rings are inscribed polygons of 6 k sides: area (n / 2) sin(2 pi / n) a b for the outer n.
    const int n = 6 * static_cast<int>(std::ceil(a / size - 1e-9));
    EXPECT_NEAR(A, 0.5 * n * std::sin(2 * std::numbers::pi / n) * a * b, 1e-9) << size;
    EXPECT_GT(nsum.normalized().z(), 1.0 - 1e-12);
    EXPECT_LE(longest_edge(m), 1.6 * size);  // 2:1: the rings' points crowd where the ellipse is flat
    EXPECT_NO_THROW(check_surface_mesh(m, "cracks[0].ellipse"));
  }
}

TEST(CrackSurfaces3D, AnEmbeddedPennyHasOneClosedFrontWithFramesPointingOutwards) {
  const V3 c(0.5, 0.5, 0.5), n = V3(1, 1, 1).normalized();
  const Surface<3> s = surface_of(ellipse_mesh(c, n, V3(1, 0, 0), 0.2, 0.2, 0.02));
  const auto fronts = crack_fronts(s, [](const V3&) { return true; });
  ASSERT_EQ(fronts.size(), 1u);
  const auto& f = fronts[0];
  EXPECT_TRUE(f.closed);
  EXPECT_EQ(f.nodes.size(), 60u);
  for (std::size_t k = 0; k < f.nodes.size(); ++k) {
    const V3 radial = (s.points[f.nodes[k]] - c).normalized();
    EXPECT_NEAR((s.points[f.nodes[k]] - c).norm(), 0.2, 1e-12);
    EXPECT_GT(f.normal[k].dot(n), 1.0 - 1e-9);
    EXPECT_GT(f.ahead[k].dot(radial), 1.0 - 1e-9);  // into the uncracked material
    EXPECT_NEAR(f.tangent[k].dot(f.normal[k]), 0.0, 1e-12);
    EXPECT_NEAR(f.tangent[k].norm(), 1.0, 1e-12);
    EXPECT_NEAR(f.ahead[k].norm(), 1.0, 1e-12);
  }
}

TEST(CrackSurfaces3D, ASurfaceCrackLeavingTheBodyKeepsItsInsidePartAndItsEdgesOutsideAreMouths) {
  // Half of a circle sticks out of the block y > 0: the part outside goes, the front is the arc inside.
  const auto inside = [](const V3& x) { return x.y() > 0.0; };
  const TriMesh m = clip_to(ellipse_mesh(V3(0, 0, 0), V3(0, 0, 1), V3(1, 0, 0), 1.0, 1.0, 0.1), inside);
  EXPECT_NO_THROW(check_surface_mesh(m, "cracks[0]"));
  for (const auto& t : m.triangles)
    EXPECT_TRUE(inside(m.points[t[0]]) || inside(m.points[t[1]]) || inside(m.points[t[2]]));
  const auto fronts = crack_fronts(surface_of(m), inside);
  ASSERT_EQ(fronts.size(), 1u);
  EXPECT_FALSE(fronts[0].closed);
  for (const int32_t p : fronts[0].nodes) EXPECT_NEAR(m.points[p].norm(), 1.0, 1e-12);  // on the circle
  EXPECT_GT(fronts[0].nodes.size(), 25u);  // about half of the 60 rim points
}

TEST(CrackSurfaces3D, RefiningCutsSharedEdgesAtTheSamePointsSoTheSurfaceStaysOneManifold) {
  TriMesh m{{V3(0, 0, 0), V3(1, 0, 0), V3(1, 1, 0.5), V3(0, 1, 0)}, {{0, 1, 2}, {0, 2, 3}}};
  const TriMesh r = refine(m, 0.3);  // k = ceil(1.5 / 0.3) = 5
  EXPECT_EQ(r.triangles.size(), 2u * 25u);
  EXPECT_EQ(r.points.size(), 2u * 21u - 6u);  // two triangles of 21 lattice points sharing 6
  EXPECT_NEAR(area(r), area(m), 1e-12);
  EXPECT_NO_THROW(check_surface_mesh(r, "cracks[0]"));
  EXPECT_EQ(surface_of(r).boundary().size(), 4u * 5u);
}

TEST(CrackSurfaces3D, EveryFormOfTheSceneGivesTheSameSquare) {
  const json forms = json::parse(R"([
    {"name": "t", "triangles": [[[0,0,0],[1,0,0],[1,1,0]], [[0,0,0],[1,1,0],[0,1,0]]]},
    {"name": "q", "quad": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]},
    {"name": "m", "mesh": {"points": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "triangles": [[0,1,2],[0,2,3]]}},
    {"name": "r", "rectangle": {"corner": [0,0,0], "edges": [[1,0,0],[0,1,0]]}}])");
  const auto s = parse_surfaces3d(forms, "cracks", 1.0, {0.25, true});
  ASSERT_EQ(s.size(), 4u);
  for (const auto& c : s) {
    TriMesh m{c.points, c.simplices};
    EXPECT_NEAR(area(m), 1.0, 1e-12) << c.name;
    EXPECT_LE(longest_edge(m), 0.25 * std::sqrt(2.0) + 1e-12) << c.name;  // refined to the size
    double perimeter = 0.0;  // shared vertices: the boundary is the square's
    for (const auto& e : c.boundary()) perimeter += (c.points[e[1]] - c.points[e[0]]).norm();
    EXPECT_NEAR(perimeter, 4.0, 1e-12) << c.name;
    EXPECT_EQ(crack_fronts(c, [](const V3&) { return true; }).size(), 1u) << c.name;
  }
  // Peridynamics keeps given triangles as they are.
  const auto pd = parse_surfaces3d(forms, "cracks", 1.0, {0.25, false});
  EXPECT_EQ(pd[0].simplices.size(), 2u);
  EXPECT_EQ(pd[3].simplices.size(), 32u);  // generated shapes are meshed at the size
  // The scene's length unit applies to every coordinate and size.
  const auto mm = parse_surfaces3d(json::parse(R"([{"name": "e", "element_size": 100,
      "ellipse": {"center": [0,0,0], "normal": [0,0,1], "radius": 1000}}])"), "cracks", 1e-3, {0.25, true});
  EXPECT_NEAR(mm[0].hi.x(), 1.0, 1e-12);
  EXPECT_EQ(crack_fronts(mm[0], [](const V3&) { return true; })[0].nodes.size(), 60u);
}

TEST(CrackSurfaces3D, BadSurfacesAreRefusedNamingTheCrackAndTheTriangle) {
  auto err = [](const char* j) { return error_of(json::parse(j)); };
  EXPECT_NE(err(R"([{"name": "a", "triangles": [[[0,0,0],[1,0,0],[1,1,0]], [[0,0,0],[1,1,0],[2,2,0]]]}])")
                .find("cracks[0].triangles: triangle 1"),
            std::string::npos);  // degenerate
  EXPECT_NE(err(R"([{"name": "a", "mesh": {"points": [[0,0,0],[1,0,0],[0,1,0],[0,-1,0],[0,0,1]],
                    "triangles": [[0,1,2],[1,0,3],[0,1,4]]}}])").find("manifold"),
            std::string::npos);
  EXPECT_NE(err(R"([{"name": "a", "mesh": {"points": [[0,0,0],[1,0,0],[0,1,0],[1,1,0]],
                    "triangles": [[0,1,2],[1,3,2],[2,1,3]]}}])").find("manifold"),
            std::string::npos);
  EXPECT_NE(err(R"([{"name": "a", "mesh": {"points": [[0,0,0],[1,0,0],[0,1,0],[1,1,0]],
                    "triangles": [[0,1,2],[1,2,3]]}}])").find("oriented inconsistently"),
            std::string::npos);
  EXPECT_NE(err(R"([{"name": "a", "triangles": [[[0,0,0],[2,0,0],[0,2,0]], [[0.5,0.5,-1],[0.5,0.5,1],[3,3,0]]]}])")
                .find("self-intersecting"),
            std::string::npos);
  EXPECT_NE(err(R"([{"name": "a", "mesh": {"points": [[0,0,0],[1,0,0],[0,1,0]], "triangles": [[0,1,3]]}}])")
                .find("cracks[0].mesh.triangles[0][2]"),
            std::string::npos);
  // An index above 2^63 (nlohmann keeps it unsigned) is refused as given, not wrapped to -1.
  EXPECT_NE(err(R"([{"name": "a", "mesh": {"points": [[0,0,0],[1,0,0],[0,1,0]], "triangles": [[0,1,18446744073709551615]]}}])")
                .find("cracks[0].mesh.triangles[0][2]: expected a point index from 0 to 2 (got 18446744073709551615)"),
            std::string::npos);
  EXPECT_NE(err(R"([{"name": "a", "quad": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "ellipse": {}}])").find("not both"),
            std::string::npos);
  EXPECT_NE(err(R"([{"name": "a"}])").find("missing the surface"), std::string::npos);
  EXPECT_NE(err(R"([{"name": "a", "ellipse": {"center": [0,0,0], "normal": [0,0,0], "radius": 1}}])")
                .find("cracks[0].ellipse.normal"),
            std::string::npos);
  EXPECT_NE(err(R"([{"name": "a", "rectangle": {"corner": [0,0,0], "edges": [[1,0,0],[2,0,0]]}}])").find("no area"),
            std::string::npos);
  EXPECT_NE(err(R"([{"name": "a", "file": "/nonexistent/crack.stl"}])").find("/nonexistent/crack.stl: cannot open"),
            std::string::npos);
  EXPECT_NE(err(R"([{"name": "a", "file": "crack.obj"}])").find("crack.obj"), std::string::npos);
}

class MeshFiles : public ::testing::Test {
 protected:
  std::filesystem::path dir = std::filesystem::temp_directory_path() /
                              ("cleave_mesh_files_" + std::to_string(::getpid()));
  void SetUp() override { std::filesystem::create_directories(dir); }
  void TearDown() override { std::filesystem::remove_all(dir); }
  std::filesystem::path write(const std::string& name, const std::string& text) {
    std::ofstream(dir / name, std::ios::binary) << text;
    return dir / name;
  }
  static void expect_unit_square(const TriMesh& m) {
    EXPECT_EQ(m.points.size(), 4u);
    EXPECT_EQ(m.triangles.size(), 2u);
    V3 n = V3::Zero();
    EXPECT_NEAR(area(m, &n), 1.0, 1e-6);
    EXPECT_GT(n.normalized().z(), 0.999999);
    EXPECT_NO_THROW(check_surface_mesh(m, "f"));
  }
};

TEST_F(MeshFiles, AsciiAndBinaryStlGiveTheSameSurfaceWithSharedVertices) {
  const auto ascii = write("s.stl", R"(solid square
facet normal 0 0 1
 outer loop
  vertex 0 0 0
  vertex 1 0 0
  vertex 1 1 0
 endloop
endfacet
facet normal 0 0 1
 outer loop
  vertex 0 0 0
  vertex 1 1 0
  vertex 0 1 0
 endloop
endfacet
endsolid square
)");
  expect_unit_square(read_mesh_file(ascii, "cracks[0].file"));
  std::string bin(80, ' ');
  bin.replace(0, 5, "solid");  // as some exporters write: recognised by the size
  const uint32_t n = 2;
  bin.append(reinterpret_cast<const char*>(&n), 4);
  const float tris[2][12] = {{0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 1, 0}, {0, 0, 1, 0, 0, 0, 1, 1, 0, 0, 1, 0}};
  for (const auto& t : tris) {
    bin.append(reinterpret_cast<const char*>(t), 48);
    bin.append(2, '\0');
  }
  expect_unit_square(read_mesh_file(write("b.stl", bin), "cracks[0].file"));
  EXPECT_THROW(read_mesh_file(write("t.stl", bin.substr(0, 120)), "cracks[0].file"), SceneError);  // truncated
}

// What is not a regular file, or is larger than the cap, is refused before a byte of it is read:
// "/dev/zero" was read until memory ran out, and a FIFO blocks the reader for ever (issue 15).
TEST_F(MeshFiles, ADeviceAFifoOrAFileOverOneGibIsRefusedNamingTheCrackKeyAndTheFile) {
  auto refusal = [](const std::filesystem::path& f) {
    try {
      read_mesh_file(f, "cracks[0].file");
    } catch (const SceneError& e) {
      return e;
    }
    return SceneError("(accepted)", "");
  };
  auto has = [](const std::string& text, const std::string& word) { return text.find(word) != std::string::npos; };
  std::filesystem::create_symlink("/dev/zero", dir / "zero.stl");
  const SceneError zero = refusal(dir / "zero.stl");
  EXPECT_EQ(zero.key_path(), "cracks[0].file");
  EXPECT_TRUE(has(zero.reason(), (dir / "zero.stl").string() + ": not a regular file")) << zero.reason();
  ASSERT_EQ(::mkfifo((dir / "pipe.msh").c_str(), 0600), 0);
  const SceneError fifo = refusal(dir / "pipe.msh");
  EXPECT_EQ(fifo.key_path(), "cracks[0].file");
  EXPECT_TRUE(has(fifo.reason(), (dir / "pipe.msh").string() + ": not a regular file")) << fifo.reason();
  // "/dev/zero" itself has no mesh file type: refused before it is opened.
  const SceneError bare = refusal("/dev/zero");
  EXPECT_TRUE(has(bare.reason(), "/dev/zero: unknown mesh file type")) << bare.reason();
  // A sparse file one byte over the cap (no disk blocks allocated).
  std::ofstream(dir / "big.stl").close();
  std::filesystem::resize_file(dir / "big.stl", kMaxMeshFileBytes + 1);
  const SceneError big = refusal(dir / "big.stl");
  EXPECT_EQ(big.key_path(), "cracks[0].file");
  EXPECT_TRUE(has(big.reason(), (dir / "big.stl").string() + ": the file has 1073741825 bytes, more than"))
      << big.reason();
  // The same through a 3D scene's cracks: the key path of the crack's file.
  const std::string scene = error_of(json::array({{{"name", "a"}, {"file", (dir / "zero.stl").string()}}}));
  EXPECT_TRUE(has(scene, "cracks[0].file: " + (dir / "zero.stl").string() + ": not a regular file")) << scene;
}

TEST_F(MeshFiles, GmshFormats22And41GiveTheSameSurface) {
  const auto v22 = write("a.msh", R"($MeshFormat
2.2 0 8
$EndMeshFormat
$Nodes
4
1 0 0 0
2 1 0 0
3 1 1 0
4 0 1 0
$EndNodes
$Elements
3
1 15 2 0 1 1
2 2 2 0 1 1 2 3
3 2 2 0 1 1 3 4
$EndElements
)");
  expect_unit_square(read_mesh_file(v22, "cracks[0].file"));
  const auto v41 = write("b.msh", R"($MeshFormat
4.1 0 8
$EndMeshFormat
$Nodes
1 4 1 4
2 1 0 4
1
2
3
4
0 0 0
1 0 0
1 1 0
0 1 0
$EndNodes
$Elements
2 3 1 3
0 1 15 1
1 1
2 1 2 2
2 1 2 3
3 1 3 4
$EndElements
)");
  expect_unit_square(read_mesh_file(v41, "cracks[0].file"));
  try {
    read_mesh_file(write("c.msh", "$MeshFormat\n4.1 1 8\n$EndMeshFormat\n"), "cracks[0].file");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("binary .msh"), std::string::npos);
  }
}

}  // namespace
