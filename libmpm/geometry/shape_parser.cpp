// parse_shape: scene JSON -> Shape. All validation lives here so that the shape classes can stay
// plain geometry; every error names the scene key path of the value that is wrong.
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "libmpm/core/error.hpp"
#include "libmpm/geometry/csg.hpp"
#include "libmpm/geometry/json_fields.hpp"
#include "libmpm/geometry/primitives.hpp"
#include "libmpm/geometry/shape.hpp"

namespace cleave::geom {
namespace {

using nlohmann::json;
using detail::index_path;
using detail::key_path;

struct TypeInfo {
  std::string name;
  int dim;  // 2, 3, or 0 for both
  std::vector<std::string> keys;
  std::string counterpart;  // the nearest type of the other dimension, for the mismatch hint
};

const std::vector<TypeInfo>& type_table() {
  static const std::vector<TypeInfo> table = {
      {"rectangle", 2, {"type", "min", "max"}, "box"},
      {"disk", 2, {"type", "center", "radius"}, "sphere or cylinder"},
      {"ellipse", 2, {"type", "center", "semi_axes", "angle"}, "ellipsoid"},
      {"polygon", 2, {"type", "points"}, "prism"},
      {"box", 3, {"type", "min", "max"}, "rectangle"},
      {"sphere", 3, {"type", "center", "radius"}, "disk"},
      {"cylinder", 3, {"type", "center", "axis", "radius", "length"}, "disk"},
      {"ellipsoid", 3, {"type", "center", "semi_axes"}, "ellipse"},
      {"prism", 3, {"type", "points", "z"}, "polygon"},
      {"union", 0, {"type", "shapes"}, ""},
      {"difference", 0, {"type", "shapes"}, ""},
  };
  return table;
}

std::string valid_types(int dim) {
  std::vector<std::string> names;
  for (const auto& t : type_table())
    if (t.dim == dim || t.dim == 0) names.push_back(t.name);
  return "valid " + std::to_string(dim) + "D types: " + detail::join(names);
}

// The raw scene text of a number, so that messages quote what the user wrote (not metres).
std::string raw(const json& v) { return v.dump(); }

class Parser {
 public:
  explicit Parser(double scale) : scale_(scale) {}

  template <int Dim>
  std::unique_ptr<Shape<Dim>> shape(const json& j, const std::string& path) const {
    const TypeInfo& info = lookup<Dim>(j, path);
    detail::reject_unknown_keys(j, path, info.keys);
    const std::string& t = info.name;
    if (t == "union") return std::make_unique<Union<Dim>>(members<Dim>(j, path, 1));
    if (t == "difference") {
      ShapeList<Dim> list = members<Dim>(j, path, 2);
      auto base = std::move(list.front());
      list.erase(list.begin());
      return std::make_unique<Difference<Dim>>(std::move(base), std::move(list));
    }
    if (t == "rectangle" || t == "box") return axis_box<Dim>(j, path);
    if (t == "disk" || t == "sphere")
      return std::make_unique<Ball<Dim>>(point<Dim>(j, "center", path), length(j, "radius", path));
    if constexpr (Dim == 2) {
      if (t == "ellipse") return ellipse(j, path);
      if (t == "polygon") return std::make_unique<Polygon>(polygon(j, path));
    } else {
      if (t == "ellipsoid")
        return std::make_unique<Ellipsoid>(point<3>(j, "center", path), semi_axes<3>(j, path));
      if (t == "cylinder") return cylinder(j, path);
      if (t == "prism") return prism(j, path);
    }
    throw std::logic_error("shape type '" + t + "' has no builder");  // table and code disagree
  }

 private:
  double scale_;

