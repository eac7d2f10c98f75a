// "symmetry": a mirror plane normal to `axis` at `position` (the normal velocity component is 0).
#include "libmpm/scene/loads.hpp"
#include "libmpm/scene/sections.hpp"

namespace cleave::scene {
namespace {

template <int Dim>
void read_symmetry(const nlohmann::json& j, const std::string& path, const LoadContext& c, LoadSpec<Dim>& s) {
  const ObjectReader r(j, path, {"type", "axis", "position"});
  s.axis = axis_of<Dim>(r.string("axis"), r.at("axis"));
  s.position = r.number("position", c.units.factor(Quantity::Length));
}

}  // namespace

CLEAVE_REGISTER_LOAD_KIND("symmetry", 4, read_symmetry)

}  // namespace cleave::scene
