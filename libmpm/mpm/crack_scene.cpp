// MPM's crack sections of the scene, read once the model has its grid and particles: "cracks" (the
// polylines, checked against the grid and the bodies, tips resolved) and "crack_tips" (the J-integral
// contour, checked against the grid, the other cracks and the materials).
#include "libmpm/mpm/crack_scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "libmpm/core/error.hpp"
#include "libmpm/core/json_reader.hpp"
#include "libmpm/crack/crack2d.hpp"
#include "libmpm/crack/crack3d.hpp"
#include "libmpm/crack/fronts.hpp"
#include "libmpm/crack/mesh3d.hpp"
#include "libmpm/crack/tip_parameters.hpp"
#include "libmpm/method/describe.hpp"
#include "libmpm/mpm/crack_front_scene.hpp"
#include "libmpm/mpm/material_probe.hpp"
#include "libmpm/scene/sections.hpp"

namespace cleave {
namespace {

using nlohmann::json;

// Is x within r of crack c's polyline (of some segment)?
bool near_polyline(const crack::Crack2D& c, const Vec<2>& x, double r) {
  for (std::size_t s = 0; s + 1 < c.points.size(); ++s) {
    const Vec<2> a = c.points[s], d = c.points[s + 1] - a;
    const double t = std::clamp((x - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
    if ((x - (a + t * d)).norm() <= r) return true;
  }
  return false;
}

// Checks that need the model: every crack point inside the grid (with room for its nodes), and
// every crack touching a body (some particle within one cell of a segment).
void check_cracks(const Model<2>& m) {
  const double h = m.grid.h;
  const Vec<2> lo = m.grid.origin, hi = m.grid.upper();
  for (const auto& c : m.cracks) {
    const std::string path = "cracks[" + std::to_string(c.id) + "]";
    for (std::size_t i = 0; i < c.points.size(); ++i) {
      const Vec<2>& x = c.points[i];
      if (!((x.array() > lo.array() + h).all() && (x.array() < hi.array() - h).all()))
        throw SceneError(path, "crack '" + c.name + "': point " + std::to_string(i) + " (" + std::to_string(x.x()) +
                                   ", " + std::to_string(x.y()) +
                                   ") m lies outside the grid or within one cell of its edge; enlarge the grid");
    }
    bool touches = false;
    const Vec<2> clo = c.lo.array() - h, chi = c.hi.array() + h;
    for (std::size_t p = 0; p < m.particles.size() && !touches; ++p) {
      const Vec<2>& x = m.particles.x[p];
      if ((x.array() < clo.array()).any() || (x.array() > chi.array()).any()) continue;
      touches = near_polyline(c, x, h);
    }
    if (!touches)
      throw SceneError(path, "crack '" + c.name + "' lies outside every body (no particle within one cell of it)");
  }
}

// An end within a cell of a free edge, with material ahead of it up to that edge, leaves a
// ligament narrower than a cell: MPM cannot resolve it, and it joins the two faces through the
// nodes its particles share (NairnMPM's DCB input ends its crack half a cell short of the loaded
// edge; the arms stayed joined and J read 0-3 J/m^2). Such an end is carried on through the edge
// (half a cell beyond the material) and becomes a mouth, not a tip, with a warning; an end that
// the scene names as a tip is left where it is, with a warning.
void cut_through_near_edges(Model<2>& m) {
  const double h = m.grid.h;
  const std::vector<double> half_size = particle_half_sizes(m);
  for (auto& c : m.cracks) {
    for (int end = 0; end < 2; ++end) {
      const crack::TipFrame f = crack::tip_frame(c, end);
      // The material on the crack line ahead of the end, within two cells: where it stops. A
      // particle whose domain reaches the line counts, also one whose centre lies exactly half a
      // spacing off it (the rows on either side of a crack between particle rows), and the edge is
      // compared with a cell to 1e-9 of one: both are exact figures that rounding decided before
      // (2026-11-27: a crack on a node line ending half a cell short of the edge stayed a tip).
      const double tol = 1e-9 * h;
      const double edge = material_ahead(m, half_size, f.tip, f.e1, f.e2, 2.0 * h, tol);
      if (edge == 0.0 || edge > h - tol) continue;  // none ahead, or a ligament of a cell or more
      const std::string where = "crack '" + c.name + "': its " + (end ? "end" : "start") + " lies " +
                                format("%.4g m (%.3g cell)", edge, edge / h) + " from a free edge ahead of it, a ligament MPM cannot resolve";
      const bool named_tip = c.tips != "auto" && c.tip[end];
      const Vec<2> through = f.tip + (edge + 0.5 * h) * f.e1;
      const Vec<2> lo = m.grid.origin, hi = m.grid.upper();
      if (named_tip || !((through.array() > lo.array() + h).all() && (through.array() < hi.array() - h).all())) {
        m.warnings.push_back(where + (named_tip ? ": it stays a tip as \"tips\" says, and the faces stay joined there"
                                                : ": the grid has no room to carry it through; enlarge the grid"));
        continue;
      }
      m.warnings.push_back(where + ": carried on through the edge to " + position_text<2>(through) +
                           ", where it is a mouth, not a tip");
      if (end == 0) c.points.insert(c.points.begin(), through);
      else c.points.push_back(through);
      c.above = c.below = c.reference = c.points;
      crack::set_polyline_segments(c);
      c.tip[end] = 0;
      c.update_extent();
    }
  }
}

// Is there material ahead of end `end` of crack c: a particle within one cell of the point one cell
// ahead along the crack?
bool material_ahead_of(const Model<2>& m, const crack::Crack2D& c, int end) {
  const double h = m.grid.h;
  const crack::TipFrame f = crack::tip_frame(c, end);
  const Vec<2> ahead = f.tip + h * f.e1;
  for (std::size_t p = 0; p < m.particles.size(); ++p)
    if ((m.particles.x[p] - ahead).norm() <= h) return true;
  return false;
}
// "tips": "auto" makes an end point a crack tip when there is material ahead of it: the end of a
// crack cut in from a free edge is no tip.
void resolve_tips(Model<2>& m) {
  for (auto& c : m.cracks) {
    if (c.tips != "auto") continue;
    for (int end = 0; end < 2; ++end)
      if (c.tip[end]) c.tip[end] = material_ahead_of(m, c, end);  // (0: carried through a free edge)
  }
}

// Which ends the crossing test cuts back (ExplicitCrack::update_crossing): the ends with material
// ahead, whatever "tips" says (it chooses where J and K are computed, not the physics), except an end
// within a cell of another crack (it joins that crack: cut back, it would leave a bridge) and the
// ends carried through a free edge. cracks[i].tip_cut was read in cells.
void resolve_cut_ends(Model<2>& m) {
  const double h = m.grid.h;
  auto near_other_crack = [&](const crack::Crack2D& c, const Vec<2>& x) {
    for (const auto& o : m.cracks)
      if (&o != &c && near_polyline(o, x, h)) return true;
    return false;
  };
  for (auto& c : m.cracks) {
    c.tip_cut *= h;
    c.cut_reach = c.tip_cut + 2.5 * h;  // (a particle-node line is at most 1.5 sqrt(2) cells long)
    for (int end = 0; end < 2; ++end) {
      const Vec<2> x = end ? c.points.back() : c.points.front();
      c.cut_end[end] = c.tip_cut > 0.0 && material_ahead_of(m, c, end) && !near_other_crack(c, x);
    }
    c.update_extent();
  }
}

bool same_contact(const crack::ContactSettings& a, const crack::ContactSettings& b) {
  return a.contact_law == b.contact_law && a.friction == b.friction && a.detection == b.detection &&
         a.v_sep == b.v_sep && a.v_contact == b.v_contact && a.d_contact == b.d_contact;
}

// End e of a polyline crack: 0 its start, 1 its end.
Vec<2> end_point(const crack::Crack2D& c, int e) { return e ? c.points.back() : c.points.front(); }

// One end of crack i and one of crack j (i < j).
struct EndPair {
  std::size_t i, j;
  int ei, ej;
};
// f(pair) for every pair of ends of two different cracks, in crack order, until f returns true.
template <class F>
bool any_end_pair(const Model<2>& m, F&& f) {
  for (std::size_t i = 0; i < m.cracks.size(); ++i)
    for (std::size_t j = i + 1; j < m.cracks.size(); ++j)
      for (int ei = 0; ei < 2; ++ei)
        for (int ej = 0; ej < 2; ++ej)
          if (f(EndPair{i, j, ei, ej})) return true;
  return false;
}

// Two cracks whose ends coincide, with no third crack ending there, cut the body along one kinked
// line: they are read as one polyline. Kept as two, the material beyond the kink reached each node
// near the junction as two fields (one behind each crack, their keys differing in two cracks, so
// never paired) and each met the node's own field in contact: the torn plate gained 113 % of its
// energy in 40 us, as one polyline 1.7 % (docs/validation.md, "Stability at the extremes"). The
// junction is then no crack tip (the material around it is cut on both sides). Not joined, and
// warned about by warn_meeting_ends: ends a cell or less apart that do not coincide, three or more
// ends at a point, cracks with different contact settings, a crack that grows (its "propagation"
// belongs to its own scene entry), an end the scene names as a tip. Runs after resolve_tips and
// read_propagation (which read the scene entry at each crack's id); renumbers the ids.
bool joinable(const Model<2>& m, const EndPair& e) {
  const double tol = 1e-9 * m.grid.h;
  const crack::Crack2D &a = m.cracks[e.i], &b = m.cracks[e.j];
  const Vec<2> x = end_point(a, e.ei);
  if (!((end_point(b, e.ej) - x).norm() <= tol)) return false;
  int ends_here = 0;
  for (const auto& c : m.cracks)
    for (int k = 0; k < 2; ++k) ends_here += (end_point(c, k) - x).norm() <= tol;
  const auto grows = [&](std::size_t i) { return !m.propagation.empty() && m.propagation[i].has_value(); };
  const auto named_tip = [](const crack::Crack2D& c, int k) { return c.tips != "auto" && c.tip[k]; };
  return ends_here == 2 && same_contact(a, b) && !grows(e.i) && !grows(e.j) && !named_tip(a, e.ei) &&
         !named_tip(b, e.ej);
}

// Crack j joined to crack i at the ends of e: i keeps its direction (its above and below), j follows
// on from the junction; j is removed and the ids renumbered.
void join_pair(Model<2>& m, const EndPair& e) {
  crack::Crack2D &a = m.cracks[e.i], &b = m.cracks[e.j];
  const bool b_reversed = e.ei == e.ej;
  std::vector<Vec<2>> bp = b.points;
  if (b_reversed) std::reverse(bp.begin(), bp.end());
  std::vector<Vec<2>> pts;
  uint8_t tip0, tip1;
  if (e.ei == 1) {  // a ... x, then b from x on
    pts = a.points;
    pts.insert(pts.end(), bp.begin() + 1, bp.end());
    tip0 = a.tip[0], tip1 = b.tip[1 - e.ej];
  } else {  // b up to x, then a from x on
    pts = bp;
    pts.insert(pts.end(), a.points.begin() + 1, a.points.end());
    tip0 = b.tip[1 - e.ej], tip1 = a.tip[1];
  }
  m.warnings.push_back("cracks '" + a.name + "' and '" + b.name + "' meet end to end at " +
                       position_text<2>(end_point(a, e.ei)) + ": read as one kinked crack '" + a.name + "+" + b.name +
                       "' in the direction of '" + a.name + "'" +
                       (b_reversed ? " ('" + b.name + "' reversed: its above and below swap)" : "") +
                       "; the junction is no crack tip");
  a.name += "+" + b.name;
  if (a.tips != "auto" || b.tips != "auto") a.tips = tip0 && tip1 ? "both" : tip0 ? "start" : tip1 ? "end" : "none";
  a.tip = {tip0, tip1};
  a.points = std::move(pts);
  a.above = a.below = a.reference = a.points;
  crack::set_polyline_segments(a);
  a.update_extent();
  m.cracks.erase(m.cracks.begin() + static_cast<std::ptrdiff_t>(e.j));
  if (!m.propagation.empty()) m.propagation.erase(m.propagation.begin() + static_cast<std::ptrdiff_t>(e.j));
  for (std::size_t k = 0; k < m.cracks.size(); ++k) m.cracks[k].id = static_cast<int>(k);
}

void join_cracks_meeting_end_to_end(Model<2>& m) {
  EndPair found{};
  while (any_end_pair(m, [&](const EndPair& e) { return joinable(m, e) && (found = e, true); })) join_pair(m, found);
}

// Two cracks whose ends lie within a cell of each other share nodes near the junction, where the
// node's own field meets the material beyond each crack as two fields; their contacts there make
// energy (docs/validation.md, "Stability at the extremes": the torn plate gains 113 % in 40 us,
// the same kinked crack as one polyline 1.7 %; three cracks from one point 61 %). Those that
// join_cracks_meeting_end_to_end could not join: warn, and say why.
void warn_meeting_ends(Model<2>& m) {
  const double h = m.grid.h;
  any_end_pair(m, [&](const EndPair& e) {
    const auto &a = m.cracks[e.i], &b = m.cracks[e.j];
    const Vec<2> xa = end_point(a, e.ei);
    const double d = (xa - end_point(b, e.ej)).norm();
    if (!(d < h)) return false;
    char gap[64];
    std::snprintf(gap, sizeof gap, "%.2g", d / h);
    m.warnings.push_back("cracks '" + a.name + "' and '" + b.name + "': the " + (e.ei ? "end" : "start") +
                         " of one and the " + (e.ej ? "end" : "start") + " of the other lie " + gap + " cell apart at " +
                         position_text<2>(xa) + "; contact at such a junction makes energy (docs/validation.md, "
                         "\"Stability at the extremes\"): write a kinked crack as one polyline (two cracks are read as one "
                         "only where their ends coincide, no third crack ends there, their contact settings agree, "
                         "neither grows and neither names the junction a tip)");
    return false;
  });
}

// The scene key "crack_tips": J-integral contour and output interval (default: global_interval).
// The J-integral's path independence holds for a contour around one crack tip only: warn when a
// contour encloses part of another crack (or of the same crack away from the tip's own segments),
// sampling every segment at quarter cells.
void warn_contour_meets_cracks(const Model<2>& m, const crack::TipSettings& s, const crack::Crack2D& c, int end,
                                      std::vector<std::string>& warnings) {
  const double h = m.grid.h;
  const crack::TipFrame f = crack::tip_frame(c, end);
  const double reach = s.radius * h * std::sqrt(2.0);  // the contour's farthest point from the tip
  // Arc length of the tip's own crack from its start to each vertex.
  std::vector<double> arc(c.points.size(), 0.0);
  for (std::size_t j = 1; j < c.points.size(); ++j) arc[j] = arc[j - 1] + (c.points[j] - c.points[j - 1]).norm();
  for (const auto& o : m.cracks)
    for (std::size_t i = 0; i + 1 < o.points.size(); ++i) {
      const Vec<2> a = o.points[i], b = o.points[i + 1];
      const int n = std::max(1, static_cast<int>(std::ceil(4 * (b - a).norm() / h)));
      bool inside = false;
      for (int k = 0; k <= n && !inside; ++k) {
        const Vec<2> x = a + (b - a) * (static_cast<double>(k) / n);
        // The tip's own crack runs into the contour along its last stretch: skip the points on it
        // within the contour's reach of the tip, measured along the crack.
        if (&o == &c) {
          const double from_start = arc[i] + (x - a).norm();  // distance from the tip along the crack
          const double along = end == 1 ? arc.back() - from_start : from_start;
          if (along <= reach + 1e-9 * h) continue;
        }
        inside = crack::inside_contour(f, s, h, x);
      }
      if (inside) {
        warnings.push_back("crack_tips: the contour around the " + std::string(end ? "end" : "start") + " tip of crack '" +
                           c.name + "' encloses part of crack '" + o.name +
                           "'; J there is not path-independent (use a smaller crack_tips.radius or move the cracks apart)");
        return;
      }
    }
}

// The largest contour radius (cells) that fits round the tip of `end`: the contour, with the nodes it
// interpolates from (a cell beyond it), inside the grid, and the crack's far end a cell outside it (so
// that the contour meets the tip's own crack, and no other tip lies inside it).
// The contour's farthest point from the tip per unit radius: 1 (circle) or sqrt 2 (the square's corner).
double corner_factor(const crack::TipSettings& s) {
  return s.contour == crack::TipSettings::Contour::Circle ? 1.0 : std::sqrt(2.0);
}

double largest_fitting_radius(const Model<2>& m, const crack::TipSettings& s, const crack::Crack2D& c, int end) {
  const double h = m.grid.h;
  const double corner = corner_factor(s);
  const Vec<2> x = crack::tip_frame(c, end).tip;
  const Vec<2> room = (x - m.grid.origin).cwiseMin(m.grid.upper() - x);
  const double in_grid = (room.minCoeff() - h) / (corner * h);
  const double in_crack = (crack::vertex_from_tip(c, end, c.points.size() - 1) - x).norm() / (corner * h) - 1.0;
  return std::min(in_grid, in_crack);
}

crack::TipSettings read_tip_settings(const json& scene, Model<2>& m, double time_scale,
                                          std::vector<std::string>& warnings) {
  crack::TipSettings s = read_contour_settings(scene, m, time_scale, {});
  const bool default_radius = !scene["crack_tips"].contains("radius");
  const double h = m.grid.h;
  // The default radius shrinks where it does not fit (a short crack, a tip near the grid's edge),
  // to no less than a cell, and says so; a radius the scene gives, or a default that cannot shrink
  // that far, is kept (with a warning below) or refused.
  if (default_radius) {
    double fit = s.radius;
    std::string where;
    for (const auto& c : m.cracks)
      for (int end = 0; end < 2; ++end)
        if (c.tip[end]) {
          const double r = std::floor(largest_fitting_radius(m, s, c, end) * 4.0) / 4.0;  // quarter cells
          if (r < fit) fit = r, where = std::string(end ? "end" : "start") + " tip of crack '" + c.name + "'";
        }
    if (fit < s.radius && fit >= 1.0) {
      warnings.push_back("crack_tips.radius: the default " + scene::fmt(s.radius) + "-cell contour does not fit round the " +
                         where + " (the grid's edge or the crack's other end is too near); " + scene::fmt(fit) +
                         " cells used (give crack_tips.radius to choose)");
      s.radius = fit;
    }
  }
  // Every contour, with the nodes it interpolates from, must lie inside the grid.
  const double extent = s.radius * h * corner_factor(s) + h;
  bool any = false;
  for (const auto& c : m.cracks)
    for (int end = 0; end < 2; ++end) {
      if (!c.tip[end]) continue;
      any = true;
      const Vec<2> x = crack::tip_frame(c, end).tip;
      if ((x.array() - extent < m.grid.origin.array()).any() || (x.array() + extent > m.grid.upper().array()).any())
        throw SceneError("crack_tips.radius", "the contour around the " + std::string(end ? "end" : "start") +
                                                  " tip of crack '" + c.name + "' leaves the grid; enlarge the grid");
      if (largest_fitting_radius(m, s, c, end) < s.radius)  // a given radius, or a default that could not shrink
        warnings.push_back("crack_tips: the contour around the " + std::string(end ? "end" : "start") + " tip of crack '" +
                           c.name + "' reaches within a cell of the crack's other end; J there is not that of one tip "
                           "(use a smaller crack_tips.radius)");
      warn_contour_meets_cracks(m, s, c, end, warnings);
      for (std::size_t p = 0; p < m.particles.size(); ++p)
        if ((m.particles.x[p] - x).norm() <= extent) {
          double g, nu;
          if (!m.materials[m.particles.material[p]]->isotropic_elastic(g, nu))
            throw SceneError("crack_tips", "crack '" + c.name + "': K from J needs an isotropic elastic material at its tips");
          break;
        }
    }
  if (!any) throw SceneError("crack_tips", "no crack has a tip (every end lies outside the material, or \"tips\": \"none\")");
  return s;
}

// 3D: each surface clipped to the material (a surface crack's part outside the body goes, but for a
// band of a cell; its edges there are mouths), checked against the grid, and its fronts found (boundary edges inside the
// material) with their frames; "tips" other than "none" makes every front a crack tip.
void build_cracks3d(Model<3>& m) {
  const double h = m.grid.h;
  const MaterialProbe inside(m);
  const Vec<3> lo = m.grid.origin, hi = m.grid.upper();
  for (auto& c : m.cracks) {
    const std::string path = "cracks[" + std::to_string(c.id) + "]";
    crack::TriMesh mesh{c.points, c.simplices};
    const std::size_t given = mesh.triangles.size();
    // Kept: every triangle with a vertex within a cell of the material. The nodes up to a cell
    // outside a body receive mass from its particles; a crack that ended at the body's face would
    // leave those nodes joining the faces (2D keeps its polylines whole for the same reason).
    mesh = crack::clip_to(mesh, [&](const Vec<3>& x) { return inside.near(x, h); });
    if (mesh.triangles.empty())
      throw SceneError(path, "crack '" + c.name + "' lies outside every body (none of its " + std::to_string(given) +
                                 " triangles has a vertex within a cell of the material)");
    if (mesh.triangles.size() < given)
      m.warnings.push_back("crack '" + c.name + "': " + std::to_string(given - mesh.triangles.size()) + " of its " +
                           std::to_string(given) + " triangles lie more than a cell outside the material and were "
                           "dropped");
    c.points = mesh.points;
    c.simplices = mesh.triangles;
    for (std::size_t i = 0; i < c.points.size(); ++i) {
      const Vec<3>& x = c.points[i];
      if (!((x.array() > lo.array()).all() && (x.array() < hi.array()).all()))
        throw SceneError(path, "crack '" + c.name + "': point " + std::to_string(i) + " " + position_text<3>(x) +
                                   " lies outside the grid; enlarge the grid");
    }
    c.fronts = crack::crack_fronts(c, inside);
    // The band the crossing test leaves out along the fronts (front_cut.hpp); its triangles' lists of
    // front edges hold while the crack deforms by less than half a cell.
    c.tip_cut *= h;
    c.front_cut = crack::make_front_cut(c, c.fronts, c.tip_cut, 0.5 * h);
    c.tip.assign(c.fronts.size(), c.tips == "none" ? 0 : 1);
    c.above = c.below = c.points;
    c.update_extent();
  }
}

// cracks[i].propagation: how each crack grows (crack/propagation.hpp). The crack needs a tip, and
// the material at each of its tips an isotropic elastic law and a toughness.
void read_propagation(const json& scene, double length, Model<2>& m) {
  const json& cracks = scene["cracks"];
  for (const auto& c : m.cracks) {
    const json& cj = cracks[static_cast<std::size_t>(c.id)];
    if (!cj.contains("propagation")) continue;
    const std::string path = "cracks[" + std::to_string(c.id) + "].propagation";
    if (m.propagation.empty()) m.propagation.resize(m.cracks.size());
    m.propagation[c.id] = crack::parse_propagation(cj["propagation"], path, length);
    if (!c.tip[0] && !c.tip[1])
      throw SceneError(path, "crack '" + c.name + "' has no tip to grow from (both ends lie outside the material, or "
                             "\"tips\" says none)");
    for (int end = 0; end < 2; ++end) {
      if (!c.tip[end]) continue;
      const Vec<2> x = crack::tip_frame(c, end).tip;
      std::size_t near = 0;
      double best = INFINITY;
      for (std::size_t p = 0; p < m.particles.size(); ++p)
        if (const double d = (m.particles.x[p] - x).squaredNorm(); d < best) best = d, near = p;
      const int k = m.particles.material[near];
      const Material<2>& mat = *m.materials[k];
      const std::string mpath = "materials[" + std::to_string(k) + "]";
      double mu = 0.0, nu = 0.0;
      if (!mat.isotropic_elastic(mu, nu))
        throw SceneError(mpath, "crack '" + c.name + "' grows into it: growth needs an isotropic elastic material");
      if (!(mat.toughness_Gc() > 0.0 || mat.toughness_KIc() > 0.0))
        throw SceneError(mpath, "missing toughness: crack '" + c.name + "' grows (" + path +
                                    ") into material '" + mat.name() + "', which gives neither \"G_c\" nor \"K_Ic\"");
    }
  }
}

}  // namespace

template <int Dim>
void read_cracks(const json& scene, double length, Model<Dim>& m) {
  if (scene["cracks"].is_array() && scene["cracks"].size() > static_cast<std::size_t>(crack::kMaxCracks))
    throw SceneError("cracks", "holds " + std::to_string(scene["cracks"].size()) + " cracks; at most " +
                                   std::to_string(crack::kMaxCracks) + " (a velocity field's key numbers them in 12 bits)");
  if constexpr (Dim == 3) {
    // Crack particles at half a cell, as the seed's (its §4: "crack particles ... about half the cell size").
    // Keys of 2D cracks that 3D cracks do not take yet, each with the reason.
    const std::pair<const char*, const char*> only_2d[] = {
        {"propagation", "3D cracks do not grow yet (growth is 2D so far); remove the key"},
        {"tip_split", "3D fronts are cut back only crossing by crossing (tip_cut); remove the key"}};
    for (std::size_t i = 0; i < scene["cracks"].size(); ++i)
      for (const auto& [key, why] : only_2d)
        if (scene["cracks"][i].is_object() && scene["cracks"][i].contains(key))
          throw SceneError("cracks[" + std::to_string(i) + "]." + key, why);
    m.cracks = crack::parse_cracks3d(scene["cracks"], "cracks", length, {0.5 * m.grid.h, true});
    build_cracks3d(m);
  } else {
    m.cracks = crack::parse_cracks(scene["cracks"], "cracks", length);
    check_cracks(m);
    cut_through_near_edges(m);
    resolve_tips(m);
    read_propagation(scene, length, m);
    join_cracks_meeting_end_to_end(m);
    warn_meeting_ends(m);
    resolve_cut_ends(m);
  }
}

template <int Dim>
void warn_volume_detection_when_slow(Model<Dim>& m) {
  if (!(m.damping > 0.0 || m.static_tolerance > 0.0)) return;
  for (const auto& c : m.cracks)
    if (c.detection == crack::Detection::Volume && c.contact_law != crack::ContactLaw::None)
      m.warnings.push_back(c.key + ".contact.detection: \"volume\" (the default) in a " +
                           (m.static_tolerance > 0.0 ? "static" : "damped") + " run ratchets crack '" + c.name +
                           "' open: it cannot tell faces open by a small part of a cell from closed ones, so small "
                           "oscillations open the faces and contact stops them closing (static DCB: J +25 %); give "
                           "\"detection\": \"displacement\" (docs/scenes.md, \"Choosing the detection\")");
}

template <int Dim>
crack::TipSettings read_contour_settings(const json& scene, Model<Dim>& m, double time_scale,
                                         std::span<const char* const> more_keys) {
  const ObjectReader r(scene["crack_tips"], "crack_tips", crack_tips_keys(more_keys));
  if (m.cracks.empty()) throw SceneError("crack_tips", "the scene declares no cracks (key \"cracks\")");
  crack::TipSettings s;
  // crack_tips.interval: the older spelling of output.tip_interval, the key of every method.
  if (r.has("interval")) {
    if (scene.contains("output") && scene["output"].contains("tip_interval"))
      throw SceneError(r.at("interval"), "give output.tip_interval (or crack_tips.interval), not both");
    m.output.tip_interval = r.positive("interval", time_scale);
  }
  const std::string shape = r.string_or("contour", "circle");
  if (shape == "rectangle") s.contour = crack::TipSettings::Contour::Rectangle;
  else if (shape != "circle") throw SceneError(r.at("contour"), "unknown contour \"" + shape + "\"; valid: circle, rectangle");
  // Defaults, 2D: a 4-cell circle with eq. 33. The 2-cell contour lies in the tip's coarsely resolved
  // cells (static DCB +4.7 % against its compliance derivative, Freund 8.2 %, 4 cells: +1.0 %, 3.2 %),
  // and eq. 32 ignores the inertia inside the contour (30 % low in Freund's problem); an evaluation
  // costs 0.53 ms instead of 0.39 ms (the DCB at 57 600 particles, once per crack_tips.csv row;
  // docs/validation.md, "The defaults"). 3D: 2 cells and eq. 32 (issue 17's seed 000 settings).
  const double default_radius = Dim == 2 ? 4.0 : 2.0;
  s.volume_term = Dim == 2;
  s.radius = r.positive_or("radius", default_radius);
  if (s.radius < 1.0)
    throw SceneError(r.at("radius"), "at least 1 cell (the contour must reach past the tip's own cell; default " +
                                         scene::fmt(default_radius) + ")");
  // 16 suffice on the circle (seed 000); the square's corners need 32 for the same accuracy.
  s.points = r.integer_or("points", s.contour == crack::TipSettings::Contour::Circle ? 16 : 32, 16, 100000);
  if (r.has("volume_term")) {
    if (!r["volume_term"].is_boolean()) throw SceneError(r.at("volume_term"), "expected true or false");
    s.volume_term = r["volume_term"].get<bool>();
  }
  return s;
}

template <int Dim>
void read_crack_tips(const json& scene, const UnitSystem& units, Model<Dim>& m) {
  if constexpr (Dim == 3)
    read_front_tips(scene, units, m);
  else
    m.crack_tips = read_tip_settings(scene, m, units.factor(Quantity::Time), m.warnings);
}

template void read_cracks<2>(const json&, double, Model<2>&);
template void read_cracks<3>(const json&, double, Model<3>&);
template void read_crack_tips<2>(const json&, const UnitSystem&, Model<2>&);
template void read_crack_tips<3>(const json&, const UnitSystem&, Model<3>&);
template void warn_volume_detection_when_slow<2>(Model<2>&);
template void warn_volume_detection_when_slow<3>(Model<3>&);
template crack::TipSettings read_contour_settings<2>(const json&, Model<2>&, double, std::span<const char* const>);
template crack::TipSettings read_contour_settings<3>(const json&, Model<3>&, double, std::span<const char* const>);

}  // namespace cleave
