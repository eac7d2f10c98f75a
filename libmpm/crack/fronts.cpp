#include "libmpm/crack/fronts.hpp"

#include <map>
#include <stdexcept>

#include <Eigen/Geometry>

namespace cleave::crack {
namespace {

void add_frames(const Surface<3>& s, const std::vector<Vec<3>>& normals, CrackFront& f) {
  const std::size_t m = f.nodes.size();
  for (std::size_t k = 0; k < m; ++k) {
    const Vec<3>& x = s.points[f.nodes[k]];
    const bool has_prev = f.closed || k > 0, has_next = f.closed || k + 1 < m;
    const Vec<3>& prev = has_prev ? s.points[f.nodes[(k + m - 1) % m]] : x;
    const Vec<3>& next = has_next ? s.points[f.nodes[(k + 1) % m]] : x;
    // The mean of the two edges' unit directions (one edge at an end of an open front).
    Vec<3> t = Vec<3>::Zero();
    if (has_prev) t += (x - prev).normalized();
    if (has_next) t += (next - x).normalized();
    const Vec<3> n = normals[f.nodes[k]];
    t = (t - t.dot(n) * n).normalized();
    f.normal.push_back(n);
    f.tangent.push_back(t);
    f.ahead.push_back(t.cross(n));  // the triangles lie on the left of the boundary, seen from above
  }
}

}  // namespace

// (The sum of the normals (b - a) x (c - a) of the triangles around each point, whose length is
// twice the area: area-weighted.)
std::vector<Vec<3>> point_normals(const Surface<3>& s) {
  std::vector<Vec<3>> n(s.points.size(), Vec<3>::Zero());
  for (const auto& t : s.simplices) {
    const Vec<3> a = (s.points[t[1]] - s.points[t[0]]).cross(s.points[t[2]] - s.points[t[0]]);
    for (int k = 0; k < 3; ++k) n[t[k]] += a;
  }
  for (auto& v : n)
    if (v.squaredNorm() > 0.0) v.normalize();
  return n;
}

std::vector<CrackFront> crack_fronts(const Surface<3>& s, const std::function<bool(const Vec<3>&)>& inside) {
  // Boundary edges, oriented as in their triangles, chained start -> end.
  std::map<int32_t, int32_t> next;
  for (const auto& e : s.boundary())
    if (!next.emplace(e[0], e[1]).second)
      throw std::invalid_argument("crack '" + s.name + "': two boundary edges start at one point (the surface "
                                  "touches itself at a vertex)");
  const std::vector<Vec<3>> normals = point_normals(s);
  std::vector<CrackFront> out;
  while (!next.empty()) {
    std::vector<int32_t> loop{next.begin()->first};  // the lowest index: a deterministic start
    for (int32_t p = next.begin()->second; p != loop[0];) {
      loop.push_back(p);
      const auto it = next.find(p);
      if (it == next.end()) throw std::invalid_argument("crack '" + s.name + "': its boundary is not closed");
      p = it->second;
    }
    for (const int32_t p : loop) next.erase(p);
    const std::size_t m = loop.size();
    std::vector<uint8_t> front(m);  // edge k: loop[k] -> loop[k + 1]
    bool all = true, any = false;
    for (std::size_t k = 0; k < m; ++k) {
      front[k] = inside(0.5 * (s.points[loop[k]] + s.points[loop[(k + 1) % m]]));
      all = all && front[k], any = any || front[k];
    }
    if (all) {
      CrackFront f;
      f.nodes = loop, f.closed = true;
      add_frames(s, normals, f);
      out.push_back(std::move(f));
      continue;
    }
    if (!any) continue;
    // Runs of front edges, starting after a mouth edge so that no run wraps around the start.
    std::size_t start = 0;
    while (front[start]) ++start;
    for (std::size_t i = 1; i <= m; ++i) {
      const std::size_t k = (start + i) % m;
      if (!front[k]) continue;
      CrackFront f;
      f.nodes.push_back(loop[k]);
      std::size_t j = k;
      while (front[j]) {
        f.nodes.push_back(loop[(j + 1) % m]);
        j = (j + 1) % m;
        ++i;
      }
      --i;
      add_frames(s, normals, f);
      out.push_back(std::move(f));
    }
  }
  return out;
}

}  // namespace cleave::crack
