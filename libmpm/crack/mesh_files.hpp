// Crack surfaces drawn in a CAD or meshing tool: STL (ASCII and binary) and Gmsh's .msh (ASCII,
// formats 2.2 and 4.1; the triangles of every entity). Coordinates are returned as stored (the
// caller scales them to metres); vertices that STL repeats per facet are merged.
#pragma once
#include <filesystem>
#include <string>

#include "libmpm/crack/mesh3d.hpp"

namespace cleave::crack {

// Throws SceneError at `key` naming the file and the reason: cannot open, not an STL / msh file,
// truncated, a malformed line (with its number), no triangles.
TriMesh read_mesh_file(const std::filesystem::path& file, const std::string& key);

}  // namespace cleave::crack