  template <int Dim>
  const TypeInfo& lookup(const json& j, const std::string& path) const {
    if (!j.is_object())
      throw SceneError(path, "expected a shape object with a \"type\" key, got " + detail::describe(j));
    const std::string tpath = key_path(path, "type");
    auto it = j.find("type");
    if (it == j.end()) throw SceneError(tpath, "missing required key 'type'; " + valid_types(Dim));
    if (!it->is_string())
      throw SceneError(tpath, "expected a shape type name, got " + detail::describe(*it) + "; " +
                                  valid_types(Dim));
    const std::string name = it->get<std::string>();
    for (const auto& t : type_table()) {
      if (t.name != name) continue;
      if (t.dim != 0 && t.dim != Dim)
        throw SceneError(tpath, "'" + name + "' is a " + std::to_string(t.dim) + "D shape; this is a " +
                                    std::to_string(Dim) + "D scene (the " + std::to_string(Dim) +
                                    "D counterpart is " + t.counterpart + "; " + valid_types(Dim) + ")");
      return t;
    }
    throw SceneError(tpath, "unknown shape type '" + name + "'; " + valid_types(Dim));
  }

  // A scene length or coordinate in metres; a finite scene value can still overflow or vanish
  // when multiplied by the unit, which would silently corrupt the geometry.
  double metres(const json& v, const std::string& path) const {
    const double x = v.get<double>();
    const double m = x * scale_;
    if (!std::isfinite(m) || (x != 0.0 && m == 0.0))
      throw SceneError(path, "value " + raw(v) + " is out of range once converted to metres");
    return m;
  }

  template <int N>
  Vec<N> scaled_numbers(const json& v, const std::string& path, const std::vector<std::string>& labels) const {
    detail::read_numbers(v, path, labels);  // validates shape and finiteness
    Vec<N> out;
    for (int i = 0; i < N; ++i) out[i] = metres(v[i], index_path(path, static_cast<std::size_t>(i)));
    return out;
  }

  template <int N>
  Vec<N> point(const json& obj, const std::string& key, const std::string& path) const {
    static const std::vector<std::string> xy = {"x", "y"}, xyz = {"x", "y", "z"};
    return scaled_numbers<N>(detail::require(obj, key, path), key_path(path, key), N == 2 ? xy : xyz);
  }

  // A strictly positive length (radius, cylinder length).
  double length(const json& obj, const std::string& key, const std::string& path) const {
    const std::string p = key_path(path, key);
    const json& v = detail::require(obj, key, path);
    if (detail::read_number(v, p) <= 0.0) throw SceneError(p, key + " must be > 0, got " + raw(v));
    return metres(v, p);
  }

  template <int N>
  Vec<N> semi_axes(const json& obj, const std::string& path) const {
    static const std::vector<std::string> ab = {"a", "b"}, abc = {"a", "b", "c"};
    const std::string p = key_path(path, "semi_axes");
    const json& v = detail::require(obj, "semi_axes", path);
    Vec<N> out = scaled_numbers<N>(v, p, N == 2 ? ab : abc);
    for (int i = 0; i < N; ++i) {
      const std::size_t k = static_cast<std::size_t>(i);
      if (out[i] <= 0.0) throw SceneError(index_path(p, k), "semi-axis must be > 0, got " + raw(v[k]));
    }
    return out;
  }

  template <int Dim>
  std::unique_ptr<Shape<Dim>> axis_box(const json& j, const std::string& path) const {
    Box<Dim> b{point<Dim>(j, "min", path), point<Dim>(j, "max", path)};
    for (int i = 0; i < Dim; ++i) {
      if (b.hi[i] > b.lo[i]) continue;
      const std::size_t k = static_cast<std::size_t>(i);
      const std::string c = "[" + std::to_string(i) + "]";
      throw SceneError(index_path(key_path(path, "max"), k),
                       "max" + c + " must be greater than min" + c + " = " + raw(j["min"][k]) + ", got " +
                           raw(j["max"][k]));
    }
    return std::make_unique<AxisBox<Dim>>(b);
  }

