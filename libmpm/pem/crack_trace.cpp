#include "libmpm/pem/crack_trace.hpp"

#include <algorithm>
#include <tuple>

#include "libmpm/pem/pem_scene.hpp"

namespace cleave::pem {

template <int Dim>
CrackTracer<Dim>::CrackTracer(const PemSystem<Dim>& m) : m_(m) {
  const auto& N = m.pairs;
  const std::size_t n = m.points.x0.size();
  std::vector<std::tuple<int32_t, int32_t, int32_t>> pe;  // (i, j, element)
  std::vector<std::pair<int32_t, int32_t>> pp;
  for (std::size_t e = 0; e < m.mesh.element_count(); ++e) {
    element_pairs(m.mesh, e, pp);
    for (auto [i, j] : pp) pe.emplace_back(i, j, static_cast<int32_t>(e));
  }
  std::sort(pe.begin(), pe.end());
  // Canonical entries in (i, j) order: particle i's entries with partner > i.
  for (std::size_t i = 0; i < n; ++i)
    for (int64_t e = N.offset[i]; e < N.offset[i + 1]; ++e)
      if (static_cast<std::size_t>(N.partner[e]) > i) entry_.push_back(e);
  start_.assign(entry_.size() + 1, 0);
  std::size_t c = 0, q = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (int64_t e = N.offset[i]; e < N.offset[i + 1]; ++e) {
      const int32_t j = N.partner[e];
      if (static_cast<std::size_t>(j) <= i) continue;
      while (q < pe.size() && std::make_pair(std::get<0>(pe[q]), std::get<1>(pe[q])) < std::make_pair(int32_t(i), j)) ++q;
      for (; q < pe.size() && std::get<0>(pe[q]) == int32_t(i) && std::get<1>(pe[q]) == j; ++q)
        elements_.push_back(std::get<2>(pe[q]));
      start_[++c] = static_cast<int64_t>(elements_.size());
    }
}

template <int Dim>
io::PointSet CrackTracer<Dim>::trace(const std::vector<Vec<Dim>>& y, const PemPairs& N) const {
  io::PointSet ps;
  io::PointArray initial{"initial", 1, {}};
  auto point = [&](const Vec<Dim>& x, double init) {
    for (int d = 0; d < 3; ++d) ps.points.push_back(d < Dim ? x[d] : 0.0);
    initial.values.push_back(init);
    return static_cast<int64_t>(ps.size() - 1);
  };
  const auto& mesh = m_.mesh;
  for (std::size_t c = 0; c < entry_.size(); ++c) {
    const int64_t e = entry_[c];
    if (N.intact[e]) continue;
    // The lower particle of the pair: the owner of entry e.
    const auto i = static_cast<int32_t>(std::upper_bound(N.offset.begin(), N.offset.end(), e) - N.offset.begin() - 1);
    const int32_t j = N.partner[e];
    const double init = N.initial[e] ? 0.0 : 1.0;
    const Vec<Dim> mid = 0.5 * (y[i] + y[j]);
    for (int64_t q = start_[c]; q < start_[c + 1]; ++q) {
      const auto el = static_cast<std::size_t>(elements_[q]);
      const int k = mesh.nodes_of(el);
      const int32_t* en = mesh.element(el);
      Vec<Dim> centre = Vec<Dim>::Zero();
      for (int a = 0; a < k; ++a) centre += y[en[a]];
      centre /= k;
      if constexpr (Dim == 2) {
        const int64_t a = point(mid, init), b = point(centre, init);
        ps.polylines.push_back({a, b});
      } else {
        // The element's other nodes: each with i and j makes a face holding the pair (tetrahedra: two).
        std::vector<int32_t> others;
        for (int a = 0; a < k; ++a)
          if (en[a] != i && en[a] != j) others.push_back(en[a]);
        if (others.size() != 2) {  // hexahedra: the piece as the segment to the centroid
          const int64_t a = point(mid, init), b = point(centre, init);
          ps.polylines.push_back({a, b});
          continue;
        }
        const Vec<Dim> f0 = (y[i] + y[j] + y[others[0]]) / 3.0, f1 = (y[i] + y[j] + y[others[1]]) / 3.0;
        const int64_t pm = point(mid, init), p0 = point(f0, init), pc = point(centre, init), p1 = point(f1, init);
        ps.triangles.push_back({pm, p0, pc});
        ps.triangles.push_back({pm, pc, p1});
      }
    }
  }
  ps.arrays.push_back(std::move(initial));
  return ps;
}

template class CrackTracer<2>;
template class CrackTracer<3>;

}  // namespace cleave::pem
