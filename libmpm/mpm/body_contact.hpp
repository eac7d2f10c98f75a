// Contact between bodies (the scene's "contact" key, docs/scenes.md): which bodies move on velocity
// fields of their own where they meet, and the law between each pair. Without it every body adds
// into one field per node, so bodies that come within a cell of each other stick together.
// The fields live where the crack fields live (libmpm/mpm/crack_fields/): one multi-field machinery
// for crack faces and for bodies (crack_fields/body_groups.hpp says how a body's field is keyed).
#pragma once
#include <cstdint>
#include <vector>

#include "libmpm/crack/explicit_crack.hpp"

namespace cleave {

struct BodyContact {
  // Field groups: every body named in a declared pair has a group of its own (1, 2, ...); the other
  // bodies share group 0, as all bodies share one field without contact.
  static constexpr int kMaxGroups = 32;  // (a node's groups are a 32-bit mask)
  std::vector<uint8_t> group;            // per body (Model::bodies)
  int groups = 0;                        // 0: no contact between bodies
  // groups x groups: the index in `laws` of the pair's law, or -1 for a pair the scene did not
  // declare (they stick, as in one field).
  std::vector<int16_t> pair;
  std::vector<crack::ContactSettings> laws;
  // Per law: the group whose surface gives the pair's contact normal (the scene's "normal": a flat or
  // stiff face), or -1 for the difference of the two bodies' mass gradients ("average").
  std::vector<int> normal_from;

  bool active() const { return groups > 1; }
  const crack::ContactSettings* law(int ga, int gb) const {
    const int16_t i = pair[static_cast<std::size_t>(ga * groups + gb)];
    return i < 0 ? nullptr : &laws[static_cast<std::size_t>(i)];
  }
  int normal_group(int ga, int gb) const {
    const int16_t i = pair[static_cast<std::size_t>(ga * groups + gb)];
    return i < 0 ? -1 : normal_from[static_cast<std::size_t>(i)];
  }
};

}  // namespace cleave
