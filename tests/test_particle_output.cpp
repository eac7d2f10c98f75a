// A file written by a run is read back by VTK's reader and by meshio (Debian's python3), and every
// array equals the model's state bit for bit (issue: outputs).
#include <gtest/gtest.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>

#include "libmpm/io/particle_fields.hpp"
#include "libmpm/mpm/particle_output.hpp"
#include "libmpm/mpm/mpm_method.hpp"
#include "support.hpp"

namespace cleave {
namespace {

namespace fs = std::filesystem;

template <int Dim>
void check_run_output(const nlohmann::json& scene, const std::string& tag) {
  const fs::path out = fs::path(CLEAVE_BINARY_DIR) / "test_particle_output" / tag;
  fs::remove_all(out);
  Model<Dim> m = build_model<Dim>(scene);
  RunOptions opt;
  opt.out = out;
  const RunSummary sum = run_model<Dim>(m, opt);
  ASSERT_GE(sum.frames, 2);
  // The last frame holds the final state, which is still in m.
  char name[64];
  std::snprintf(name, sizeof name, "particles_%06d.vtu", sum.frames - 1);
  const fs::path vtu = out / name;
  const io::PointSet expect = particle_point_set<Dim>(m, m.output.fields);
  ASSERT_EQ(expect.arrays.size(), Dim == 2 ? 11u : 10u);  // "rotation" is 2D only

  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(vtu.c_str());
  reader->Update();
  vtkUnstructuredGrid* ug = reader->GetOutput();
  ASSERT_EQ(static_cast<std::size_t>(ug->GetNumberOfPoints()), m.particles.size());
  for (vtkIdType i = 0; i < ug->GetNumberOfPoints(); ++i) {
    double x[3];
    ug->GetPoint(i, x);
    for (int d = 0; d < 3; ++d) ASSERT_EQ(x[d], expect.points[3 * i + d]);
  }
  for (const auto& a : expect.arrays) {
    vtkDataArray* got = ug->GetPointData()->GetArray(a.name.c_str());
    ASSERT_NE(got, nullptr) << a.name;
    ASSERT_EQ(got->GetNumberOfComponents(), a.components) << a.name;
    for (vtkIdType i = 0; i < got->GetNumberOfTuples(); ++i)
      for (int c = 0; c < a.components; ++c)
        ASSERT_EQ(got->GetComponent(i, c), a.values[a.components * i + c]) << a.name << " point " << i;
  }

  // meshio: dump every array as text with 17 significant digits and compare exactly.
  const fs::path dump = out / "meshio_dump.txt";
  const fs::path script = out / "dump.py";
  std::ofstream(script) << "import meshio, sys\n"
                           "m = meshio.read(sys.argv[1])\n"
                           "with open(sys.argv[2], 'w') as f:\n"
                           "    f.write('points %d\\n' % m.points.size)\n"
                           "    f.write(' '.join('%.17g' % v for v in m.points.ravel()) + '\\n')\n"
                           "    for k in sorted(m.point_data):\n"
                           "        a = m.point_data[k].ravel()\n"
                           "        f.write('%s %d\\n' % (k, a.size))\n"
                           "        f.write(' '.join('%.17g' % v for v in a) + '\\n')\n";
  const std::string cmd = "/usr/bin/python3 " + script.string() + " " + vtu.string() + " " + dump.string();
  ASSERT_EQ(std::system(cmd.c_str()), 0) << "meshio (python3-meshio) could not read " << vtu;
  std::ifstream in(dump);
  std::string key;
  std::size_t n;
  std::map<std::string, std::vector<double>> got;
  while (in >> key >> n) {
    auto& v = got[key];
    v.resize(n);
    for (auto& x : v) in >> x;
  }
  ASSERT_EQ(got["points"], expect.points);
  for (const auto& a : expect.arrays) EXPECT_EQ(got[a.name], a.values) << a.name;
}

TEST(ParticleOutput, BeamImpactFileReadsBackExactly) {
  nlohmann::json s = load_scene_file(CLEAVE_SOURCE_DIR "/data/scenes/beam_impact.json");
  s["grid"]["cell_size"] = 1.0;
  s["time"] = {{"end", 0.05}, {"cfl", 0.5}};
  s["output"] = {{"interval", 0.025}};
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
  s["time"] = {{"end", 2e-5}, {"cfl", 0.5}};
  s["output"] = {{"interval", 1e-5}};
  check_run_output<3>(s, "sphere");
}

}  // namespace
}  // namespace cleave
