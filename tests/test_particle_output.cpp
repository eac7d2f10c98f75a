// Every file written by a run is read back by VTK's reader and by meshio (Debian's python3) with the
// same values, and the last frame's arrays equal the model's state bit for bit (issue: outputs;
// issue 14: meshio 5.0.0 misread some frames of raw appended data).
#include <gtest/gtest.h>
#include <vtkDataArray.h>
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

#include "libmpm/io/particle_fields.hpp"
#include "libmpm/method/run_scene.hpp"
#include "libmpm/mpm/particle_output.hpp"
#include "libmpm/mpm/mpm_method.hpp"
#include "support.hpp"

namespace cleave {
namespace {

namespace fs = std::filesystem;

// "points" and every point-data array of one frame, flattened.
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
                           "            f.write(' '.join('%.17g' % v for v in a) + '\\n')\n";
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
  EXPECT_EQ(last.size(), 1 + expect.arrays.size());
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
  EXPECT_EQ(vtk.back().size(), 3u);  // points, displacement, stress
}

// A cracked run's crack frames (polylines with the opening arrays): every one reads back in meshio.
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
}

}  // namespace
}  // namespace cleave
