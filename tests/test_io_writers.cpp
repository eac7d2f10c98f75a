// The output writers are only useful if other tools read exactly what was written: read every
// .vtu back with VTK itself and with meshio (an independent parser) and compare bit for bit.
#include <gtest/gtest.h>
#include <vtkCellArray.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "libmpm/io/csv_writer.hpp"
#include "libmpm/io/point_set.hpp"
#include "libmpm/io/pvd_writer.hpp"
#include "libmpm/io/vtu_writer.hpp"

namespace fs = std::filesystem;
using cleave::io::CsvSeries;
using cleave::io::PointArray;
using cleave::io::PointSet;
using cleave::io::PvdIndex;
using cleave::io::write_vtu;

namespace {

// A fresh directory per test case, so ctest can run the cases in parallel.
fs::path test_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  fs::path d = fs::path(CLEAVE_BINARY_DIR) / "test_io_writers_tmp" /
               (std::string(info->test_suite_name()) + "." + info->name());
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string slurp(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Awkward doubles: signs, extremes of the exponent range, subnormals, negative zero, and values
// whose 17th digit matters.
double nasty(std::size_t i) {
  static const double special[] = {1e-300,  -1e-300, 1e300, -1e300,
                                   4.9406564584124654e-324, -0.0, 0.1, 1.0 / 3.0,
                                   std::numeric_limits<double>::max(),
                                   std::numeric_limits<double>::min(), -2.5e-17};
  constexpr std::size_t ns = sizeof(special) / sizeof(special[0]);
  if (i % 7 == 3) return special[(i / 7) % ns];
  return std::sin(1.0 + 0.37 * static_cast<double>(i)) * std::pow(10.0, static_cast<double>(i % 41) - 20.0);
}

PointSet make_cloud(std::size_t n) {
  PointSet ps;
  ps.points.resize(3 * n);
  for (std::size_t i = 0; i < 3 * n; ++i) ps.points[i] = nasty(i + 11);
  for (auto [name, comps] : {std::pair<const char*, int>{"damage", 1}, {"velocity", 3}, {"stress", 6}}) {
    PointArray a{name, comps, std::vector<double>(n * comps)};
    for (std::size_t i = 0; i < a.values.size(); ++i) a.values[i] = nasty(i * 3 + comps);
    ps.arrays.push_back(std::move(a));
  }
  return ps;
}

bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

// Compares element-wise by bit pattern and reports the first mismatch.
void expect_bits(const std::vector<double>& want, const std::vector<double>& got, const std::string& what) {
  ASSERT_EQ(want.size(), got.size()) << what;
  for (std::size_t i = 0; i < want.size(); ++i)
    ASSERT_TRUE(same_bits(want[i], got[i])) << what << "[" << i << "]: wrote " << want[i] << " read " << got[i];
}

std::vector<double> to_vector(vtkDataArray* a) {
  std::vector<double> v(static_cast<std::size_t>(a->GetNumberOfTuples() * a->GetNumberOfComponents()));
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
    for (int c = 0; c < a->GetNumberOfComponents(); ++c)
      v[static_cast<std::size_t>(i * a->GetNumberOfComponents() + c)] = a->GetComponent(i, c);
  return v;
}

vtkSmartPointer<vtkUnstructuredGrid> read_vtk(const fs::path& f) {
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(f.c_str());
  reader->Update();
  EXPECT_EQ(reader->GetErrorCode(), 0u);
  vtkSmartPointer<vtkUnstructuredGrid> ug = reader->GetOutput();
  return ug;
}

std::vector<double> read_f64(const fs::path& f) {
  std::string bytes = slurp(f);
  std::vector<double> v(bytes.size() / sizeof(double));
  std::memcpy(v.data(), bytes.data(), v.size() * sizeof(double));
  return v;
}

}  // namespace

TEST(WriteVtu, VtkReadsBackBitExact) {
  const fs::path f = test_dir() / "cloud.vtu";
  const std::size_t n = 347;
  const PointSet ps = make_cloud(n);
  write_vtu(f, ps);
  EXPECT_FALSE(fs::exists(fs::path(f.string() + ".tmp")));

  auto ug = read_vtk(f);
  ASSERT_TRUE(ug);
  ASSERT_EQ(ug->GetNumberOfPoints(), static_cast<vtkIdType>(n));
  ASSERT_EQ(ug->GetNumberOfCells(), static_cast<vtkIdType>(n));
  ASSERT_EQ(ug->GetPoints()->GetData()->GetDataType(), VTK_DOUBLE);
  expect_bits(ps.points, to_vector(ug->GetPoints()->GetData()), "points");

  ASSERT_EQ(ug->GetPointData()->GetNumberOfArrays(), 3);
  for (const auto& a : ps.arrays) {
    vtkDataArray* got = ug->GetPointData()->GetArray(a.name.c_str());
    ASSERT_NE(got, nullptr) << a.name;
    EXPECT_EQ(got->GetDataType(), VTK_DOUBLE) << a.name;
    EXPECT_EQ(got->GetNumberOfComponents(), a.components) << a.name;
    expect_bits(a.values, to_vector(got), a.name);
  }
  for (vtkIdType c = 0; c < ug->GetNumberOfCells(); ++c) {
    ASSERT_EQ(ug->GetCellType(c), VTK_VERTEX);
    vtkNew<vtkIdList> ids;
    ug->GetCellPoints(c, ids);
    ASSERT_EQ(ids->GetNumberOfIds(), 1);
    ASSERT_EQ(ids->GetId(0), c);
  }
}

namespace {

// Writes `ps` to dir/cloud.vtu, reads it with meshio and compares every value bit for bit.
void expect_meshio_reads_back(const PointSet& ps, const fs::path& dir) {
  const std::string py = CLEAVE_DEBIAN_PYTHON;
  const std::size_t n = ps.size();
  const fs::path f = dir / "cloud.vtu";
  write_vtu(f, ps);

  // The script dumps raw little-endian doubles (no decimal round trip to doubt) plus a manifest
  // "name components rows" per array and "cells type count" per cell block.
  const fs::path script = dir / "dump.py";
  std::ofstream(script) << R"(import sys, meshio, numpy as np
m = meshio.read(sys.argv[1])
out = sys.argv[2]
with open(out + "/manifest.txt", "w") as man:
    def dump(name, a):
        a = np.asarray(a, dtype="<f8")
        a.tofile(out + "/" + name + ".bin")
        man.write("%s %d %d\n" % (name, 1 if a.ndim == 1 else a.shape[1], a.shape[0]))
    dump("points", m.points)
    for k, v in m.point_data.items():
        dump(k, v)
    for b in m.cells:
        man.write("cells %s %d\n" % (b.type, len(b.data)))
)";
  const fs::path out = dir / "meshio";
  fs::create_directories(out);
  const std::string cmd = py + " '" + script.string() + "' '" + f.string() + "' '" + out.string() + "'";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;

