// Every file written by a run is read back by VTK's reader and by meshio (Debian's python3) with the
// same values, and the last frame's arrays equal the model's state bit for bit (issue: outputs;
// issue 14: meshio 5.0.0 misread some frames of raw appended data).
#include <gtest/gtest.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "libmpm/core/error.hpp"
#include "libmpm/io/particle_fields.hpp"
#include "libmpm/method/run_scene.hpp"
#include "libmpm/mpm/particle_output.hpp"
#include "libmpm/mpm/mpm_method.hpp"
#include "support.hpp"

namespace cleave {
namespace {

namespace fs = std::filesystem;

// "points", every point-data array and the cells' point ids by cell type ("cells:vertex",
// "cells:line") of one frame, flattened.
using Arrays = std::map<std::string, std::vector<double>>;

Arrays read_with_vtk(const fs::path& vtu) {
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(vtu.c_str());
  reader->Update();
  vtkUnstructuredGrid* ug = reader->GetOutput();
  Arrays got;
  auto& pts = got["points"];
  for (vtkIdType i = 0; i < ug->GetNumberOfPoints(); ++i) {
    double x[3];
    ug->GetPoint(i, x);
    pts.insert(pts.end(), x, x + 3);
  }
  vtkPointData* pd = ug->GetPointData();
  for (int a = 0; a < pd->GetNumberOfArrays(); ++a) {
    vtkDataArray* arr = pd->GetArray(a);
    auto& v = got[arr->GetName()];
    for (vtkIdType i = 0; i < arr->GetNumberOfTuples(); ++i)
      for (int c = 0; c < arr->GetNumberOfComponents(); ++c) v.push_back(arr->GetComponent(i, c));
  }
  for (vtkIdType c = 0; c < ug->GetNumberOfCells(); ++c) {
    const int type = ug->GetCellType(c);
    auto& v = got[type == VTK_VERTEX ? "cells:vertex" : type == VTK_LINE ? "cells:line" : "cells:" + std::to_string(type)];
    vtkNew<vtkIdList> ids;
    ug->GetCellPoints(c, ids);
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k) v.push_back(double(ids->GetId(k)));
  }
  return got;
}

// meshio (Debian's python3-meshio) reads every file in one python process; each array is dumped as
// text with 17 significant digits, which round-trips a double exactly. Fails the test (and returns
// fewer frames) when meshio cannot read one.
std::vector<Arrays> read_with_meshio(const std::vector<fs::path>& files, const fs::path& work) {
  const fs::path script = work / "dump.py";
  std::ofstream(script) << "import meshio, sys\n"
                           "for i, name in enumerate(sys.argv[2:]):\n"
                           "    m = meshio.read(name)\n"
                           "    with open('%s/meshio_%d.txt' % (sys.argv[1], i), 'w') as f:\n"
                           "        f.write('points %d\\n' % m.points.size)\n"
                           "        f.write(' '.join('%.17g' % v for v in m.points.ravel()) + '\\n')\n"
                           "        for k in sorted(m.point_data):\n"
                           "            a = m.point_data[k].ravel()\n"
                           "            f.write('%s %d\\n' % (k, a.size))\n"
                           "            f.write(' '.join('%.17g' % v for v in a) + '\\n')\n"
                           "        for b in m.cells:\n"
                           "            f.write('cells:%s %d\\n' % (b.type, b.data.size))\n"
                           "            f.write(' '.join('%d' % v for v in b.data.ravel()) + '\\n')\n";
  std::string cmd = "/usr/bin/python3 " + script.string() + " " + work.string();
  for (const auto& f : files) {
    cmd += ' ';
    cmd += f.string();
  }
  cmd += " 2>";
  cmd += (work / "meshio_stderr.txt").string();
  std::vector<Arrays> frames;
  if (std::system(cmd.c_str()) != 0) {
    std::ifstream err(work / "meshio_stderr.txt");
    ADD_FAILURE() << "meshio (python3-meshio) could not read every frame:\n" << err.rdbuf();
    return frames;
  }
  for (std::size_t i = 0; i < files.size(); ++i) {
    std::ifstream in(work / ("meshio_" + std::to_string(i) + ".txt"));
    std::string key;
    std::size_t n;
    Arrays& got = frames.emplace_back();
    while (in >> key >> n) {
      auto& v = got[key];
      v.resize(n);
      for (auto& x : v) in >> x;
    }
  }
  return frames;
}

// Every frame of `series` in `out` (frames 0 .. count-1) reads back in meshio with exactly the
// values VTK's reader gives. Returns what VTK read, frame by frame.
std::vector<Arrays> check_every_frame(const fs::path& out, const std::string& series, int count) {
  std::vector<fs::path> files;
  for (int k = 0; k < count; ++k) {
    char name[64];
    std::snprintf(name, sizeof name, "%s_%06d.vtu", series.c_str(), k);
    files.push_back(out / name);
  }
  const std::vector<Arrays> meshio = read_with_meshio(files, out);
  std::vector<Arrays> vtk;
  for (const auto& f : files) vtk.push_back(read_with_vtk(f));
  if (meshio.size() != files.size()) return vtk;
  for (std::size_t k = 0; k < files.size(); ++k) {
    SCOPED_TRACE(files[k].filename().string());
    EXPECT_FALSE(vtk[k]["points"].empty());
    EXPECT_EQ(meshio[k].size(), vtk[k].size()) << "arrays";
    for (const auto& [name, values] : vtk[k]) {
      const auto it = meshio[k].find(name);
      if (it == meshio[k].end()) ADD_FAILURE() << "meshio lacks " << name;
      else EXPECT_EQ(it->second, values) << name;
    }
  }
  return vtk;
}

template <int Dim>
void check_run_output(const nlohmann::json& scene, const std::string& tag) {
  const fs::path out = fs::path(CLEAVE_BINARY_DIR) / "test_particle_output" / tag;
  fs::remove_all(out);
  Model<Dim> m = build_model<Dim>(scene);
  RunOptions opt;
  opt.out = out;
  const RunSummary sum = run_model<Dim>(m, opt);
  ASSERT_GE(sum.frames, 3);
  // Every frame: meshio reads what VTK reads.
  std::vector<Arrays> vtk = check_every_frame(out, "particles", sum.frames);
  // The last frame holds the final state, which is still in m: VTK (and so meshio) read it exactly.
  const io::PointSet expect = particle_point_set<Dim>(m, m.output.fields);
  ASSERT_EQ(expect.arrays.size(), Dim == 2 ? 11u : 10u);  // "rotation" is 2D only
  Arrays& last = vtk.back();
  ASSERT_EQ(last["points"].size(), 3 * m.particles.size());
  EXPECT_EQ(last["points"], expect.points);
  EXPECT_EQ(last.size(), 2 + expect.arrays.size());  // points, the arrays, cells:vertex
  for (const auto& a : expect.arrays) EXPECT_EQ(last[a.name], a.values) << a.name;
}

TEST(ParticleOutput, BeamImpactFileReadsBackExactly) {
  nlohmann::json s = load_scene_file(CLEAVE_SOURCE_DIR "/data/scenes/beam_impact.json");
  s["resolution"] = 1.0;
  s["time"] = {{"end", 0.05}, {"cfl", 0.5}};
  s["output"] = {{"interval", 0.01}};
  check_run_output<2>(s, "beam");
}

TEST(ParticleOutput, Solid3DFileReadsBackExactly) {
  nlohmann::json s;
  s["analysis"] = {{"type", "3d"}};
  s["grid"] = {{"cell_size", 0.01}};
  s["materials"] = nlohmann::json::array({test::material("m", 1e9, 0.3, 1000)});
  s["bodies"] = nlohmann::json::array({{{"name", "b"}, {"material", "m"}, {"velocity", {1.0, -2.0, 0.5}},
                                        {"shape", {{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 0.04}}}}});
  s["loads"] = nlohmann::json::array({{{"type", "symmetry"}, {"axis", "x"}, {"position", 0.0}}});
  s["time"] = {{"end", 3e-5}, {"cfl", 0.5}};
  s["output"] = {{"interval", 1e-5}};
  check_run_output<3>(s, "sphere");
}

// A subset of the fields: with raw appended data, meshio 5.0.0 gave this layout's "Points" the
// bytes of another array (whatever the particle count).
TEST(ParticleOutput, EveryFrameWithAFewFieldsReadsBackInMeshio) {
  const fs::path out = fs::path(CLEAVE_BINARY_DIR) / "test_particle_output" / "fields";
  fs::remove_all(out);
  nlohmann::json s;
  s["analysis"] = {{"type", "plane_strain"}};
  s["grid"] = {{"cell_size", 0.01}};
  s["materials"] = nlohmann::json::array({test::material("steel", 2e11, 0.3, 7800)});
  s["bodies"] = nlohmann::json::array({{{"name", "block"}, {"material", "steel"}, {"velocity", {1.0, 0.5}},
                                        {"shape", {{"type", "rectangle"}, {"min", {0, 0}}, {"max", {0.1, 0.05}}}}}});
  s["time"] = {{"end", 3e-5}, {"cfl", 0.5}};
  s["output"] = {{"interval", 5e-6}, {"fields", {"displacement", "stress"}}};
  RunOptions opt;
  opt.out = out;
  const RunSummary sum = run_scene(s, {}, opt);
  ASSERT_GE(sum.frames, 5);
  const std::vector<Arrays> vtk = check_every_frame(out, "particles", sum.frames);
  EXPECT_EQ(vtk.back().size(), 4u);  // points, displacement, stress, cells:vertex
}

// A cracked run's crack frames (crack paths as line segments with the opening arrays): meshio reads
// every segment and every point array of every one (it dropped the VTK_POLY_LINE cells written
// before issue 15).
TEST(ParticleOutput, EveryCrackFrameOfARunReadsBackInMeshio) {
  const fs::path out = fs::path(CLEAVE_BINARY_DIR) / "test_particle_output" / "dcb";
  fs::remove_all(out);
  nlohmann::json s = load_scene_file(CLEAVE_SOURCE_DIR "/data/scenes/dcb_crack.json");
  s["time"]["end"] = 0.02;
  s["output"]["interval"] = 0.002;
  RunOptions opt;
  opt.out = out;
  const RunSummary sum = run_scene(s, {}, opt);
  ASSERT_GE(sum.frames, 10);
  check_every_frame(out, "particles", sum.frames);
  const std::vector<Arrays> vtk = check_every_frame(out, "cracks", sum.frames);
  EXPECT_TRUE(vtk.back().count("cod")) << "a crack frame with its openings";
  for (const Arrays& frame : vtk) {  // one crack: a segment between each two consecutive points
    const std::size_t points = frame.at("points").size() / 3;
    ASSERT_GE(points, 2u);
    std::vector<double> segments;
    for (std::size_t i = 1; i < points; ++i) segments.insert(segments.end(), {double(i - 1), double(i)});
    ASSERT_TRUE(frame.count("cells:line"));
    EXPECT_EQ(frame.at("cells:line"), segments);
    EXPECT_EQ(frame.size(), 8u);  // points, above, below, cod, cod_normal, cod_tangential, crack, cells:line
  }
}

// output.compression = zlib with output.precision = float32: every frame of a cracked run reads
// back in meshio as in VTK, and the last particle frame is the model's final state rounded to float.
TEST(ParticleOutput, ZlibFloat32FramesOfARunReadBackInMeshioAndVtkToFloatRounding) {
  const fs::path out = fs::path(CLEAVE_BINARY_DIR) / "test_particle_output" / "dcb_zlib_float32";
  fs::remove_all(out);
  nlohmann::json s = load_scene_file(CLEAVE_SOURCE_DIR "/data/scenes/dcb_crack.json");
  s["time"]["end"] = 0.01;
  s["output"]["interval"] = 0.002;
  s["output"]["compression"] = "zlib";
  s["output"]["precision"] = "float32";
  Model<2> m = build_model<2>(s);
  EXPECT_TRUE(m.output.zlib);
  EXPECT_TRUE(m.output.float32);
  RunOptions opt;
  opt.out = out;
  const RunSummary sum = run_model<2>(m, opt);
  ASSERT_GE(sum.frames, 5);
  check_every_frame(out, "cracks", sum.frames);
  Arrays last = check_every_frame(out, "particles", sum.frames).back();
  auto rounded = [](std::vector<double> v) {
    for (double& x : v) x = double(float(x));
    return v;
  };
  const io::PointSet expect = particle_point_set<2>(m, m.output.fields);
  EXPECT_EQ(last["points"], rounded(expect.points));
  for (const auto& a : expect.arrays) EXPECT_EQ(last[a.name], rounded(a.values)) << a.name;
  std::ifstream vtu(out / "particles_000000.vtu");
  std::string header;
  std::getline(vtu, header), std::getline(vtu, header);
  EXPECT_NE(header.find("compressor=\"vtkZLibDataCompressor\""), std::string::npos) << header;
}

// The defaults keep today's files (raw Float64); other values are refused, naming the key.
TEST(ParticleOutput, CompressionAndPrecisionDefaultToRawFloat64AndRefuseOtherValues) {
  nlohmann::json s = load_scene_file(CLEAVE_SOURCE_DIR "/data/scenes/dcb_crack.json");
  const Model<2> plain = build_model<2>(s);
  EXPECT_FALSE(plain.output.zlib);
  EXPECT_FALSE(plain.output.float32);
  auto error_of = [](const nlohmann::json& scene) {
    try {
      build_model<2>(scene);
    } catch (const SceneError& e) {
      return e.key_path() + ": " + e.what();
    }
    return std::string("no error");
  };
  s["output"]["compression"] = "lz4";
  EXPECT_NE(error_of(s).find("output.compression"), std::string::npos) << error_of(s);
  EXPECT_NE(error_of(s).find("valid: none, zlib"), std::string::npos) << error_of(s);
  s["output"]["compression"] = "none";
  s["output"]["precision"] = 32;
  EXPECT_NE(error_of(s).find("output.precision"), std::string::npos) << error_of(s);
  s["output"]["precision"] = "half";
  EXPECT_NE(error_of(s).find("valid: float64, float32"), std::string::npos) << error_of(s);
  s["output"]["precision"] = "float64";
  EXPECT_EQ(error_of(s), "no error");
}

}  // namespace
}  // namespace cleave
