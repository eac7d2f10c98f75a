// Frozen-stress slices of 3D frames (viz/raster/slice.hpp): the slab's particles gathered into
// columns normal to the plane, their in-plane stress integrated through the slab.
#include "viz/raster/slice.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "viz/raster/footprints.hpp"
#include "viz/raster/rasterize.hpp"

namespace cleave::viz {

using detail::array_with;
using detail::finite3;

namespace {

struct Member {
  std::size_t p;  // particle index in the 3D frame
  double l;       // thickness it stands for inside the slab
};

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  const auto mid = v.begin() + std::ptrdiff_t(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace

ParticleFrame slice_plane(const ParticleFrame& f, std::array<double, 3> point, std::array<double, 3> normal,
                          double thickness) {
  if (!(thickness > 0) || !std::isfinite(thickness))
    throw std::invalid_argument("slice thickness must be positive and finite");
  const auto [u, w] = plane_axes(normal);  // throws for a zero normal
  const double len = std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
  for (double& c : normal) c /= len;
  auto dot = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  };
  const std::vector<double> size = particle_sizes(f);
  const double h = 0.5 * thickness;

  // The slab: each particle stands for the thickness of its edge s along the normal (a lattice of
  // cubes of edge s tiles a column with one particle per s, whatever the normal), and counts with
  // the part of it inside the slab, so a slab whose faces cut through a layer takes that layer in
  // part, not whole or not at all as rounding falls.
  std::vector<Member> slab;
  std::vector<double> sizes;
  for (std::size_t p = 0; p < f.x.size(); ++p) {
    if (!finite3(f.x[p])) continue;
    const double d = dot(normal, {f.x[p][0] - point[0], f.x[p][1] - point[1], f.x[p][2] - point[2]});
    const double l = std::min(d + 0.5 * size[p], h) - std::max(d - 0.5 * size[p], -h);
    if (l <= 0) continue;
    slab.push_back({p, l});
    sizes.push_back(size[p]);
  }
  ParticleFrame out;
  out.time = f.time;
  out.dim = 2;
  out.file = f.file;
  if (slab.empty()) return out;

  // Columns: bins of the median size, centred on the first particle's in-plane position, so that a
  // lattice column (particles at the same u, v up to their small displacements) is one bin.
  const double s = median(sizes);
  const double u0 = dot(u, f.x[slab.front().p]), w0 = dot(w, f.x[slab.front().p]);
  std::map<std::pair<long long, long long>, std::vector<Member>> columns;
  for (const Member& m : slab) {
    const double pu = dot(u, f.x[m.p]), pw = dot(w, f.x[m.p]);
    columns[{std::llround((pu - u0) / s), std::llround((pw - w0) / s)}].push_back(m);
  }

  const std::size_t n = columns.size();
  out.x.reserve(n);
  std::vector<double> weight;  // sum of l per column
  weight.reserve(n);
  for (const auto& [key, ms] : columns) {
    double su = 0, sw = 0, sl = 0;
    for (const Member& m : ms) su += m.l * dot(u, f.x[m.p]), sw += m.l * dot(w, f.x[m.p]), sl += m.l;
    out.x.push_back({su / sl, sw / sl, 0.0});
    weight.push_back(sl);
  }
  // Column sums of l * (per-particle values, c per particle), divided per column by `by`.
  auto gather = [&](const std::vector<double>& per, std::size_t c, const std::vector<double>& by) {
    std::vector<double> r(n * c, 0.0);
    std::size_t k = 0;
    for (const auto& [key, ms] : columns) {
      for (const Member& m : ms)
        for (std::size_t j = 0; j < c; ++j) r[k * c + j] += m.l * per[m.p * c + j];
      for (std::size_t j = 0; j < c; ++j) r[k * c + j] /= by[k];
      ++k;
    }
    return r;
  };

  for (const auto& [name, a] : f.arrays) {
    const std::size_t c = static_cast<std::size_t>(a.components);
    if (a.components < 1 || a.values.size() != f.x.size() * c) continue;  // inconsistent: dropped
    PointArray b;
    b.components = a.components;
    if (name == "material") {  // an id: the heaviest particle's, never a mean of two materials
      b.values.reserve(n * c);
      for (const auto& [key, ms] : columns) {
        const Member* best = &ms.front();
        for (const Member& m : ms)
          if (m.l > best->l) best = &m;
        b.values.insert(b.values.end(), &a.values[best->p * c], &a.values[best->p * c] + c);
      }
    } else {
      b.values = gather(a.values, c, weight);
    }
    out.arrays[name] = std::move(b);
  }
  // The in-plane tensors: the strain as a mean (for the footprints), the stress integrated through
  // the slab and divided by its thickness (for fringes with the slab thickness).
  const std::vector<double> by_thickness(n, thickness);
  for (const char* name : {"strain", "stress"}) {
    const PointArray* t6 = array_with(f, name, 6);
    if (!t6) continue;
    const std::size_t c = static_cast<std::size_t>(t6->components);
    std::vector<double> per(3 * f.x.size(), 0.0);
    for (const Member& m : slab) {
      const auto t = detail::in_plane_tensor(&t6->values[m.p * c], u, w);
      std::copy(t.begin(), t.end(), &per[3 * m.p]);
    }
    PointArray b;
    b.components = 3;
    b.values = gather(per, 3, std::string(name) == "stress" ? by_thickness : weight);
    out.arrays[std::string(name) + "_uv"] = std::move(b);
  }
  out.arrays["size"] = PointArray{1, std::vector<double>(n, s)};
  return out;
}

}  // namespace cleave::viz
