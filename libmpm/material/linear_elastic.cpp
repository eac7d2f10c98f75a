// Registration of the built-in materials.
#include "libmpm/material/linear_elastic.hpp"

namespace cleave {

void register_builtin_materials() {
  static bool done = [] {
    MaterialRegistry<2>::instance().add("linear_elastic", [](const MaterialArgs& a) {
      return std::unique_ptr<Material<2>>(new LinearElastic<2>(a));
    });
    MaterialRegistry<3>::instance().add("linear_elastic", [](const MaterialArgs& a) {
      return std::unique_ptr<Material<3>>(new LinearElastic<3>(a));
    });
    return true;
  }();
  (void)done;
}

}  // namespace cleave
