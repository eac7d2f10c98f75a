#include "libmpm/crack/mesh3d.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include <Eigen/Geometry>

#include "libmpm/core/error.hpp"
#include "libmpm/crack/crossing3d.hpp"

namespace cleave::crack {
namespace {

std::string point_text(const Vec<3>& x) {
  char b[96];
  std::snprintf(b, sizeof b, "(%.6g, %.6g, %.6g)", x.x(), x.y(), x.z());
  return b;
}

int cells_for(double length, double size) { return std::max(1, static_cast<int>(std::ceil(length / size - 1e-9))); }

}  // namespace

TriMesh rectangle_mesh(const Vec<3>& corner, const Vec<3>& e1, const Vec<3>& e2, double size) {
  const int nx = cells_for(e1.norm(), size), ny = cells_for(e2.norm(), size);
  TriMesh m;
  for (int i = 0; i <= nx; ++i)
    for (int j = 0; j <= ny; ++j) m.points.push_back(corner + (double(i) / nx) * e1 + (double(j) / ny) * e2);
  auto id = [&](int i, int j) { return static_cast<int32_t>(i * (ny + 1) + j); };
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j) {
      const int32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2 == 0) {  // alternating diagonals: no preferred direction
        m.triangles.push_back({a, b, c}), m.triangles.push_back({a, c, d});
      } else {
        m.triangles.push_back({a, b, d}), m.triangles.push_back({b, c, d});
      }
    }
  return m;
}

TriMesh ellipse_mesh(const Vec<3>& centre, const Vec<3>& normal, const Vec<3>& major, double a, double b,
                     double size) {
  const Vec<3> n = normal.normalized();
  const Vec<3> u = (major - major.dot(n) * n).normalized(), v = n.cross(u);
  const int rings = cells_for(std::max(a, b), size);
  TriMesh m;
  m.points.push_back(centre);
  std::vector<int32_t> inner{0};  // ring k - 1's point indices (ring 0: the centre)
  for (int k = 1; k <= rings; ++k) {
    const int count = 6 * k;
    const double r = double(k) / rings;
    std::vector<int32_t> outer;
    for (int j = 0; j < count; ++j) {
      const double t = 2.0 * std::numbers::pi * j / count;
      outer.push_back(static_cast<int32_t>(m.points.size()));
      m.points.push_back(centre + (a * r * std::cos(t)) * u + (b * r * std::sin(t)) * v);
    }
    // Join the rings by walking both, each step closing the triangle with the shorter new edge
    // (inner -> outer -> next outer, or inner -> outer -> next inner: both counter-clockwise about
    // n), which keeps the triangles near equilateral on an ellipse too.
    const int ni = static_cast<int>(inner.size());
    if (ni == 1) {
      for (int j = 0; j < count; ++j) m.triangles.push_back({0, outer[j], outer[(j + 1) % count]});
    } else {
      int i = 0, j = 0;
      while (i < ni || j < count) {
        const auto& X = m.points;
        const bool take_outer =
            j < count && (i == ni || (X[outer[(j + 1) % count]] - X[inner[i]]).squaredNorm() <
                                         (X[inner[(i + 1) % ni]] - X[outer[j]]).squaredNorm());
        if (take_outer) {
          m.triangles.push_back({inner[i % ni], outer[j], outer[(j + 1) % count]});
          ++j;
        } else {
          m.triangles.push_back({inner[i], outer[j % count], inner[(i + 1) % ni]});
          ++i;
        }
      }
    }
    inner = std::move(outer);
  }
  return m;
}

TriMesh refine(const TriMesh& m, double size) {
  double longest = 0.0;
  for (const auto& t : m.triangles)
    for (int e = 0; e < 3; ++e) longest = std::max(longest, (m.points[t[(e + 1) % 3]] - m.points[t[e]]).norm());
  const int k = cells_for(longest, size);
  if (k == 1) return m;
  // A lattice point is the weights it gives to the original vertices, in vertex order; the same
  // key from two triangles is the same point.
  using Key = std::array<std::pair<int32_t, int>, 3>;
  std::map<Key, int32_t> index;
  TriMesh out;
  auto point = [&](const std::array<int32_t, 3>& t, int wb, int wc) {
    std::array<std::pair<int32_t, int>, 3> w = {{{t[0], k - wb - wc}, {t[1], wb}, {t[2], wc}}};
    std::sort(w.begin(), w.end());
    Key key{};
    int n = 0;
    for (const auto& [id, wt] : w)
      if (wt > 0) key[n++] = {id, wt};
    for (; n < 3; ++n) key[n] = {-1, 0};
    const auto [it, added] = index.try_emplace(key, static_cast<int32_t>(out.points.size()));
    if (added) {
      Vec<3> x = Vec<3>::Zero();
      for (const auto& [id, wt] : key)
        if (id >= 0) x += (double(wt) / k) * m.points[id];
      out.points.push_back(x);
    }
    return it->second;
  };
  for (const auto& t : m.triangles)
    for (int i = 0; i < k; ++i)
      for (int j = 0; i + j < k; ++j) {
        out.triangles.push_back({point(t, i, j), point(t, i + 1, j), point(t, i, j + 1)});
        if (i + j < k - 1) out.triangles.push_back({point(t, i + 1, j), point(t, i + 1, j + 1), point(t, i, j + 1)});
      }
  return out;
}

