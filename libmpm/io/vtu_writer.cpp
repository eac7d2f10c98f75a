// Layout of the file: an XML header whose DataArrays all point (offset=...) into one raw
// <AppendedData> section, in the reverse of their declaration order (write_vtu says why); each
// block there is a UInt64 byte count followed by the bytes, or with zlib VTK's compression header
// and the deflated blocks (io/appended_blocks.hpp). Offsets count from the byte after the
// leading '_'. The section ends with '\n' before </AppendedData> because meshio's raw reader strips
// everything after the last newline.
#include "libmpm/io/vtu_writer.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "libmpm/io/appended_blocks.hpp"
#include "libmpm/io/file_sync.hpp"

namespace cleave::io {

// Raw blocks are memcpy'd host memory, and the header claims LittleEndian.
static_assert(std::endian::native == std::endian::little, "vtu writer assumes a little-endian host");

namespace detail {

void write_atomically(const std::filesystem::path& file,
                      const std::function<void(std::ostream&)>& body) {
  std::filesystem::path tmp = file;
  tmp += ".tmp";
  auto fail = [&](const std::string& why) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);  // best effort; the original error is what matters
    throw std::runtime_error("cannot write " + file.string() + ": " + why);
  };
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) fail("cannot open " + tmp.string());
    body(out);
    out.flush();
    if (!out) fail("write error");
    out.close();
    if (out.fail()) fail("close error");
  }
  // On the disk before the rename (io/file_sync.hpp): a power cut leaves the old file or the new.
  if (const int e = sync_file(tmp)) fail("fsync: " + std::error_code(e, std::generic_category()).message());
  std::error_code ec;
  std::filesystem::rename(tmp, file, ec);
  if (ec) fail("rename from " + tmp.string() + ": " + ec.message());
}

std::string xml_escape(const std::string& s) {
  std::string r;
  for (char c : s) {
    switch (c) {
      case '&': r += "&amp;"; break;
      case '<': r += "&lt;"; break;
      case '>': r += "&gt;"; break;
      case '"': r += "&quot;"; break;
      default: r += c;
    }
  }
  return r;
}

}  // namespace detail

namespace {

// One DataArray: its XML attributes and where its bytes come from.
struct Block {
  std::string type, name;
  int components;
  const void* data;
  std::uint64_t bytes;
};

void check(const PointSet& ps) {
  if (ps.points.size() % 3 != 0)
    throw std::invalid_argument("PointSet: points.size() is not a multiple of 3");
  const std::size_t n = ps.size();
  for (const auto& a : ps.arrays) {
    if (a.components < 1)
      throw std::invalid_argument("PointSet array '" + a.name + "': components < 1");
    if (a.values.size() != static_cast<std::size_t>(a.components) * n)
      throw std::invalid_argument("PointSet array '" + a.name + "': has " +
                                  std::to_string(a.values.size()) + " values, expected " +
                                  std::to_string(a.components) + " x " + std::to_string(n));
  }
  for (const auto& line : ps.polylines)
    for (std::int64_t id : line)
      if (id < 0 || static_cast<std::size_t>(id) >= n)
        throw std::invalid_argument("PointSet polyline: point id " + std::to_string(id) +
                                    " out of range");
  for (const auto& t : ps.triangles)
    for (std::int64_t id : t)
      if (id < 0 || static_cast<std::size_t>(id) >= n)
        throw std::invalid_argument("PointSet triangle: point id " + std::to_string(id) + " out of range");
}

// A double as the nearest float; beyond float's range +-inf (a plain cast would be undefined there).
float to_float(double v) {
  constexpr double kMax = std::numeric_limits<float>::max();
  if (v > kMax) return std::numeric_limits<float>::infinity();
  if (v < -kMax) return -std::numeric_limits<float>::infinity();
  return static_cast<float>(v);
}

}  // namespace

