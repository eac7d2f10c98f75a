// Crack surfaces drawn in a CAD or meshing tool: STL (ASCII and binary) and Gmsh's .msh (ASCII,
// formats 2.2 and 4.1; the triangles of every entity). Coordinates are returned as stored (the
// caller scales them to metres); vertices that STL repeats per facet are merged.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>

#include "libmpm/crack/mesh3d.hpp"

namespace cleave::crack {

// The largest crack surface file read: 1 GiB (a binary STL of about 21 million triangles).
inline constexpr std::uintmax_t kMaxMeshFileBytes = std::uintmax_t(1) << 30;

// Throws SceneError at `key` naming the file and the reason: cannot open, not a regular file (a
// device such as /dev/zero or a FIFO, refused before it is opened), larger than kMaxMeshFileBytes,
// not an STL / msh file, truncated, a malformed line (with its number), no triangles.
TriMesh read_mesh_file(const std::filesystem::path& file, const std::string& key);

}  // namespace cleave::crack