  std::map<std::string, std::pair<int, std::size_t>> shape;
  std::ifstream man(out / "manifest.txt");
  std::string name, cell_type;
  std::size_t cells = 0;
  for (std::string tag; man >> tag;) {
    if (tag == "cells") {
      man >> cell_type >> cells;
    } else {
      int comps;
      std::size_t rows;
      man >> comps >> rows;
      shape[tag] = {comps, rows};
    }
  }
  EXPECT_EQ(cell_type, "vertex");
  EXPECT_EQ(cells, n);
  ASSERT_EQ(shape.count("points"), 1u);
  EXPECT_EQ(shape["points"], (std::pair<int, std::size_t>{3, n}));
  expect_bits(ps.points, read_f64(out / "points.bin"), "meshio points");
  ASSERT_EQ(shape.size(), 1 + ps.arrays.size());
  for (const auto& a : ps.arrays) {
    ASSERT_EQ(shape.count(a.name), 1u) << a.name;
    EXPECT_EQ(shape[a.name], (std::pair<int, std::size_t>{a.components, n})) << a.name;
    expect_bits(a.values, read_f64(out / (a.name + ".bin")), "meshio " + a.name);
  }
}

}  // namespace

TEST(WriteVtu, MeshioReadsBackBitExact) {
  const std::string py = CLEAVE_DEBIAN_PYTHON;
  if (std::system((py + " -c 'import meshio, numpy' >/dev/null 2>&1").c_str()) != 0)
    FAIL() << py << " cannot import meshio and numpy: install python3-meshio (the README's test command does)";
  const fs::path dir = test_dir();
  expect_meshio_reads_back(make_cloud(213), dir);
}

