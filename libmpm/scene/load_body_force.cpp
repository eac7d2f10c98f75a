// "body_force": a uniform acceleration of every body (gravity); several add up.
#include "libmpm/scene/loads.hpp"

namespace cleave::scene {
namespace {

template <int Dim>
void read_body_force(const nlohmann::json& j, const std::string& path, const LoadContext& c, LoadSpec<Dim>& s) {
  const ObjectReader r(j, path, {"type", "acceleration"});
  s.vector = r.vec<Dim>("acceleration", c.units.factor(Quantity::Acceleration));
}

}  // namespace

CLEAVE_REGISTER_LOAD_KIND("body_force", 2, read_body_force)

}  // namespace cleave::scene
