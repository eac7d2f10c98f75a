#include "libmpm/mpm/crack_front_scene.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "libmpm/core/error.hpp"
#include "libmpm/core/json_reader.hpp"
#include "libmpm/crack/front_parameters.hpp"
#include "libmpm/method/describe.hpp"
#include "libmpm/mpm/crack_front_eval.hpp"  // kCodCells
#include "libmpm/mpm/crack_scene.hpp"
#include "libmpm/mpm/material_probe.hpp"

namespace cleave {
namespace {

using nlohmann::json;

std::string node_name(const crack::ExplicitCrack<3>& c, std::size_t front, std::size_t k) {
  return "node " + std::to_string(k) + " of front " + std::to_string(front) + " of crack '" + c.name + "'";
}

// "1, 2, 5 and 3 more" for a warning.
std::string list_nodes(const std::vector<std::size_t>& nodes) {
  std::string s;
  for (std::size_t i = 0; i < nodes.size() && i < 8; ++i) s += (i ? ", " : "") + std::to_string(nodes[i]);
  if (nodes.size() > 8) s += " and " + std::to_string(nodes.size() - 8) + " more";
  return s;
}

// The particle nearest to x (its material is the material at x).
std::size_t nearest_particle(const Model<3>& m, const Vec<3>& x) {
  std::size_t nearest = 0;
  double best = INFINITY;
  for (std::size_t p = 0; p < m.particles.size(); ++p)
    if (const double d = (m.particles.x[p] - x).squaredNorm(); d < best) best = d, nearest = p;
  return nearest;
}

// crack_tips.reference: {"type": "embedded_crack", "crack": name, "stress": s, "load_axis": d}, the
// named crack declared by "ellipse" (its centre, axes and semi-axes are the reference's).
crack::EllipseReference read_reference(const json& scene, const UnitSystem& units, const Model<3>& m) {
  const ObjectReader r(scene["crack_tips"]["reference"], "crack_tips.reference", {"type", "crack", "stress", "load_axis"});
  const std::string type = r.string("type");
  if (type != "embedded_crack")
    throw SceneError(r.at("type"), "unknown reference \"" + type + "\"; valid: embedded_crack (Irwin's elliptical "
                                   "crack in an infinite body; a circle also under an inclined load)");
  const std::string name = r.string("crack");
  const auto it = std::find_if(m.cracks.begin(), m.cracks.end(), [&](const auto& c) { return c.name == name; });
  if (it == m.cracks.end()) throw SceneError(r.at("crack"), "no crack is named \"" + name + "\"");
  const json& decl = scene["cracks"][static_cast<std::size_t>(it->id)];
  if (!decl.contains("ellipse"))
    throw SceneError(r.at("crack"), "crack '" + name + "' is not declared by \"ellipse\": the reference takes its "
                                    "centre, axes and semi-axes from that declaration");
  const json& e = decl["ellipse"];
  const double L = units.factor(Quantity::Length);
  const std::string at = "cracks[" + std::to_string(it->id) + "].ellipse";
  crack::EllipseReference ref;
  ref.crack = it->id;
  ref.center = ObjectReader::vec_of<3>(e["center"], at + ".center", L);
  ref.normal = ObjectReader::vec_of<3>(e["normal"], at + ".normal").normalized();
  if (e.contains("radius")) {
    ref.a = ref.b = ObjectReader::number_of(e["radius"], at + ".radius") * L;
    ref.major = std::abs(ref.normal.x()) < 0.9 ? Vec<3>::UnitX() : Vec<3>::UnitY();
    if (e.contains("major_axis")) ref.major = ObjectReader::vec_of<3>(e["major_axis"], at + ".major_axis");
  } else {
    ref.a = ObjectReader::number_of(e["semi_axes"][0], at + ".semi_axes[0]") * L;
    ref.b = ObjectReader::number_of(e["semi_axes"][1], at + ".semi_axes[1]") * L;
    ref.major = ObjectReader::vec_of<3>(e["major_axis"], at + ".major_axis");
  }
  ref.major = (ref.major - ref.major.dot(ref.normal) * ref.normal).normalized();
  ref.stress = r.number("stress", units.factor(Quantity::Stress));
  ref.load_axis = r.has("load_axis") ? r.vec<3>("load_axis") : ref.normal;
  if (!(ref.load_axis.norm() > 0.0)) throw SceneError(r.at("load_axis"), "must not be zero");
  ref.load_axis.normalize();
  // nu of the material at the crack (the K_II, K_III of a circle depend on it).
  double g = 0;
  if (!m.materials[m.particles.material[nearest_particle(m, ref.center)]]->isotropic_elastic(g, ref.nu))
    throw SceneError(r.at("crack"), "the reference needs an isotropic elastic material at the crack");
  if (ref.a != ref.b && ref.load_axis.cross(ref.normal).norm() > 1e-9)
    throw SceneError(r.at("load_axis"), "an elliptical (not circular) crack's reference is Irwin's, for a load "
                                        "along the crack's normal only");
  return ref;
}

// A front that crosses a symmetry plane meets it at a right angle (the mirrored front continues it
// smoothly), but the frame at its end node, from one side only, leans by half an edge's turn: set
// its tangent to the plane's normal, so that the contour lies in the plane and its other half is the
// mirror image (crack_front_eval.hpp mirrors the out-of-plane term there).
void square_frames_on_symmetry_planes(Model<3>& m) {
  const double tol = 1e-6 * m.grid.h;
  for (auto& c : m.cracks)
    for (auto& front : c.fronts)
      for (std::size_t k = 0; k < front.nodes.size(); ++k)
        for (const auto& [axis, position] : m.symmetry_planes) {
          const Vec<3>& x = c.points[front.nodes[k]];
          if (std::fabs(x[axis] - position) > tol || std::fabs(front.tangent[k][axis]) < 0.5) continue;
          Vec<3> t = Vec<3>::Zero();
          t[axis] = front.tangent[k][axis] > 0 ? 1.0 : -1.0;
          const Vec<3> n = (front.normal[k] - front.normal[k].dot(t) * t).normalized();
          front.tangent[k] = t, front.normal[k] = n, front.ahead[k] = t.cross(n);
        }
}

}  // namespace

void read_front_tips(const json& scene, const UnitSystem& units, Model<3>& m) {
  static constexpr const char* kFrontKeys[] = {"reference", "out_of_plane_term", "integral", "along", "inner"};
  crack::TipSettings s = read_contour_settings(scene, m, units.factor(Quantity::Time), kFrontKeys);
  {
    const ObjectReader r(scene["crack_tips"], "crack_tips", crack_tips_keys(kFrontKeys));
    if (r.has("out_of_plane_term")) {
      if (!r["out_of_plane_term"].is_boolean()) throw SceneError(r.at("out_of_plane_term"), "expected true or false");
      s.out_of_plane_term = r["out_of_plane_term"].get<bool>();
    }
    const std::string integral = r.string_or("integral", "contour");
    if (integral == "domain") s.integral = crack::TipSettings::Integral::Domain;
    else if (integral != "contour")
      throw SceneError(r.at("integral"), "unknown integral \"" + integral + "\"; valid: contour, domain");
    const bool domain = s.integral == crack::TipSettings::Integral::Domain;
    for (const char* key : {"along", "inner"})
      if (r.has(key) && !domain)
        throw SceneError(r.at(key), "only with \"integral\": \"domain\" (the domain integral's weight)");
    s.along = r.positive_or("along", s.along);
    if (s.along < 1.0) throw SceneError(r.at("along"), "at least 1 cell (got " + r["along"].dump() + ")");
    s.inner = r.number_or("inner", s.inner);
    if (!(s.inner >= 0.0 && s.inner < 1.0))
      throw SceneError(r.at("inner"), "from 0 to less than 1 (got " + r["inner"].dump() + ")");
  }
  square_frames_on_symmetry_planes(m);
  const double h = m.grid.h;
  const MaterialProbe material(m);
  const Vec<3> lo = m.grid.origin, hi = m.grid.upper();
  const double cod = std::max(s.radius, kCodCells) * h;
  bool any = false;
  for (auto& c : m.cracks)
    for (std::size_t f = 0; f < c.fronts.size(); ++f) {
      auto& front = c.fronts[f];
      front.flags.assign(front.nodes.size(), 0);
      if (!c.tip[f]) continue;
      any = true;
      std::vector<std::size_t> outside, crossing;
      for (std::size_t k = 0; k < front.nodes.size(); ++k) {
        const crack::FrontFrame fr = crack::front_frame(c, f, k);
        const auto contour = crack::front_contour_points(fr, s, h);
        // Every contour point and the opening probes, with the nodes they interpolate from (a cell).
        std::vector<Vec<3>> pts;
        for (const auto& cp : contour) pts.push_back(cp.x);
        pts.push_back(fr.x - cod * fr.e1);
        for (const auto& x : pts)
          if ((x.array() - h < lo.array()).any() || (x.array() + h > hi.array()).any())
            throw SceneError("crack_tips.radius", "the contour of " + node_name(c, f, k) + " at " +
                                                      position_text<3>(fr.x) + " leaves the grid; enlarge the grid "
                                                      "or use a smaller crack_tips.radius");
        uint8_t flag = 0;
        // (A point on the body's face counts as inside: the contour of a node on a symmetry plane
        // lies in that plane, with the mirrored material beyond it.)
        for (const auto& cp : contour)
          if (!material.near(cp.x, 1e-6 * h)) flag |= crack::kFlagContourOutside;
        // The circle meets its own crack once, between its last and first points; any other
        // crossing is another crack (or another part of this one) inside the contour.
        for (std::size_t i = 0; i < contour.size(); ++i) {
          const Vec<3>& a = contour[i].x;
          const Vec<3>& b = contour[(i + 1) % contour.size()].x;
          for (const auto& o : m.cracks) {
            if (&o == &c && i + 1 == contour.size()) continue;
            if (crack::segment_crosses(o, a, b)) flag |= crack::kFlagContourCrossesCrack;
          }
        }
        front.flags[k] = flag;
        if (flag & crack::kFlagContourOutside) outside.push_back(k);
        if (flag & crack::kFlagContourCrossesCrack) crossing.push_back(k);
        if (k == 0 || k + 1 == front.nodes.size()) {  // the material at the front (one probe per end)
          double g = 0, nu = 0;
          if (!m.materials[m.particles.material[nearest_particle(m, fr.x)]]->isotropic_elastic(g, nu))
            throw SceneError("crack_tips", "crack '" + c.name + "': K from J needs an isotropic elastic material at "
                                           "its fronts");
        }
      }
      const std::string which = "front " + std::to_string(f) + " of crack '" + c.name + "'";
      const std::string of = " of the " + std::to_string(front.nodes.size()) + " nodes of " + which;
      // (With the domain integral the same circle bounds the tube's cross-section.)
      const bool domain = s.integral == crack::TipSettings::Integral::Domain;
      if (!outside.empty())
        m.warnings.push_back(std::string("crack_tips: the ") + (domain ? "integration domains" : "contours") + " of " +
                             std::to_string(outside.size()) + of + " (nodes " + list_nodes(outside) +
                             ") leave the material (a free surface or a symmetry plane within " +
                             format("%g", s.radius) + " cells): their J misses that part of the " +
                             (domain ? "domain" : "contour") + "; their crack_fronts.csv rows carry flag 1");
      if (!crossing.empty())
        m.warnings.push_back("crack_tips: the contours of " + std::to_string(crossing.size()) + of + " (nodes " +
                             list_nodes(crossing) + ") cross a crack; J there is not path-independent (use a smaller "
                             "crack_tips.radius or move the cracks apart); their rows carry flag 4");
    }
  if (!any)
    throw SceneError("crack_tips", "no crack has a front inside the material (every edge of every crack lies on a "
                                   "body's face or a symmetry plane, or \"tips\": \"none\")");
  if (scene["crack_tips"].contains("reference")) m.front_references.push_back(read_reference(scene, units, m));
  m.crack_tips = s;
  m.particles.rotation3.assign(m.particles.size(), Vec<3>::Zero());
}

}  // namespace cleave
