// Solid geometry used to build bodies: a Shape answers "is this point inside?" and gives an
// axis-aligned bounding box, which is all the particle seeder needs (it walks the box on a lattice
// and keeps the points the shape contains). Shapes come from scene JSON through parse_shape, which
// looks the "type" up among the registered shape readers (shape_reader.hpp).
#pragma once
#include <limits>
#include <memory>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "libmpm/core/types.hpp"

namespace cleave::geom {

// Axis-aligned box [lo, hi]. The default box is empty (lo = +inf, hi = -inf) so that it is the
// identity of united(): folding united() over any number of boxes needs no special first case.
template <int Dim>
struct Box {
  Vec<Dim> lo = Vec<Dim>::Constant(std::numeric_limits<double>::infinity());
  Vec<Dim> hi = Vec<Dim>::Constant(-std::numeric_limits<double>::infinity());

  // A box with lo == hi in some component is a degenerate but non-empty (closed) box.
  bool empty() const { return (lo.array() > hi.array()).any(); }
  Box united(const Box& o) const {
    if (empty()) return o;
    if (o.empty()) return *this;
    return Box{lo.cwiseMin(o.lo), hi.cwiseMax(o.hi)};
  }
  bool contains(const Vec<Dim>& x) const {
    return (x.array() >= lo.array()).all() && (x.array() <= hi.array()).all();
  }
};

template <int Dim>
class Shape {
 public:
  virtual ~Shape() = default;
  // Closed-set membership (boundary points count as inside where floating point can tell).
  virtual bool contains(const Vec<Dim>& x) const = 0;
  // Axis-aligned box holding every point for which contains() is true.
  virtual Box<Dim> bounds() const = 0;
};

// Parses one shape object. key_path is the scene path of `j` (e.g. "bodies[0].shape"); every
// SceneError names the offending key below it (e.g. "bodies[0].shape.shapes[1].radius").
// length_scale converts the scene's length unit to metres and multiplies every coordinate and
// length (angles and cylinder axis directions are unitless). Throws cleave::SceneError for an
// invalid scene and std::invalid_argument if length_scale is not finite and > 0 (a caller bug).
//   2D types: rectangle, disk, ellipse, polygon, union, difference
//   3D types: box, sphere, cylinder, ellipsoid, prism, union, difference
template <int Dim>
std::unique_ptr<Shape<Dim>> parse_shape(const nlohmann::json& j, const std::string& key_path,
                                        double length_scale);

}  // namespace cleave::geom
