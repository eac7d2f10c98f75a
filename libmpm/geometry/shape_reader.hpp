// Shape readers by scene "type". Each shape kind registers itself in the file that defines it
// (primitives.cpp, polygon.cpp, csg.cpp) with its dimension, its keys and a builder per dimension;
// parse_shape (shape_parser.cpp) looks the type up and rejects unknown keys before the builder
// runs. The builders validate through ShapeReader, so every message reads alike and names the
// scene key path of the offending value; the shape classes stay plain geometry.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "libmpm/core/registry.hpp"
#include "libmpm/core/types.hpp"
#include "libmpm/geometry/shape.hpp"

namespace cleave::geom {

// The checked readers every builder uses; scale converts the scene's length unit to metres.
class ShapeReader {
 public:
  explicit ShapeReader(double scale) : scale_(scale) {}

  // The shape object at `path`, of any registered type (CSG members recurse through here).
  template <int Dim>
  std::unique_ptr<Shape<Dim>> shape(const nlohmann::json& j, const std::string& path) const;

  // A scene length or coordinate in metres (out of range once scaled: an error, not inf or 0).
  double metres(const nlohmann::json& v, const std::string& path) const;
  // An array of N finite numbers in metres; labels name them in messages ({"x", "y"}).
  template <int N>
  Vec<N> scaled_numbers(const nlohmann::json& v, const std::string& path, const std::vector<std::string>& labels) const;
  // obj[key], a point [x, y(, z)] in metres.
  template <int N>
  Vec<N> point(const nlohmann::json& obj, const std::string& key, const std::string& path) const;
  // obj[key], a strictly positive length (radius, cylinder length) in metres.
  double length(const nlohmann::json& obj, const std::string& key, const std::string& path) const;
  // obj["semi_axes"], N strictly positive lengths in metres.
  template <int N>
  Vec<N> semi_axes(const nlohmann::json& obj, const std::string& path) const;

 private:
  double scale_;
};

// The raw scene text of a value, so that messages quote what the user wrote (not metres).
inline std::string raw(const nlohmann::json& v) { return v.dump(); }

template <int Dim>
using ShapeBuilder = std::unique_ptr<Shape<Dim>> (*)(const ShapeReader&, const nlohmann::json&, const std::string&);

// A registered shape type.
struct ShapeKind {
  int dim;                        // 2, 3, or 0 for both
  std::vector<std::string> keys;  // every key the type accepts, "type" first (listed in that order)
  std::string counterpart;        // the nearest type of the other dimension, for the mismatch hint
  ShapeBuilder<2> build2;         // null when dim == 3
  ShapeBuilder<3> build3;         // null when dim == 2
};

// Listed by rank (the order of docs/scenes.md: 2D types, 3D types, then CSG).
using ShapeKinds = NameTable<ShapeKind>;

}  // namespace cleave::geom

// Registers a shape type: CLEAVE_REGISTER_SHAPE("disk", rank, dim, {keys...}, "counterpart",
// builder2, builder3). Put it in the file that defines the shape.
#define CLEAVE_REGISTER_SHAPE(name, rank, ...)                                   \
  namespace {                                                                  \
  [[maybe_unused]] const bool CLEAVE_REGISTRAR(cleave_shape_) =                \
      ::cleave::geom::ShapeKinds::instance().add(                              \
          name, ::cleave::geom::ShapeKind{__VA_ARGS__}, rank);                 \
  }
