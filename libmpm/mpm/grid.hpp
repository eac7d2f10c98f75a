// The regular background grid: geometry (origin, cell size, node counts) and the node arrays the
// MPM step fills and discards every step (Task 8). Node index: x slowest, last axis fastest, so
// that particles stored cell column by cell column touch neighbouring memory.
#pragma once
#include <array>
#include <vector>

#include "libmpm/core/types.hpp"

namespace cleave {

template <int Dim>
struct GridGeometry {
  Vec<Dim> origin = Vec<Dim>::Zero();
  double h = 1.0;               // cell size (square/cubic cells)
  std::array<int, Dim> nodes{};  // nodes per axis (cells + 1)

  std::size_t node_count() const {
    std::size_t n = 1;
    for (int d = 0; d < Dim; ++d) n *= static_cast<std::size_t>(nodes[d]);
    return n;
  }
  Vec<Dim> upper() const {
    Vec<Dim> u;
    for (int d = 0; d < Dim; ++d) u[d] = origin[d] + h * (nodes[d] - 1);
    return u;
  }
  std::size_t index(const std::array<int, Dim>& ijk) const {
    std::size_t idx = static_cast<std::size_t>(ijk[0]);
    for (int d = 1; d < Dim; ++d) idx = idx * nodes[d] + ijk[d];
    return idx;
  }
  Vec<Dim> position(const std::array<int, Dim>& ijk) const {
    Vec<Dim> p;
    for (int d = 0; d < Dim; ++d) p[d] = origin[d] + h * ijk[d];
    return p;
  }
  // Strides for each axis in the linear node index.
  std::array<std::size_t, Dim> strides() const {
    std::array<std::size_t, Dim> s{};
    s[Dim - 1] = 1;
    for (int d = Dim - 2; d >= 0; --d) s[d] = s[d + 1] * nodes[d + 1];
    return s;
  }
};

// Node fields of a single velocity field (cracks add more fields in a later module).
template <int Dim>
struct GridFields {
  std::vector<double> mass;
  std::vector<Vec<Dim>> momentum;
  std::vector<Vec<Dim>> force;
  void resize(std::size_t n) {
    mass.assign(n, 0.0);
    momentum.assign(n, Vec<Dim>::Zero());
    force.assign(n, Vec<Dim>::Zero());
  }
};

}  // namespace cleave
