// Boolean combinations of shapes. Only union and difference are offered: together with the
// primitives they cover notches, holes and composite bodies without an intersection operator.
#pragma once
#include <memory>
#include <vector>

#include "libmpm/geometry/shape.hpp"

namespace cleave::geom {

template <int Dim>
using ShapeList = std::vector<std::unique_ptr<Shape<Dim>>>;

// Points inside any member. Requires at least one member.
template <int Dim>
class Union final : public Shape<Dim> {
 public:
  explicit Union(ShapeList<Dim> members);
  bool contains(const Vec<Dim>& x) const override;
  Box<Dim> bounds() const override { return box_; }

 private:
  ShapeList<Dim> members_;
  Box<Dim> box_;
};

// Points inside `base` and inside none of `cuts`. The bounds are the base's: a cut may leave the
// box loose but can never make it wrong, and computing a tight box would need real geometry.
template <int Dim>
class Difference final : public Shape<Dim> {
 public:
  Difference(std::unique_ptr<Shape<Dim>> base, ShapeList<Dim> cuts);
  bool contains(const Vec<Dim>& x) const override;
  Box<Dim> bounds() const override { return base_->bounds(); }

 private:
  std::unique_ptr<Shape<Dim>> base_;
  ShapeList<Dim> cuts_;
};

}  // namespace cleave::geom
