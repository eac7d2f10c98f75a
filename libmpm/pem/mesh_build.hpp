// Internal to libmpm/pem: from the elements a mesher or a mesh file gives to a checked Mesh<Dim>.
// Meshes made by Gmsh and meshes read from files pass through the same checks, so both give PEM
// the same guarantees (positive measure, dense node numbering, one plane in 2D).
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "libmpm/core/error.hpp"
#include "libmpm/core/types.hpp"
#include "libmpm/pem/mesh.hpp"

namespace cleave::pem::detail {

// Throws the caller's SceneError with this reason; never returns.
using Fail = std::function<void(const std::string& reason)>;
[[noreturn]] inline void raise(const Fail& fail, const std::string& reason) {
  fail(reason);
  throw std::logic_error("pem mesh: a Fail returned: " + reason);
}

// Elements as a source gives them: points in the source's coordinates (z = 0 for a 2D model),
// elements as lists of point indices, first-order kinds only (3, 4 or 8 points; which kind 4 points
// make depends on the dimension).
struct RawMesh {
  std::vector<Vec<3>> points;
  std::vector<int32_t> offset{0};
  std::vector<int32_t> nodes;
  std::vector<int32_t> region;        // index into regions
  std::vector<std::string> regions;
  std::vector<std::size_t> source;    // per element, its number in the source (Gmsh tag, VTK cell)
  std::string source_label;           // "Gmsh element", "cell" (messages); empty: no number

  template <class It>
  void add(It first, It last, int32_t r, std::size_t number) {
    for (; first != last; ++first) nodes.push_back(static_cast<int32_t>(*first));
    offset.push_back(static_cast<int32_t>(nodes.size()));
    region.push_back(r);
    source.push_back(number);
  }
};

// The element kinds PEM takes, by node count and dimension ("triangle", ...).
const char* kind_name(int dim, int nodes);

// Checks and converts: in 2D every point an element uses lies in one plane z = constant; points no
// element uses are dropped (the others keep their order); coordinates become metres through
// to_metres; every element has a non-zero measure and is not tangled (a quadrangle or hexahedron
// whose corners are out of order: its sub-triangles or sub-tetrahedra have opposite signs), else
// fail() names it (its index, its number in the source, its measure); an element of negative
// measure is re-oriented (clockwise triangles, negative tetrahedra): PEM uses an element's node
// pairs and its measure, not the source's orientation convention.
template <int Dim>
Mesh<Dim> finish_mesh(RawMesh raw, const std::function<Vec<Dim>(const Vec<3>&)>& to_metres, const Fail& fail);

}  // namespace cleave::pem::detail
