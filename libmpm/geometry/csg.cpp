#include "libmpm/geometry/csg.hpp"

#include <algorithm>
#include <utility>

#include "libmpm/core/error.hpp"
#include "libmpm/geometry/json_fields.hpp"
#include "libmpm/geometry/shape_reader.hpp"

namespace cleave::geom {

template <int Dim>
Union<Dim>::Union(ShapeList<Dim> members) : members_(std::move(members)) {
  for (const auto& m : members_) box_ = box_.united(m->bounds());
}

template <int Dim>
bool Union<Dim>::contains(const Vec<Dim>& x) const {
  return std::any_of(members_.begin(), members_.end(), [&](const auto& m) { return m->contains(x); });
}

template <int Dim>
Difference<Dim>::Difference(std::unique_ptr<Shape<Dim>> base, ShapeList<Dim> cuts)
    : base_(std::move(base)), cuts_(std::move(cuts)) {}

template <int Dim>
bool Difference<Dim>::contains(const Vec<Dim>& x) const {
  return base_->contains(x) &&
         std::none_of(cuts_.begin(), cuts_.end(), [&](const auto& c) { return c->contains(x); });
}

template class Union<2>;
template class Union<3>;
template class Difference<2>;
template class Difference<3>;

// --- scene readers: "union" and "difference", in both dimensions ----------------------------------
namespace {

using nlohmann::json;

template <int Dim>
ShapeList<Dim> members(const ShapeReader& r, const json& j, const std::string& path, std::size_t at_least) {
  const std::string sp = detail::key_path(path, "shapes");
  const json& v = detail::require(j, "shapes", path);
  if (!v.is_array()) throw SceneError(sp, "expected an array of shape objects, got " + detail::describe(v));
  if (v.size() < at_least) {
    throw SceneError(sp, at_least == 1 ? "a union needs at least 1 shape, got 0"
                                       : "a difference needs a base shape and at least one cut "
                                         "(>= 2 shapes), got " + std::to_string(v.size()));
  }
  ShapeList<Dim> out;
  for (std::size_t i = 0; i < v.size(); ++i) out.push_back(r.shape<Dim>(v[i], detail::index_path(sp, i)));
  return out;
}

template <int Dim>
std::unique_ptr<Shape<Dim>> union_of(const ShapeReader& r, const json& j, const std::string& path) {
  return std::make_unique<Union<Dim>>(members<Dim>(r, j, path, 1));
}

template <int Dim>
std::unique_ptr<Shape<Dim>> difference_of(const ShapeReader& r, const json& j, const std::string& path) {
  ShapeList<Dim> list = members<Dim>(r, j, path, 2);
  auto base = std::move(list.front());
  list.erase(list.begin());
  return std::make_unique<Difference<Dim>>(std::move(base), std::move(list));
}

}  // namespace

CLEAVE_REGISTER_SHAPE("union", 10, 0, {"type", "shapes"}, "", &union_of<2>, &union_of<3>)
CLEAVE_REGISTER_SHAPE("difference", 11, 0, {"type", "shapes"}, "", &difference_of<2>, &difference_of<3>)

}  // namespace cleave::geom
