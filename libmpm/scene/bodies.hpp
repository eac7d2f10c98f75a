// The "materials" and "bodies" sections as every method reads them: the array walks, the names, the
// shapes, the initial motion. What a method builds from them (MPM particles in grid cells, a
// peridynamic lattice, a mesh) is the method's; so is the meaning of a material's keys (each
// method's material registry).
#pragma once
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "libmpm/core/json_reader.hpp"
#include "libmpm/core/types.hpp"
#include "libmpm/core/units.hpp"
#include "libmpm/geometry/shape.hpp"
#include "libmpm/scene/sections.hpp"

namespace cleave::scene {

// "materials": a non-empty array of objects with string "name" (unique) and "type". make(path,
// type, object) builds the method's material from its own registry, in array order (the style
// checks its own keys). Returns name -> index.
template <class Make>
std::map<std::string, int> read_materials(const nlohmann::json& scene, Make&& make);

// One entry of "bodies": the keys every method reads. The keys only some methods use
// (particles_per_cell, thickness) are read by the method through reader(); a method that has no use
// for one rejects it.
template <int Dim>
struct BodySpec {
  std::string path;  // "bodies[i]"
  std::string name;  // default "body<i>"
  int material = 0;  // index into the materials array
  std::unique_ptr<geom::Shape<Dim>> shape;
  Vec<Dim> velocity = Vec<Dim>::Zero();  // m/s
  const nlohmann::json* object = nullptr;
  ObjectReader reader() const;

  // Adds the body's rigid rotation to the velocities v[0..n) of its points x[0..n) (scene keys
  // "angular_velocity" (2D: a rate about z; 3D: a vector), about "rotation_center" or else the points' centroid):
  // v += w x (x - c). No-op when the body does not rotate.
  void add_rotation(const UnitSystem& units, double length, const Vec<Dim>* x, Vec<Dim>* v, std::size_t n) const;
};

// "bodies": a non-empty array; names unique; "material" one of `materials`; "shape" required.
template <int Dim>
std::vector<BodySpec<Dim>> read_bodies(const nlohmann::json& scene, const UnitSystem& units,
                                       const std::map<std::string, int>& materials);

// ---- template definitions --------------------------------------------------------------------

template <class Make>
std::map<std::string, int> read_materials(const nlohmann::json& scene, Make&& make) {
  std::map<std::string, int> index;
  const nlohmann::json& mats = array_at(scene, "materials", true);
  if (mats.empty()) throw SceneError("materials", "at least one material is needed");
  for (std::size_t i = 0; i < mats.size(); ++i) {
    const std::string path = index_path("materials", i);
    if (!mats[i].is_object()) throw SceneError(path, "expected an object");
    for (const char* key : {"name", "type"}) {
      if (!mats[i].contains(key) || mats[i][key].is_null()) throw SceneError(path + "." + key, "missing");
      if (!mats[i][key].is_string()) throw SceneError(path + "." + key, "expected a string");
    }
    const std::string name = mats[i]["name"].get<std::string>();
    if (index.count(name)) throw SceneError(path + ".name", "duplicate material name '" + name + "'");
    make(path, mats[i]["type"].get<std::string>(), mats[i]);
    index[name] = static_cast<int>(i);
  }
  return index;
}

}  // namespace cleave::scene
