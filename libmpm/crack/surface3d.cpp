#include "libmpm/crack/surface3d.hpp"

#include <cmath>
#include <set>

#include <Eigen/Geometry>

#include <nlohmann/json.hpp>

#include "libmpm/core/error.hpp"
#include "libmpm/core/json_reader.hpp"

namespace cleave::crack {
namespace {

// Sign of the volume of tetrahedron (a, b, c, d): positive when d lies on the side of the
// counter-clockwise normal of (a, b, c).
int orient3d(const Vec<3>& a, const Vec<3>& b, const Vec<3>& c, const Vec<3>& d) {
  const double v = (b - a).cross(c - a).dot(d - a);
  return (v > 0.0) - (v < 0.0);
}

}  // namespace

bool segment_hits_triangle(const Vec<3>& p, const Vec<3>& q, const Vec<3>& a, const Vec<3>& b,
                           const Vec<3>& c) {
  const int sp = orient3d(a, b, c, p), sq = orient3d(a, b, c, q);
  if (sp * sq > 0 || (sp == 0 && sq == 0)) return false;  // same side, or in the plane
  // The line p-q meets the plane inside the closed triangle iff it sees the three edges turning
  // the same way (zero: through an edge or a vertex, which counts).
  const int e0 = orient3d(p, q, a, b), e1 = orient3d(p, q, b, c), e2 = orient3d(p, q, c, a);
  const bool has_neg = e0 < 0 || e1 < 0 || e2 < 0, has_pos = e0 > 0 || e1 > 0 || e2 > 0;
  return !(has_neg && has_pos);
}

std::vector<Crack3D> parse_cracks3d(const nlohmann::json& cracks, const std::string& key_path,
                                    double length_scale) {
  if (!cracks.is_array()) throw SceneError(key_path, "expected an array of cracks");
  std::vector<Crack3D> out;
  std::set<std::string> names;
  auto point = [&](const nlohmann::json& j, const std::string& path) {
    return ObjectReader::vec_of<3>(j, path, length_scale);
  };
  for (std::size_t i = 0; i < cracks.size(); ++i) {
    const std::string path = key_path + "[" + std::to_string(i) + "]";
    ObjectReader r(cracks[i], path, {"name", "triangles", "quad"});
    Crack3D c;
    c.name = r.string("name");
    if (c.name.empty()) throw SceneError(r.at("name"), "must not be empty");
    if (!names.insert(c.name).second) throw SceneError(r.at("name"), "duplicate crack name '" + c.name + "'");
    if (r.has("triangles") == r.has("quad"))
      throw SceneError(path, "give exactly one of \"triangles\" or \"quad\" for a 3D crack surface");
    if (r.has("quad")) {
      const auto& q = r["quad"];
      if (!q.is_array() || q.size() != 4) throw SceneError(r.at("quad"), "expected 4 points [x, y, z]");
      std::array<Vec<3>, 4> p;
      for (int k = 0; k < 4; ++k) p[k] = point(q[k], r.at("quad") + "[" + std::to_string(k) + "]");
      c.triangles.push_back({p[0], p[1], p[2]});
      c.triangles.push_back({p[0], p[2], p[3]});
    } else {
      const auto& t = r["triangles"];
      if (!t.is_array() || t.empty()) throw SceneError(r.at("triangles"), "expected a non-empty array of triangles");
      for (std::size_t k = 0; k < t.size(); ++k) {
        const std::string tp = r.at("triangles") + "[" + std::to_string(k) + "]";
        if (!t[k].is_array() || t[k].size() != 3) throw SceneError(tp, "expected 3 points [x, y, z]");
        c.triangles.push_back({point(t[k][0], tp + "[0]"), point(t[k][1], tp + "[1]"), point(t[k][2], tp + "[2]")});
      }
    }
    c.lo = c.triangles[0][0];
    c.hi = c.lo;
    for (std::size_t k = 0; k < c.triangles.size(); ++k) {
      const auto& T = c.triangles[k];
      const double area2 = (T[1] - T[0]).cross(T[2] - T[0]).norm();
      const double scale = std::max({(T[1] - T[0]).norm(), (T[2] - T[0]).norm(), (T[2] - T[1]).norm()});
      if (!(area2 > 1e-12 * scale * scale))
        throw SceneError(r.has("quad") ? r.at("quad") : r.at("triangles") + "[" + std::to_string(k) + "]",
                         "degenerate triangle (zero area)");
      for (const auto& v : T) c.lo = c.lo.cwiseMin(v), c.hi = c.hi.cwiseMax(v);
    }
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace cleave::crack
