// The four stress-update schemes of seed 002 (section 2.3, Appendix A), described by where the
// particle stresses are updated in the step, so one step routine serves all of them.
#pragma once
#include <optional>
#include <string>

namespace cleave {

enum class Scheme { USL, MUSL, USF, USAVG };

struct SchemeTraits {
  bool update_before_forces;  // Task 2 update (USF, USAVG)
  bool update_after_move;     // Task 6a update with p' (USL)
  bool reextrapolate;         // Task 6c: p'' from new velocities, then update (MUSL, USAVG)
  double fraction;            // share of dt per update: 1/2 for USAVG, which updates twice
};

inline SchemeTraits traits(Scheme s) {
  switch (s) {
    case Scheme::USL: return {false, true, false, 1.0};
    case Scheme::MUSL: return {false, false, true, 1.0};
    case Scheme::USF: return {true, false, false, 1.0};
    case Scheme::USAVG: return {true, false, true, 0.5};
  }
  return {true, false, true, 0.5};
}

inline const char* scheme_name(Scheme s) {
  switch (s) {
    case Scheme::USL: return "USL";
    case Scheme::MUSL: return "MUSL";
    case Scheme::USF: return "USF";
    case Scheme::USAVG: return "USAVG";
  }
  return "?";
}

inline std::optional<Scheme> scheme_from_name(const std::string& n) {
  for (Scheme s : {Scheme::USL, Scheme::MUSL, Scheme::USF, Scheme::USAVG})
    if (n == scheme_name(s)) return s;
  return std::nullopt;
}

}  // namespace cleave
