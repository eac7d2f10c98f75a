// The finite-element mesh whose nodes are the particles of the particle equilibrium method (PEM,
// seed 004): made by Gmsh from the scene's bodies, or read from a mesh file (Gmsh .msh, VTK .vtu).
// Only what PEM needs is kept: node coordinates (metres), the elements' node lists, and which body
// (region, physical group) each element belongs to. A PEM particle interacts with the particles of
// the elements it belongs to (every pair of nodes of an element; docs/pem.md).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "libmpm/core/types.hpp"

namespace cleave::pem {

template <int Dim>
struct Mesh {
  std::vector<Vec<Dim>> nodes;          // metres
  // Element e holds nodes element_nodes[element_offset[e] .. element_offset[e+1]): first-order
  // triangles (3) or quadrangles (4) in 2D, tetrahedra (4) or hexahedra (8) in 3D, Gmsh's node order.
  std::vector<int32_t> element_offset{0};
  std::vector<int32_t> element_nodes;
  std::vector<int32_t> element_region;  // index into `regions`
  std::vector<std::string> regions;     // a body's name, or a mesh file's physical group name
  std::size_t element_count() const { return element_region.size(); }
  int32_t nodes_of(std::size_t e) const { return element_offset[e + 1] - element_offset[e]; }
  const int32_t* element(std::size_t e) const { return element_nodes.data() + element_offset[e]; }
};

// How a body is meshed (scene section "pem.mesh"): element size (m), element kind, and whether a
// shape that allows it (rectangle, box) is meshed as a structured grid (transfinite: a 8 m x 1 m
// rectangle at 0.1 m gives the 81 x 11 nodes of seed 004's cantilever).
struct MeshOptions {
  double size = 0.0;             // target element edge length, metres (> 0)
  bool quads = false;            // 2D: recombine into quadrangles (3D: hexahedra where structured)
  bool structured = false;       // transfinite meshing of rectangles and boxes
};

// One body for meshing: its name (the region), its shape object as written in the scene (with the
// scene path of that object for errors), and the length unit's factor to metres.
struct BodyShape {
  std::string name;
  const nlohmann::json* shape = nullptr;
  std::string path;  // "bodies[2].shape"
};

// Meshes all bodies together with Gmsh (OpenCASCADE kernel), conforming where bodies touch (they
// share nodes there, so touching bodies are bonded); bodies that overlap are refused (SceneError at
// the later body's shape, naming both). Regions are the bodies, in order. Throws SceneError naming
// the key (a shape Gmsh cannot build or mesh, a mesh with no element, a size that would give more
// than `max_nodes` nodes: at `size_key`).
template <int Dim>
Mesh<Dim> mesh_bodies(const std::vector<BodyShape>& bodies, double length_scale, const MeshOptions& opt,
                      const std::string& size_key, std::size_t max_nodes);

// Reads a mesh file (.msh, any version Gmsh reads, ASCII or binary; .vtu, any encoding VTK reads) and
// scales its coordinates by length_scale. Regions: the physical groups of the elements of the mesh's
// dimension (.msh; elements in no group form the region "" ) or the values of the cell array named
// "region", "gmsh:physical" or "CellEntityIds" (.vtu; names are the values as text); elements of a
// lower dimension (boundary lines, faces) are dropped. Throws SceneError(key, "<file>: reason"):
// cannot open, unknown extension, unreadable, no element of the dimension, an element kind PEM does
// not take (second order, prisms, pyramids: named), an inverted or zero-volume element (its index).
// Inverted means tangled (a quadrangle or hexahedron whose corners are out of order); an element
// merely given in the other orientation (clockwise triangle, negative tetrahedron) is re-oriented.
// A 2D mesh must lie in a plane z = constant; nodes that no element uses are dropped.
template <int Dim>
Mesh<Dim> read_mesh_file(const std::string& file, const std::string& key, double length_scale);

// Signed measure of element e (area in 2D, volume in 3D; negative when inverted).
template <int Dim>
double element_measure(const Mesh<Dim>& m, std::size_t e);

}  // namespace cleave::pem
