// 2D: which side of a crack a particle a hair from its line belongs to, decided in the reference
// configuration. Seed 002's line crossing sorts a particle by its side of the crack's current line
// (crossing.hpp). A particle that lies within a hair of that line sits on a knife edge: the line moves
// with the velocity read at the discrete crack and the particle with its own field, so they drift
// against each other by ~1e-4 cell, and near a tip the singular field bends a particle row across the
// line by ~1e-3 cell within a cell ahead of it. A growing crack 1e-4 cell above a particle row met
// that row's particles on both sides of its line, its discrete crack stepped half a cell where they
// changed sides, and it turned 0.23 cell off its line (docs/validation.md, growing cracks 2). The
// particle's side of the crack's line in the reference configuration (its position at t = 0, x - u,
// against the crack's reference points, ExplicitCrack::reference) does not move with either, so such
// a particle is sorted by that: the crossing test takes it at the same distance from the line on its
// reference side. Beyond the hair the current line decides, as before.
#pragma once
#include <cmath>
#include <cstdint>

#include "libmpm/crack/explicit_crack.hpp"

namespace cleave::crack {

// Cells: how near the crack's line a particle is sorted by its reference side: larger than the drift
// and the near-tip bending above (up to 4e-4 cell measured), and small enough that a line crossing the
// particle rows at an angle finds a particle this near it only rarely (the reference line of a
// growing crack is drawn at the current line's kink angles, crack_growth.cpp, and departs from the
// material's own line where the body shears: such a particle may then go to the other face).
inline constexpr double kSortingHair = 2e-3;
// Of the hair: a particle this near the reference line has no reference side.
inline constexpr double kOnReferenceLine = 1e-6;

// The particle at x (reference position X) against segments lo..hi of 2D crack c (the polyline its
// crossing test uses: carried on past cut ends node by node): when x lies within `hair` (m) of a
// segment, beside it, |distance| goes to `dist` and, when X lies on the other side of the same
// reference segment's line (or x on the line and X off it), `out` to x moved across the line to that
// distance on X's side. Returns whether the particle is within the hair; out is set only when it
// changes sides (not when X lies on the reference line, within kOnReferenceLine of the hair).
inline bool reference_side(const ExplicitCrack<2>& c, int32_t lo, int32_t hi, const Vec<2>& x, const Vec<2>& X,
                           double hair, double& dist, Vec<2>& out, bool& moved) {
  moved = false;
  if (c.reference.size() != c.points.size()) return false;
  const Vec<2>* line = c.cuts() && c.node_split && !c.split_points.empty() ? c.split_points.data() : c.points.data();
  double best = hair;
  int32_t seg = -1;
  double d = 0.0;
  for (int32_t s = lo; s <= hi; ++s) {
    const Vec<2> a = line[s], t = line[s + 1] - a, r = x - a;
    const double l2 = t.squaredNorm(), along = r.dot(t);
    if (!(l2 > 0.0) || along < 0.0 || along > l2) continue;
    const double ds = (t.x() * r.y() - t.y() * r.x()) / std::sqrt(l2);  // > 0: left of the segment (above)
    if (std::abs(ds) < best) best = std::abs(ds), d = ds, seg = s;
  }
  if (seg < 0) return false;
  dist = best;
  const Vec<2> A = c.reference[static_cast<std::size_t>(seg)], T = c.reference[static_cast<std::size_t>(seg) + 1] - A;
  const Vec<2> R = X - A;
  const double side = T.x() * R.y() - T.y() * R.x();
  // On the reference line itself, to round-off (a crack drawn through particle centres, as the
  // inclined centre crack at 45 degrees through a node in every cell): no side there; the current line
  // decides, as before (sorted by the round-off, K_II at the 45-degree tip read +4.7 % for +0.6 %).
  if (std::abs(side) <= kOnReferenceLine * hair * std::sqrt(T.squaredNorm())) return true;
  if (d != 0.0 && (d > 0.0) == (side > 0.0)) return true;
  const Vec<2> t = (line[seg + 1] - line[seg]).normalized(), n(-t.y(), t.x());
  const double to = (side > 0.0 ? 1.0 : -1.0) * std::max(std::abs(d), 1e-3 * hair);
  out = x + (to - d) * n;
  moved = true;
  return true;
}

// One particle against several cracks, or the index ranges of their segments (consider each): the
// nearest crack within the hair decides; `at` is where the crossing test takes the particle (x itself
// when no crack is that near or the nearest agrees).
struct SortingPosition {
  Vec<2> x, X, at;
  double hair;
  SortingPosition(const Vec<2>& x_, const Vec<2>& X_, double hair_) : x(x_), X(X_), at(x_), hair(hair_) {}
  void consider(const ExplicitCrack<2>& c, int32_t lo, int32_t hi) {
    double dist = 0.0;
    Vec<2> out = x;
    bool moved = false;
    // (reference_side answers only for a crack nearer than the hair, which then shrinks to it)
    if (lo <= hi && reference_side(c, lo, hi, x, X, hair, dist, out, moved)) hair = dist, at = moved ? out : x;
  }
};

// The same against every crack of `cracks`, each over all its segments.
template <class Cracks>
Vec<2> sorting_position(const Cracks& cracks, const Vec<2>& x, const Vec<2>& X, double hair) {
  SortingPosition sp(x, X, hair);
  for (const auto& c : cracks) sp.consider(c, 0, static_cast<int32_t>(c.points.size()) - 2);
  return sp.at;
}

}  // namespace cleave::crack