// Array layouts that meshio 5.0.0 misread when the writer used raw appended data: it looks each
// block up by its offset string while rewriting the offsets it has passed, and an earlier array's
// rewritten offset could equal a later array's (here "Points", then "connectivity").
TEST(WriteVtu, MeshioReadsBackEveryArrayLayoutBitExact) {
  const std::string py = CLEAVE_DEBIAN_PYTHON;
  if (std::system((py + " -c 'import meshio, numpy' >/dev/null 2>&1").c_str()) != 0)
    FAIL() << py << " cannot import meshio and numpy: install python3-meshio (the README's test command does)";
  const fs::path dir = test_dir();
  const std::vector<std::vector<std::pair<std::string, int>>> layouts = {
      {{"displacement", 3}, {"stress", 6}},         // output.fields = displacement, stress: every count
      {{"material", 1}, {"mass", 1}, {"volume", 1}},  // three scalars: counts that are multiples of 3
      {{"stress", 6}},
      {}};
  for (std::size_t l = 0; l < layouts.size(); ++l)
    for (std::size_t n : {1, 2, 3, 5, 10, 11, 213, 1000}) {
      SCOPED_TRACE("layout " + std::to_string(l) + ", " + std::to_string(n) + " points");
      PointSet ps = make_cloud(n);
      ps.arrays.clear();
      for (const auto& [name, comps] : layouts[l]) {
        PointArray a{name, comps, std::vector<double>(n * comps)};
        for (std::size_t i = 0; i < a.values.size(); ++i) a.values[i] = nasty(i * 5 + comps + l);
        ps.arrays.push_back(std::move(a));
      }
      const fs::path d = dir / (std::to_string(l) + "_" + std::to_string(n));
      fs::create_directories(d);
      expect_meshio_reads_back(ps, d);
      // VTK reads the same file back exactly too.
      auto ug = read_vtk(d / "cloud.vtu");
      ASSERT_TRUE(ug);
      expect_bits(ps.points, to_vector(ug->GetPoints()->GetData()), "vtk points");
      for (const auto& a : ps.arrays) {
        vtkDataArray* got = ug->GetPointData()->GetArray(a.name.c_str());
        ASSERT_NE(got, nullptr) << a.name;
        expect_bits(a.values, to_vector(got), "vtk " + a.name);
      }
    }
}

TEST(WriteVtu, PolylinesReadBack) {
  const fs::path f = test_dir() / "cracks.vtu";
  PointSet ps;
  for (int i = 0; i < 9; ++i) ps.points.insert(ps.points.end(), {0.5 * i, 0.25 * i * i, 0.0});
  ps.arrays.push_back({"opening", 1, {0, 1, 2, 3, 4, 5, 6, 7, 8}});
  ps.polylines = {{0, 1, 2, 3}, {4, 5}, {8, 7, 6}};
  write_vtu(f, ps);

  auto ug = read_vtk(f);
  ASSERT_TRUE(ug);
  ASSERT_EQ(ug->GetNumberOfPoints(), 9);
  ASSERT_EQ(ug->GetNumberOfCells(), 3);
  expect_bits(ps.points, to_vector(ug->GetPoints()->GetData()), "points");
  for (vtkIdType c = 0; c < 3; ++c) {
    EXPECT_EQ(ug->GetCellType(c), VTK_POLY_LINE);
    vtkNew<vtkIdList> ids;
    ug->GetCellPoints(c, ids);
    const auto& want = ps.polylines[static_cast<std::size_t>(c)];
    ASSERT_EQ(ids->GetNumberOfIds(), static_cast<vtkIdType>(want.size()));
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k) EXPECT_EQ(ids->GetId(k), want[static_cast<std::size_t>(k)]);
  }
}

