// parse_shape: scene JSON -> Shape, through the registered shape readers (shape_reader.hpp). The
// type look-up and the readers shared by every builder live here; each builder lives beside its
// shape. Every error names the scene key path of the value that is wrong.
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "libmpm/core/error.hpp"
#include "libmpm/geometry/json_fields.hpp"
#include "libmpm/geometry/shape.hpp"
#include "libmpm/geometry/shape_reader.hpp"

namespace cleave::geom {
namespace {

using nlohmann::json;
using detail::index_path;
using detail::key_path;

std::string valid_types(int dim) {
  const auto names = ShapeKinds::instance().names_where(
      [dim](const std::string&, const ShapeKind& k) { return k.dim == dim || k.dim == 0; });
  return "valid " + std::to_string(dim) + "D types: " + detail::join(names);
}

template <int Dim>
const ShapeKind& lookup(const json& j, const std::string& path) {
  if (!j.is_object()) throw SceneError(path, "expected a shape object with a \"type\" key, got " + detail::describe(j));
  const std::string tpath = key_path(path, "type");
  auto it = j.find("type");
  if (it == j.end()) throw SceneError(tpath, "missing required key 'type'; " + valid_types(Dim));
  if (!it->is_string())
    throw SceneError(tpath, "expected a shape type name, got " + detail::describe(*it) + "; " + valid_types(Dim));
  const std::string name = it->get<std::string>();
  const ShapeKind* t = ShapeKinds::instance().find(name);
  if (!t) throw SceneError(tpath, "unknown shape type '" + name + "'; " + valid_types(Dim));
  if (t->dim != 0 && t->dim != Dim)
    throw SceneError(tpath, "'" + name + "' is a " + std::to_string(t->dim) + "D shape; this is a " +
                                std::to_string(Dim) + "D scene (the " + std::to_string(Dim) + "D counterpart is " +
                                t->counterpart + "; " + valid_types(Dim) + ")");
  return *t;
}

}  // namespace

template <int Dim>
std::unique_ptr<Shape<Dim>> ShapeReader::shape(const json& j, const std::string& path) const {
  const ShapeKind& kind = lookup<Dim>(j, path);
  detail::reject_unknown_keys(j, path, kind.keys);
  const ShapeBuilder<Dim> build = [&] {
    if constexpr (Dim == 2) return kind.build2;
    else return kind.build3;
  }();
  if (!build) throw std::logic_error("shape type '" + j["type"].get<std::string>() + "' has no builder");
  return build(*this, j, path);
}

// A finite scene value can still overflow or vanish when multiplied by the unit, which would
// silently corrupt the geometry.
double ShapeReader::metres(const json& v, const std::string& path) const {
  const double x = v.get<double>();
  const double m = x * scale_;
  if (!std::isfinite(m) || (x != 0.0 && m == 0.0))
    throw SceneError(path, "value " + raw(v) + " is out of range once converted to metres");
  return m;
}

template <int N>
Vec<N> ShapeReader::scaled_numbers(const json& v, const std::string& path,
                                   const std::vector<std::string>& labels) const {
  detail::read_numbers(v, path, labels);  // validates shape and finiteness
  Vec<N> out;
  for (int i = 0; i < N; ++i) out[i] = metres(v[i], index_path(path, static_cast<std::size_t>(i)));
  return out;
}

template <int N>
Vec<N> ShapeReader::point(const json& obj, const std::string& key, const std::string& path) const {
  static const std::vector<std::string> xy = {"x", "y"}, xyz = {"x", "y", "z"};
  return scaled_numbers<N>(detail::require(obj, key, path), key_path(path, key), N == 2 ? xy : xyz);
}

double ShapeReader::length(const json& obj, const std::string& key, const std::string& path) const {
  const std::string p = key_path(path, key);
  const json& v = detail::require(obj, key, path);
  if (detail::read_number(v, p) <= 0.0) throw SceneError(p, key + " must be > 0, got " + raw(v));
  return metres(v, p);
}

template <int N>
Vec<N> ShapeReader::semi_axes(const json& obj, const std::string& path) const {
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

template std::unique_ptr<Shape<2>> ShapeReader::shape<2>(const json&, const std::string&) const;
template std::unique_ptr<Shape<3>> ShapeReader::shape<3>(const json&, const std::string&) const;
template Vec<2> ShapeReader::scaled_numbers<2>(const json&, const std::string&, const std::vector<std::string>&) const;
template Vec<3> ShapeReader::scaled_numbers<3>(const json&, const std::string&, const std::vector<std::string>&) const;
template Vec<2> ShapeReader::point<2>(const json&, const std::string&, const std::string&) const;
template Vec<3> ShapeReader::point<3>(const json&, const std::string&, const std::string&) const;
template Vec<2> ShapeReader::semi_axes<2>(const json&, const std::string&) const;
template Vec<3> ShapeReader::semi_axes<3>(const json&, const std::string&) const;

template <int Dim>
std::unique_ptr<Shape<Dim>> parse_shape(const nlohmann::json& j, const std::string& key_path, double length_scale) {
  if (!std::isfinite(length_scale) || length_scale <= 0.0)
    throw std::invalid_argument("parse_shape: length_scale must be finite and > 0");
  return ShapeReader(length_scale).shape<Dim>(j, key_path);
}

template std::unique_ptr<Shape<2>> parse_shape<2>(const nlohmann::json&, const std::string&, double);
template std::unique_ptr<Shape<3>> parse_shape<3>(const nlohmann::json&, const std::string&, double);

}  // namespace cleave::geom
