// VTK XML UnstructuredGrid (.vtu) writer for a PointSet. Everything goes in one appended block
// (UInt64 headers), raw Float64 by default so values round-trip bit-exactly and writing costs one
// memcpy; zlib compression and Float32 values are options (the scene's output.compression and
// output.precision).
#pragma once
#include <filesystem>
#include <functional>
#include <string>
#include <ostream>

#include "libmpm/io/point_set.hpp"

namespace cleave::io {

// How the appended data is encoded. Both options are what VTK's own writer produces, so VTK,
// ParaView and meshio read them.
struct VtuFormat {
  // compressor="vtkZLibDataCompressor": each array in 32 KiB blocks, each deflated on its own.
  bool zlib = false;
  // Points and point data as Float32 (rounded to nearest; beyond float's range: +-inf). Cell
  // arrays stay integers.
  bool float32 = false;
};

// Writes `file` atomically (file + ".tmp", then rename) so a viewer polling the output directory
// never sees a half-written frame. Throws std::runtime_error naming the file on I/O failure and
// std::invalid_argument if the PointSet is inconsistent (array sizes, polyline ids out of range).
void write_vtu(const std::filesystem::path& file, const PointSet& ps, const VtuFormat& format = {});

namespace detail {
// Shared by all writers: runs `body` on a binary stream to file + ".tmp", then renames it over
// `file`. On any failure the temporary is removed and std::runtime_error names `file`.
void write_atomically(const std::filesystem::path& file,
                      const std::function<void(std::ostream&)>& body);
// `s` as XML attribute text (& < > " escaped): array and file names in the writers' XML.
std::string xml_escape(const std::string& s);
}  // namespace detail

}  // namespace cleave::io
