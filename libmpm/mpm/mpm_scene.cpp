#include "libmpm/mpm/mpm_scene.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <unordered_set>

#include "libmpm/geometry/shape.hpp"
#include "libmpm/core/json_reader.hpp"
#include "libmpm/core/units.hpp"
#include "libmpm/mpm/body_contact_scene.hpp"
#include "libmpm/mpm/crack_scene.hpp"
#include "libmpm/scene/bodies.hpp"
#include "libmpm/scene/budget.hpp"
#include "libmpm/scene/loads.hpp"
#include "libmpm/scene/overlap.hpp"
#include "libmpm/scene/resolution.hpp"
#include "libmpm/scene/sections.hpp"

namespace cleave {
namespace {

using nlohmann::json;
using scene::array_at;

const char* const kFieldNames[] = {"displacement", "velocity", "stress", "strain", "material",
                                   "mass", "volume", "size", "rotation", "von_mises", "principal_stress_difference"};

// Lattice coordinates of a particle, used to find boundary faces for tractions.
// A shape reaching far beyond an explicit grid (a union member far away) would need a lattice loop
// that long, and lattice keys beyond int64's range (undefined behaviour): refused beyond 1e6 cells. (A function of its
// own: inside the particle fill, the check changed how GCC contracted the fill's arithmetic, and the
// particles' positions by an ulp.)
template <int Dim>
[[gnu::noinline]] void check_lattice_reach(const Vec<Dim>& lo, const Vec<Dim>& hi, const GridGeometry<Dim>& g,
                                           const std::string& path, const std::string& body) {
  for (int d = 0; d < Dim; ++d) {
    const double a = std::floor((lo[d] - g.origin[d]) / g.h) - 1, b = std::ceil((hi[d] - g.origin[d]) / g.h) + 1;
    if (!(std::isfinite(a) && std::isfinite(b) && a >= -1e6 && b <= g.nodes[d] + 1e6))
      throw SceneError(path, "body '" + body + "' reaches more than 1e6 cells outside the grid along axis " +
                                 std::string(1, "xyz"[d]) + " (its shape's bounding box); enlarge grid.min/grid.max "
                                 "or move the shape");
    if (Dim == 3 && b > 2e6)  // LatticeKey's range in 3D
      throw SceneError(path, "body '" + body + "' reaches more than 2e6 cells from the grid's origin along axis " +
                                 std::string(1, "xyz"[d]) + "; a 3D lattice that long is not supported (coarser resolution)");
  }
}

template <int Dim>
struct LatticeKey {
  std::array<int64_t, Dim> c;
  // (Signed and exact: check_lattice_reach keeps |c| within 2e6 cells in 3D, so |k| < 2^63. Written
  // with wrapping unsigned arithmetic the same keys compiled to a particle fill whose positions differed
  // by an ulp from before: GCC's contraction of the fill follows the shape of the code.)
  int64_t hash() const {
    int64_t k = 0;
    for (int d = 0; d < Dim; ++d) k = k * 2000003 + c[d];
    return k;
  }
};

template <int Dim>
struct BodyLattice {
  int n = 2;                          // particles per cell per axis
  std::unordered_set<int64_t> occupied;
  std::vector<std::array<int64_t, Dim>> coord;  // per particle of the body
};

// Memory of a run (bytes), measured as peak RSS of runs of blocks (2D: 2e4 to 3.2e5 particles, and
// grids of 1.6e7 and 6.4e7 nodes; 3D: 1.25e5 and 1e6 particles): about 440 (2D) and 470 (3D) bytes
// a particle, 70 bytes a 2D node, rounded up; 100 MB for the program and its libraries.
template <int Dim>
double mpm_memory_bytes(double particles, double nodes) {
  return 100e6 + particles * (Dim == 2 ? 480.0 : 520.0) + nodes * (Dim == 2 ? 80.0 : 110.0);
}

}  // namespace

// A traction acts on the particle faces on its side that no particle of the same body covers
// (boundary faces), inside its region (default: the whole grid), on its body (default: every body).
template <int Dim>
static TractionLoad<Dim> resolve_traction(const Model<Dim>& m, const std::vector<BodyLattice<Dim>>& lattices,
                                          const scene::LoadSpec<Dim>& s) {
  TractionLoad<Dim> t;
  t.name = s.name;
  t.traction = s.vector;
  t.time_function.rise_time = s.rise_time;
  t.side = s.side;
  t.axis = s.axis;
  const double h = m.grid.h;
  const Vec<Dim> lo = s.has_region ? s.lo : m.grid.origin, hi = s.has_region ? s.hi : m.grid.upper();
  for (std::size_t k = 0; k < m.bodies.size(); ++k) {
    if (s.body >= 0 && static_cast<int>(k) != s.body) continue;
    const auto& B = m.bodies[k];
    const auto& lat = lattices[k];
    for (std::size_t j = 0; j < B.count; ++j) {
      const std::size_t p = B.first + j;
      const auto& x = m.particles.x[p];
      bool inside = true;
      for (int d = 0; d < Dim; ++d) inside = inside && x[d] >= lo[d] - 1e-9 * h && x[d] <= hi[d] + 1e-9 * h;
      if (!inside) continue;
      LatticeKey<Dim> nb{lat.coord[j]};
      nb.c[t.axis] += t.side;
      if (lat.occupied.count(nb.hash())) continue;  // not a boundary face of the body
      t.particles.push_back(static_cast<int32_t>(p));
      t.face_area.push_back(m.particles.volume0[p] / (h / lat.n));
    }
  }
  if (t.particles.empty())
    throw SceneError(s.path, "no particle face on side " + s.face + " lies inside the region: nothing would be loaded");
  return t;
}

template <int Dim>
Model<Dim> build_model(const json& scene) {
  ObjectReader top(scene, "", {"title", "description", "units", "method", "analysis", "resolution", "grid", "mpm",
                               "peridynamics", "pem", "materials", "bodies", "contact", "loads", "cracks", "crack_tips", "damping", "static", "time", "output", "checks"});
  if (top.has("method") && top.string("method") != "mpm")  // peridynamics: libmpm/pd/pd_scene.cpp
    throw SceneError("method", "build_model reads MPM scenes only (\"method\": \"mpm\")");
  Model<Dim> m;
  const UnitSystem units = UnitSystem::from_json(scene.value("units", json()), "units");
  const double L = units.factor(Quantity::Length);
  m.title = top.string_or("title", "");
  double thickness = 1.0;
  m.analysis = scene::read_analysis(scene, L, thickness);
  if (dimension_of(m.analysis) != Dim) throw SceneError("analysis.type", "dimension mismatch");

  // --- method -------------------------------------------------------------------------------
  // spin_transfer: on by default where a body is given a spin (the nodes' velocities then carry it:
  // spin_transfer.hpp); a body set spinning by an impact may ask for it.
  if (scene.contains("bodies") && scene["bodies"].is_array())
    for (const auto& b : scene["bodies"]) m.spin_transfer = m.spin_transfer || (b.is_object() && b.contains("angular_velocity"));
  if (top.has("mpm")) {
    ObjectReader r(scene["mpm"], "mpm", {"shape_function", "stress_update", "spin_transfer"});
    m.spin_transfer = r.boolean_or("spin_transfer", m.spin_transfer);
    const std::string sf = r.string_or("shape_function", "ugimp");
    const auto& styles = ShapeFunctions::instance();
    const ShapeFunctionStyle* style = styles.find(sf);
    if (!style) throw SceneError("mpm.shape_function", unknown_name("shape function", sf, styles.names_joined()));
    m.shape_function = style->kind;
    const std::string su = r.string_or("stress_update", "USAVG");
    auto s = scheme_from_name(su);
    if (!s) throw SceneError("mpm.stress_update", "unknown scheme '" + su + "'; valid: USL, MUSL, USF, USAVG");
    m.scheme = *s;
  }

  // --- materials and bodies: scene/bodies.hpp (shapes first, so the grid can be derived) --------
  auto& registry = MaterialRegistry<Dim>::instance();
  const auto material_index = scene::read_materials(scene, [&](const std::string& path, const std::string& type,
                                                               const json& j) {
    // Each material style checks its own keys (linear_elastic.cpp).
    if (!registry.has(type)) throw SceneError(path + ".type", registry.unknown("material type", type));
    m.materials.push_back(registry.create(type, MaterialArgs{j, path, units, m.analysis}));
  });
  const auto specs = scene::read_bodies<Dim>(scene, units, material_index);
  geom::Box<Dim> all;
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const auto b = specs[i].shape->bounds();
    all = i == 0 ? b : all.united(b);
  }