  std::unique_ptr<Ellipse> ellipse(const json& j, const std::string& path) const {
    const Vec<2> c = point<2>(j, "center", path);
    const Vec<2> ab = semi_axes<2>(j, path);
    double degrees = 0.0;
    if (auto it = j.find("angle"); it != j.end()) degrees = detail::read_number(*it, key_path(path, "angle"));
    return std::make_unique<Ellipse>(c, ab, degrees * std::numbers::pi / 180.0);
  }

  std::unique_ptr<Cylinder> cylinder(const json& j, const std::string& path) const {
    const Vec<3> c = point<3>(j, "center", path);
    const std::string ap = key_path(path, "axis");
    const json& av = detail::require(j, "axis", path);
    const std::vector<double> a = detail::read_numbers(av, ap, {"x", "y", "z"});  // a direction: no unit
    Vec<3> axis(a[0], a[1], a[2]);
    const double biggest = axis.cwiseAbs().maxCoeff();
    if (biggest == 0.0) throw SceneError(ap, "axis must be a non-zero direction, got " + raw(av));
    axis = (axis / biggest).normalized();  // pre-divide so huge components cannot overflow the norm
    return std::make_unique<Cylinder>(c, axis, length(j, "radius", path), length(j, "length", path));
  }

  Polyline polygon(const json& j, const std::string& path) const;

  std::unique_ptr<Prism> prism(const json& j, const std::string& path) const {
    Polyline section = polygon(j, path);
    const std::string zp = key_path(path, "z");
    const json& zv = detail::require(j, "z", path);
    const Vec<2> z = scaled_numbers<2>(zv, zp, {"zmin", "zmax"});
    if (!(z[1] > z[0])) throw SceneError(zp, "zmax must be greater than zmin, got " + raw(zv));
    return std::make_unique<Prism>(std::move(section), z[0], z[1]);
  }

  template <int Dim>
  ShapeList<Dim> members(const json& j, const std::string& path, std::size_t at_least) const {
    const std::string sp = key_path(path, "shapes");
    const json& v = detail::require(j, "shapes", path);
    if (!v.is_array()) throw SceneError(sp, "expected an array of shape objects, got " + detail::describe(v));
    if (v.size() < at_least) {
      throw SceneError(sp, at_least == 1 ? "a union needs at least 1 shape, got 0"
                                         : "a difference needs a base shape and at least one cut "
                                           "(>= 2 shapes), got " + std::to_string(v.size()));
    }
    ShapeList<Dim> out;
    for (std::size_t i = 0; i < v.size(); ++i) out.push_back(shape<Dim>(v[i], index_path(sp, i)));
    return out;
  }
};

// Reads "points" and checks that they form a simple polygon with non-zero area; a self-crossing
// outline has no meaningful inside, and silently picking one would seed the wrong body.
Polyline Parser::polygon(const json& j, const std::string& path) const {
  const std::string pp = key_path(path, "points");
  const json& v = detail::require(j, "points", path);
  if (!v.is_array() || v.size() < 3) {
    throw SceneError(pp, "a polygon needs at least 3 points [[x, y], ...], got " +
                             (v.is_array() ? std::to_string(v.size()) + " points" : detail::describe(v)));
  }
  Polyline p;
  for (std::size_t i = 0; i < v.size(); ++i) p.push_back(scaled_numbers<2>(v[i], index_path(pp, i), {"x", "y"}));

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

}  // namespace

template <int Dim>
std::unique_ptr<Shape<Dim>> parse_shape(const nlohmann::json& j, const std::string& key_path, double length_scale) {
  if (!std::isfinite(length_scale) || length_scale <= 0.0)
    throw std::invalid_argument("parse_shape: length_scale must be finite and > 0");
  return Parser(length_scale).shape<Dim>(j, key_path);
}

template std::unique_ptr<Shape<2>> parse_shape<2>(const nlohmann::json&, const std::string&, double);
template std::unique_ptr<Shape<3>> parse_shape<3>(const nlohmann::json&, const std::string&, double);

}  // namespace cleave::geom
