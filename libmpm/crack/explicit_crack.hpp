// An explicit crack (seed 002, CRAMP) in any dimension: the crack's geometry as a Surface<Dim> (a
// polyline in 2D, a triangle mesh in 3D; its boundary is the fronts) plus what the MPM crack
// fields need: contact law and detection, which fronts are crack tips, and the two faces (above /
// below) that the crack's particles carry. Peridynamics reads the same scene key into plain
// surfaces; MPM builds these. Only the 2D crack fields exist so far (crack2d.hpp: the polyline
// reader and crossing test; libmpm/mpm/crack_fields/).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "libmpm/core/types.hpp"
#include "libmpm/crack/front_cut.hpp"
#include "libmpm/crack/fronts.hpp"
#include "libmpm/crack/surface.hpp"

namespace cleave::crack {

// Contact law between the faces, scene names "stick" | "frictionless" | "friction" (Coulomb, mu) |
// "none" (faces may interpenetrate: for cracks known to stay open, and for the crack patch test
// against a half model, which has none). The names are registered in crack2d.cpp (ContactLaws).
enum class ContactLaw { Stick, Frictionless, Friction, None };
// Contact detection: seed 002's nodal volume (V_rel > v_contact: contact; V_rel < v_sep: apart;
// between: approaching faces are in contact), seed 000's nodal displacement (approaching faces
// whose displacements overlap are in contact), or, between bodies, position (approaching fields
// whose mass centres come within d_contact cells along the normal are in contact).
enum class Detection { Volume, Displacement, Position };

// Cells by which a 2D crack's tips are cut back for the crossing test when the scene does not say
// (cracks[i].tip_cut; ExplicitCrack::cut_end says why). The discrete crack was measured to end about
// 0.1 cell short of its first whole node (a centre crack whose tips sit on nodes reads the
// K of its declared length), so a cut of about 0.4-0.5 cell centres it on the declared tip; 0.5 itself
// would cut a tip half-way between nodes (the common placement, e.g. dcb_crack.json) exactly onto a
// node, where the split would turn on round-off. Measured on the mixed-mode plate at 0.4, 0.45, 0.5 and
// 0.6 (docs/validation.md, "Where the discrete crack ends").
inline constexpr double kDefaultTipCut = 0.45;
// 3D fronts are not cut unless the scene asks (seed 000's rule): measured with 0.45 (docs/validation.md,
// "Crack-front parameters"), the cut evens K_I along the penny's front (spread 6.4 -> 2.4 %) but lowers
// K everywhere by more than the band's width accounts for (rod at 3 mm, K_I(A) +1.4 -> -6.6 %; inclined
// penny K_I(A) -8.2 -> -11.3 % of K_0): the uncut 3D discrete crack already reads the penny's K.
inline constexpr double kDefaultFrontCut = 0.0;

// 3D cracks keep their fronts (boundary edges inside the material, with frames: fronts.hpp); in 2D
// the fronts are the two end points, described by `tip` alone.
template <int Dim>
struct FrontsOf {};
template <>
struct FrontsOf<3> {
  std::vector<CrackFront> fronts;
  FrontCut front_cut;  // the band along the fronts that the crossing test leaves out (tip_cut)
};

// How two velocity fields at a node interact: a crack's faces, or two bodies (the scene's "contact"
// object, contact_keys.hpp).
struct ContactSettings {
  ContactLaw contact_law = ContactLaw::Frictionless;
  double friction = 0.0;  // Coulomb mu, only for "friction"
  Detection detection = Detection::Volume;
  double v_sep = 0.9, v_contact = 1.1;
  double d_contact = 0.8;  // cells (position detection)
};

template <int Dim>
struct ExplicitCrack : Surface<Dim>, FrontsOf<Dim>, ContactSettings {
  using ContactLaw = crack::ContactLaw;
  using Detection = crack::Detection;

