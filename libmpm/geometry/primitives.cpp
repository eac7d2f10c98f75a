#include "libmpm/geometry/primitives.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "libmpm/core/error.hpp"
#include "libmpm/geometry/json_fields.hpp"
#include "libmpm/geometry/shape_reader.hpp"

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

// --- scene readers (validation here, so the classes above stay plain geometry) ---------------
namespace {

using nlohmann::json;
using detail::index_path;
using detail::key_path;

template <int Dim>
std::unique_ptr<Shape<Dim>> axis_box(const ShapeReader& r, const json& j, const std::string& path) {
  Box<Dim> b{r.point<Dim>(j, "min", path), r.point<Dim>(j, "max", path)};
  for (int i = 0; i < Dim; ++i) {
    if (b.hi[i] > b.lo[i]) continue;
    const std::size_t k = static_cast<std::size_t>(i);
    const std::string c = std::to_string(i);
    throw SceneError(index_path(key_path(path, "max"), k), "max[" + c + "] must be greater than min[" + c + "] = " +
                                                               raw(j["min"][k]) + ", got " + raw(j["max"][k]));
  }
  return std::make_unique<AxisBox<Dim>>(b);
}

template <int Dim>
std::unique_ptr<Shape<Dim>> ball(const ShapeReader& r, const json& j, const std::string& path) {
  return std::make_unique<Ball<Dim>>(r.point<Dim>(j, "center", path), r.length(j, "radius", path));
}

std::unique_ptr<Shape<2>> ellipse(const ShapeReader& r, const json& j, const std::string& path) {
  const Vec<2> c = r.point<2>(j, "center", path);
  const Vec<2> ab = r.semi_axes<2>(j, path);
  double degrees = 0.0;
  if (auto it = j.find("angle"); it != j.end()) degrees = detail::read_number(*it, key_path(path, "angle"));
  return std::make_unique<Ellipse>(c, ab, degrees * std::numbers::pi / 180.0);
}

std::unique_ptr<Shape<3>> ellipsoid(const ShapeReader& r, const json& j, const std::string& path) {
  return std::make_unique<Ellipsoid>(r.point<3>(j, "center", path), r.semi_axes<3>(j, path));
}

std::unique_ptr<Shape<3>> cylinder(const ShapeReader& r, const json& j, const std::string& path) {
  const Vec<3> c = r.point<3>(j, "center", path);
  const std::string ap = key_path(path, "axis");
  const json& av = detail::require(j, "axis", path);
  const std::vector<double> a = detail::read_numbers(av, ap, {"x", "y", "z"});  // a direction: no unit
  Vec<3> axis(a[0], a[1], a[2]);
  const double biggest = axis.cwiseAbs().maxCoeff();
  if (biggest == 0.0) throw SceneError(ap, "axis must be a non-zero direction, got " + raw(av));
  axis = (axis / biggest).normalized();  // pre-divide so huge components cannot overflow the norm
  return std::make_unique<Cylinder>(c, axis, r.length(j, "radius", path), r.length(j, "length", path));
}

}  // namespace

// Ranks: the order docs/scenes.md and the "valid types" messages list them in (polygon.cpp: 4, 9;
// csg.cpp: 10, 11).
CLEAVE_REGISTER_SHAPE("rectangle", 1, 2, {"type", "min", "max"}, "box", &axis_box<2>, nullptr)
CLEAVE_REGISTER_SHAPE("disk", 2, 2, {"type", "center", "radius"}, "sphere or cylinder", &ball<2>, nullptr)
CLEAVE_REGISTER_SHAPE("ellipse", 3, 2, {"type", "center", "semi_axes", "angle"}, "ellipsoid", &ellipse, nullptr)
CLEAVE_REGISTER_SHAPE("box", 5, 3, {"type", "min", "max"}, "rectangle", nullptr, &axis_box<3>)
CLEAVE_REGISTER_SHAPE("sphere", 6, 3, {"type", "center", "radius"}, "disk", nullptr, &ball<3>)
CLEAVE_REGISTER_SHAPE("cylinder", 7, 3, {"type", "center", "axis", "radius", "length"}, "disk", nullptr, &cylinder)
CLEAVE_REGISTER_SHAPE("ellipsoid", 8, 3, {"type", "center", "semi_axes"}, "ellipse", nullptr, &ellipsoid)

}  // namespace cleave::geom
