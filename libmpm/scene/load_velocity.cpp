// "velocity": prescribed velocity components (null: free) inside a region; a fixed support is 0.
#include "libmpm/scene/loads.hpp"
#include "libmpm/scene/sections.hpp"

namespace cleave::scene {
namespace {

template <int Dim>
void read_velocity(const nlohmann::json& j, const std::string& path, const LoadContext& c, LoadSpec<Dim>& s) {
  const ObjectReader r(j, path, {"type", "region", "velocity"});
  if (!r.has("region")) throw SceneError(r.at("region"), "missing: a velocity condition needs a region");
  s.has_region = true;
  read_region<Dim>(r, "region", c.units.factor(Quantity::Length), s.lo, s.hi);
  const auto [mask, v] = r.partial_vec<Dim>("velocity", c.units.factor(Quantity::Velocity));
  s.mask = mask;
  s.vector = v;
}

}  // namespace

CLEAVE_REGISTER_LOAD_KIND("velocity", 3, read_velocity)

}  // namespace cleave::scene
