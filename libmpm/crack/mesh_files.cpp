#include "libmpm/crack/mesh_files.hpp"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "libmpm/core/error.hpp"

namespace cleave::crack {
namespace {

struct Failure {
  const std::filesystem::path& file;
  const std::string& key;
  [[noreturn]] void operator()(const std::string& why) const { throw SceneError(key, file.string() + ": " + why); }
};

// Reads the whole file, refusing before reading anything what is not a regular file (a device such
// as /dev/zero, a FIFO, a socket: endless or blocking) or is larger than kMaxMeshFileBytes.
std::string read_all(const std::filesystem::path& file, const Failure& fail) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(file, ec);  // follows links: a link to a device is a device
  if (!fs::exists(st)) fail("cannot open: " + (ec ? ec.message() : std::string("no such file")));
  if (fs::is_directory(st)) fail("cannot open: is a directory");
  if (!fs::is_regular_file(st))
    fail("not a regular file (a device, FIFO or socket); a crack surface is read from an .stl or .msh file");
  const std::uintmax_t size = fs::file_size(file, ec);
  if (ec) fail("cannot open: " + ec.message());
  if (size > kMaxMeshFileBytes)
    fail("the file has " + std::to_string(size) + " bytes, more than a crack surface file may have (" +
         std::to_string(kMaxMeshFileBytes) + " bytes, 1 GiB)");
  std::ifstream in(file, std::ios::binary);
  if (!in) fail(std::string("cannot open: ") + std::strerror(errno));
  // At most the size found above (+1 to see a file that grew since): never more than the cap.
  std::string d(static_cast<std::size_t>(size) + 1, '\0');
  in.read(d.data(), static_cast<std::streamsize>(d.size()));
  if (in.bad()) fail(std::string("cannot read: ") + std::strerror(errno));
  d.resize(static_cast<std::size_t>(in.gcount()));
  if (d.size() > size) fail("the file grew while it was read");
  return d;
}

// Binary STL: 80-byte header, uint32 count, 50 bytes per facet (normal, three vertices as
// float32, uint16 attribute). Recognised by its size, since many binary files also begin "solid".
bool is_binary_stl(const std::string& d) {
  if (d.size() < 84) return false;
  uint32_t n;
  std::memcpy(&n, d.data() + 80, 4);
  return d.size() == 84 + 50ull * n;
}

TriMesh binary_stl(const std::string& d) {
  uint32_t n;
  std::memcpy(&n, d.data() + 80, 4);
  TriMesh m;
  for (uint32_t k = 0; k < n; ++k) {
    const char* f = d.data() + 84 + 50ull * k + 12;  // skip the normal: the vertex order is the orientation
    std::array<int32_t, 3> t;
    for (int v = 0; v < 3; ++v) {
      float c[3];
      std::memcpy(c, f + 12 * v, 12);
      t[v] = static_cast<int32_t>(m.points.size());
      m.points.emplace_back(c[0], c[1], c[2]);
    }
    m.triangles.push_back(t);
  }
  return merge_identical_points(m);
}

TriMesh ascii_stl(const std::string& d, const Failure& fail) {
  std::istringstream in(d);
  std::string line, word;
  TriMesh m;
  std::vector<int32_t> facet;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    std::istringstream ls(line);
    if (!(ls >> word)) continue;
    if (word == "vertex") {
      double x, y, z;
      if (!(ls >> x >> y >> z)) fail("line " + std::to_string(number) + ": expected \"vertex x y z\"");
      facet.push_back(static_cast<int32_t>(m.points.size()));
      m.points.emplace_back(x, y, z);
    } else if (word == "endloop") {
      if (facet.size() != 3)
        fail("line " + std::to_string(number) + ": a facet with " + std::to_string(facet.size()) +
             " vertices (triangles only)");
      m.triangles.push_back({facet[0], facet[1], facet[2]});
      facet.clear();
    }
  }
  return merge_identical_points(m);
}

