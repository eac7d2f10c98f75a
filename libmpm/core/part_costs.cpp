#include "libmpm/core/part_costs.hpp"

namespace cleave::costs {

// Out of line on purpose (part_costs.hpp): a call is all the caller sees.
int enter(int part) noexcept { return active ? active->enter(part) : Step; }
void leave(int was) noexcept {
  if (active) active->leave(was);
}

}  // namespace cleave::costs