void write_vtu(const std::filesystem::path& file, const PointSet& ps, const VtuFormat& format) {
  check(ps);
  const std::size_t n = ps.size();

  // Cell arrays: one vertex per point, or the polylines cut into VTK_LINE segments (meshio, like
  // many readers, has no VTK_POLY_LINE; a segment list is the same path in every reader). A
  // one-point polyline becomes a vertex so that no point is left without a cell.
  std::vector<std::int64_t> connectivity, offsets;
  std::vector<std::uint8_t> types;
  auto cell = [&](std::initializer_list<std::int64_t> ids, std::uint8_t type) {
    connectivity.insert(connectivity.end(), ids);
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
    types.push_back(type);
  };
  if (ps.polylines.empty() && ps.triangles.empty()) {
    for (std::size_t i = 0; i < n; ++i) cell({static_cast<std::int64_t>(i)}, 1);  // VTK_VERTEX
  } else {
    for (const auto& line : ps.polylines) {
      if (line.size() == 1) cell({line[0]}, 1);
      for (std::size_t k = 1; k < line.size(); ++k) cell({line[k - 1], line[k]}, 3);  // VTK_LINE
    }
    for (const auto& t : ps.triangles) cell({t[0], t[1], t[2]}, 5);  // VTK_TRIANGLE
  }

  // Float32: converted copies (reserved up front, so the blocks' pointers stay valid).
  std::vector<std::vector<float>> narrowed;
  narrowed.reserve(ps.arrays.size() + 1);
  auto real = [&](const std::string& name, int comps, const std::vector<double>& v) {
    if (!format.float32) return Block{"Float64", name, comps, v.data(), v.size() * sizeof(double)};
    auto& f = narrowed.emplace_back(v.size());
    std::transform(v.begin(), v.end(), f.begin(), to_float);
    return Block{"Float32", name, comps, f.data(), f.size() * sizeof(float)};
  };
  std::vector<Block> point_data;
  for (const auto& a : ps.arrays) point_data.push_back(real(a.name, a.components, a.values));
  const Block points = real("Points", 3, ps.points);
  const std::vector<Block> cells = {
      {"Int64", "connectivity", 1, connectivity.data(), connectivity.size() * sizeof(std::int64_t)},
      {"Int64", "offsets", 1, offsets.data(), offsets.size() * sizeof(std::int64_t)},
      {"UInt8", "types", 1, types.data(), types.size()}};

  // Header. The blocks are appended in the reverse of the order they are declared (the first
  // declared array's block comes last): offsets are free in the format, and this order is the one
  // meshio 5.0.0 (Debian 12) reads right. Its appended-data reader (raw or compressed) converts the
  // blocks to base64 one by one, from the start of the section, rewriting each DataArray's
  // offset="..." in place and finding the next block's array as the first in document order whose
  // offset equals the block's raw offset. In declaration order an earlier array's rewritten offset
  // can equal a later array's raw offset (fields "displacement, stress": "Points" then reads another
  // array's bytes); in reverse order every array not yet converted precedes the converted ones, so
  // the first match is the right one. Raw rather than base64: 3/4 of the size, and about ten times
  // faster for VTK to read.
  std::vector<const Block*> order;
  std::string xml;
  std::vector<std::size_t> offset_at;  // where in `xml` each declared array's offset goes
  auto declare = [&](const Block& b, const char* indent) {
    xml += indent;
    xml += "<DataArray type=\"" + b.type + "\" Name=\"" + detail::xml_escape(b.name) +
           "\" NumberOfComponents=\"" + std::to_string(b.components) + "\" format=\"appended\" offset=\"";
    offset_at.push_back(xml.size());
    xml += "\"/>\n";
    order.push_back(&b);
  };
  xml +=
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\"";
  if (format.zlib) xml += " compressor=\"vtkZLibDataCompressor\"";
  xml +=
      ">\n"
      "  <UnstructuredGrid>\n"
      "    <Piece NumberOfPoints=\"" + std::to_string(n) + "\" NumberOfCells=\"" +
      std::to_string(types.size()) + "\">\n";
  xml += "      <PointData>\n";
  for (const auto& b : point_data) declare(b, "        ");
  xml += "      </PointData>\n      <Points>\n";
  declare(points, "        ");
  xml += "      </Points>\n      <Cells>\n";
  for (const auto& b : cells) declare(b, "        ");
  xml +=
      "      </Cells>\n"
      "    </Piece>\n"
      "  </UnstructuredGrid>\n"
      "  <AppendedData encoding=\"raw\">\n"
      "   _";
  std::reverse(order.begin(), order.end());
  std::vector<std::span<const char>> bytes;
  for (const Block* b : order) bytes.emplace_back(static_cast<const char*>(b->data), b->bytes);
  const std::vector<AppendedBlock> encoded = encode_appended(bytes, format.zlib);
  std::uint64_t offset = 0;
  std::vector<std::string> offsets_text(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) {  // appended order: the last declared first
    offsets_text[order.size() - 1 - k] = std::to_string(offset);
    offset += encoded[k].size();
  }
  for (std::size_t k = order.size(); k-- > 0;) xml.insert(offset_at[k], offsets_text[k]);  // back to front

  detail::write_atomically(file, [&](std::ostream& out) {
    out.write(xml.data(), static_cast<std::streamsize>(xml.size()));
    for (const AppendedBlock& b : encoded) {
      out.write(reinterpret_cast<const char*>(b.header.data()),
                static_cast<std::streamsize>(b.header.size() * sizeof(std::uint64_t)));
      if (!b.payload.empty()) out.write(b.payload.data(), static_cast<std::streamsize>(b.payload.size()));
    }
    out << "\n  </AppendedData>\n</VTKFile>\n";
  });
}

}  // namespace cleave::io
