// The neutral in-memory form of one output frame: points plus named per-point arrays. Solvers fill
// it (2D data padded with z = 0) and the writers serialise it, so no writer knows about particles.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace cleave::io {

// One point-data array; values.size() == components * n_points, stored point-major
// (all components of point 0, then point 1, ...), which is exactly VTK's tuple layout.
struct PointArray {
  std::string name;
  int components = 1;
  std::vector<double> values;
};

struct PointSet {
  std::vector<double> points;  // 3 per point (2D data padded with z = 0)
  std::vector<PointArray> arrays;  // point data
  // Optional paths through the points (crack paths, 3D crack fronts) and triangles (3D crack
  // surfaces). With neither, every point becomes a VTK_VERTEX cell (type 1); otherwise each path is
  // written as VTK_LINE cells (type 3), one per segment in path order (a one-point path: a vertex),
  // then the triangles as VTK_TRIANGLE cells (type 5), and there are no other cells. Not
  // VTK_POLY_LINE (type 4): meshio drops it.
  std::vector<std::vector<int64_t>> polylines;
  std::vector<std::array<int64_t, 3>> triangles;
  std::size_t size() const { return points.size() / 3; }
};

}  // namespace cleave::io
