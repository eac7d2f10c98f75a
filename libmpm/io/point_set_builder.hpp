// Builds a particle frame (io::PointSet) the same way for every method: the positions, then each
// requested point array (the scene's output.fields), with the stress and its derived scalars written
// alike by all of them.
#pragma once
#include <algorithm>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "libmpm/core/types.hpp"
#include "libmpm/io/particle_fields.hpp"
#include "libmpm/io/point_set.hpp"

namespace cleave::io {

template <int Dim>
class PointSetBuilder {
 public:
  // `position(p)` gives point p's position (Vec<Dim>).
  template <class Position>
  PointSetBuilder(const std::set<std::string>& fields, std::size_t n, Position&& position) : fields_(fields), n_(n) {
    ps_.points.assign(3 * n, 0.0);
    for (std::size_t p = 0; p < n; ++p) {
      const Vec<Dim> x = position(p);
      for (int d = 0; d < Dim; ++d) ps_.points[3 * p + d] = x[d];
    }
  }
  bool wants(const char* name) const { return fields_.count(name) != 0; }
  // Adds the array `name` of `comps` components when it is requested; fill(p, out) writes point p's.
  template <class Fill>
  void add(const char* name, int comps, Fill&& fill) {
    if (!wants(name)) return;
    PointArray a{name, comps, std::vector<double>(comps * n_, 0.0)};
    for (std::size_t p = 0; p < n_; ++p) fill(p, &a.values[comps * p]);
    ps_.arrays.push_back(std::move(a));
  }
  // A vector per point, padded to 3 components (2D: z = 0).
  void add_vectors(const char* name, const std::vector<Vec<Dim>>& v) {
    add(name, 3, [&](std::size_t p, double* o) { for (int d = 0; d < Dim; ++d) o[d] = v[p][d]; });
  }
  template <class Value>
  void add_scalars(const char* name, Value&& value) {
    add(name, 1, [&](std::size_t p, double* o) { o[0] = value(p); });
  }
  // "stress" (VTK's 6 components), "von_mises" and "principal_stress_difference" from one stress per
  // point; `stress(p)` gives point p's.
  template <class Stress>
  void add_stress(Stress&& stress) {
    add("stress", 6, [&](std::size_t p, double* o) { const auto t = to_vtk6<Dim>(stress(p)); std::copy(t.begin(), t.end(), o); });
    add_scalars("von_mises", [&](std::size_t p) { return von_mises<Dim>(stress(p)); });
    add_scalars("principal_stress_difference", [&](std::size_t p) { return principal_stress_difference<Dim>(stress(p)); });
  }
  bool wants_stress() const { return wants("stress") || wants("von_mises") || wants("principal_stress_difference"); }
  PointSet take() { return std::move(ps_); }

 private:
  const std::set<std::string>& fields_;
  std::size_t n_;
  PointSet ps_;
};

}  // namespace cleave::io
