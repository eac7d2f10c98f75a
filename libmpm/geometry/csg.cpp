#include "libmpm/geometry/csg.hpp"

#include <algorithm>
#include <utility>

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

}  // namespace cleave::geom
