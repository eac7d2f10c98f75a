#include "libmpm/pd/pd_scene.hpp"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <limits>
#include <map>
#include <unordered_map>

#include "libmpm/geometry/shape.hpp"
#include "libmpm/crack/surface.hpp"
#include "libmpm/core/json_reader.hpp"
#include "libmpm/core/units.hpp"
#include "libmpm/pd/pd_material.hpp"
#include "libmpm/scene/bodies.hpp"
#include "libmpm/scene/budget.hpp"
#include "libmpm/scene/loads.hpp"
#include "libmpm/scene/resolution.hpp"
#include "libmpm/scene/sections.hpp"

namespace cleave::pd {
namespace {

using nlohmann::json;
using scene::array_at;
using scene::in_box;
using scene::read_region;

const char* const kPdFields[] = {"displacement", "velocity", "damage", "stress", "von_mises",
                                 "principal_stress_difference", "material", "volume", "size"};

// Lattice index of a point: points sit at (k + 1/2) dx on every axis, one lattice for all bodies.
template <int Dim>
int64_t lattice_key(const std::array<int64_t, Dim>& q) {
  // Wrapping (unsigned) arithmetic: a body far from the origin overflowed the signed key (undefined
  // behaviour); keys stay distinct while the points span under about 1e6 sites per axis.
  uint64_t k = 0;
  for (int d = 0; d < Dim; ++d) k = k * 4000037u + static_cast<uint64_t>(q[d]);
  return static_cast<int64_t>(k);
}

// Memory of a run of `points` points with horizon factor m (bytes), measured as peak RSS of runs
// of 2D and 3D blocks (2e4 to 8e4 points): about 110 bytes per bond and a few hundred per point;
// bonds per point about 0.65 of the lattice sites in the horizon (pi m^2, 4/3 pi m^3), as the
// lattice ball is cut at the body's faces. 100 MB for the program and its libraries.
template <int Dim>
double pd_memory_bytes(double points, int m) {
  const double sites = Dim == 2 ? 3.14159 * m * m : 4.18879 * m * m * m;
  return 100e6 + points * (110.0 * 0.65 * sites + 300.0);
}

}  // namespace

template <int Dim>
PdSystem<Dim> build_pd_system(const json& scene) {
  // The sections of the other methods ("mpm", "pem") are theirs: one scene runs under each. MPM's
  // "grid" stays an error (it looks like the spacing, which is "resolution" here).
  ObjectReader top(scene, "", {"title", "description", "units", "method", "analysis", "resolution", "peridynamics", "mpm",
                               "pem", "materials",
                               "bodies", "cracks", "loads", "damping", "static", "time", "output", "checks"});
  PdSystem<Dim> m;
  const UnitSystem units = UnitSystem::from_json(scene.value("units", json()), "units");
  const double L = units.factor(Quantity::Length);
  m.title = top.string_or("title", "");

  m.analysis = scene::read_analysis(scene, L, m.thickness);
  if (dimension_of(m.analysis) != Dim) throw SceneError("analysis.type", "dimension mismatch");
  if (Dim == 3) m.thickness = 1.0;
  const PdModel model = m.analysis == Analysis::PlaneStress   ? PdModel::PlaneStress
                            : m.analysis == Analysis::PlaneStrain ? PdModel::PlaneStrain
                                                                  : PdModel::ThreeD;

  // --- peridynamics ---------------------------------------------------------------------------
  std::vector<std::pair<Vec<Dim>, Vec<Dim>>> no_fail;
  std::string dx_key;  // the scene key the lattice spacing came from, for the errors about it
  {
    static const json no_section = json::object();  // every key is optional with "resolution"
    ObjectReader r(top.has("peridynamics") ? scene["peridynamics"] : no_section, "peridynamics", {"spacing", "horizon_factor", "no_fail", "crack_tips",
                                                           "tip_damage"});
    const auto spacing = scene::read_resolution(scene, "peridynamics", "spacing", "the lattice spacing", L);
    m.dx = spacing.length;
    dx_key = spacing.key;
    m.horizon_factor = r.integer_or("horizon_factor", 3, 1, 12);
    m.delta = m.horizon_factor * m.dx;
    m.tip_threshold = r.number_or("tip_damage", 0.3);
    if (!(m.tip_threshold > 0.0 && m.tip_threshold < 1.0))
      throw SceneError(r.at("tip_damage"), "must lie strictly between 0 and 1");
    if (r.has("no_fail")) {
      const json& nf = r["no_fail"];
      if (!nf.is_array()) throw SceneError(r.at("no_fail"), "expected an array of regions {min, max}");
      for (std::size_t i = 0; i < nf.size(); ++i) {
        const std::string p = index_path(r.at("no_fail"), i);
        ObjectReader rr(nf[i], p, {"min", "max"});
        Vec<Dim> lo = rr.vec<Dim>("min", L), hi = rr.vec<Dim>("max", L);
        for (int d = 0; d < Dim; ++d)
          if (!(hi[d] >= lo[d])) throw SceneError(rr.at("max"), "region max is below region min");
        no_fail.emplace_back(lo, hi);
      }
    }
    if (r.has("crack_tips")) {
      const json& ct = r["crack_tips"];
      if (!ct.is_array() || ct.empty()) throw SceneError(r.at("crack_tips"), "expected a non-empty array of trackers");
      for (std::size_t i = 0; i < ct.size(); ++i) {
        const std::string p = index_path(r.at("crack_tips"), i);
        ObjectReader rr(ct[i], p, {"name", "direction", "region"});
        TipTracker<Dim> t;
        t.name = rr.string_or("name", std::to_string(i));
        const Vec<Dim> d = rr.vec<Dim>("direction");
        if (!(d.norm() > 0)) throw SceneError(rr.at("direction"), "must not be the zero vector");
        t.direction = d.normalized();
        if (rr.has("region")) {
          t.has_region = true;
          read_region<Dim>(rr, "region", L, t.lo, t.hi);
        }
        for (const auto& o : m.trackers)
          if (o.name == t.name) throw SceneError(rr.at("name"), "duplicate tracker name '" + t.name + "'");
        m.trackers.push_back(t);
      }
    } else {
      TipTracker<Dim> t;
      t.name = "0";
      m.trackers.push_back(t);  // the damaged point farthest along +x
    }
  }

  // --- materials: looked up by "type" among the peridynamic material styles ----------------------
  const PdMaterialContext mc{units, model, m.delta, m.thickness, m.warnings};
  const auto material_index = scene::read_materials(scene, [&](const std::string& path, const std::string& type,
                                                               const json& j) {
    // Each style checks its own keys (pd_linear_elastic.cpp).
    const auto& styles = PdMaterialStyles::instance();
    const PdMaterialReader* read = styles.find(type);
    if (!read)
      throw SceneError(path + ".type", "unknown material type '" + type + "' for peridynamics; valid: " +
                                           styles.names_joined());
    m.materials.push_back((*read)(j, path, mc));
    m.materials.back().name = j["name"].get<std::string>();
  });

  // --- bodies on one lattice: points at (k + 1/2) dx ---------------------------------------------
  const auto specs = scene::read_bodies<Dim>(scene, units, material_index);
  m.size_key = dx_key;
  {
    // Refused before any point or bond is made (scene/budget.hpp), as a scene error at the spacing.
    double points = 0;
    for (const auto& spec : specs) points += scene::estimate_points<Dim>(*spec.shape, m.dx);
    scene::check_memory(pd_memory_bytes<Dim>(points, m.horizon_factor), dx_key, scene::fmt(points) + " points");
  }
  auto& P = m.points;
  std::unordered_map<int64_t, int32_t> occupied;  // lattice key -> point
  std::vector<std::array<int64_t, Dim>> coord;
  const double vol = std::pow(m.dx, Dim) * (Dim == 2 ? m.thickness : 1.0);
  for (const auto& spec : specs) {
    const ObjectReader r = spec.reader();
    if (r.has("particles_per_cell"))
      m.warnings.push_back(r.at("particles_per_cell") + " is ignored: it is an MPM key (peridynamics' lattice spacing "
                                                        "is \"resolution\")");
    if (r.has("thickness"))
      throw SceneError(r.at("thickness"), "peridynamics uses analysis.thickness for every body");
    const std::string& name = spec.name;
    const int mi = spec.material;
    const auto& shape = spec.shape;
    const Vec<Dim> v0 = spec.velocity;
    const auto bb = shape->bounds();
    std::array<int64_t, Dim> c0, c1;
    double cells = 1;
    std::array<double, Dim> lo, hi;
    for (int d = 0; d < Dim; ++d) {
      lo[d] = std::floor(bb.lo[d] / m.dx) - 1;
      hi[d] = std::ceil(bb.hi[d] / m.dx) + 1;
      cells *= hi[d] - lo[d];
      // Lattice indices are int64 and exact in a double: a shape 1e15 spacings from the origin has none.
      if (!(std::fabs(lo[d]) < 1e15 && std::fabs(hi[d]) < 1e15))
        throw SceneError(r.at("shape"), "body '" + name + "' lies more than 1e15 lattice spacings from the origin "
                                        "along axis " + std::string(1, "xyz"[d]) + "; move it or use a coarser " + dx_key);
    }
    if (cells > 2e9) throw SceneError(dx_key, "body '" + name + "' would need more than 2e9 lattice sites");
    for (int d = 0; d < Dim; ++d) {  // checked above: in int64's range
      c0[d] = static_cast<int64_t>(lo[d]);
      c1[d] = static_cast<int64_t>(hi[d]);
    }
    const std::size_t first = P.size();
    std::array<int64_t, Dim> q;
    for (q[0] = c0[0]; q[0] < c1[0]; ++q[0])
      for (q[1] = c0[1]; q[1] < c1[1]; ++q[1])
        for (int64_t z = (Dim == 3 ? c0[Dim - 1] : 0); z < (Dim == 3 ? c1[Dim - 1] : 1); ++z) {
          if constexpr (Dim == 3) q[2] = z;
          Vec<Dim> x;
          for (int d = 0; d < Dim; ++d) x[d] = m.dx * (static_cast<double>(q[d]) + 0.5);
          if (!shape->contains(x)) continue;
          const int64_t key = lattice_key<Dim>(q);
          if (auto it = occupied.find(key); it != occupied.end())
            throw SceneError(r.at("shape"), "body '" + name + "' overlaps body '" + m.bodies[P.body[it->second]] +
                                                "' (peridynamic bodies may not share lattice points)");
          const auto p = static_cast<int32_t>(P.size());
          occupied.emplace(key, p);
          P.resize(P.size() + 1);
          P.x0[p] = x;
          P.u[p].setZero();
          P.v[p] = v0;
          P.a[p].setZero();
          P.b[p].setZero();
          P.volume[p] = vol;
          P.mass[p] = m.materials[mi].density * vol;
          P.material[p] = mi;
          P.body[p] = static_cast<int32_t>(m.bodies.size());
          P.no_fail[p] = 0;
          P.fixed[p] = 0;
          P.v_fixed[p].setZero();
          coord.push_back(q);
        }
    if (P.size() == first)
      throw SceneError(r.at("shape"), "body '" + name + "' holds no lattice point at this spacing");
    spec.add_rotation(units, L, &P.x0[first], &P.v[first], P.size() - first);
    m.bodies.push_back(name);
  }
  if (P.size() > static_cast<std::size_t>(std::numeric_limits<int32_t>::max()))
    throw SceneError(dx_key, "more than 2^31 - 1 points");
  const double tol = 1e-9 * m.dx;
  for (std::size_t p = 0; p < P.size(); ++p)
    for (const auto& [lo, hi] : no_fail)
      if (in_box<Dim>(P.x0[p], lo, hi, tol)) P.no_fail[p] = 1;

  // --- loads: read by scene/loads.hpp, resolved here on lattice points ---------------------------
  scene::LoadResolvers<Dim> resolvers;
  resolvers["traction"] = [&](const scene::LoadSpec<Dim>& s) {
    PdLoad<Dim> ld;
    ld.name = s.name;
    ld.force_density = s.vector / m.dx;  // the traction spread over one lattice layer
    ld.rise_time = s.rise_time;
    for (std::size_t p = 0; p < P.size(); ++p) {
      if (s.body >= 0 && P.body[p] != s.body) continue;
      if (s.has_region && !in_box<Dim>(P.x0[p], s.lo, s.hi, tol)) continue;
      auto nq = coord[p];
      nq[s.axis] += s.side;
      auto it = occupied.find(lattice_key<Dim>(nq));
      if (it != occupied.end() && P.body[it->second] == P.body[p]) continue;  // not on the body's face
      ld.points.push_back(static_cast<int32_t>(p));
    }
    if (ld.points.empty())
      throw SceneError(s.path, "no point on side " + s.face + " lies inside the region: nothing would be loaded");
    if (s.total_force) {  // the total force spread evenly over the loaded points' volume
      double volume = 0;
      for (int32_t p : ld.points) volume += P.volume[std::size_t(p)];
      ld.force_density = s.vector / volume;
    }
    m.loads.push_back(std::move(ld));
  };
  resolvers["body_force"] = [&](const scene::LoadSpec<Dim>& s) { m.gravity += s.vector; };
  resolvers["velocity"] = [&](const scene::LoadSpec<Dim>& s) {
    int count = 0;
    for (std::size_t p = 0; p < P.size(); ++p) {
      if (!in_box<Dim>(P.x0[p], s.lo, s.hi, tol)) continue;
      ++count;
      P.fixed[p] |= s.mask;
      for (int d = 0; d < Dim; ++d)
        if (s.mask & (1u << d)) P.v_fixed[p][d] = s.vector[d], P.v[p][d] = s.vector[d];
    }
    if (!count) throw SceneError(s.at("region"), "no lattice point lies inside the region");
  };
  const std::map<std::string, std::string> refused = {
      {"symmetry", "symmetry is not available with peridynamics (lattice points do not lie on the plane); model "
                   "the whole specimen or use a velocity condition"}};
  scene::read_loads<Dim>(scene, {units, m.bodies}, "peridynamics", resolvers, refused);

  // --- bonds: same body only, minus those crossing a pre-crack -----------------------------------
  {
    // build_bonds bins the points in cells of edge delta + dx/2 over their bounding box, at most
    // max(8 per point, 2^20) cells (pd/bonds.cpp, make_grid; std::invalid_argument beyond): bodies
    // far apart leave that box nearly empty. Refused here, naming the bodies.
    Vec<Dim> lo = P.x0[0], hi = P.x0[0];
    for (const auto& x : P.x0) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
    const double edge = m.delta + 0.5 * m.dx, most = std::max(8.0 * double(P.size()), double(1 << 20));
    double cells = 1.0;
    for (int d = 0; d < Dim; ++d) cells *= std::floor((hi[d] - lo[d]) / edge) + 1.0;
    if (cells > most)
      throw SceneError("bodies", "the points lie too far apart for the bond search (bodies far from one another, or a "
                                     "shape's far-apart pieces): they span " + scene::fmt(cells) +
                                     " cells of one horizon, at most " + scene::fmt(most) + " (8 per point) can be "
                                     "indexed; bring them closer together or use a coarser " + dx_key);
  }
  BondList<Dim> bl = build_bonds<Dim>(P.x0, m.dx, m.delta);
  std::vector<uint8_t> keep(bl.size(), 1);
  for (std::size_t k = 0; k < bl.size(); ++k)
    if (P.body[bl.i[k]] != P.body[bl.j[k]]) keep[k] = 0;
  if (top.has("cracks")) {
    for (const auto& c : crack::read_surfaces<Dim>(scene["cracks"], "cracks", L, {m.dx, false})) {
      std::size_t cut = 0;
      for (std::size_t k = 0; k < bl.size(); ++k)
        if (keep[k] && crack::segment_crosses<Dim>(c, P.x0[bl.i[k]], P.x0[bl.j[k]])) keep[k] = 0, ++cut;
      if (!cut) m.warnings.push_back("crack '" + c.name + "' cuts no bond (it lies outside every body)");
      m.precrack_bonds += cut;
    }
    // An MPM scene's growing crack run here: peridynamics' cracks grow by breaking bonds at the
    // critical stretch (from the material's fracture energy), whatever the crack's criterion says.
    for (std::size_t i = 0; i < scene["cracks"].size(); ++i)
      if (scene["cracks"][i].is_object() && scene["cracks"][i].contains("propagation"))
        m.warnings.push_back("cracks[" + std::to_string(i) +
                             "].propagation is ignored: peridynamics grows every crack by breaking bonds at the critical "
                             "stretch of the material's fracture energy");
  }
  // Directed neighbour lists (pd_model.hpp): count, then fill in (i, j) order.
  {
    auto& N = m.nb;
    const std::size_t n = P.size();
    N.offset.assign(n + 1, 0);
    for (std::size_t k = 0; k < bl.size(); ++k)
      if (keep[k]) ++N.offset[bl.i[k] + 1], ++N.offset[bl.j[k] + 1], ++m.bond_count;
    for (std::size_t p = 0; p < n; ++p) N.offset[p + 1] += N.offset[p];
    const std::size_t ne = static_cast<std::size_t>(N.offset[n]);
    N.partner.resize(ne), N.r0.resize(ne), N.stiff.resize(ne), N.s0.resize(ne), N.w0.resize(ne);
    N.intact.assign(ne, 1);
    // Entries of p: first the bonds where p is j (partners i < p, in increasing i, since the list is
    // sorted by i), then those where p is i (partners j > p, increasing): sorted by partner.
    std::vector<int64_t> fill(N.offset.begin(), N.offset.end() - 1);
    auto put = [&](int32_t p, int32_t q, std::size_t k) {
      const auto e = static_cast<std::size_t>(fill[p]++);
      const auto& mat = m.materials[P.material[p]];
      N.partner[e] = q;
      N.r0[e] = bl.xi_len[k];
      N.w0[e] = bl.vol_factor[k] * P.volume[q];
      N.stiff[e] = mat.k.c * N.w0[e];
      N.s0[e] = (P.no_fail[p] || P.no_fail[q]) ? std::numeric_limits<double>::infinity() : mat.k.s0;
    };
    for (std::size_t k = 0; k < bl.size(); ++k)
      if (keep[k]) put(bl.j[k], bl.i[k], k);
    for (std::size_t k = 0; k < bl.size(); ++k)
      if (keep[k]) put(bl.i[k], bl.j[k], k);
  }
  // Points left without any bond take no force: they stay where they are, at their initial velocity,
  // while the body leaves them behind (a pre-crack through a row of points removes every bond that
  // touches it). Said, since the damage of such a point reads 0 (docs/validation.md, "Stability at
  // the extremes").
  {
    std::size_t lone = 0, first = 0;
    for (std::size_t p = 0; p < P.size(); ++p)
      if (m.nb.offset[p + 1] == m.nb.offset[p] && lone++ == 0) first = p;
    if (lone > 0) {
      std::string at = "(";
      for (int d = 0; d < Dim; ++d) {
        char v[32];
        std::snprintf(v, sizeof v, "%g", P.x0[first][d]);
        at += (d ? ", " : "") + std::string(v);
      }
      m.warnings.push_back(std::to_string(lone) + " of " + std::to_string(P.size()) + " points have no bond (the first at " +
                           at + ") m): they take no force and keep their initial velocity, " +
                           "and their damage reads 0; a pre-crack through a row of points cuts every bond of those " +
                           "points: put cracks between lattice rows (points lie at (k + 1/2) " + dx_key + ")");
    }
  }
  // Eq. 15 of seed 003, per point: dt_i = sqrt(2 rho_i / sum_j V_j c_ij), c_ij = c beta / |xi|.
  {
    double worst = std::numeric_limits<double>::infinity();
    for (std::size_t p = 0; p < P.size(); ++p) {
      double s = 0.0;
      for (int64_t e = m.nb.offset[p]; e < m.nb.offset[p + 1]; ++e) s += m.nb.stiff[e] / m.nb.r0[e];
      if (s > 0) worst = std::min(worst, std::sqrt(2.0 * m.materials[P.material[p]].density / s));
    }
    m.stable_dt = worst;
  }

  // --- damping, time, output, checks (shared sections) -------------------------------------------
  m.damping = scene::read_damping(scene, units);
  m.static_tolerance = scene::read_static(scene, m.damping);
  scene::read_time(scene, units, m.stable_dt, "sqrt(2 rho / sum_j V_j c_ij) (seed 003 eq. 15)",
                   "no point has a bond, so there is no stable step to scale", m);
  scene::read_output(scene, units, kPdFields, " for peridynamics", !m.trackers.empty(), m);
  scene::check_frame_count(m);
  m.memory_bytes = pd_memory_bytes<Dim>(double(P.size()), m.horizon_factor);
  scene::read_checks(scene, m);
  return m;
}

template PdSystem<2> build_pd_system<2>(const json&);
template PdSystem<3> build_pd_system<3>(const json&);

}  // namespace cleave::pd
