// Internal to libmpm/pem: scene shape objects (the JSON geometry/ reads) as OpenCASCADE entities in
// Gmsh's current model.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "libmpm/core/types.hpp"

namespace cleave::pem::detail {

using DimTags = std::vector<std::pair<int, int>>;  // gmsh::vectorpair: (dimension, tag)

// OpenCASCADE's tolerances are absolute (1e-7 model units), so the model is built where the bodies
// span about one unit, whatever the scene's length unit: model = (metres - origin) / unit.
template <int Dim>
struct ModelFrame {
  Vec<Dim> origin = Vec<Dim>::Zero();  // metres
  double unit = 1.0;                   // metres per model unit
  double scale = 1.0;                  // the scene's length unit, metres

  double coordinate(double scene, int axis) const { return (scene * scale - origin[axis]) / unit; }
  double length(double scene) const { return scene * scale / unit; }
};

// Builds the entities (of dimension Dim) of one shape object that geom::parse_shape has accepted:
// rectangle, disk, ellipse, polygon / box, sphere, cylinder, ellipsoid, prism, and union and
// difference of any of them. Throws SceneError at `path` (or below it) for a shape that leaves
// nothing (a difference that removes all) or a type this mesher does not know; Gmsh's own failures
// propagate as Gmsh throws them (gmsh_guarded turns them into SceneError).
template <int Dim>
DimTags occ_shape(const nlohmann::json& shape, const std::string& path, const ModelFrame<Dim>& frame);

}  // namespace cleave::pem::detail