  int id = 0;  // position in the model's cracks: the scene's "cracks" array, less any joined to an earlier crack
  std::string key;  // the scene key that gave it, for messages ("cracks[2]"; of two joined, the first's)
  // points (Surface): vertices (massless crack particles), SI; in 2D the direction points[0] ->
  // points[1] -> ... defines above (left) / below (right). Contact law and detection: ContactSettings.
  // Which fronts are crack tips (where crack_tips computes J and K): the scene's "auto" (a front
  // with material ahead of it; the scene reader decides), "both", "start", "end" or "none". One
  // flag per front; 2D: tip[0] is points[0], tip[1] is points.back().
  std::string tips = "auto";
  std::vector<uint8_t> tip = std::vector<uint8_t>(2, 1);
  // The faces above and below (crack particles moved with the velocity field of each side), in
  // step with `points`; the crack opening displacement is above - below. Set from points when empty.
  std::vector<Vec<Dim>> above, below;
  // 2D: the points where the material they cut stood at t = 0 (the reference configuration), in step
  // with `points`: a particle a hair from the crack's line is sorted by its side of this line
  // (crack/reference_side.hpp). Set from points when the scene is read; a growing crack grows it at
  // the same kink angles (crack_growth.cpp). Empty in 3D.
  std::vector<Vec<Dim>> reference;
  // Extent (Surface::lo, hi) of all vertices: empty (+inf / -inf) until update_extent(), so that a
  // crack whose extent was never computed screens every pair out; call it after moving the points.
  void update_extent() {
    Surface<Dim>::update_extent();
    if constexpr (Dim == 2) update_crossing();
  }

