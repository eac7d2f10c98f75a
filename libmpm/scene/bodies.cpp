#include "libmpm/scene/bodies.hpp"

#include <Eigen/Geometry>

namespace cleave::scene {

template <int Dim>
ObjectReader BodySpec<Dim>::reader() const {
  return ObjectReader(*object, path,
                      {"name", "material", "shape", "particles_per_cell", "velocity", "angular_velocity",
                       "rotation_center", "thickness"});
}

template <int Dim>
void BodySpec<Dim>::add_rotation(const UnitSystem& units, double length, const Vec<Dim>* x, Vec<Dim>* v,
                                 std::size_t n) const {
  const ObjectReader r = reader();
  if (!r.has("angular_velocity")) {
    if (r.has("rotation_center")) throw SceneError(r.at("rotation_center"), "only with angular_velocity");
    return;
  }
  // Rigid rotation about the centre: v = v0 + w x (x - c); w a rate about z in 2D, a vector in 3D.
  Vec<Dim> c = Vec<Dim>::Zero();
  if (r.has("rotation_center")) {
    c = r.vec<Dim>("rotation_center", length);
  } else {
    for (std::size_t p = 0; p < n; ++p) c += x[p];
    c /= static_cast<double>(n);
  }
  if constexpr (Dim == 3) {
    const Vec<3> w = r.vec<3>("angular_velocity", units.factor(Quantity::InverseTime));
    for (std::size_t p = 0; p < n; ++p) v[p] += w.cross(x[p] - c);
  } else {
    const double w = r.number("angular_velocity", units.factor(Quantity::InverseTime));
    for (std::size_t p = 0; p < n; ++p) v[p] += w * Vec<2>(-(x[p].y() - c.y()), x[p].x() - c.x());
  }
}

template <int Dim>
std::vector<BodySpec<Dim>> read_bodies(const nlohmann::json& scene, const UnitSystem& units,
                                       const std::map<std::string, int>& materials) {
  const nlohmann::json& bodies = array_at(scene, "bodies", true);
  if (bodies.empty()) throw SceneError("bodies", "at least one body is needed");
  const double L = units.factor(Quantity::Length);
  std::vector<BodySpec<Dim>> out;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    BodySpec<Dim> b;
    b.path = index_path("bodies", i);
    b.object = &bodies[i];
    const ObjectReader r = b.reader();
    b.name = r.string_or("name", "body" + std::to_string(i));
    for (const auto& other : out)
      if (other.name == b.name) throw SceneError(r.at("name"), "duplicate body name '" + b.name + "'");
    const std::string mat = r.string("material");
    const auto it = materials.find(mat);
    if (it == materials.end()) throw SceneError(r.at("material"), "no material named '" + mat + "'");
    b.material = it->second;
    if (!r.has("shape")) throw SceneError(r.at("shape"), "missing");
    b.shape = geom::parse_shape<Dim>(bodies[i]["shape"], r.at("shape"), L);
    if (r.has("velocity")) b.velocity = r.vec<Dim>("velocity", units.factor(Quantity::Velocity));
    out.push_back(std::move(b));
  }
  return out;
}

template struct BodySpec<2>;
template struct BodySpec<3>;
template std::vector<BodySpec<2>> read_bodies<2>(const nlohmann::json&, const UnitSystem&, const std::map<std::string, int>&);
template std::vector<BodySpec<3>> read_bodies<3>(const nlohmann::json&, const UnitSystem&, const std::map<std::string, int>&);

}  // namespace cleave::scene
