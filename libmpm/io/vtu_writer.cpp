// Layout of the file: an XML header whose DataArrays all point (offset=...) into one raw
// <AppendedData> section, in the reverse of their declaration order (write_vtu says why); each
// block there is a UInt64 byte count followed by the bytes. Offsets count from the byte after the
// leading '_'. The section ends with '\n' before </AppendedData> because meshio's raw reader strips
// everything after the last newline.
#include "libmpm/io/vtu_writer.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

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
  std::error_code ec;
  std::filesystem::rename(tmp, file, ec);
  if (ec) fail("rename from " + tmp.string() + ": " + ec.message());
}

}  // namespace detail

namespace {

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
}

}  // namespace

void write_vtu(const std::filesystem::path& file, const PointSet& ps) {
  check(ps);
  const std::size_t n = ps.size();

  // Cell arrays: one vertex per point, or the given polylines.
  std::vector<std::int64_t> connectivity, offsets;
  std::vector<std::uint8_t> types;
  if (ps.polylines.empty()) {
    connectivity.resize(n);
    offsets.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      connectivity[i] = static_cast<std::int64_t>(i);
      offsets[i] = static_cast<std::int64_t>(i + 1);
    }
    types.assign(n, 1);  // VTK_VERTEX
  } else {
    for (const auto& line : ps.polylines) {
      connectivity.insert(connectivity.end(), line.begin(), line.end());
      offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
    }
    types.assign(ps.polylines.size(), 4);  // VTK_POLY_LINE
  }

  auto f64 = [](const std::string& name, int comps, const std::vector<double>& v) {
    return Block{"Float64", name, comps, v.data(), v.size() * sizeof(double)};
  };
  std::vector<Block> point_data;
  for (const auto& a : ps.arrays) point_data.push_back(f64(a.name, a.components, a.values));
  const Block points = f64("Points", 3, ps.points);
  const std::vector<Block> cells = {
      {"Int64", "connectivity", 1, connectivity.data(), connectivity.size() * sizeof(std::int64_t)},
      {"Int64", "offsets", 1, offsets.data(), offsets.size() * sizeof(std::int64_t)},
      {"UInt8", "types", 1, types.data(), types.size()}};

  // Header. The blocks are appended in the reverse of the order they are declared (the first
  // declared array's block comes last): offsets are free in the format, and this order is the one
  // meshio 5.0.0 (Debian 12) reads right. Its raw reader converts the blocks to base64 one by one,
  // from the start of the section, rewriting each DataArray's offset="..." in place and finding
  // the next block's array as the first in document order whose offset equals the block's raw
  // offset. In declaration order an earlier array's rewritten offset can equal a later array's raw
  // offset (fields "displacement, stress": "Points" then reads another array's bytes); in reverse
  // order every array not yet converted precedes the converted ones, so the first match is the
  // right one. Raw rather than base64: 3/4 of the size, and about ten times faster for VTK to read.
  std::vector<const Block*> order;
  std::string xml;
  std::vector<std::size_t> offset_at;  // where in `xml` each declared array's offset goes
  auto declare = [&](const Block& b, const char* indent) {
    xml += indent;
    xml += "<DataArray type=\"" + b.type + "\" Name=\"" + xml_escape(b.name) +
           "\" NumberOfComponents=\"" + std::to_string(b.components) + "\" format=\"appended\" offset=\"";
    offset_at.push_back(xml.size());
    xml += "\"/>\n";
    order.push_back(&b);
  };
  xml +=
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n"
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
  std::uint64_t offset = 0;
  std::vector<std::string> offsets_text(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) {  // appended order: the last declared first
    offsets_text[order.size() - 1 - k] = std::to_string(offset);
    offset += sizeof(std::uint64_t) + order[k]->bytes;
  }
  for (std::size_t k = order.size(); k-- > 0;) xml.insert(offset_at[k], offsets_text[k]);  // back to front

  detail::write_atomically(file, [&](std::ostream& out) {
    out.write(xml.data(), static_cast<std::streamsize>(xml.size()));
    for (const Block* b : order) {
      out.write(reinterpret_cast<const char*>(&b->bytes), sizeof(b->bytes));
      if (b->bytes) out.write(static_cast<const char*>(b->data), static_cast<std::streamsize>(b->bytes));
    }
    out << "\n  </AppendedData>\n</VTKFile>\n";
  });
}

}  // namespace cleave::io
