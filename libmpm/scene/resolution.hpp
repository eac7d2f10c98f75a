// The scene's length scale of discretisation, one key for every method: "resolution" (a length in
// the scene's unit). Each method reads it its own way: MPM as the grid's cell size, peridynamics as
// the lattice spacing, a mesh-based method as its element size. A study that refines a scene
// changes this one key whatever the method. The method's own spelling (grid.cell_size,
// peridynamics.spacing) is accepted in its place; giving both is an error naming both keys.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

namespace cleave::scene {

// The discretisation length: `length` in metres, and `key`, the scene key it came from, for the
// method's later errors about it ("resolution" or e.g. "grid.cell_size").
struct Resolution {
  double length;
  std::string key;
};

// The scene's "resolution", or else section[key] (section_path names the section, e.g. "grid"; the
// section may be absent). `meaning` says what the method makes of it, for the error when neither
// is given ("the grid's cell size"). `length` converts the scene's length unit to metres. Throws
// SceneError: both given, neither given, not a positive finite number.
Resolution read_resolution(const nlohmann::json& scene, const std::string& section_path, const char* key,
                       const std::string& meaning, double length);

}  // namespace cleave::scene
