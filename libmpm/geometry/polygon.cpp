#include "libmpm/geometry/polygon.hpp"

#include <algorithm>
#include <cmath>

#include "libmpm/core/error.hpp"
#include "libmpm/geometry/json_fields.hpp"
#include "libmpm/geometry/primitives.hpp"
#include "libmpm/geometry/shape_reader.hpp"

namespace cleave::geom {
namespace {

// Twice the signed area of triangle (a, b, c); > 0 when c is left of a->b.
double orient(const Vec<2>& a, const Vec<2>& b, const Vec<2>& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

int sign(double v) { return (v > 0) - (v < 0); }

// c is known to be collinear with a-b; is it inside the segment's box (hence on the segment)?
bool within(const Vec<2>& a, const Vec<2>& b, const Vec<2>& c) {
  return std::min(a.x(), b.x()) <= c.x() && c.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= c.y() && c.y() <= std::max(a.y(), b.y());
}

// Closed segments a-b and c-d share at least one point (crossing, touching or overlapping).
bool segments_meet(const Vec<2>& a, const Vec<2>& b, const Vec<2>& c, const Vec<2>& d) {
  const int o1 = sign(orient(a, b, c)), o2 = sign(orient(a, b, d));
  const int o3 = sign(orient(c, d, a)), o4 = sign(orient(c, d, b));
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  return (o1 == 0 && within(a, b, c)) || (o2 == 0 && within(a, b, d)) ||
         (o3 == 0 && within(c, d, a)) || (o4 == 0 && within(c, d, b));
}

}  // namespace

double signed_area(const Polyline& p) {
  const std::size_t n = p.size();
  double twice = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec<2>& a = p[i];
    const Vec<2>& b = p[(i + 1) % n];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * twice;
}

bool all_collinear(const Polyline& p, double tol) {
  if (p.size() < 3) return true;
  // Measure against the line through p[0] and the vertex farthest from it: the longest available
  // baseline keeps the direction well conditioned.
  std::size_t far = 0;
  for (std::size_t i = 1; i < p.size(); ++i)
    if ((p[i] - p[0]).squaredNorm() > (p[far] - p[0]).squaredNorm()) far = i;
  const double base = (p[far] - p[0]).norm();
  if (base == 0.0) return true;
  for (const Vec<2>& q : p)
    if (std::abs(orient(p[0], p[far], q)) / base > tol) return false;
  return true;
}

std::optional<std::pair<int, int>> find_self_intersection(const Polyline& p) {
  const int n = static_cast<int>(p.size());
  auto at = [&](int i) -> const Vec<2>& { return p[static_cast<std::size_t>(i % n)]; };
  for (int i = 0; i < n; ++i) {
    // Adjacent edges share a vertex by construction; they are only wrong if the second runs
    // straight back along the first (a zero-width spike).
    const Vec<2>& a = at(i);
    const Vec<2>& b = at(i + 1);
    const Vec<2>& c = at(i + 2);
    if (orient(a, b, c) == 0.0 && (b - a).dot(c - b) < 0.0) {
      const int e1 = i, e2 = (i + 1) % n;
      return std::make_pair(std::min(e1, e2), std::max(e1, e2));
    }
  }
  for (int i = 0; i < n; ++i) {
    for (int j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // adjacent through the closing vertex
      if (segments_meet(at(i), at(i + 1), at(j), at(j + 1))) return std::make_pair(i, j);
    }
  }
  return std::nullopt;
}

bool polygon_contains(const Polyline& p, const Vec<2>& x) {
  const std::size_t n = p.size();
  int winding = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec<2>& a = p[i];
    const Vec<2>& b = p[(i + 1) % n];
    const double o = orient(a, b, x);
    if (o == 0.0 && within(a, b, x)) return true;  // on the boundary: closed set
    // Half-open rule in y: an upward edge includes its start and excludes its end, a downward
    // edge the reverse, so a ray through a vertex is counted exactly once.
    if (a.y() <= x.y()) {
      if (b.y() > x.y() && o > 0.0) ++winding;
    } else if (b.y() <= x.y() && o < 0.0) {
      --winding;
    }
  }
  return winding != 0;
}

// --- scene readers: "polygon" and its extrusion "prism" ------------------------------------------
namespace {

using nlohmann::json;
using detail::index_path;
using detail::key_path;

// Reads "points" and checks that they form a simple polygon with non-zero area; a self-crossing
// outline has no meaningful inside, and silently picking one would seed the wrong body.
Polyline outline(const ShapeReader& r, const json& j, const std::string& path) {
  const std::string pp = key_path(path, "points");
  const json& v = detail::require(j, "points", path);
  if (!v.is_array() || v.size() < 3) {
    throw SceneError(pp, "a polygon needs at least 3 points [[x, y], ...], got " +
                             (v.is_array() ? std::to_string(v.size()) + " points" : detail::describe(v)));
  }
  Polyline p;
  for (std::size_t i = 0; i < v.size(); ++i) p.push_back(r.scaled_numbers<2>(v[i], index_path(pp, i), {"x", "y"}));

  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t next = (i + 1) % n;
    if (p[i] != p[next]) continue;
    const std::string hint = next == 0 ? "; the outline closes by itself, do not repeat the first point" : "";
    throw SceneError(index_path(pp, next == 0 ? i : next),
                     "repeats points[" + std::to_string(next == 0 ? next : i) + "]" + hint);
  }

  Box<2> box;
  for (const Vec<2>& q : p) box = box.united(Box<2>{q, q});
  const double extent = (box.hi - box.lo).maxCoeff();
  const double tol = 1e-12 * extent;  // relative: scenes in metres and in millimetres behave alike
  if (all_collinear(p, tol)) throw SceneError(pp, "polygon has zero area (all points lie on one line)");
  if (auto hit = find_self_intersection(p)) {
    auto edge = [n](int e) {
      return "points[" + std::to_string(e) + "]-points[" + std::to_string((static_cast<std::size_t>(e) + 1) % n) + "]";
    };
    throw SceneError(pp, "polygon is not simple: edge " + edge(hit->first) + " and edge " + edge(hit->second) +
                             " intersect (list the points in order around the outline)");
  }
  if (std::abs(signed_area(p)) <= tol * extent) throw SceneError(pp, "polygon has zero area");
  return p;
}

std::unique_ptr<Shape<2>> polygon(const ShapeReader& r, const json& j, const std::string& path) {
  return std::make_unique<Polygon>(outline(r, j, path));
}

std::unique_ptr<Shape<3>> prism(const ShapeReader& r, const json& j, const std::string& path) {
  Polyline section = outline(r, j, path);
  const std::string zp = key_path(path, "z");
  const json& zv = detail::require(j, "z", path);
  const Vec<2> z = r.scaled_numbers<2>(zv, zp, {"zmin", "zmax"});
  if (!(z[1] > z[0])) throw SceneError(zp, "zmax must be greater than zmin, got " + raw(zv));
  return std::make_unique<Prism>(std::move(section), z[0], z[1]);
}

}  // namespace

CLEAVE_REGISTER_SHAPE("polygon", 4, 2, {"type", "points"}, "prism", &polygon, nullptr)
CLEAVE_REGISTER_SHAPE("prism", 9, 3, {"type", "points", "z"}, "polygon", nullptr, &prism)

}  // namespace cleave::geom
