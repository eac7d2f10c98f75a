#include "libmpm/scene/overlap.hpp"

namespace cleave::scene {

template <int Dim>
std::vector<std::string> overlap_warnings(const std::vector<BodySpec<Dim>>& specs,
                                          const std::vector<std::pair<const Vec<Dim>*, std::size_t>>& points,
                                          const std::string& unit, const std::string& consequence) {
  std::vector<std::string> out;
  // Points of body b inside the shape of body a, testing only those inside a's bounding box.
  auto inside = [&](std::size_t a, std::size_t b) {
    const auto box = specs[a].shape->bounds();
    std::size_t n = 0;
    for (std::size_t k = 0; k < points[b].second; ++k) {
      const Vec<Dim>& x = points[b].first[k];
      n += box.contains(x) && specs[a].shape->contains(x);
    }
    return n;
  };
  for (std::size_t a = 0; a < specs.size(); ++a)
    for (std::size_t b = a + 1; b < specs.size(); ++b) {
      const auto ba = specs[a].shape->bounds(), bb = specs[b].shape->bounds();
      if (((ba.hi.array() < bb.lo.array()) || (bb.hi.array() < ba.lo.array())).any()) continue;
      const std::size_t n = inside(a, b) + inside(b, a);
      if (n)
        out.push_back("bodies '" + specs[a].name + "' (" + specs[a].path + ") and '" + specs[b].name + "' (" +
                      specs[b].path + ") overlap: " + std::to_string(n) + " " + unit + (n == 1 ? "" : "s") +
                      " of one lie inside the other's shape; " + consequence +
                      " (cut one out of the other with a \"difference\" shape)");
    }
  return out;
}

template std::vector<std::string> overlap_warnings<2>(const std::vector<BodySpec<2>>&,
                                                      const std::vector<std::pair<const Vec<2>*, std::size_t>>&,
                                                      const std::string&, const std::string&);
template std::vector<std::string> overlap_warnings<3>(const std::vector<BodySpec<3>>&,
                                                      const std::vector<std::pair<const Vec<3>*, std::size_t>>&,
                                                      const std::string&, const std::string&);

}  // namespace cleave::scene
