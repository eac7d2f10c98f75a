// "traction": a surface load on the faces of a body that look along `face`, optionally only inside
// a region and on one body, ramped up over rise_time.
#include "libmpm/scene/loads.hpp"
#include "libmpm/scene/sections.hpp"

namespace cleave::scene {
namespace {

template <int Dim>
void read_traction(const nlohmann::json& j, const std::string& path, const LoadContext& c, LoadSpec<Dim>& s) {
  const ObjectReader r(j, path, {"type", "name", "body", "region", "face", "traction", "force", "rise_time"});
  s.name = r.string_or("name", path);
  if (r.has("traction") == r.has("force"))
    throw SceneError(path, "give either \"traction\" (force per area) or \"force\" (the total force on the faces)");
  s.total_force = r.has("force");
  s.vector = s.total_force ? r.vec<Dim>("force", c.units.factor(Quantity::Force))
                           : r.vec<Dim>("traction", c.units.factor(Quantity::Stress));
  s.rise_time = r.has("rise_time") ? r.positive("rise_time", c.units.factor(Quantity::Time)) : 0.0;
  s.face = r.string("face");
  if (s.face.size() != 2 || (s.face[0] != '+' && s.face[0] != '-'))
    throw SceneError(r.at("face"), "expected a face such as \"+y\" or \"-x\"");
  s.side = s.face[0] == '+' ? 1 : -1;
  s.axis = axis_of<Dim>(s.face.substr(1), r.at("face"));
  s.has_region = r.has("region");
  if (s.has_region) read_region<Dim>(r, "region", c.units.factor(Quantity::Length), s.lo, s.hi);
  if (r.has("body")) {
    const std::string bn = r.string("body");
    for (std::size_t k = 0; k < c.bodies.size(); ++k)
      if (c.bodies[k] == bn) s.body = static_cast<int>(k);
    if (s.body < 0) throw SceneError(r.at("body"), "no body named '" + bn + "'");
  }
}

}  // namespace

CLEAVE_REGISTER_LOAD_KIND("traction", 1, read_traction)

}  // namespace cleave::scene
