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

#include "libmpm/crack/crack2d.hpp"
#include "libmpm/crack/fronts.hpp"
#include "libmpm/crack/mesh3d.hpp"
#include "libmpm/crack/tip_parameters.hpp"
#include "libmpm/io/crack_output.hpp"
#include "libmpm/io/csv_writer.hpp"
#include "libmpm/io/point_set.hpp"
#include "libmpm/io/pvd_writer.hpp"
#include "libmpm/io/vtu_writer.hpp"

namespace fs = std::filesystem;
using cleave::io::CsvSeries;
using cleave::io::PointArray;
using cleave::io::PointSet;
using cleave::io::PvdIndex;
using cleave::io::VtuFormat;
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

// What a reader gives back for values written in `format`: the doubles, or each rounded to the
// nearest float (beyond float's range: +-inf).
std::vector<double> as_written(const std::vector<double>& v, const VtuFormat& format) {
  if (!format.float32) return v;
  std::vector<double> r(v.size());
  for (std::size_t i = 0; i < v.size(); ++i)
    r[i] = std::fabs(v[i]) > std::numeric_limits<float>::max() ? std::copysign(HUGE_VAL, v[i])
                                                                : static_cast<double>(static_cast<float>(v[i]));
  return r;
}

// The cells a PointSet is written as, (VTK type, point ids) in file order: a vertex per point, or
// the polylines' segments (a one-point polyline: a vertex), then the triangles.
std::vector<std::pair<int, std::vector<std::int64_t>>> expected_cells(const PointSet& ps) {
  std::vector<std::pair<int, std::vector<std::int64_t>>> cells;
  if (ps.polylines.empty() && ps.triangles.empty())
    for (std::size_t i = 0; i < ps.size(); ++i) cells.push_back({VTK_VERTEX, {std::int64_t(i)}});
  for (const auto& line : ps.polylines) {
    if (line.size() == 1) cells.push_back({VTK_VERTEX, {line[0]}});
    for (std::size_t k = 1; k < line.size(); ++k) cells.push_back({VTK_LINE, {line[k - 1], line[k]}});
  }
  for (const auto& t : ps.triangles) cells.push_back({VTK_TRIANGLE, {t[0], t[1], t[2]}});
  return cells;
}

std::string format_name(const VtuFormat& f) {
  return std::string(f.zlib ? "zlib" : "raw") + (f.float32 ? "_float32" : "_float64");
}
const VtuFormat kEveryFormat[] = {{false, false}, {true, false}, {false, true}, {true, true}};

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

// Debian's python with meshio and numpy, which the README's test command installs.
bool has_meshio() {
  static const bool ok =
      std::system((std::string(CLEAVE_DEBIAN_PYTHON) + " -c 'import meshio, numpy' >/dev/null 2>&1").c_str()) == 0;
  return ok;
}
const std::string kNoMeshio = std::string(CLEAVE_DEBIAN_PYTHON) +
                              " cannot import meshio and numpy: install python3-meshio (the README's test command does)";

// Writes `ps` to dir/cloud.vtu in `format`, reads it with meshio and compares every value bit for
// bit (float32: with the floats written) and every cell.
void expect_meshio_reads_back(const PointSet& ps, const fs::path& dir, const VtuFormat& format = {}) {
  const std::string py = CLEAVE_DEBIAN_PYTHON;
  const std::size_t n = ps.size();
  const fs::path f = dir / "cloud.vtu";
  write_vtu(f, ps, format);

  // The script dumps raw little-endian doubles (no decimal round trip to doubt) plus a manifest
  // "name components rows" per array and "cells type count" per cell block, whose point ids go to
  // cells_K.bin as little-endian int64.
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
    for i, b in enumerate(m.cells):
        np.asarray(b.data, dtype="<i8").tofile(out + "/cells_%d.bin" % i)
        man.write("cells %s %d\n" % (b.type, len(b.data)))
)";
  const fs::path out = dir / "meshio";
  fs::create_directories(out);
  const std::string cmd = py + " '" + script.string() + "' '" + f.string() + "' '" + out.string() + "'";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;

  std::map<std::string, std::pair<int, std::size_t>> shape;
  std::vector<std::pair<int, std::vector<std::int64_t>>> cells;  // as meshio gives them, in order
  std::ifstream man(out / "manifest.txt");
  for (std::string tag; man >> tag;) {
    if (tag == "cells") {
      std::string type;
      std::size_t count;
      man >> type >> count;
      const int vtk_type = type == "vertex"     ? VTK_VERTEX
                           : type == "line"     ? VTK_LINE
                           : type == "triangle" ? VTK_TRIANGLE
                                                : -1;
      ASSERT_NE(vtk_type, -1) << "meshio cell type " << type;
      cells.push_back({vtk_type, std::vector<std::int64_t>(count)});
    } else {
      int comps;
      std::size_t rows;
      man >> comps >> rows;
      shape[tag] = {comps, rows};
    }
  }
  // Each block's ids, flattened; then one (type, ids) per cell.
  std::vector<std::pair<int, std::vector<std::int64_t>>> got;
  for (std::size_t b = 0; b < cells.size(); ++b) {
    const std::string bytes = slurp(out / ("cells_" + std::to_string(b) + ".bin"));
    std::vector<std::int64_t> ids(bytes.size() / sizeof(std::int64_t));
    std::memcpy(ids.data(), bytes.data(), ids.size() * sizeof(std::int64_t));
    const std::size_t count = cells[b].second.size(), per = count ? ids.size() / count : 0;
    ASSERT_EQ(per * count, ids.size());
    for (std::size_t c = 0; c < count; ++c)
      got.push_back({cells[b].first, std::vector<std::int64_t>(ids.begin() + c * per, ids.begin() + (c + 1) * per)});
  }
  EXPECT_EQ(got, expected_cells(ps)) << "meshio cells";
  ASSERT_EQ(shape.count("points"), 1u);
  EXPECT_EQ(shape["points"], (std::pair<int, std::size_t>{3, n}));
  expect_bits(as_written(ps.points, format), read_f64(out / "points.bin"), "meshio points");
  ASSERT_EQ(shape.size(), 1 + ps.arrays.size());
  for (const auto& a : ps.arrays) {
    ASSERT_EQ(shape.count(a.name), 1u) << a.name;
    EXPECT_EQ(shape[a.name], (std::pair<int, std::size_t>{a.components, n})) << a.name;
    expect_bits(as_written(a.values, format), read_f64(out / (a.name + ".bin")), "meshio " + a.name);
  }
}

}  // namespace