TriMesh merge_identical_points(const TriMesh& m) {
  std::map<std::array<double, 3>, int32_t> index;
  std::vector<int32_t> map(m.points.size());
  TriMesh out;
  for (std::size_t p = 0; p < m.points.size(); ++p) {
    const auto& x = m.points[p];
    const auto [it, added] = index.try_emplace({x.x(), x.y(), x.z()}, static_cast<int32_t>(out.points.size()));
    if (added) out.points.push_back(x);
    map[p] = it->second;
  }
  for (const auto& t : m.triangles) out.triangles.push_back({map[t[0]], map[t[1]], map[t[2]]});
  return out;
}

TriMesh clip_to(const TriMesh& m, const std::function<bool(const Vec<3>&)>& inside) {
  std::vector<int8_t> in(m.points.size());
  for (std::size_t p = 0; p < m.points.size(); ++p) in[p] = inside(m.points[p]);
  std::vector<int32_t> map(m.points.size(), -1);
  TriMesh out;
  for (const auto& t : m.triangles) {
    if (!in[t[0]] && !in[t[1]] && !in[t[2]]) continue;
    std::array<int32_t, 3> nt;
    for (int e = 0; e < 3; ++e) {
      if (map[t[e]] < 0) map[t[e]] = static_cast<int32_t>(out.points.size()), out.points.push_back(m.points[t[e]]);
      nt[e] = map[t[e]];
    }
    out.triangles.push_back(nt);
  }
  return out;
}

void check_surface_mesh(const TriMesh& m, const std::string& path) {
  const auto& P = m.points;
  const auto& T = m.triangles;
  auto tri_text = [&](std::size_t k) {
    return "triangle " + std::to_string(k) + " " + point_text(P[T[k][0]]) + " " + point_text(P[T[k][1]]) + " " +
           point_text(P[T[k][2]]);
  };
  for (std::size_t k = 0; k < T.size(); ++k) {
    const Vec<3>&a = P[T[k][0]], &b = P[T[k][1]], &c = P[T[k][2]];
    const double scale = std::max({(b - a).norm(), (c - a).norm(), (c - b).norm()});
    if (!((b - a).cross(c - a).norm() > 1e-12 * scale * scale))
      throw SceneError(path, tri_text(k) + " is degenerate (zero area)");
  }
  // Edges: each directed edge once; the reverse edge is its neighbour's.
  std::map<std::pair<int32_t, int32_t>, std::vector<std::size_t>> uses;  // sorted edge -> triangles
  std::map<std::pair<int32_t, int32_t>, std::size_t> directed;
  for (std::size_t k = 0; k < T.size(); ++k)
    for (int e = 0; e < 3; ++e) {
      const int32_t a = T[k][e], b = T[k][(e + 1) % 3];
      auto& u = uses[{std::min(a, b), std::max(a, b)}];
      u.push_back(k);
      if (u.size() > 2)
        throw SceneError(path, "the edge " + point_text(P[a]) + " - " + point_text(P[b]) + " is shared by " +
                                   std::to_string(u.size()) + " triangles (" + std::to_string(u[0]) + ", " +
                                   std::to_string(u[1]) + ", " + std::to_string(u[2]) +
                                   "): a crack surface must be a manifold");
      const auto [it, added] = directed.try_emplace({a, b}, k);
      if (!added)
        throw SceneError(path, "triangles " + std::to_string(it->second) + " and " + std::to_string(k) +
                                   " are oriented inconsistently (both run along their shared edge " + point_text(P[a]) +
                                   " -> " + point_text(P[b]) +
                                   "): a crack's above side is the side its triangles' normals point to");
    }
  // Self-intersection: triangles with no common vertex whose boxes overlap, tested edge against
  // triangle both ways (two triangles that meet off-plane meet along a segment whose ends lie on
  // edges of one or the other). Triangles that overlap within one plane are not detected.
  std::vector<Vec<3>> lo(T.size()), hi(T.size());
  for (std::size_t k = 0; k < T.size(); ++k) {
    lo[k] = P[T[k][0]].cwiseMin(P[T[k][1]]).cwiseMin(P[T[k][2]]);
    hi[k] = P[T[k][0]].cwiseMax(P[T[k][1]]).cwiseMax(P[T[k][2]]);
  }
  std::vector<std::size_t> order(T.size());
  for (std::size_t k = 0; k < T.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return lo[x].x() < lo[y].x(); });
  // Exact signs: the points of a generated or refined plane surface are coplanar only to rounding,
  // and rounded signs made neighbouring triangles of one plane "intersect".
  const auto exact = [](const Vec<3>& a, const Vec<3>& b, const Vec<3>& c, const Vec<3>& d) {
    return volume_sign(a, b, c, d);
  };
  auto edges_hit = [&](std::size_t s, std::size_t t) {
    for (int e = 0; e < 3; ++e)
      if (segment_meets_triangle(P[T[s][e]], P[T[s][(e + 1) % 3]], P[T[t][0]], P[T[t][1]], P[T[t][2]], exact))
        return true;
    return false;
  };
  for (std::size_t i = 0; i < order.size(); ++i) {
    const std::size_t s = order[i];
    for (std::size_t j = i + 1; j < order.size() && lo[order[j]].x() <= hi[s].x(); ++j) {
      const std::size_t t = order[j];
      if ((lo[t].array() > hi[s].array()).any() || (lo[s].array() > hi[t].array()).any()) continue;
      bool shared = false;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) shared = shared || T[s][a] == T[t][b];
      if (shared) continue;
      if (edges_hit(s, t) || edges_hit(t, s))
        throw SceneError(path, "self-intersecting surface: " + tri_text(std::min(s, t)) + " and " +
                                   tri_text(std::max(s, t)) + " intersect");
    }
  }
}

}  // namespace cleave::crack
