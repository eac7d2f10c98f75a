// VTK XML UnstructuredGrid (.vtu) writer for a PointSet. Everything goes in one raw appended block
// (UInt64 headers, Float64 data) so values round-trip bit-exactly and writing costs one memcpy.
#pragma once
#include <filesystem>
#include <functional>
#include <ostream>

#include "libmpm/io/point_set.hpp"

namespace cleave::io {

// Writes `file` atomically (file + ".tmp", then rename) so a viewer polling the output directory
// never sees a half-written frame. Throws std::runtime_error naming the file on I/O failure and
// std::invalid_argument if the PointSet is inconsistent (array sizes, polyline ids out of range).
void write_vtu(const std::filesystem::path& file, const PointSet& ps);

namespace detail {
// Shared by all writers: runs `body` on a binary stream to file + ".tmp", then renames it over
// `file`. On any failure the temporary is removed and std::runtime_error names `file`.
void write_atomically(const std::filesystem::path& file,
                      const std::function<void(std::ostream&)>& body);
}  // namespace detail

}  // namespace cleave::io