TEST(WriteVtu, MeshioReadsBackBitExact) {
  if (!has_meshio()) FAIL() << kNoMeshio;
  const fs::path dir = test_dir();
  expect_meshio_reads_back(make_cloud(213), dir);
}

// Array layouts that meshio 5.0.0 misread when the writer used raw appended data: it looks each
// block up by its offset string while rewriting the offsets it has passed, and an earlier array's
// rewritten offset could equal a later array's (here "Points", then "connectivity").
TEST(WriteVtu, MeshioReadsBackEveryArrayLayoutBitExact) {
  if (!has_meshio()) FAIL() << kNoMeshio;
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

namespace {

// VTK's reader gives back every value of `ps` (float32: the floats written), with the written
// type, and exactly the cells of expected_cells.
void expect_vtk_reads_back(const fs::path& f, const PointSet& ps, const VtuFormat& format) {
  auto ug = read_vtk(f);
  ASSERT_TRUE(ug);
  const int type = format.float32 ? VTK_FLOAT : VTK_DOUBLE;
  ASSERT_EQ(ug->GetNumberOfPoints(), static_cast<vtkIdType>(ps.size()));
  if (ps.size()) {
    EXPECT_EQ(ug->GetPoints()->GetData()->GetDataType(), type);
    expect_bits(as_written(ps.points, format), to_vector(ug->GetPoints()->GetData()), "vtk points");
  }
  ASSERT_EQ(ug->GetPointData()->GetNumberOfArrays(), static_cast<int>(ps.arrays.size()));
  for (const auto& a : ps.arrays) {
    vtkDataArray* got = ug->GetPointData()->GetArray(a.name.c_str());
    ASSERT_NE(got, nullptr) << a.name;
    EXPECT_EQ(got->GetDataType(), type) << a.name;
    EXPECT_EQ(got->GetNumberOfComponents(), a.components) << a.name;
    expect_bits(as_written(a.values, format), to_vector(got), "vtk " + a.name);
  }
  std::vector<std::pair<int, std::vector<std::int64_t>>> cells;
  for (vtkIdType c = 0; c < ug->GetNumberOfCells(); ++c) {
    vtkNew<vtkIdList> ids;
    ug->GetCellPoints(c, ids);
    auto& cell = cells.emplace_back(ug->GetCellType(c), std::vector<std::int64_t>{});
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k) cell.second.push_back(ids->GetId(k));
  }
  EXPECT_EQ(cells, expected_cells(ps)) << "vtk cells";
}

// `ps` written in every encoding, each read back by meshio and by VTK.
void expect_every_format_reads_back(const PointSet& ps) {
  const fs::path dir = test_dir();
  for (const VtuFormat& format : kEveryFormat) {
    SCOPED_TRACE(format_name(format));
    const fs::path d = dir / format_name(format);
    fs::create_directories(d);
    expect_meshio_reads_back(ps, d, format);
    expect_vtk_reads_back(d / "cloud.vtu", ps, format);
  }
}

// Two cracks as the run writes them (io/crack_output.hpp), with tip values on their tips.
PointSet crack_file_contents() {
  std::vector<cleave::crack::Crack2D> cracks(2);
  for (int c = 0; c < 2; ++c) {
    auto& k = cracks[c];
    k.id = c;
    for (int i = 0; i < 5 + 3 * c; ++i) {
      const cleave::Vec<2> x(1e-3 * i, 2e-3 * c + 1e-4 * i * i);
      k.points.push_back(x);
      k.above.push_back(x + cleave::Vec<2>(1e-6 * i, 3e-6 * (4 - i)));
      k.below.push_back(x - cleave::Vec<2>(0, 2e-6 * (4 - i)));
    }
  }
  std::vector<cleave::crack::TipRecord> tips(2);
  tips[0].crack = 0, tips[0].end = 1, tips[0].J1 = 12.5, tips[0].KI = 1.5e6, tips[0].KII = -2e4;
  tips[1].crack = 1, tips[1].end = 0, tips[1].J1 = 0.25, tips[1].J2 = -0.125, tips[1].KI = 3e5;
  return cleave::io::crack_point_set(cracks, tips);
}

// A 3D crack's frame: a penny crack (rings of triangles) opened by 1 um along its normal and slid
// by 0.5 um, with its closed front.
PointSet crack3d_file_contents() {
  using V3 = cleave::Vec<3>;
  const V3 n = V3(0, 0.6, 0.8);
  const auto mesh = cleave::crack::ellipse_mesh(V3(0.01, 0.02, 0.03), n, V3(1, 0, 0), 4e-3, 4e-3, 1e-3);
  std::vector<cleave::crack::ExplicitCrack<3>> cracks(1);
  auto& c = cracks[0];
  c.id = 0;
  c.points = mesh.points, c.simplices = mesh.triangles;
  c.update_extent();
  for (const auto& x : c.points) c.above.push_back(x + 1e-6 * n + 5e-7 * V3(1, 0, 0)), c.below.push_back(x);
  c.fronts = cleave::crack::crack_fronts(c, [](const V3&) { return true; });
  return cleave::io::crack_point_set(cracks);
}

}  // namespace