TEST(WriteVtu, EmptyOverwriteAndErrors) {
  const fs::path dir = test_dir();
  // An empty frame is still a valid file.
  write_vtu(dir / "empty.vtu", PointSet{});
  auto ug = read_vtk(dir / "empty.vtu");
  ASSERT_TRUE(ug);
  EXPECT_EQ(ug->GetNumberOfPoints(), 0);

  // Overwriting replaces the file whole.
  write_vtu(dir / "a.vtu", make_cloud(50));
  write_vtu(dir / "a.vtu", make_cloud(5));
  EXPECT_EQ(read_vtk(dir / "a.vtu")->GetNumberOfPoints(), 5);

  // An unwritable target names the file.
  const fs::path bad = dir / "no_such_dir" / "x.vtu";
  try {
    write_vtu(bad, make_cloud(3));
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(bad.string()), std::string::npos) << e.what();
  }

  PointSet wrong = make_cloud(4);
  wrong.arrays[1].values.pop_back();
  EXPECT_THROW(write_vtu(dir / "w.vtu", wrong), std::invalid_argument);
  PointSet out_of_range = make_cloud(4);
  out_of_range.polylines = {{0, 4}};
  EXPECT_THROW(write_vtu(dir / "w.vtu", out_of_range), std::invalid_argument);
  EXPECT_FALSE(fs::exists(dir / "w.vtu"));
}

TEST(PvdIndex, WriteLoadTruncateRoundTrip) {
  const fs::path pvd = test_dir() / "particles.pvd";
  PvdIndex index(pvd);
  const std::vector<double> times = {0.0, 2.5e-7, 0.1, 1.0 / 3.0, 0.7000000000000001, 1e300};
  char name[64];
  for (std::size_t i = 0; i < times.size(); ++i) {
    std::snprintf(name, sizeof(name), "particles_%06zu.vtu", i);
    index.add(times[i], name);
  }
  index.write();
  EXPECT_FALSE(fs::exists(fs::path(pvd.string() + ".tmp")));

  // VTK's own XML parser accepts it and sees the expected structure.
  vtkNew<vtkXMLDataParser> parser;
  parser->SetFileName(pvd.c_str());
  ASSERT_EQ(parser->Parse(), 1);
  vtkXMLDataElement* root = parser->GetRootElement();
  ASSERT_NE(root, nullptr);
  EXPECT_STREQ(root->GetName(), "VTKFile");
  EXPECT_STREQ(root->GetAttribute("type"), "Collection");
  vtkXMLDataElement* coll = root->FindNestedElementWithName("Collection");
  ASSERT_NE(coll, nullptr);
  ASSERT_EQ(coll->GetNumberOfNestedElements(), static_cast<int>(times.size()));
  for (int i = 0; i < coll->GetNumberOfNestedElements(); ++i) {
    vtkXMLDataElement* ds = coll->GetNestedElement(i);
    EXPECT_STREQ(ds->GetName(), "DataSet");
    EXPECT_STREQ(ds->GetAttribute("file"), index.entries()[static_cast<std::size_t>(i)].second.c_str());
    EXPECT_STREQ(ds->GetAttribute("part"), "0");
    const char* ts = ds->GetAttribute("timestep");
    ASSERT_NE(ts, nullptr);
    double t = 0;
    std::from_chars(ts, ts + std::strlen(ts), t);
    EXPECT_TRUE(same_bits(t, times[static_cast<std::size_t>(i)])) << ts;
  }

  // load() gives back exactly what was added.
  PvdIndex loaded = PvdIndex::load(pvd);
  ASSERT_EQ(loaded.entries(), index.entries());

  // Resume at t = 1/3: later frames go, the frame at exactly t stays; the rewrite is loadable.
  loaded.truncate_after(1.0 / 3.0);
  ASSERT_EQ(loaded.entries().size(), 4u);
  EXPECT_EQ(loaded.entries().back().second, "particles_000003.vtu");
  loaded.add(0.5, "particles_000004.vtu");
  loaded.write();
  const PvdIndex again = PvdIndex::load(pvd);
  ASSERT_EQ(again.entries(), loaded.entries());

  EXPECT_THROW(PvdIndex::load(pvd.parent_path() / "missing.pvd"), std::runtime_error);
  std::ofstream(pvd.parent_path() / "broken.pvd") << "<VTKFile type=\"Collection\"><Collection><DataSet timestep=\"x\"";
  EXPECT_THROW(PvdIndex::load(pvd.parent_path() / "broken.pvd"), std::runtime_error);
}

