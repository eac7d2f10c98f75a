#include "libmpm/scene/loads.hpp"

#include "libmpm/scene/sections.hpp"

namespace cleave::scene {

template <int Dim>
void read_loads(const nlohmann::json& scene, const LoadContext& c, const std::string& method,
                const LoadResolvers<Dim>& resolvers, const std::map<std::string, std::string>& refusals) {
  const LoadKinds& kinds = LoadKinds::instance();
  const std::vector<std::string> accepted =
      kinds.names_where([&](const std::string& n, const LoadKind&) { return resolvers.count(n) != 0; });
  const nlohmann::json& loads = array_at(scene, "loads", false);
  for (std::size_t i = 0; i < loads.size(); ++i) {
    const std::string path = index_path("loads", i);
    if (!loads[i].is_object() || !loads[i].contains("type"))
      throw SceneError(path + ".type", "missing (" + join_names(accepted, " or ") + ")");
    const std::string type = loads[i]["type"].is_string() ? loads[i]["type"].get<std::string>() : "";
    const LoadKind* kind = kinds.find(type);
    const auto resolve = resolvers.find(type);
    if (kind && resolve == resolvers.end()) {
      const auto why = refusals.find(type);
      throw SceneError(path + ".type", why != refusals.end() ? why->second
                                                             : type + " loads are not available with " + method);
    }
    if (!kind) throw SceneError(path + ".type", unknown_name("load type", type, join_names(accepted)));
    LoadSpec<Dim> s;
    s.kind = type;
    s.path = s.name = path;
    if constexpr (Dim == 2) kind->read2(loads[i], path, c, s);
    else kind->read3(loads[i], path, c, s);
    resolve->second(s);
  }
}

template void read_loads<2>(const nlohmann::json&, const LoadContext&, const std::string&, const LoadResolvers<2>&,
                            const std::map<std::string, std::string>&);
template void read_loads<3>(const nlohmann::json&, const LoadContext&, const std::string&, const LoadResolvers<3>&,
                            const std::map<std::string, std::string>&);

}  // namespace cleave::scene
