// What the renderer draws of OUT/cracks.pvd: the crack frame nearest a particle frame's time, its
// 2D crack paths (overlays and smoothing barriers of 2D frames), its 3D crack surfaces (faces over
// the particle cubes, traces in sections). docs/rendering.md, "Crack files the renderer reads".
#pragma once
#include <vtkSmartPointer.h>
#include <vtkType.h>
#include <vtkUnstructuredGrid.h>

#include <array>
#include <filesystem>
#include <vector>

#include "viz/raster/crack_section.hpp"
#include "viz/render/headless.hpp"

namespace cleave::viz {

// The frame of OUT/cracks.pvd nearest to time t; grid null when the run has no crack series.
struct CrackFrame {
  vtkSmartPointer<vtkUnstructuredGrid> grid;
  double time = 0;
  std::filesystem::path file;
};
CrackFrame nearest_crack_frame(const std::filesystem::path& dir, double t);

// Whether the crack frame holds 3D crack surfaces (triangle cells).
bool has_crack_surfaces(vtkUnstructuredGrid* g);

// The 2D crack paths of a crack frame, as point ids in order along each crack (none for a 3D crack
// frame, whose line cells are crack fronts, not paths).
std::vector<std::vector<vtkIdType>> crack_paths(vtkUnstructuredGrid* g);

// The 2D crack paths of a crack frame in red (none in 3D), and of the crack frame nearest time t
// (none without cracks).
std::vector<Polyline2D> crack_overlays(vtkUnstructuredGrid* g);
std::vector<Polyline2D> crack_overlays(const std::filesystem::path& dir, double t);

// The triangles of a crack frame and its faces: point data "above" and "below" (3 components), or
// the points themselves for both where the file has no face data.
CrackSurfaces crack_surfaces(vtkUnstructuredGrid* g);

// The two faces as drawn over 3D particles, the opening scaled by K (crack_section.hpp): "above"
// in red first, then "below" in blue, so where the faces coincide (an unopened crack) the surface
// is red, as before faces were drawn apart. Shaded (lit, so an exaggerated opening shows its
// shape) when K != 1; flat colours at K = 1.
CrackSurfaces3D crack_faces_3d(const CrackSurfaces& s, double K);

// The traces of both faces (opening scaled by K) in the cutting plane {point, normal}, in the
// section's coordinates: "above" red, "below" blue.
std::vector<Polyline2D> section_overlays(const CrackSurfaces& s, double K, const std::array<double, 6>& plane);

}  // namespace cleave::viz
