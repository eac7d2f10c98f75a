// 3D crack surfaces as the renderer draws them (no VTK): the two faces of a crack, their opening
// exaggerated by a factor, and their traces in a cutting plane (the lines a section shows).
//
// A 3D crack frame (libmpm/io/crack_output.cpp) holds the crack surface as triangles over its
// points, and per point the positions of its two faces, "above" and "below" (cod = above - below).
// The opening is a few tens of micrometres in a specimen of centimetres, invisible at 1:1, so the
// faces are drawn at x_mid + K (face - x_mid), x_mid = (above + below) / 2: K = 1 draws each face
// where it is, K > 1 widens the gap K times about the mid-surface and moves nothing else.
#pragma once
#include <array>
#include <cstddef>
#include <vector>

namespace cleave::viz {

using Point3 = std::array<double, 3>;

// One crack frame's surfaces: triangles over points, and each point's two faces. A file without
// face data (older or foreign crack files) has above = below = the surface points.
struct CrackSurfaces {
  std::vector<Point3> above, below;
  std::vector<std::array<std::size_t, 3>> triangles;
};

enum class CrackFace { Above, Below };

// x_mid + K (face - x_mid), x_mid = (above + below) / 2.
Point3 opened_face_point(const Point3& above, const Point3& below, double K, CrackFace face);

// One face of every crack as drawn: each point moved by opened_face_point (the triangles are
// s.triangles). Throws std::invalid_argument when above and below differ in length.
std::vector<Point3> opened_face_points(const CrackSurfaces& s, double K, CrackFace face);

// Largest |above - below| over the points (0: the crack has not opened anywhere).
double max_opening(const CrackSurfaces& s);

// The trace of one face (opening scaled by K) in the plane through `point` with `normal`: the
// polylines along which the face's triangles cross the plane, in the plane's in-plane coordinates
// (u.x, v.x) with (u, v) = plane_axes(normal), the coordinates cut_plane gives the section's
// particles, so the traces lie where the crack is in the section. Segments of triangles that share
// an edge are joined into one polyline (a closed trace repeats its first point at the end). A
// point exactly on the plane counts as in front of it, so a trace through mesh points is taken
// once. Throws std::invalid_argument for a zero normal.
std::vector<std::vector<std::array<double, 2>>> face_section(const CrackSurfaces& s, double K, CrackFace face,
                                                             const Point3& point, const Point3& normal);

// Segments {u0, v0, u1, v1} of the traces of both faces where they are (K = 1): barriers that the
// stress smoothing of a section does not average across (viz/raster/smooth.hpp).
std::vector<std::array<double, 4>> section_barriers(const CrackSurfaces& s, const Point3& point, const Point3& normal);

}  // namespace cleave::viz
