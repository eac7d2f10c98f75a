// The scene's contact between bodies: which bodies get fields of their own, and each pair's law.
#include "libmpm/mpm/body_contact_scene.hpp"

#include <algorithm>
#include <map>

#include "libmpm/core/error.hpp"
#include "libmpm/core/json_reader.hpp"
#include "libmpm/crack/contact_keys.hpp"

namespace cleave {

BodyContact read_body_contact(const nlohmann::json& scene, const std::vector<std::string>& body_names) {
  const nlohmann::json& list = scene["contact"];
  if (!list.is_array()) throw SceneError("contact", "expected an array of {\"bodies\": [...], \"law\": ...} objects");
  const std::size_t nb = body_names.size();
  struct Entry {
    std::vector<std::size_t> bodies;
    crack::ContactSettings law;
    int normal_body = -1;
  };
  std::vector<Entry> entries;
  std::vector<uint8_t> named(nb, 0);
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string path = "contact[" + std::to_string(i) + "]";
    const ObjectReader r(list[i], path, {"bodies", "law", "mu", "detection", "v_sep", "v_contact", "d_contact", "normal"});
    if (!r.has("bodies")) throw SceneError(r.at("bodies"), "missing (the names of the bodies in contact, or \"all\")");
    Entry e;
    const nlohmann::json& b = r["bodies"];
    if (b.is_string() && b.get<std::string>() == "all") {
      for (std::size_t k = 0; k < nb; ++k) e.bodies.push_back(k);
    } else if (b.is_array()) {
      for (std::size_t k = 0; k < b.size(); ++k) {
        const std::string at = r.at("bodies") + "[" + std::to_string(k) + "]";
        if (!b[k].is_string()) throw SceneError(at, "expected a body's name");
        const std::string name = b[k].get<std::string>();
        const auto it = std::find(body_names.begin(), body_names.end(), name);
        if (it == body_names.end()) {
          std::string valid;
          for (const auto& n : body_names) valid += (valid.empty() ? "" : ", ") + n;
          throw SceneError(at, "no body is named \"" + name + "\"; bodies: " + valid);
        }
        const std::size_t id = static_cast<std::size_t>(it - body_names.begin());
        if (std::find(e.bodies.begin(), e.bodies.end(), id) != e.bodies.end())
          throw SceneError(at, "body \"" + name + "\" is named twice");
        e.bodies.push_back(id);
      }
    } else {
      throw SceneError(r.at("bodies"), "expected an array of body names or \"all\"");
    }
    if (e.bodies.size() < 2)
      throw SceneError(r.at("bodies"), "names " + std::to_string(e.bodies.size()) +
                                           " body; contact needs at least two (every pair among them)");
    read_contact_settings(r, e.law, true);
    if (r.has("normal") && r.string("normal") != "average") {
      const std::string name = r.string("normal");
      const auto it = std::find_if(e.bodies.begin(), e.bodies.end(), [&](std::size_t k) { return body_names[k] == name; });
      if (it == e.bodies.end())
        throw SceneError(r.at("normal"), "\"" + name + "\" is not one of this entry's bodies; give \"average\" (the "
                                         "default) or the name of the body whose surface gives the contact normal");
      e.normal_body = static_cast<int>(*it);
    }
    for (std::size_t k : e.bodies) named[k] = 1;
    entries.push_back(std::move(e));
  }
  BodyContact bc;
  if (entries.empty()) return bc;
  // Groups: the named bodies one each, in body order, after group 0 for the others (if any).
  const bool all_named = std::all_of(named.begin(), named.end(), [](uint8_t x) { return x != 0; });
  int next = all_named ? 0 : 1;
  bc.group.assign(nb, 0);
  for (std::size_t k = 0; k < nb; ++k)
    if (named[k]) bc.group[k] = static_cast<uint8_t>(next++);
  if (next > BodyContact::kMaxGroups)
    throw SceneError("contact", "gives " + std::to_string(next) + " bodies fields of their own; at most " +
                                    std::to_string(BodyContact::kMaxGroups));
  bc.groups = next;
  bc.pair.assign(static_cast<std::size_t>(next * next), -1);
  for (const Entry& e : entries) {
    const auto law = static_cast<int16_t>(bc.laws.size());
    bc.laws.push_back(e.law);
    bc.normal_from.push_back(e.normal_body < 0 ? -1 : bc.group[static_cast<std::size_t>(e.normal_body)]);
    for (std::size_t a : e.bodies)
      for (std::size_t b : e.bodies)
        if (a != b) bc.pair[static_cast<std::size_t>(bc.group[a] * next + bc.group[b])] = law;
  }
  return bc;
}

}  // namespace cleave
