// Frozen-stress slicing: the section of a 3D frame as 3D photoelasticity sees it. A slice of
// thickness t is cut from the (stress-frozen) model normal to the light; the polariscope shows
// the retardation integrated through the slice, N = (1/f_sigma) * integral of (s1 - s2) over the
// thickness, of the secondary (in-plane) stress. Averaging the in-plane stress tensor through the
// slice and taking N = t (s1 - s2)(mean tensor) / f_sigma is the standard approximation, exact when
// the secondary principal axes do not turn through the thickness (a thin slice).
#pragma once
#include <array>

#include "viz/raster/series.hpp"

namespace cleave::viz {

// The particles of a 3D frame within the slab of `thickness` (model units, > 0) centred on the
// plane through `point` with `normal`, gathered through the thickness into one particle per
// in-plane position, as a 2D frame in the plane's coordinates (x = (u.x, v.x, 0) with (u, v) =
// plane_axes(normal), as cut_plane gives them), dim = 2, time and file kept:
//  - columns: the slab's particles binned on a square grid of the median particle size s in (u, v),
//    centred on the first slab particle, so each column of a particle lattice normal to the plane
//    falls in one bin; a particle stands for the thickness s along the normal, and counts with
//    the length l of [d - s/2, d + s/2] (d its distance from the plane) inside the slab;
//  - "stress_uv": sum of l * (s_uu, s_vv, s_uv) over the column divided by `thickness`: the
//    slab's mean in-plane stress where the column runs through the whole slab, less where the body
//    ends inside it (the retardation counts only material). Fringes use it with the slab
//    thickness as the specimen thickness;
//  - "strain_uv" and every other array: the l-weighted mean over the column, but "material", which
//    is the value of the column's heaviest particle (lowest index on a tie);
//  - "size": s; the position: the l-weighted mean of the column's (u, v).
// A uniform stress gives back that stress; a stress linear through the thickness gives its value
// on the plane when the slab is centred on a particle layer or between two (the midpoint rule).
// An empty frame when no particle reaches the slab. Throws std::invalid_argument for a zero normal
// or a thickness that is not positive and finite.
ParticleFrame slice_plane(const ParticleFrame& frame, std::array<double, 3> point, std::array<double, 3> normal,
                          double thickness);

}  // namespace cleave::viz