  // 2D: each end in cut_end is cut back by tip_cut (m) for the crossing test. Why: a node is split
  // when a line from a particle crosses the crack, and the crack's displacement jump then falls
  // linearly to zero at the next node that is not split, so the discrete crack ends at the first
  // whole node beyond the last split one: up to a cell beyond its tip, a whole cell when the tip lies
  // on a node (pure mode II at a = 8 cells: K_II +9.2 %). Cut back by tip_cut, the first whole node
  // lies between tip_cut cells behind the tip and 1 - tip_cut beyond it (docs/validation.md, "Where
  // the discrete crack ends"). Two ways to cut (cracks[i].tip_split):
  //  - line (node_split false): the crossing test runs on the crack with its ends walked back by
  //    tip_cut (cross_points); a node near the tip is split for the particles whose lines meet the
  //    crack short of the cut point, for a crack off a node line the particles of one face only;
  //  - node (node_split true): a node past the cut point (past_cut) stays whole, a node behind it is
  //    split by the whole crack carried on past its tip (split_points): every node near the tip is
  //    split for all its particles or none.
  //    The faces are then treated alike: a mode I crack a tenth of a cell off a node line reads
  //    K_II / K_I 0.01 % (line: -1 %, and growing it wandered a cell off its line within 20
  //    cells), the DCB turned 30 degrees -0.007 % (line: -2.7 %); but a tip carried through the
  //    cells switches whole nodes, and a moving, turning cracked plate departs further from the
  //    plate at rest (10.4 % of the peak opening at 0.5 mm cells, line 6.6 %, bound 10.2 %).
  //    The default for growing cracks, whose direction reads K_II / K_I.
  // An end with no material ahead (a mouth) is not cut. The scene reader sets cut_end, tip_cut,
  // cut_reach and node_split; update_extent() finds the cut points.
  std::vector<uint8_t> cut_end = std::vector<uint8_t>(2, 0);
  double tip_cut = 0.0;
  double cut_reach = std::numeric_limits<double>::infinity();  // m: past_cut looks this far from a cut point
  bool node_split = false;
  bool cuts() const { return tip_cut > 0.0 && (cut_end[0] || cut_end[1]); }
  // Does the node lie past a cut end: ahead of the line through the cut point across the crack,
  // within cut_reach of that point? Every node is past when the cuts leave nothing of the crack.
  bool past_cut(const Vec<Dim>& node) const {
    if (cut_away) return true;
    for (int k = 0; k < 2; ++k) {
      if (!cut_end[k]) continue;
      const Vec<Dim> r = node - cut_at[k];
      if (r.dot(cut_out[k]) > 0.0 && r.squaredNorm() < cut_reach * cut_reach) return true;
    }
    return false;
  }
  // The polyline a line to `node` is tested on, with its segments narrowed to lo .. hi (the crack's
  // numbering, which cross_points shares); nullptr when this crack splits the node for no line: past
  // a cut point node by node, or nothing left of the crack once cut.
  const Vec<Dim>* crossing_polyline(const Vec<Dim>& node, int32_t& lo, int32_t& hi) const {
    if (!cuts()) return this->points.data();
    if (node_split) return past_cut(node) ? nullptr : split_points.data();
    lo = std::max(lo, cross_first), hi = std::min(hi, cross_last - 1);
    return lo <= hi ? cross_points.data() : nullptr;
  }
  // Set by update_crossing: each cut end's cut point and the crack's outward direction there, and
  // whether the cuts leave nothing; cross_points: the crack with its cut ends walked back by tip_cut,
  // points cross_first .. cross_last (the line rule's crossing polyline).
  Vec<Dim> cut_at[2] = {Vec<Dim>::Zero(), Vec<Dim>::Zero()}, cut_out[2] = {Vec<Dim>::Zero(), Vec<Dim>::Zero()};
  bool cut_away = false;
  std::vector<Vec<Dim>> cross_points;
  int32_t cross_first = 0, cross_last = -1;
  void update_crossing() {
    if (!cuts()) return;
    cross_points = this->points;
    cross_first = 0, cross_last = static_cast<int32_t>(cross_points.size()) - 1;
    // Walks from one end (step +1 from the start, -1 from the end), consuming whole segments shorter
    // than what is left to cut and moving the end point onto the segment where the cut ends.
    auto cut = [&](int32_t& end, int step) {
      double left = tip_cut;
      while (cross_last > cross_first) {
        Vec<Dim>& x = cross_points[static_cast<std::size_t>(end)];
        const Vec<Dim>& next = cross_points[static_cast<std::size_t>(end + step)];
        const double l = (next - x).norm();
        if (left < l) {
          x += (next - x) * (left / l);
          return;
        }
        left -= l;
        end += step;
      }
    };
    if (cut_end[0]) cut(cross_first, 1);
    if (cut_end[1]) cut(cross_last, -1);
    cut_away = cross_last <= cross_first;
    if (cut_away) return;
    const auto f = static_cast<std::size_t>(cross_first), l = static_cast<std::size_t>(cross_last);
    cut_at[0] = cross_points[f], cut_out[0] = cross_points[f] - cross_points[f + 1];
    cut_at[1] = cross_points[l], cut_out[1] = cross_points[l] - cross_points[l - 1];
    split_points = this->points;
    const std::size_t n = split_points.size();
    const double carry = std::isfinite(cut_reach) ? cut_reach : 0.0;  // (the scene reader sets it)
    if (n >= 2 && carry > 0.0) {
      if (cut_end[0]) split_points[0] += carry * (split_points[0] - split_points[1]).normalized();
      if (cut_end[1]) split_points[n - 1] += carry * (split_points[n - 1] - split_points[n - 2]).normalized();
    }
  }
  // Node by node, the polyline a split node's lines are tested on: the crack carried on past each
  // cut end by cut_reach. A particle ahead of the tip (in the ligament) whose line reaches a split
  // node behind the cut point is then sorted by its side of the crack's line, not by whether that
  // line happens to cross the crack short of the tip: at a mid-cell tip of a crack c cells above a
  // node line, the upper row's ligament particle joined the lower field for c > 1/6 and its lower
  // twin never the upper one, K_II / K_I read -0.5 % and the growing crack wandered 0.26 cell (0.2
  // off) within 20 cells; now 0.01 (docs/validation.md, growing cracks 2).
  std::vector<Vec<Dim>> split_points;
};

// 3D Subtask 1: can the particle-node line touch the surface? The closed box spanned by particle and
// node meets the closed extent (exact: comparisons only; the 2D one is in crack2d.hpp).
inline bool extent_overlaps(const Surface<3>& c, const Vec<3>& particle, const Vec<3>& node) {
  return (particle.cwiseMin(node).array() <= c.hi.array()).all() &&
         (particle.cwiseMax(node).array() >= c.lo.array()).all();
}

}  // namespace cleave::crack
