#include "libmpm/crack/crack3d.hpp"

#include <nlohmann/json.hpp>

#include "libmpm/core/error.hpp"
#include "libmpm/core/json_reader.hpp"
#include "libmpm/crack/contact_keys.hpp"
#include "libmpm/crack/surface3d.hpp"

namespace cleave::crack {

std::vector<ExplicitCrack<3>> parse_cracks3d(const nlohmann::json& cracks, const std::string& key_path,
                                             double length_scale, const SurfaceMeshing& meshing) {
  std::vector<Surface<3>> surfaces = parse_surfaces3d(cracks, key_path, length_scale, meshing);
  std::vector<ExplicitCrack<3>> out(surfaces.size());
  for (std::size_t i = 0; i < surfaces.size(); ++i) {
    ExplicitCrack<3>& c = out[i];
    static_cast<Surface<3>&>(c) = std::move(surfaces[i]);
    c.id = static_cast<int>(i);
    c.key = index_path(key_path, i);
    const ObjectReader r(cracks[i], index_path(key_path, i),
                         {"name", "triangles", "quad", "mesh", "rectangle", "ellipse", "file", "element_size",
                          "contact", "tips", "propagation", "tip_cut"});
    if (r.has("contact")) read_crack_contact(r, c);
    c.tips = r.string_or("tips", "auto");
    if (c.tips != "auto" && c.tips != "all" && c.tips != "none")
      throw SceneError(r.at("tips"), "unknown value \"" + c.tips + "\"; valid for 3D cracks: auto, all, none");
    // Cells, as in 2D; the MPM scene reader converts it to metres (build_cracks3d).
    c.tip_cut = read_tip_cut(r, kDefaultFrontCut);
    c.above = c.below = c.points;
  }
  return out;
}

}  // namespace cleave::crack
