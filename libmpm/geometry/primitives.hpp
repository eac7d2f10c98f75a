// Primitive solids. Constructors take already-validated values in metres (the scene readers
// registered in primitives.cpp and polygon.cpp do the checking and report scene errors); they do
// not re-validate.
#pragma once
#include "libmpm/geometry/polygon.hpp"
#include "libmpm/geometry/shape.hpp"

namespace cleave::geom {

// "rectangle" (2D) and "box" (3D): the closed box itself.
template <int Dim>
class AxisBox final : public Shape<Dim> {
 public:
  explicit AxisBox(const Box<Dim>& box) : box_(box) {}
  bool contains(const Vec<Dim>& x) const override { return box_.contains(x); }
  Box<Dim> bounds() const override { return box_; }

 private:
  Box<Dim> box_;
};

// "disk" (2D) and "sphere" (3D). Requires radius > 0.
template <int Dim>
class Ball final : public Shape<Dim> {
 public:
  Ball(const Vec<Dim>& center, double radius) : center_(center), radius_(radius) {}
  bool contains(const Vec<Dim>& x) const override;
  Box<Dim> bounds() const override;

 private:
  Vec<Dim> center_;
  double radius_;
};

// "ellipse": semi-axis a along the direction at `angle_rad` from +x, b perpendicular to it.
class Ellipse final : public Shape<2> {
 public:
  Ellipse(const Vec<2>& center, const Vec<2>& semi_axes, double angle_rad);
  bool contains(const Vec<2>& x) const override;
  Box<2> bounds() const override;

 private:
  Vec<2> center_, semi_axes_;
  double cos_, sin_;
};

// "ellipsoid": axis-aligned semi-axes (a, b, c) along x, y, z.
class Ellipsoid final : public Shape<3> {
 public:
  Ellipsoid(const Vec<3>& center, const Vec<3>& semi_axes) : center_(center), semi_axes_(semi_axes) {}
  bool contains(const Vec<3>& x) const override;
  Box<3> bounds() const override { return Box<3>{center_ - semi_axes_, center_ + semi_axes_}; }

 private:
  Vec<3> center_, semi_axes_;
};

// "cylinder": solid circular cylinder; `center` is the mid-point of the axis, `unit_axis` must have
// unit length, `length` is the full extent along the axis.
class Cylinder final : public Shape<3> {
 public:
  Cylinder(const Vec<3>& center, const Vec<3>& unit_axis, double radius, double length);
  bool contains(const Vec<3>& x) const override;
  Box<3> bounds() const override;

 private:
  Vec<3> center_, axis_;
  double radius_, half_length_;
};

// "polygon": simple polygon (validated non-self-intersecting, non-zero area), closed set.
class Polygon final : public Shape<2> {
 public:
  explicit Polygon(Polyline points);
  bool contains(const Vec<2>& x) const override;
  Box<2> bounds() const override { return box_; }

 private:
  Polyline points_;
  Box<2> box_;  // cheap rejection before the O(n) winding test
};

// "prism": the polygon extruded along z over [zmin, zmax].
class Prism final : public Shape<3> {
 public:
  Prism(Polyline points, double zmin, double zmax);
  bool contains(const Vec<3>& x) const override;
  Box<3> bounds() const override;

 private:
  Polygon section_;
  double zmin_, zmax_;
};

}  // namespace cleave::geom
