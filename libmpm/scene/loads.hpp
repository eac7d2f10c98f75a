// One reader of the scene's "loads" for every method. Each load kind registers, in its own file
// (scene/load_*.cpp), how its keys are read into a method-neutral LoadSpec; a method then resolves
// each spec on its own discretisation (MPM: particle faces and grid nodes; peridynamics: lattice
// points), in scene order. A method resolves the kinds it names: any other kind is refused at
// loads[i].type with the method's reason, and the missing / unknown-type messages list only the
// kinds it accepts.
#pragma once
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "libmpm/core/json_reader.hpp"
#include "libmpm/core/registry.hpp"
#include "libmpm/core/types.hpp"
#include "libmpm/core/units.hpp"

namespace cleave::scene {

// One entry of "loads", in SI. Which fields a kind fills is the kind's (see its file).
template <int Dim>
struct LoadSpec {
  std::string kind;         // the registered name: "traction", "body_force", ...
  std::string path;         // "loads[2]": errors found while resolving name keys below it
  std::string name;         // the load's name (default: path)
  int body = -1;            // index into LoadContext::bodies; -1: every body
  bool has_region = false;  // lo, hi given by "region"
  Vec<Dim> lo = Vec<Dim>::Zero(), hi = Vec<Dim>::Zero();
  std::string face;         // as written ("+y"), for messages
  int axis = 0, side = 1;   // a face's normal axis and side, or a plane's normal axis
  Vec<Dim> vector = Vec<Dim>::Zero();  // traction (Pa), acceleration (m/s^2), velocity (m/s)
  uint8_t mask = 0;         // bit d: component d of `vector` is prescribed (velocity)
  double position = 0.0;    // a plane's position along `axis` (m)
  double rise_time = 0.0;   // linear ramp to full value (s); 0: full value from t = 0
  bool total_force = false; // traction given as "force": `vector` is the total force (N) on the loaded
                            // faces, turned into a traction by the method that finds their area
  std::string at(const char* key) const { return path + "." + key; }
};

// What a key reader needs besides the load's JSON.
struct LoadContext {
  const UnitSystem& units;
  const std::vector<std::string>& bodies;  // body names, for "body"
};

// Reads the keys of one load (the object at `path`, checking its allowed keys) into s; s.kind,
// s.path and s.name (= path) are set before.
template <int Dim>
using LoadKeyReader = void (*)(const nlohmann::json& j, const std::string& path, const LoadContext& c,
                               LoadSpec<Dim>& s);

struct LoadKind {
  LoadKeyReader<2> read2;
  LoadKeyReader<3> read3;
};
// Listed by rank: traction, body_force, velocity, symmetry (the order of docs/scenes.md).
using LoadKinds = NameTable<LoadKind>;

// How a method resolves each kind it supports, by kind name. Any other registered kind is refused
// at loads[i].type, with the reason in `refusals` or "<kind> loads are not available with <method>".
template <int Dim>
using LoadResolvers = std::map<std::string, std::function<void(const LoadSpec<Dim>&)>>;

// Reads "loads" and resolves each entry in scene order before reading the next, so that errors
// come in the order of the array.
template <int Dim>
void read_loads(const nlohmann::json& scene, const LoadContext& c, const std::string& method,
                const LoadResolvers<Dim>& resolvers, const std::map<std::string, std::string>& refusals = {});

}  // namespace cleave::scene

// Registers a load kind: Reader<Dim> is a LoadKeyReader<Dim> template. Put it in the kind's file.
#define CLEAVE_REGISTER_LOAD_KIND(name, rank, Reader)                           \
  namespace {                                                                  \
  [[maybe_unused]] const bool CLEAVE_REGISTRAR(cleave_load_kind_) =            \
      ::cleave::scene::LoadKinds::instance().add(                              \
          name, ::cleave::scene::LoadKind{&Reader<2>, &Reader<3>}, rank);      \
  }