// Gmsh ASCII .msh: $Nodes and $Elements (type 2 = 3-node triangle) in format 2.2 or 4.1.
TriMesh gmsh(const std::string& d, const Failure& fail) {
  std::istringstream in(d);
  std::string word;
  double version = 0;
  int file_type = 0;
  std::map<long, int32_t> node;  // gmsh tag -> point index
  TriMesh m;
  auto expect = [&](bool ok, const char* what) {
    if (!ok) fail(std::string("malformed ") + what + " section");
  };
  while (in >> word) {
    if (word == "$MeshFormat") {
      int size;
      expect(static_cast<bool>(in >> version >> file_type >> size), "$MeshFormat");
      if (file_type != 0) fail("binary .msh files are not read: save it as ASCII (Gmsh: -format msh41, Binary off)");
      if (!(version >= 2.0 && version < 3.0) && !(version >= 4.0 && version < 5.0))
        fail("format " + std::to_string(version) + " is not read (2.2 and 4.1 are)");
    } else if (word == "$Nodes") {
      if (version >= 4.0) {
        long blocks, count, lo, hi;
        expect(static_cast<bool>(in >> blocks >> count >> lo >> hi), "$Nodes");
        for (long b = 0; b < blocks; ++b) {
          int dim, parametric;
          long entity, n;
          expect(static_cast<bool>(in >> dim >> entity >> parametric >> n), "$Nodes");
          if (parametric) fail("parametric nodes are not read");
          // Each tag takes at least two bytes of the file: a larger count is not allocated.
          expect(n >= 0 && static_cast<std::size_t>(n) <= d.size() / 2, "$Nodes");
          std::vector<long> tags(n);
          for (auto& t : tags) expect(static_cast<bool>(in >> t), "$Nodes");
          for (long t : tags) {
            double x, y, z;
            expect(static_cast<bool>(in >> x >> y >> z), "$Nodes");
            node[t] = static_cast<int32_t>(m.points.size());
            m.points.emplace_back(x, y, z);
          }
        }
      } else {
        long n;
        expect(static_cast<bool>(in >> n), "$Nodes");
        for (long k = 0; k < n; ++k) {
          long t;
          double x, y, z;
          expect(static_cast<bool>(in >> t >> x >> y >> z), "$Nodes");
          node[t] = static_cast<int32_t>(m.points.size());
          m.points.emplace_back(x, y, z);
        }
      }
    } else if (word == "$Elements") {
      auto triangle = [&](long a, long b, long c) {
        std::array<int32_t, 3> t;
        const long v[3] = {a, b, c};
        for (int k = 0; k < 3; ++k) {
          const auto it = node.find(v[k]);
          if (it == node.end()) fail("an element names node " + std::to_string(v[k]) + ", which $Nodes lacks");
          t[k] = it->second;
        }
        m.triangles.push_back(t);
      };
      if (version >= 4.0) {
        long blocks, count, lo, hi;
        expect(static_cast<bool>(in >> blocks >> count >> lo >> hi), "$Elements");
        for (long b = 0; b < blocks; ++b) {
          int dim, type;
          long entity, n;
          expect(static_cast<bool>(in >> dim >> entity >> type >> n), "$Elements");
          std::string rest;
          std::getline(in, rest);
          for (long k = 0; k < n; ++k) {
            std::string line;
            expect(static_cast<bool>(std::getline(in, line)), "$Elements");
            if (type != 2) continue;  // points, lines, quads: not part of the surface
            std::istringstream ls(line);
            long tag, a, bb, c;
            expect(static_cast<bool>(ls >> tag >> a >> bb >> c), "$Elements");
            triangle(a, bb, c);
          }
        }
      } else {
        long n;
        expect(static_cast<bool>(in >> n), "$Elements");
        std::string rest;
        std::getline(in, rest);
        for (long k = 0; k < n; ++k) {
          std::string line;
          expect(static_cast<bool>(std::getline(in, line)), "$Elements");
          std::istringstream ls(line);
          long tag, ntags;
          int type;
          expect(static_cast<bool>(ls >> tag >> type >> ntags), "$Elements");
          for (long t = 0; t < ntags; ++t) {
            long skip;
            expect(static_cast<bool>(ls >> skip), "$Elements");
          }
          if (type != 2) continue;
          long a, b, c;
          expect(static_cast<bool>(ls >> a >> b >> c), "$Elements");
          triangle(a, b, c);
        }
      }
    }
  }
  if (version == 0) fail("not a Gmsh .msh file (no $MeshFormat)");
  return m;
}

}  // namespace

TriMesh read_mesh_file(const std::filesystem::path& file, const std::string& key) {
  const Failure fail{file, key};
  const std::string ext = file.extension().string();
  const bool stl = ext == ".stl" || ext == ".STL";
  if (!stl && ext != ".msh") fail("unknown mesh file type \"" + ext + "\" (read: .stl, .msh)");  // before reading
  const std::string d = read_all(file, fail);
  TriMesh m;
  if (stl) {
    if (is_binary_stl(d)) m = binary_stl(d);
    else if (d.rfind("solid", 0) == 0) m = ascii_stl(d, fail);
    else fail("not an STL file (neither \"solid\" text nor a binary file of 84 + 50 n bytes)");
  } else {
    m = gmsh(d, fail);
  }
  if (m.triangles.empty()) fail("no triangles in the file");
  return m;
}

}  // namespace cleave::crack