// A 3D crack's file: its surface as triangles and its front as line segments; the opening split
// along the surface normal (1 um) and across it (the slide); the front's frame on the front nodes.
TEST(WriteVtu, A3DCrackIsItsSurfaceAsTrianglesAndItsFrontsAsLinesThatMeshioAndVtkReadBack) {
  if (!has_meshio()) FAIL() << kNoMeshio;
  const PointSet ps = crack3d_file_contents();
  ASSERT_EQ(ps.triangles.size(), 6u * (1 + 3 + 5 + 7));  // four rings: 6 (2k - 1) triangles in ring k
  ASSERT_EQ(ps.polylines.size(), 1u);
  EXPECT_EQ(ps.polylines[0].size(), 24u + 1u);  // the outer ring, closed
  std::map<std::string, const cleave::io::PointArray*> a;
  for (const auto& x : ps.arrays) a[x.name] = &x;
  for (const char* name : {"above", "below", "cod", "cod_normal", "cod_tangential", "crack", "front_normal",
                           "front_tangent", "front_ahead"})
    ASSERT_TRUE(a.count(name)) << name;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    EXPECT_NEAR(a["cod_normal"]->values[i], 1e-6, 1e-15);
    EXPECT_NEAR(cleave::Vec<3>(&a["cod_tangential"]->values[3 * i]).norm(), 5e-7, 1e-15);
  }
  const std::int64_t front_node = ps.polylines[0][0];
  EXPECT_NEAR(cleave::Vec<3>(&a["front_ahead"]->values[3 * front_node]).norm(), 1.0, 1e-12);
  EXPECT_EQ(a["front_ahead"]->values[0], 0.0);  // the centre is no front node
  expect_every_format_reads_back(ps);
}

// Crack paths are written as VTK_LINE segments in path order (meshio has no VTK_POLY_LINE); a
// one-point path is a vertex, so every point belongs to a cell.
TEST(WriteVtu, CrackPathsAreLineSegmentsThatVtkReadsBackInPathOrder) {
  const fs::path f = test_dir() / "cracks.vtu";
  PointSet ps;
  for (int i = 0; i < 10; ++i) ps.points.insert(ps.points.end(), {0.5 * i, 0.25 * i * i, 0.0});
  ps.arrays.push_back({"opening", 1, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9}});
  ps.polylines = {{0, 1, 2, 3}, {4, 5}, {8, 7, 6}, {9}};
  write_vtu(f, ps);
  EXPECT_EQ(expected_cells(ps).size(), 3u + 1u + 2u + 1u);
  expect_vtk_reads_back(f, ps, {});
}

