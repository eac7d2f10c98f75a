#include "libmpm/geometry/primitives.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace cleave::geom {

template <int Dim>
bool Ball<Dim>::contains(const Vec<Dim>& x) const {
  return (x - center_).squaredNorm() <= radius_ * radius_;
}

template <int Dim>
Box<Dim> Ball<Dim>::bounds() const {
  return Box<Dim>{(center_.array() - radius_).matrix(), (center_.array() + radius_).matrix()};
}

template class Ball<2>;
template class Ball<3>;

Ellipse::Ellipse(const Vec<2>& center, const Vec<2>& semi_axes, double angle_rad)
    : center_(center), semi_axes_(semi_axes), cos_(std::cos(angle_rad)), sin_(std::sin(angle_rad)) {}

bool Ellipse::contains(const Vec<2>& x) const {
  const Vec<2> d = x - center_;
  // Coordinates in the ellipse's own frame (rotate by -angle).
  const double u = (cos_ * d.x() + sin_ * d.y()) / semi_axes_.x();
  const double v = (-sin_ * d.x() + cos_ * d.y()) / semi_axes_.y();
  return u * u + v * v <= 1.0;
}

Box<2> Ellipse::bounds() const {
  // Tight box of a rotated ellipse: the support function along x and y.
  const double a = semi_axes_.x(), b = semi_axes_.y();
  const Vec<2> half(std::hypot(a * cos_, b * sin_), std::hypot(a * sin_, b * cos_));
  return Box<2>{center_ - half, center_ + half};
}

bool Ellipsoid::contains(const Vec<3>& x) const {
  return ((x - center_).array() / semi_axes_.array()).square().sum() <= 1.0;
}

Cylinder::Cylinder(const Vec<3>& center, const Vec<3>& unit_axis, double radius, double length)
    : center_(center), axis_(unit_axis), radius_(radius), half_length_(0.5 * length) {}

bool Cylinder::contains(const Vec<3>& x) const {
  const Vec<3> d = x - center_;
  const double t = d.dot(axis_);
  if (std::abs(t) > half_length_) return false;
  return (d - t * axis_).squaredNorm() <= radius_ * radius_;
}

Box<3> Cylinder::bounds() const {
  // Tight box: the axis segment contributes h|a_i| and each end disk r*sqrt(1 - a_i^2).
  Vec<3> half;
  for (int i = 0; i < 3; ++i)
    half[i] = half_length_ * std::abs(axis_[i]) + radius_ * std::sqrt(std::max(0.0, 1.0 - axis_[i] * axis_[i]));
  return Box<3>{center_ - half, center_ + half};
}

Polygon::Polygon(Polyline points) : points_(std::move(points)) {
  for (const Vec<2>& p : points_) box_ = box_.united(Box<2>{p, p});
}

bool Polygon::contains(const Vec<2>& x) const {
  return box_.contains(x) && polygon_contains(points_, x);
}

Prism::Prism(Polyline points, double zmin, double zmax)
    : section_(std::move(points)), zmin_(zmin), zmax_(zmax) {}

bool Prism::contains(const Vec<3>& x) const {
  return x.z() >= zmin_ && x.z() <= zmax_ && section_.contains(x.head<2>());
}

Box<3> Prism::bounds() const {
  const Box<2> b = section_.bounds();
  return Box<3>{Vec<3>(b.lo.x(), b.lo.y(), zmin_), Vec<3>(b.hi.x(), b.hi.y(), zmax_)};
}

}  // namespace cleave::geom
