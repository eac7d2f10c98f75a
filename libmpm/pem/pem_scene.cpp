#include "libmpm/pem/pem_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include <Eigen/Geometry>

#include "libmpm/core/json_reader.hpp"
#include "libmpm/core/units.hpp"
#include "libmpm/crack/surface.hpp"
#include "libmpm/geometry/shape.hpp"
#include "libmpm/pem/calibration.hpp"
#include "libmpm/pem/pem_loads.hpp"
#include "libmpm/pem/pem_material.hpp"
#include "libmpm/pem/tip_growth.hpp"
#include "libmpm/scene/bodies.hpp"
#include "libmpm/scene/budget.hpp"
#include "libmpm/scene/resolution.hpp"
#include "libmpm/scene/sections.hpp"

namespace cleave::pem {
namespace {

using nlohmann::json;

const char* const kPemFields[] = {"displacement", "velocity", "damage", "stress", "von_mises",
                                  "principal_stress_difference", "material", "volume", "size"};

// Memory of a run (bytes): particles, pair entries (two per pair; about 6 per node in 2D, 14 in 3D
// for triangles and tetrahedra) and Gmsh's structures while it meshes; 100 MB for the program.
template <int Dim>
double pem_memory_bytes(double nodes) {
  const double entries = Dim == 2 ? 6.0 : 14.0;
  return 100e6 + nodes * (400.0 + entries * 60.0 + 2000.0);
}

// Nodes Gmsh makes at element size h: about 2 / (sqrt(3) h^2) per area (equilateral triangles) and
// about 1.4 / h^3 per volume; the lattice estimate counts 1 / h^Dim.
template <int Dim>
double node_factor() { return Dim == 2 ? 1.16 : 1.4; }

// The mean over crack orientations of |t . n| for a unit t (2D: 2/pi, 3D: 1/2).
template <int Dim>
double mean_abs_cos() { return Dim == 2 ? 2.0 / 3.14159265358979323846 : 0.5; }

// The unit normal of the crack's simplex nearest to x (by centroid).
template <int Dim>
Vec<Dim> crack_normal_near(const crack::Surface<Dim>& c, const Vec<Dim>& x) {
  std::size_t best = 0;
  double dist = INFINITY;
  for (std::size_t s = 0; s < c.simplices.size(); ++s) {
    Vec<Dim> centre = Vec<Dim>::Zero();
    for (int k = 0; k < Dim; ++k) centre += c.points[c.simplices[s][k]];
    const double dd = (centre / Dim - x).squaredNorm();
    if (dd < dist) dist = dd, best = s;
  }
  const auto& sx = c.simplices[best];
  if constexpr (Dim == 2) {
    const Vec<2> t = c.points[sx[1]] - c.points[sx[0]];
    return Vec<2>(-t[1], t[0]).normalized();
  } else {
    return (c.points[sx[1]] - c.points[sx[0]]).cross(c.points[sx[2]] - c.points[sx[0]]).normalized();
  }
}

}  // namespace

template <int Dim>
void element_pairs(const Mesh<Dim>& m, std::size_t e, std::vector<std::pair<int32_t, int32_t>>& out) {
  out.clear();
  const int n = m.nodes_of(e);
  const int32_t* en = m.element(e);
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b) out.emplace_back(std::min(en[a], en[b]), std::max(en[a], en[b]));
}