TEST(CsvSeries, HeaderRowsAppendAndTruncate) {
  const fs::path csv = test_dir() / "energy.csv";
  const std::vector<std::string> cols = {"time", "kinetic", "strain"};
  {
    CsvSeries s(csv, cols, false);
    s.row({0.0, 0.1, -1e-300});
    s.row({0.5, 1.0 / 3.0, 1e300});
    EXPECT_THROW(s.row({1.0, 2.0}), std::invalid_argument);
    // Flushed per row: visible before the series is closed.
    EXPECT_EQ(slurp(csv), "time,kinetic,strain\n0,0.10000000000000001,-1e-300\n"
                          "0.5,0.33333333333333331,1.0000000000000001e+300\n");
  }
  {
    CsvSeries s(csv, cols, true);  // resume: rows kept
    s.row({1.0, 2.0, 3.0});
  }
  EXPECT_EQ(slurp(csv), "time,kinetic,strain\n0,0.10000000000000001,-1e-300\n"
                        "0.5,0.33333333333333331,1.0000000000000001e+300\n1,2,3\n");

  // Resuming with other columns is refused and names the file.
  try {
    CsvSeries s(csv, {"time", "kinetic"}, true);
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(csv.string()), std::string::npos) << e.what();
  }

  // A run killed mid-row leaves a partial line; truncate_after drops it with the later rows.
  std::ofstream(csv, std::ios::app) << "1.5,9,9\n2,7";
  CsvSeries::truncate_after(csv, 0.5);
  EXPECT_EQ(slurp(csv), "time,kinetic,strain\n0,0.10000000000000001,-1e-300\n"
                        "0.5,0.33333333333333331,1.0000000000000001e+300\n");
  EXPECT_FALSE(fs::exists(fs::path(csv.string() + ".tmp")));

  // Appending after a crash without truncating first still never glues two rows together.
  std::ofstream(csv, std::ios::app) << "0.75,1";
  {
    CsvSeries s(csv, cols, true);
    s.row({0.75, 4.0, 5.0});
  }
  EXPECT_EQ(slurp(csv), "time,kinetic,strain\n0,0.10000000000000001,-1e-300\n"
                        "0.5,0.33333333333333331,1.0000000000000001e+300\n0.75,4,5\n");

  // Not appending starts afresh; bad column names are refused; a missing file stays missing.
  { CsvSeries s(csv, {"time", "x"}, false); }
  EXPECT_EQ(slurp(csv), "time,x\n");
  EXPECT_THROW(CsvSeries(csv, {"time", "a,b"}, false), std::invalid_argument);
  CsvSeries::truncate_after(csv.parent_path() / "missing.csv", 1.0);
  EXPECT_FALSE(fs::exists(csv.parent_path() / "missing.csv"));
}