  // --- grid -----------------------------------------------------------------------------------
  {
    static const json no_grid = json::object();  // every grid key is optional with "resolution"
    ObjectReader r(top.has("grid") ? scene["grid"] : no_grid, "grid", {"cell_size", "min", "max", "margin_cells"});
    const auto [h, h_key] = scene::read_resolution(scene, "grid", "cell_size", "the grid's cell size", L);
    m.grid.h = h;
    if (r.has("min") != r.has("max"))
      throw SceneError(r.has("min") ? "grid.max" : "grid.min", "give both grid.min and grid.max, or neither");
    if (r.has("min")) {
      if (r.has("margin_cells"))
        throw SceneError("grid.margin_cells", "only used for a derived grid; remove it or remove grid.min/grid.max");
      const Vec<Dim> lo = r.vec<Dim>("min", L), hi = r.vec<Dim>("max", L);
      for (int d = 0; d < Dim; ++d) {
        const double cells = (hi[d] - lo[d]) / h;
        if (cells > 1e8) throw SceneError(h_key, "the grid would have more than 1e8 cells along one axis");
        if (!(cells >= 1.0)) throw SceneError("grid.max", "grid.max must exceed grid.min by at least one cell");
        if (std::fabs(cells - std::round(cells)) > 1e-6)
          throw SceneError("grid.max", "grid.max - grid.min must be a whole number of cells along axis " +
                                           std::to_string(d) + " (got " + std::to_string(cells) + " cells)");
        m.grid.nodes[d] = static_cast<int>(std::round(cells)) + 1;
      }
      m.grid.origin = lo;
    } else {
      // Derived: bodies' bounds plus a margin, snapped to multiples of h so that grid lines pass
      // through the origin (symmetry planes and body edges at round coordinates lie on grid lines).
      const int margin = r.integer_or("margin_cells", 2, 2, 1000);
      for (int d = 0; d < Dim; ++d) {
        const double lo = std::floor(all.lo[d] / h + 1e-9) - margin;
        const double hi = std::ceil(all.hi[d] / h - 1e-9) + margin;
        if (hi - lo > 1e8) throw SceneError(h_key, "the grid would have more than 1e8 cells along one axis");
        m.grid.origin[d] = lo * h;
        m.grid.nodes[d] = static_cast<int>(hi - lo) + 1;
      }
    }
    double nodes = 1;
    for (int d = 0; d < Dim; ++d) nodes *= m.grid.nodes[d];
    if (nodes > 2e9) throw SceneError(h_key, "the grid would have more than 2e9 nodes");
    m.size_key = h_key;
  }