template <int Dim>
PemSystem<Dim> build_pem_system(const json& scene) {
  // Sections of the other methods are left to them: one scene can run under every method.
  ObjectReader top(scene, "", {"title", "description", "units", "method", "analysis", "resolution", "pem", "mpm",
                               "peridynamics", "materials", "bodies", "cracks", "loads", "damping", "static", "time",
                               "output", "checks"});
  PemSystem<Dim> m;
  const UnitSystem units = UnitSystem::from_json(scene.value("units", json()), "units");
  const double L = units.factor(Quantity::Length);
  m.title = top.string_or("title", "");
  m.analysis = scene::read_analysis(scene, L, m.thickness);
  if (dimension_of(m.analysis) != Dim) throw SceneError("analysis.type", "dimension mismatch");
  if (Dim == 3) m.thickness = 1.0;
  const bool plane_stress = m.analysis == Analysis::PlaneStress;
  const double depth = Dim == 2 ? m.thickness : 1.0;

  // --- the "pem" section ------------------------------------------------------------------------
  static const json no_section = json::object();
  const ObjectReader r(top.has("pem") ? scene["pem"] : no_section, "pem",
                       {"mesh_size", "elements", "structured", "mesh_file", "regions", "friction", "equilibrium",
                        "break_limit", "max_halvings", "stop_on_separation", "fragment_fraction", "tip_growth"});
  MeshOptions opt;
  if (r.has("elements")) {
    const std::string e = r.string("elements");
    if (e != "triangles" && e != "quadrangles")
      throw SceneError(r.at("elements"), "unknown element kind '" + e + "'; valid: triangles, quadrangles (3D: "
                                         "tetrahedra, or hexahedra where structured)");
    opt.quads = e == "quadrangles";
  }
  opt.structured = r.boolean_or("structured", false);
  m.friction = r.number_or("friction", 0.3);
  if (!(m.friction >= 0.0)) throw SceneError(r.at("friction"), "must be >= 0 (the Coulomb friction factor)");
  m.break_limit = r.number_or("break_limit", 1e-3);
  if (!(m.break_limit > 0.0 && m.break_limit <= 1.0)) throw SceneError(r.at("break_limit"), "must lie in (0, 1]");
  m.max_halvings = r.integer_or("max_halvings", 5, 0, 20);
  m.stop_on_separation = r.boolean_or("stop_on_separation", true);
  m.fragment_fraction = r.number_or("fragment_fraction", 0.01);
  if (!(m.fragment_fraction > 0.0 && m.fragment_fraction < 1.0))
    throw SceneError(r.at("fragment_fraction"), "must lie in (0, 1)");
  if (r.has("equilibrium")) {
    const ObjectReader q(r["equilibrium"], r.at("equilibrium"), {"velocity", "residual", "checks", "interval"});
    m.equilibrium.enabled = true;
    m.equilibrium.velocity = q.positive("velocity", units.factor(Quantity::Velocity));
    m.equilibrium.residual = q.positive("residual");
    if (m.equilibrium.residual >= 1.0) throw SceneError(q.at("residual"), "must be below 1 (a relative residual force)");
    m.equilibrium.checks = q.integer_or("checks", 10, 1, 1000000);
    m.equilibrium.interval = q.integer_or("interval", 10, 1, 1000000);
  }

  // --- materials ----------------------------------------------------------------------------------
  const PemMaterialContext mc{units, m.warnings};
  const auto material_index = scene::read_materials(scene, [&](const std::string& path, const std::string& type,
                                                               const json& j) {
    const auto& styles = PemMaterialStyles::instance();
    const PemMaterialReader* read = styles.find(type);
    if (!read)
      throw SceneError(path + ".type", "unknown material type '" + type + "' for pem; valid: " + styles.names_joined());
    m.materials.push_back((*read)(j, path, mc));
    m.materials.back().name = j["name"].get<std::string>();
    m.materials.back().type = type;
  });

  // --- the mesh: Gmsh from the bodies, or a file ---------------------------------------------------
  std::vector<int> region_material;  // region -> material
  std::vector<Vec<Dim>> region_velocity;  // region -> initial velocity (a body's "velocity"; mesh files: 0)
  if (r.has("mesh_file")) {
    if (top.has("bodies"))
      throw SceneError(r.at("mesh_file"), "give bodies (meshed by Gmsh) or pem.mesh_file, not both: a mesh file's "
                                          "physical groups are the bodies");
    for (const char* k : {"mesh_size", "elements", "structured"})
      if (r.has(k)) throw SceneError(r.at(k), "not used with pem.mesh_file (the file is the mesh)");
    m.mesh_source = r.string("mesh_file");
    m.mesh = read_mesh_file<Dim>(m.mesh_source, r.at("mesh_file"), L);
    m.regions = m.mesh.regions;
    if (!r.has("regions") && m.materials.size() != 1)
      throw SceneError(r.at("regions"), "missing: with several materials, map each region (physical group) of the "
                                        "mesh file to a material: {\"<group>\": \"<material>\"}");
    std::map<std::string, std::string> map;
    if (r.has("regions")) {
      const json& g = r["regions"];
      if (!g.is_object()) throw SceneError(r.at("regions"), "expected an object {\"<group>\": \"<material>\"}");
      for (auto it = g.begin(); it != g.end(); ++it) {
        if (!it.value().is_string()) throw SceneError(r.at("regions") + "." + it.key(), "expected a material name");
        if (std::find(m.regions.begin(), m.regions.end(), it.key()) == m.regions.end())
          throw SceneError(r.at("regions") + "." + it.key(), "no region of that name in " + m.mesh_source);
        map[it.key()] = it.value().get<std::string>();
      }
    }
    for (const auto& name : m.regions) {
      std::string mat = m.materials.size() == 1 && !map.count(name) ? m.materials[0].name : "";
      if (map.count(name)) mat = map[name];
      if (mat.empty())
        throw SceneError(r.at("regions"), "region '" + name + "' of " + m.mesh_source + " has no material");
      const auto it = material_index.find(mat);
      if (it == material_index.end())
        throw SceneError(r.at("regions") + "." + name, "unknown material '" + mat + "'");
      region_material.push_back(it->second);
    }
    double lsum = 0;
    std::size_t lcount = 0;
    std::vector<std::pair<int32_t, int32_t>> pp;
    for (std::size_t e = 0; e < m.mesh.element_count(); ++e) {
      element_pairs(m.mesh, e, pp);
      for (auto [i, j] : pp) lsum += (m.mesh.nodes[j] - m.mesh.nodes[i]).norm(), ++lcount;
    }
    m.mesh_size = lsum / double(std::max<std::size_t>(lcount, 1));
    m.size_key = r.at("mesh_file");
  } else {
    const auto res = scene::read_resolution(scene, "pem", "mesh_size", "the element size", L);
    m.mesh_size = opt.size = res.length;
    m.size_key = res.key;
    m.mesh_source = "gmsh";
    const auto specs = scene::read_bodies<Dim>(scene, units, material_index);
    std::vector<BodyShape> shapes;
    double nodes = 0;
    for (const auto& spec : specs) {
      const ObjectReader br = spec.reader();
      for (const char* k : {"thickness", "angular_velocity", "rotation_center"})
        if (br.has(k)) throw SceneError(br.at(k), "not used by pem (particles are the mesh's nodes)");
      if (br.has("particles_per_cell"))
        m.warnings.push_back(br.at("particles_per_cell") + " is ignored: it is an MPM key (pem's particles are the "
                                                           "nodes of a mesh of element size \"resolution\")");
      shapes.push_back({spec.name, &(*spec.object)["shape"], spec.path + ".shape"});
      m.regions.push_back(spec.name);
      region_material.push_back(spec.material);
      nodes += node_factor<Dim>() * scene::estimate_points<Dim>(*spec.shape, opt.size);
    }
    scene::check_memory(pem_memory_bytes<Dim>(nodes), m.size_key, scene::fmt(nodes) + " particles");
    m.mesh = mesh_bodies<Dim>(shapes, L, opt, m.size_key, std::size_t(std::min(2e9, 4.0 * nodes + 1e5)));
    for (const auto& spec : specs) region_velocity.push_back(spec.velocity);
  }
  const auto& mesh = m.mesh;
  const std::size_t n = mesh.nodes.size(), ne = mesh.element_count();
  if (ne == 0) throw SceneError(m.size_key, "the mesh has no element");
  m.element_material.resize(ne);
  for (std::size_t e = 0; e < ne; ++e) m.element_material[e] = region_material[mesh.element_region[e]];

  // --- particles: volume and mass as equal shares of their elements (docs/pem.md) ----------------
  region_velocity.resize(m.regions.size(), Vec<Dim>::Zero());
  auto& P = m.points;
  P.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    P.x0[p] = mesh.nodes[p];
    P.u[p].setZero(), P.v[p].setZero(), P.a[p].setZero(), P.v_fixed[p].setZero();
    P.volume[p] = P.mass[p] = 0.0;
    P.region[p] = P.material[p] = -1;
    P.fixed[p] = 0;
  }
  std::vector<double> measure(ne);
  for (std::size_t e = 0; e < ne; ++e) {
    measure[e] = element_measure(mesh, e) * depth;
    if (!(measure[e] > 0.0))
      throw SceneError(m.size_key, "element " + std::to_string(e) + " of the mesh has no volume (" +
                                       scene::fmt(measure[e]) + ")");
    const int k = mesh.nodes_of(e);
    const double rho = m.materials[m.element_material[e]].density;
    for (int a = 0; a < k; ++a) {
      const int32_t p = mesh.element(e)[a];
      P.v[p] = region_velocity[mesh.element_region[e]];  // a node shared by bodies: the last one's
      P.volume[p] += measure[e] / k;
      P.mass[p] += rho * measure[e] / k;
      if (P.region[p] < 0) P.region[p] = mesh.element_region[e], P.material[p] = m.element_material[e];
    }
  }
  for (std::size_t p = 0; p < n; ++p) {
    if (P.region[p] < 0) throw SceneError(m.size_key, "mesh node " + std::to_string(p) + " belongs to no element");
    P.size[p] = std::pow(P.volume[p] / depth, 1.0 / Dim);
  }

  // --- pairs: every two nodes of an element, stiffness fitted element by element -----------------
  struct Share {
    int32_t i, j;
    double a;      // a = k l^2 before the material's scale
    int32_t mat;
  };
  std::vector<Share> shares;
  std::vector<NetworkTensor<Dim>> tensors(m.materials.size());
  {
    std::vector<std::pair<int32_t, int32_t>> pp;
    std::vector<Vec<Dim>> t;
    for (std::size_t e = 0; e < ne; ++e) {
      element_pairs(mesh, e, pp);
      t.clear();
      for (auto [i, j] : pp) t.push_back((mesh.nodes[j] - mesh.nodes[i]).normalized());
      const int mi = m.element_material[e];
      const double mu = m.materials[mi].E / (2.0 * (1.0 + cauchy_nu(plane_stress)));
      const auto a = fit_element_pairs<Dim>(t, measure[e], mu);
      tensors[mi].volume += measure[e];
      for (std::size_t q = 0; q < pp.size(); ++q) {
        shares.push_back({pp[q].first, pp[q].second, a[q], mi});
        tensors[mi].add(t[q], a[q]);
      }
    }
  }
  // Each material's network is scaled to its E; its nu and anisotropy are what the mesh gives.
  std::vector<double> scale(m.materials.size(), 1.0);
  for (std::size_t mi = 0; mi < m.materials.size(); ++mi) {
    auto& mat = m.materials[mi];
    if (tensors[mi].volume <= 0) continue;  // a material no element uses
    double lambda, mu;
    tensors[mi].isotropic(lambda, mu, mat.anisotropy);
    double E, nu;
    young_poisson(lambda, mu, plane_stress, E, nu);
    scale[mi] = mat.E / E;
    mat.E_network = mat.E;
    mat.nu_network = nu;
    if (mat.nu_given >= 0 && std::fabs(mat.nu_given - nu) > 0.01)
      m.warnings.push_back("materials[" + std::to_string(mi) + "].nu = " + scene::fmt(mat.nu_given) +
                           " cannot be met: a central-force pair network gives nu = " + scene::fmt(nu) +
                           " on this mesh (" + (plane_stress ? "1/3 in plane stress" : "1/4 in plane strain and 3D") +
                           " for an isotropic one); E is matched");
    if (mat.anisotropy > 0.05)
      m.warnings.push_back("materials[" + std::to_string(mi) + "]: the pair network of this mesh departs from isotropy by " +
                           scene::fmt(100 * mat.anisotropy) + " %: E is matched on average, and the response varies with "
                           "direction by up to about that much (single tetrahedra are cubic; structured triangles with "
                           "one diagonal direction stay anisotropic: use unstructured triangles or quadrangles)");
  }
  // Fracture calibration per material: S = (1/V) sum k l^3 <|t.n|>.
  {
    std::vector<double> S(m.materials.size(), 0.0);
    for (const auto& s : shares) {
      const double l = (mesh.nodes[s.j] - mesh.nodes[s.i]).norm();
      S[s.mat] += scale[s.mat] * s.a * l * mean_abs_cos<Dim>();
    }
    for (std::size_t mi = 0; mi < m.materials.size(); ++mi) {
      if (tensors[mi].volume > 0) S[mi] /= tensors[mi].volume;
      set_pair_law(m.materials[mi], S[mi], "materials[" + std::to_string(mi) + "]", !r.has("tip_growth"));
    }
  }
  std::sort(shares.begin(), shares.end(), [](const Share& x, const Share& y) { return std::tie(x.i, x.j) < std::tie(y.i, y.j); });
  // Unique pairs (i < j): stiffness summed over their elements, the weakest element's law.
  std::vector<int32_t> pi, pj, plaw;
  std::vector<double> pk, pl0;
  for (std::size_t s = 0; s < shares.size();) {
    const int32_t i = shares[s].i, j = shares[s].j;
    const double l = (mesh.nodes[j] - mesh.nodes[i]).norm();
    double a = 0;
    int32_t law = shares[s].mat;
    for (; s < shares.size() && shares[s].i == i && shares[s].j == j; ++s) {
      a += scale[shares[s].mat] * shares[s].a;
      if (m.materials[shares[s].mat].law.eps_cut < m.materials[law].law.eps_cut) law = shares[s].mat;
    }
    pi.push_back(i), pj.push_back(j), pk.push_back(a / (l * l)), pl0.push_back(l), plaw.push_back(law);
  }
  // Pairs with no stiffness (an obtuse element's long side may fit to 0) still repel and break as
  // contact; they are kept: crack tracing and damage count them.
  std::vector<uint8_t> cut(pi.size(), 0);
  std::vector<Vec<Dim>> normal(pi.size(), Vec<Dim>::Zero());
  std::vector<std::vector<Vec<Dim>>> crack_points;  // for tip growth
  std::vector<std::string> crack_names;
  if (top.has("cracks")) {
    for (const auto& c : crack::read_surfaces<Dim>(scene["cracks"], "cracks", L, {m.mesh_size, false})) {
      crack_points.push_back(c.points), crack_names.push_back(c.name);
      std::size_t count = 0;
      for (std::size_t q = 0; q < pi.size(); ++q)
        if (!cut[q] && crack::segment_crosses<Dim>(c, P.x0[pi[q]], P.x0[pj[q]])) {
          cut[q] = 1, ++count;
          normal[q] = crack_normal_near<Dim>(c, 0.5 * (P.x0[pi[q]] + P.x0[pj[q]]));
        }
      if (!count) m.warnings.push_back("crack '" + c.name + "' cuts no pair (it lies outside every body)");
      m.precrack_pairs += count;
    }
    for (std::size_t i = 0; i < scene["cracks"].size(); ++i)
      if (scene["cracks"][i].is_object() && scene["cracks"][i].contains("propagation"))
        m.warnings.push_back("cracks[" + std::to_string(i) + "].propagation is ignored: pem grows cracks by breaking "
                             "pairs at the cutoff distance of the material, or from their tips with pem.tip_growth");
  }
  m.pair_count = pi.size();
  // Directed lists: count, then fill in (i, j) order so every particle's entries are sorted by partner.
  {
    auto& N = m.pairs;
    N.offset.assign(n + 1, 0);
    for (std::size_t q = 0; q < pi.size(); ++q) ++N.offset[pi[q] + 1], ++N.offset[pj[q] + 1];
    for (std::size_t p = 0; p < n; ++p) N.offset[p + 1] += N.offset[p];
    const auto entries = static_cast<std::size_t>(N.offset[n]);
    N.partner.resize(entries), N.l0.resize(entries), N.k.resize(entries), N.law.resize(entries);
    N.xi.resize(Dim * entries);
    N.intact.resize(entries), N.initial.resize(entries);
    N.cut.assign(entries, -1);
    std::vector<int32_t> cut_index(pi.size(), -1);
    for (std::size_t q = 0; q < pi.size(); ++q)
      if (cut[q]) {
        cut_index[q] = static_cast<int32_t>(N.cut_normal.size() / Dim);
        for (int d = 0; d < Dim; ++d) N.cut_normal.push_back(normal[q][d]);
      }
    std::vector<int64_t> fill(N.offset.begin(), N.offset.end() - 1);
    auto put = [&](int32_t p, int32_t q, std::size_t s) {
      const auto e = static_cast<std::size_t>(fill[p]++);
      N.partner[e] = q, N.l0[e] = pl0[s], N.k[e] = pk[s], N.law[e] = plaw[s];
      for (int d = 0; d < Dim; ++d) N.xi[Dim * e + d] = P.x0[q][d] - P.x0[p][d];
      N.intact[e] = N.initial[e] = cut[s] ? 0 : 1;
      N.cut[e] = cut_index[s];
    };
    for (std::size_t s = 0; s < pi.size(); ++s) put(pj[s], pi[s], s);  // partners below, increasing
    for (std::size_t s = 0; s < pi.size(); ++s) put(pi[s], pj[s], s);  // partners above, increasing
    bool plastic = false;
    for (const auto& mat : m.materials) plastic = plastic || mat.law.plastic();
    if (plastic) {
      N.b = N.l0;
      N.alpha.assign(entries, 0.0);
    }
  }
  if (r.has("tip_growth"))
    read_tip_growth<Dim>(r["tip_growth"], r.at("tip_growth"), units, crack_points, crack_names, m);
  // --- stable step: sqrt(2 m_i / sum_j k_ij) (Gershgorin's bound on the highest frequency) --------
  {
    double worst = std::numeric_limits<double>::infinity();
    for (std::size_t p = 0; p < n; ++p) {
      double s = 0;
      for (int64_t e = m.pairs.offset[p]; e < m.pairs.offset[p + 1]; ++e) s += m.pairs.k[e];
      if (s > 0) worst = std::min(worst, std::sqrt(2.0 * P.mass[p] / s));
    }
    m.stable_dt = worst;
  }
  resolve_loads<Dim>(scene, units, m);
  m.damping = scene::read_damping(scene, units);
  m.static_tolerance = scene::read_static(scene, m.damping);
  scene::read_time(scene, units, m.stable_dt, "sqrt(2 m_i / sum_j k_ij) over the particles",
                   "no pair has stiffness, so there is no stable step to scale", m);
  scene::read_output(scene, units, kPemFields, " for pem", false, m);
  scene::check_frame_count(m);
  m.memory_bytes = pem_memory_bytes<Dim>(double(n));
  scene::read_checks(scene, m);
  return m;
}

template PemSystem<2> build_pem_system<2>(const json&);
template PemSystem<3> build_pem_system<3>(const json&);
template void element_pairs<2>(const Mesh<2>&, std::size_t, std::vector<std::pair<int32_t, int32_t>>&);
template void element_pairs<3>(const Mesh<3>&, std::size_t, std::vector<std::pair<int32_t, int32_t>>&);

}  // namespace cleave::pem
