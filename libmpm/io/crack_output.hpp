// Crack frames (OUT/cracks_NNNNNN.vtu, indexed by OUT/cracks.pvd): each crack a path through its
// crack particles, written as line segments (VTK_LINE, in order along the crack), with point data
//   above, below      positions of the crack surfaces above and below (m, 3 components)
//   cod               crack opening displacement above - below (m, 3 components)
//   cod_normal        its component along the left normal of the crack (opening > 0, overlap < 0)
//   cod_tangential    its component along the crack direction (sliding)
//   crack             crack id (index in the scene's "cracks" array)
// and, when the scene asks for crack-tip parameters ("crack_tips"), J1, J2 (J/m^2), KI, KII
// (Pa m^1/2) at the tip points (zero at the other points).
#pragma once
#include <vector>

#include "libmpm/crack/crack2d.hpp"
#include "libmpm/crack/front_parameters.hpp"
#include "libmpm/crack/tip_parameters.hpp"
#include "libmpm/io/point_set.hpp"

namespace cleave::io {

PointSet crack_point_set(const std::vector<crack::Crack2D>& cracks);
// The same with the crack-tip parameters on the tip points.
PointSet crack_point_set(const std::vector<crack::Crack2D>& cracks, const std::vector<crack::TipRecord>& tips);

// 3D cracks (cracks_NNNNNN.vtu): each crack's surface as triangles through its crack points, with
// point data above, below, cod (as in 2D), cod_normal (cod along the surface's normal at the point,
// opening > 0), cod_tangential (the rest of cod: sliding and tearing, 3 components), crack; and its
// fronts as line cells through their nodes, with front_normal, front_tangent and front_ahead (the
// front's frame: crack/fronts.hpp) at the front nodes and zero elsewhere.
PointSet crack_point_set(const std::vector<crack::ExplicitCrack<3>>& cracks);
// The same with the crack-front parameters J1, J2 (J/m^2), KI, KII, KIII (Pa m^1/2) and flag
// (crack_fronts.csv's) at the front nodes, zero at the other points.
PointSet crack_point_set(const std::vector<crack::ExplicitCrack<3>>& cracks, const std::vector<crack::FrontRecord>& fronts);

// Normal and tangential opening at point i of crack c (the quantities written above).
Vec<2> crack_opening(const crack::Crack2D& c, std::size_t i);

}  // namespace cleave::io
