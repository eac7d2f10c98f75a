// 3D crack faces with their opening scaled, and their traces in a cutting plane
// (viz/raster/crack_section.hpp).
#include "viz/raster/crack_section.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

#include "viz/raster/rasterize.hpp"

namespace cleave::viz {

Point3 opened_face_point(const Point3& above, const Point3& below, double K, CrackFace face) {
  const Point3& x = face == CrackFace::Above ? above : below;
  Point3 r;
  for (std::size_t d = 0; d < 3; ++d) {
    const double mid = 0.5 * (above[d] + below[d]);
    r[d] = mid + K * (x[d] - mid);
  }
  return r;
}

namespace {

bool valid_triangle(const std::array<std::size_t, 3>& t, std::size_t n) { return t[0] < n && t[1] < n && t[2] < n; }

}  // namespace

std::vector<Point3> opened_face_points(const CrackSurfaces& s, double K, CrackFace face) {
  if (s.above.size() != s.below.size())
    throw std::invalid_argument("crack surfaces: " + std::to_string(s.above.size()) + " above and " +
                                std::to_string(s.below.size()) + " below points");
  std::vector<Point3> p(s.above.size());
  for (std::size_t i = 0; i < p.size(); ++i) p[i] = opened_face_point(s.above[i], s.below[i], K, face);
  return p;
}

double max_opening(const CrackSurfaces& s) {
  double m = 0;
  for (std::size_t i = 0; i < std::min(s.above.size(), s.below.size()); ++i) {
    const double dx = s.above[i][0] - s.below[i][0], dy = s.above[i][1] - s.below[i][1], dz = s.above[i][2] - s.below[i][2];
    m = std::max(m, std::sqrt(dx * dx + dy * dy + dz * dz));
  }
  return m;
}

std::vector<std::vector<std::array<double, 2>>> face_section(const CrackSurfaces& s, double K, CrackFace face,
                                                             const Point3& point, const Point3& normal) {
  const auto [u, w] = plane_axes(normal);  // throws for a zero normal
  const std::vector<Point3> p = opened_face_points(s, K, face);
  auto dot = [](const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  // Signed distances per point, not per triangle corner, so that triangles sharing an edge find the
  // same crossing, bit for bit, and the segments join.
  std::vector<double> d(p.size());
  for (std::size_t i = 0; i < p.size(); ++i)
    d[i] = normal[0] * (p[i][0] - point[0]) + normal[1] * (p[i][1] - point[1]) + normal[2] * (p[i][2] - point[2]);

  // A crossing is named by the mesh edge it lies on (i < j), or by a mesh point on the plane (i, i).
  using Key = std::pair<std::size_t, std::size_t>;
  std::map<Key, std::array<double, 2>> where;
  std::vector<std::array<Key, 2>> segments;
  auto crossing = [&](std::size_t i, std::size_t j) {
    if (i > j) std::swap(i, j);
    Key k{i, j};
    Point3 x;
    if (d[i] == 0) k = {i, i}, x = p[i];
    else if (d[j] == 0) k = {j, j}, x = p[j];
    else {
      const double t = d[i] / (d[i] - d[j]);
      for (std::size_t c = 0; c < 3; ++c) x[c] = p[i][c] + t * (p[j][c] - p[i][c]);
    }
    where.emplace(k, std::array<double, 2>{dot(u, x), dot(w, x)});
    return k;
  };
  for (const auto& t : s.triangles) {
    if (!valid_triangle(t, p.size())) continue;
    std::vector<Key> ends;
    for (int e = 0; e < 3; ++e) {
      const std::size_t i = t[static_cast<std::size_t>(e)], j = t[static_cast<std::size_t>((e + 1) % 3)];
      if ((d[i] >= 0) != (d[j] >= 0)) ends.push_back(crossing(i, j));
    }
    if (ends.size() == 2 && ends[0] != ends[1]) segments.push_back({ends[0], ends[1]});
  }

  // Join the segments at shared crossings: open chains from their ends first, then closed loops.
  std::map<Key, std::vector<std::size_t>> at;
  for (std::size_t k = 0; k < segments.size(); ++k)
    for (const Key& e : segments[k]) at[e].push_back(k);
  std::vector<char> used(segments.size(), 0);
  std::vector<std::vector<std::array<double, 2>>> out;
  auto walk = [&](Key from) {
    std::vector<std::array<double, 2>> line{where.at(from)};
    for (;;) {
      std::size_t next = segments.size();
      for (std::size_t k : at[from])
        if (!used[k]) {
          next = k;
          break;
        }
      if (next == segments.size()) break;
      used[next] = 1;
      from = segments[next][0] == from ? segments[next][1] : segments[next][0];
      line.push_back(where.at(from));
    }
    if (line.size() > 1) out.push_back(std::move(line));
  };
  for (const auto& [key, segs] : at)
    if (segs.size() == 1 && !used[segs[0]]) walk(key);
  for (std::size_t k = 0; k < segments.size(); ++k)
    if (!used[k]) walk(segments[k][0]);
  return out;
}

std::vector<std::array<double, 4>> section_barriers(const CrackSurfaces& s, const Point3& point, const Point3& normal) {
  std::vector<std::array<double, 4>> out;
  for (CrackFace face : {CrackFace::Above, CrackFace::Below})
    for (const auto& line : face_section(s, 1.0, face, point, normal))
      for (std::size_t i = 0; i + 1 < line.size(); ++i)
        out.push_back({line[i][0], line[i][1], line[i + 1][0], line[i + 1][1]});
  return out;
}

}  // namespace cleave::viz