  // --- memory, refused before any particle is made (scene/budget.hpp) ------------------------------
  double grid_nodes = 1;
  for (int d = 0; d < Dim; ++d) grid_nodes *= m.grid.nodes[d];
  {
    double particles = 0;
    for (const auto& spec : specs)
      particles += scene::estimate_points<Dim>(
          *spec.shape, m.grid.h / spec.reader().integer_or("particles_per_cell", 2, 1, 8));
    scene::check_memory(mpm_memory_bytes<Dim>(particles, grid_nodes), m.size_key,
                        scene::fmt(particles) + " particles and " + scene::fmt(grid_nodes) + " grid nodes");
  }

  // --- particles --------------------------------------------------------------------------------
  std::vector<BodyLattice<Dim>> lattices(specs.size());
  const int K = shape_function_style(m.shape_function).K;
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const auto& spec = specs[i];
    const ObjectReader r = spec.reader();
    Body b;
    b.name = spec.name;
    b.material = spec.material;
    const int n = r.integer_or("particles_per_cell", 2, 1, 8);
    if (Dim == 3 && r.has("thickness")) throw SceneError(r.at("thickness"), "a 3D body has no thickness");
    b.thickness = Dim == 2 ? r.positive_or("thickness", thickness, L) : 1.0;
    const Vec<Dim> v0 = spec.velocity;
    const auto& shape = *spec.shape;
    const auto bb = shape.bounds();
    const double h = m.grid.h;
    std::array<int64_t, Dim> c0, c1;
    check_lattice_reach<Dim>(bb.lo, bb.hi, m.grid, r.at("shape"), b.name);
    for (int d = 0; d < Dim; ++d) {
      c0[d] = static_cast<int64_t>(std::floor((bb.lo[d] - m.grid.origin[d]) / h)) - 1;
      c1[d] = static_cast<int64_t>(std::ceil((bb.hi[d] - m.grid.origin[d]) / h)) + 1;
    }
    auto& P = m.particles;
    b.first = P.size();
    const double sub = h / n;
    const double vol = std::pow(sub, Dim) * (Dim == 2 ? b.thickness : 1.0);
    const double rho = m.materials[b.material]->density();
    auto& lat = lattices[i];
    lat.n = n;
    // Cell columns along x outermost, so particles of one x strip are contiguous in memory.
    std::array<int64_t, Dim> q;
    for (q[0] = c0[0] * n; q[0] < c1[0] * n; ++q[0])
      for (q[1] = c0[1] * n; q[1] < c1[1] * n; ++q[1])
        for (int64_t z = (Dim == 3 ? c0[Dim - 1] * n : 0); z < (Dim == 3 ? c1[Dim - 1] * n : 1); ++z) {
          if constexpr (Dim == 3) q[2] = z;
          Vec<Dim> x;
          for (int d = 0; d < Dim; ++d) x[d] = m.grid.origin[d] + sub * (q[d] + 0.5);
          if (!shape.contains(x)) continue;
          // Every node of the particle's stencil must exist.
          for (int d = 0; d < Dim; ++d) {
            if (!stencil_fits((x[d] - m.grid.origin[d]) / h, m.grid.nodes[d], K))
              throw SceneError(r.at("shape"), "body '" + b.name + "' reaches outside the grid along axis " +
                                                  std::string(1, "xyz"[d]) + " (a particle at " +
                                                  std::to_string(x[d]) + " m needs grid nodes beyond the grid; "
                                                  "enlarge grid.min/grid.max)");
          }
          const std::size_t p = P.size();
          P.resize(p + 1);
          P.x[p] = x;
          P.v[p] = v0;
          P.u[p].setZero();
          P.stress[p].setZero();
          P.strain[p].setZero();
          P.volume0[p] = vol;
          P.mass[p] = rho * vol;
          P.half_width[p] = 0.5 / n;
          P.material[p] = b.material;
          if constexpr (Dim == 2) P.rotation[p] = 0.0;
          LatticeKey<Dim> key{q};
          lat.occupied.insert(key.hash());
          lat.coord.push_back(q);
        }
    b.count = P.size() - b.first;
    if (b.count == 0)
      throw SceneError(r.at("shape"), "body '" + b.name + "' holds no particle centre at this cell size");
    spec.add_rotation(units, L, &P.x[b.first], &P.v[b.first], b.count);
    m.bodies.push_back(b);
  }

  // --- contact between bodies: mpm/body_contact_scene.cpp ---------------------------------------
  if (top.has("contact")) {
    std::vector<std::string> names;
    for (const auto& b : m.bodies) names.push_back(b.name);
    m.body_contact = read_body_contact(scene, names);
  }
  {
    std::vector<std::pair<const Vec<Dim>*, std::size_t>> points;
    for (const auto& b : m.bodies) points.emplace_back(&m.particles.x[b.first], b.count);
    for (auto& w : scene::overlap_warnings<Dim>(specs, points, "particle",
                                                "MPM gives the overlap the mass of both, and their particles share "
                                                "grid nodes, so the two stick together (or, where \"contact\" names both, each "
                                                "moves on its own field and the overlap stays: contact acts only "
                                                "while bodies approach)"))
      m.warnings.push_back(std::move(w));
  }

  // --- cracks (2D, seed 002): mpm/crack_scene.cpp ------------------------------------------------
  if (top.has("cracks")) read_cracks(scene, L, m);

  // --- loads: read by scene/loads.hpp, resolved here on particle faces and grid nodes -----------
  std::map<int64_t, std::pair<uint8_t, Vec<Dim>>> conditions;
  const double h = m.grid.h;
  auto node_loop = [&](const Vec<Dim>& lo, const Vec<Dim>& hi, auto&& fn) {
    std::array<int, Dim> a, b, ijk;
    for (int d = 0; d < Dim; ++d) {
      // Clamped before the cast: a region may reach beyond int's range of cells (1e300).
      a[d] = static_cast<int>(std::clamp(std::ceil((lo[d] - m.grid.origin[d]) / h - 1e-6), 0.0, double(m.grid.nodes[d])));
      b[d] = static_cast<int>(
          std::clamp(std::floor((hi[d] - m.grid.origin[d]) / h + 1e-6), -1.0, double(m.grid.nodes[d] - 1)));
    }
    int count = 0;
    for (ijk[0] = a[0]; ijk[0] <= b[0]; ++ijk[0])
      for (ijk[1] = a[1]; ijk[1] <= b[1]; ++ijk[1])
        for (int k = (Dim == 3 ? a[Dim - 1] : 0); k <= (Dim == 3 ? b[Dim - 1] : 0); ++k) {
          if constexpr (Dim == 3) ijk[2] = k;
          fn(static_cast<int64_t>(m.grid.index(ijk)));
          ++count;
        }
    return count;
  };
  scene::LoadResolvers<Dim> resolvers;
  resolvers["traction"] = [&](const scene::LoadSpec<Dim>& s) {
    m.tractions.push_back(resolve_traction(m, lattices, s));
    if (s.total_force) {  // the total force spread evenly over the loaded faces' area
      double area = 0;
      for (double a : m.tractions.back().face_area) area += a;
      if (!(area > 0)) throw SceneError(s.at("force"), "no particle face is loaded: the force has no area to act on");
      m.tractions.back().traction = s.vector / area;
    }
  };
  resolvers["body_force"] = [&](const scene::LoadSpec<Dim>& s) { m.gravity += s.vector; };
  resolvers["velocity"] = [&](const scene::LoadSpec<Dim>& s) {
    const int count = node_loop(s.lo, s.hi, [&](int64_t n) {
      auto& c = conditions[n];
      c.first |= s.mask;
      for (int d = 0; d < Dim; ++d)
        if (s.mask & (1u << d)) c.second[d] = s.vector[d];
    });
    if (!count) throw SceneError(s.at("region"), "no grid node lies inside the region");
  };
  resolvers["symmetry"] = [&](const scene::LoadSpec<Dim>& s) {
    const int axis = s.axis;
    const double cells = (s.position - m.grid.origin[axis]) / h;
    if (std::fabs(cells - std::round(cells)) > 1e-6 || cells < 0 || cells > m.grid.nodes[axis] - 1)
      throw SceneError(s.at("position"), "a symmetry plane must lie on a grid line inside the grid (grid lines "
                                         "are at origin + k * cell_size)");
    Vec<Dim> lo = m.grid.origin, hi = m.grid.upper();
    lo[axis] = hi[axis] = m.grid.origin[axis] + std::round(cells) * h;
    m.symmetry_planes.push_back({axis, lo[axis]});
    node_loop(lo, hi, [&](int64_t n) {
      auto& c = conditions[n];
      c.first |= uint8_t(1u << axis);
      c.second[axis] = 0.0;
    });
  };
  std::vector<std::string> body_names;
  for (const auto& b : m.bodies) body_names.push_back(b.name);
  scene::read_loads<Dim>(scene, {units, body_names}, "mpm", resolvers);
  for (auto& [node, c] : conditions) {
    m.conditions.node.push_back(node);
    m.conditions.mask.push_back(c.first);
    m.conditions.velocity.push_back(c.second);
  }

  // --- damping, time, output (shared sections) ----------------------------------------------------
  m.damping = scene::read_damping(scene, units);
  m.static_tolerance = scene::read_static(scene, m.damping);
  if (top.has("cracks")) warn_volume_detection_when_slow(m);
  {
    double cmax = 0.0, vmax = 0.0;
    for (const auto& b : m.bodies) cmax = std::max(cmax, m.materials[b.material]->wave_speed());
    for (const auto& v : m.particles.v) vmax = std::max(vmax, v.norm());
    scene::read_time(scene, units, m.grid.h / (cmax + vmax), "cell / (wave speed + particle speed)",
                     "no material has a wave speed", m);
  }
  scene::read_output(scene, units, kFieldNames, "", top.has("crack_tips"), m);
  scene::check_frame_count(m);
  m.memory_bytes = mpm_memory_bytes<Dim>(double(m.particles.size()), grid_nodes);
  if (top.has("crack_tips")) read_crack_tips(scene, units, m);
  // Bodies that share grid nodes with very different mass per particle make the node's effective
  // wave speed exceed the material estimate; linear shape functions then need a smaller CFL
  // (docs/validation.md, beam impact: 240x, unstable at CFL 0.5, stable at 0.1).
  if (m.shape_function == ShapeFunctionKind::Linear && m.bodies.size() > 1) {
    double lo = 1e300, hi = 0;
    std::string light, heavy;
    for (const auto& b : m.bodies) {
      const double mp = m.particles.mass[b.first];
      if (mp < lo) lo = mp, light = b.name;
      if (mp > hi) hi = mp, heavy = b.name;
    }
    if (hi > 10 * lo)
      m.warnings.push_back("bodies '" + heavy + "' and '" + light + "' differ " + std::to_string(int(hi / lo)) +
                           "x in particle mass: with linear shape functions contact between them can be unstable at "
                           "CFL 0.5 (use time.cfl 0.1 or mpm.shape_function ugimp)");
  }
  scene::read_checks(scene, m);
  return m;
}

template Model<2> build_model<2>(const json&);
template Model<3> build_model<3>(const json&);

}  // namespace cleave