// The crack files of a run: meshio gives back every segment of every crack and every point array
// (above, below, cod, cod_normal, cod_tangential, crack, J1, J2, KI, KII), in every encoding.
TEST(WriteVtu, MeshioReadsEverySegmentAndPointArrayOfACrackFile) {
  if (!has_meshio()) FAIL() << kNoMeshio;
  const PointSet ps = crack_file_contents();
  ASSERT_EQ(ps.arrays.size(), 10u);
  ASSERT_EQ(ps.polylines.size(), 2u);
  expect_every_format_reads_back(ps);
}

// output.compression = zlib and output.precision = float32, alone and together: VTK's reader and
// meshio give back every value (float32: rounded to the nearest float) and every cell, for sizes
// that end the compressed arrays in a partial block, a full block, or many blocks (and no points:
// empty arrays, zero blocks).
TEST(WriteVtu, EveryCompressionAndPrecisionReadsBackInVtkAndMeshio) {
  if (!has_meshio()) FAIL() << kNoMeshio;
  const fs::path dir = test_dir();
  // 4096 points: a scalar's 32 KiB of doubles fill exactly one zlib block (VTK's partial-size 0).
  for (std::size_t n : {0, 1, 3, 213, 4096, 20000})
    for (const VtuFormat& format : kEveryFormat) {
      SCOPED_TRACE(format_name(format) + ", " + std::to_string(n) + " points");
      const fs::path d = dir / (format_name(format) + "_" + std::to_string(n));
      fs::create_directories(d);
      const PointSet ps = make_cloud(n);
      if (n > 0) expect_meshio_reads_back(ps, d, format);  // meshio 5.0 reads no file without cells
      else write_vtu(d / "cloud.vtu", ps, format);
      expect_vtk_reads_back(d / "cloud.vtu", ps, format);
      const std::string text = slurp(d / "cloud.vtu");
      EXPECT_EQ(text.find("compressor=\"vtkZLibDataCompressor\"") != std::string::npos, format.zlib);
      EXPECT_EQ(text.find("type=\"Float32\"") != std::string::npos, format.float32);
      EXPECT_EQ(text.find("type=\"Float64\"") != std::string::npos, !format.float32);
    }
}

// Compression shrinks what compresses (2D frames: z = 0, stress components 0) and float32 halves
// the values; neither changes what a reader gets beyond the rounding above.
TEST(WriteVtu, ZlibAndFloat32MakeSmallerFiles) {
  const fs::path dir = test_dir();
  PointSet ps;
  const std::size_t n = 10000;
  for (std::size_t i = 0; i < n; ++i) ps.points.insert(ps.points.end(), {1e-3 * double(i % 100), 1e-3 * double(i / 100), 0.0});
  PointArray stress{"stress", 6, std::vector<double>(6 * n, 0.0)};
  for (std::size_t i = 0; i < n; ++i) stress.values[6 * i] = std::sin(0.01 * double(i)) * 1e6;
  ps.arrays.push_back(stress);
  std::map<std::string, std::uintmax_t> size;
  for (const VtuFormat& format : kEveryFormat) {
    const fs::path f = dir / (format_name(format) + ".vtu");
    write_vtu(f, ps, format);
    size[format_name(format)] = fs::file_size(f);
  }
  EXPECT_LT(size["zlib_float64"], size["raw_float64"] / 2);
  EXPECT_LT(size["raw_float32"], size["raw_float64"] * 6 / 10);
  EXPECT_LT(size["zlib_float32"], size["raw_float32"] / 2);
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

// A value that is zero is printed as 0, never -0 (a sum of cancelling terms, a momentum of -1 x 0).
TEST(CsvSeries, NegativeZeroIsWrittenAsZero) {
  const fs::path csv = test_dir() / "zero.csv";
  {
    CsvSeries s(csv, {"time_s", "momentum_x_kg_m_per_s", "x_m"}, false);
    s.row({0.0, -0.0, -1.0 * 0.0});
    s.row({1e-6, -0.0, -4.9406564584124654e-324});
  }
  EXPECT_EQ(slurp(csv), "time_s,momentum_x_kg_m_per_s,x_m\n0,0,0\n9.9999999999999995e-07,0,-4.9406564584124654e-324\n");
}

// The run loop syncs every series before a checkpoint (a power cut must not lose rows the
// checkpoint resumes after); a sync that cannot be done names the file.
TEST(CsvSeries, SyncKeepsTheRowsAndNamesTheFileWhenItFails) {
  const fs::path csv = test_dir() / "synced.csv";
  CsvSeries s(csv, {"time_s", "x_m"}, false);
  s.row({0.0, 1.0});
  EXPECT_NO_THROW(s.sync());
  EXPECT_EQ(slurp(csv), "time_s,x_m\n0,1\n");
  fs::remove(csv);  // the series' file is gone from under it: the sync cannot open it
  try {
    s.sync();
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(csv.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("No such file"), std::string::npos) << e.what();
  }
}
