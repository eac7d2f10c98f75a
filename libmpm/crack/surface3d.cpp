#include "libmpm/crack/surface3d.hpp"

#include <cmath>
#include <set>

#include <Eigen/Geometry>

#include <nlohmann/json.hpp>

#include "libmpm/core/error.hpp"
#include "libmpm/core/json_reader.hpp"
#include "libmpm/crack/crossing3d.hpp"
#include "libmpm/crack/mesh3d.hpp"
#include "libmpm/crack/mesh_files.hpp"

namespace cleave::crack {
namespace {

// The surface of one form, as given (checked: crack/mesh3d.hpp) or generated at `size`.
TriMesh read_form(const nlohmann::json& j, const std::string& form, const std::string& at, double L, double size) {
  auto point = [&](const nlohmann::json& v, const std::string& p) { return ObjectReader::vec_of<3>(v, p, L); };
  TriMesh m;
  if (form == "quad") {
    if (!j.is_array() || j.size() != 4) throw SceneError(at, "expected 4 points [x, y, z]");
    for (int k = 0; k < 4; ++k) m.points.push_back(point(j[k], index_path(at, k)));
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
  } else if (form == "triangles") {
    if (!j.is_array() || j.empty()) throw SceneError(at, "expected a non-empty array of triangles");
    for (std::size_t k = 0; k < j.size(); ++k) {
      const std::string tp = index_path(at, k);
      if (!j[k].is_array() || j[k].size() != 3) throw SceneError(tp, "expected 3 points [x, y, z]");
      const auto n = static_cast<int32_t>(m.points.size());
      for (int v = 0; v < 3; ++v) m.points.push_back(point(j[k][v], index_path(tp, v)));
      m.triangles.push_back({n, n + 1, n + 2});
    }
    m = merge_identical_points(m);
  } else if (form == "mesh") {
    const ObjectReader r(j, at, {"points", "triangles"});
    const auto& P = r["points"];
    const auto& T = r["triangles"];
    if (!r.has("points") || !P.is_array() || P.size() < 3) throw SceneError(r.at("points"), "expected at least 3 points [x, y, z]");
    if (!r.has("triangles") || !T.is_array() || T.empty())
      throw SceneError(r.at("triangles"), "expected a non-empty array of [i, j, k] point indices");
    for (std::size_t k = 0; k < P.size(); ++k) m.points.push_back(point(P[k], index_path(r.at("points"), k)));
    for (std::size_t k = 0; k < T.size(); ++k) {
      const std::string tp = index_path(r.at("triangles"), k);
      if (!T[k].is_array() || T[k].size() != 3) throw SceneError(tp, "expected 3 point indices [i, j, k]");
      std::array<int32_t, 3> t;
      for (int v = 0; v < 3; ++v) {
        const auto i = ObjectReader::integer_within(T[k][v], 0, static_cast<long long>(P.size()) - 1);
        if (!i)
          throw SceneError(index_path(tp, v), "expected a point index from 0 to " + std::to_string(P.size() - 1) +
                                                  " (got " + T[k][v].dump() + ")");
        t[v] = static_cast<int32_t>(*i);
      }
      m.triangles.push_back(t);
    }
  } else if (form == "file") {
    if (!j.is_string()) throw SceneError(at, "expected a file name (.stl or .msh)");
    m = read_mesh_file(j.get<std::string>(), at);
    for (auto& x : m.points) x *= L;
  } else if (form == "rectangle") {
    const ObjectReader r(j, at, {"corner", "edges"});
    const auto& e = r["edges"];
    if (!r.has("edges") || !e.is_array() || e.size() != 2) throw SceneError(r.at("edges"), "expected two edge vectors [e1, e2]");
    const Vec<3> e1 = point(e[0], index_path(r.at("edges"), 0)), e2 = point(e[1], index_path(r.at("edges"), 1));
    if (!(e1.cross(e2).norm() > 1e-12 * e1.norm() * e2.norm()))
      throw SceneError(r.at("edges"), "the edges are parallel or zero: the rectangle has no area");
    return rectangle_mesh(r.vec<3>("corner", L), e1, e2, size);
  } else {  // ellipse
    const ObjectReader r(j, at, {"center", "normal", "major_axis", "semi_axes", "radius"});
    const Vec<3> n = r.vec<3>("normal");
    if (!(n.norm() > 0.0)) throw SceneError(r.at("normal"), "must not be zero");
    double a, b;
    Vec<3> major;
    if (r.has("radius") == r.has("semi_axes")) throw SceneError(at, "give exactly one of \"semi_axes\" [a, b] or \"radius\"");
    if (r.has("radius")) {
      a = b = r.positive("radius", L);
      major = std::abs(n.normalized().x()) < 0.9 ? Vec<3>::UnitX() : Vec<3>::UnitY();  // any direction in the plane
      if (r.has("major_axis")) major = r.vec<3>("major_axis");
    } else {
      const auto& ax = r["semi_axes"];
      if (!ax.is_array() || ax.size() != 2) throw SceneError(r.at("semi_axes"), "expected [a, b]");
      a = ObjectReader::number_of(ax[0], index_path(r.at("semi_axes"), 0)) * L;
      b = ObjectReader::number_of(ax[1], index_path(r.at("semi_axes"), 1)) * L;
      if (!(a > 0.0 && b > 0.0)) throw SceneError(r.at("semi_axes"), "must be positive");
      major = r.vec<3>("major_axis");
    }
    const Vec<3> nu = n.normalized();
    if (!((major - major.dot(nu) * nu).norm() > 1e-9 * major.norm()))
      throw SceneError(r.has("major_axis") ? r.at("major_axis") : at, "must not be zero or along the normal");
    return ellipse_mesh(r.vec<3>("center", L), n, major, a, b, size);
  }
  check_surface_mesh(m, at);
  return m;
}

}  // namespace

bool segment_hits_triangle(const Vec<3>& p, const Vec<3>& q, const Vec<3>& a, const Vec<3>& b,
                           const Vec<3>& c) {
  return segment_meets_triangle(p, q, a, b, c, [](const Vec<3>& a, const Vec<3>& b, const Vec<3>& c, const Vec<3>& d) {
    return detail::sgn(signed_volume(a, b, c, d));  // rounded: peridynamics' bonds, as they always were
  });
}

std::vector<Surface<3>> parse_surfaces3d(const nlohmann::json& cracks, const std::string& key_path,
                                         double length_scale, const SurfaceMeshing& meshing) {
  if (!cracks.is_array()) throw SceneError(key_path, "expected an array of cracks");
  std::vector<Surface<3>> out;
  std::set<std::string> names;
  for (std::size_t i = 0; i < cracks.size(); ++i) {
    const std::string path = index_path(key_path, i);
    const ObjectReader r(cracks[i], path,
                         {"name", "triangles", "quad", "mesh", "rectangle", "ellipse", "file", "element_size", "contact", "tips", "propagation",
                          "tip_cut"});
    Surface<3> s;
    s.name = r.string("name");
    if (s.name.empty()) throw SceneError(r.at("name"), "must not be empty");
    if (!names.insert(s.name).second) throw SceneError(r.at("name"), "duplicate crack name '" + s.name + "'");
    const char* forms[] = {"triangles", "quad", "mesh", "rectangle", "ellipse", "file"};
    const char* form = nullptr;
    for (const char* f : forms)
      if (r.has(f)) {
        if (form)
          throw SceneError(path, std::string("give one form of 3D crack surface, not both \"") + form + "\" and \"" + f +
                                     "\"");
        form = f;
      }
    if (!form)
      throw SceneError(path, "missing the surface: give one of \"triangles\", \"quad\", \"mesh\", \"rectangle\", "
                             "\"ellipse\", \"file\"");
    const double size = r.positive_or("element_size", meshing.default_size, length_scale);
    const std::string at = r.at(form);
    const TriMesh m = read_form(r[form], form, at, length_scale, size);
    const bool generated = std::string(form) == "rectangle" || std::string(form) == "ellipse";
    const TriMesh fine = generated || !meshing.refine_given ? m : refine(m, size);
    s.points = fine.points;
    s.simplices = fine.triangles;
    s.update_extent();
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace cleave::crack
